"""The seed catalog and the recall evaluation data: valid, consistent with the paper, and as documented.

Files are read with the stdlib csv module and validated with :meth:`kb.features.ObjectRecord.create`, so
these tests check the data, not the catalog code.
"""

from __future__ import annotations

import csv
import re
from collections import Counter
from pathlib import Path

import pytest

from kb.features import CATEGORIES, CSV_COLUMNS, ObjectRecord, normalize_name

REPO = Path(__file__).resolve().parents[1]
SEED_CSV = REPO / "kb" / "data" / "seed_catalog.csv"
SOURCES_MD = REPO / "kb" / "data" / "SOURCES.md"
DATA = REPO / "recall" / "data"
DEV_CSV = DATA / "dev_descriptions.csv"
OPEN_CSV = DATA / "open_set_descriptions.csv"
DATA_README = DATA / "README.md"

SEED_HEADER = [*CSV_COLUMNS, "aliases", "source"]

#: The paper's Table II (Rao, Li, He), its "stiffness" soft -> squeezable.
PAPER_TABLE_II = {
    "calculator": (15.4, 7.9, 1.5, 116, "thin", "medium", "medium", "plastic", "rigid"),
    "water bottle": (21.5, 7.2, 7.2, 660, "prism", "smooth", "sturdy", "metal", "rigid"),
    "wood cylinder": (8.0, 2.9, 2.9, 21, "prism", "rough", "sturdy", "wood", "rigid"),
    "cardboard box": (15.5, 9.0, 1.8, 66, "thin", "rough", "medium", "paper", "rigid"),
    "mini rubix cube": (3.0, 3.0, 3.0, 12, "compact", "smooth", "sturdy", "plastic", "rigid"),
    "wood wedge": (6.0, 3.0, 1.5, 11, "prism", "rough", "sturdy", "wood", "rigid"),
    "wood disk": (7.2, 7.2, 2.0, 60, "compact", "rough", "sturdy", "wood", "rigid"),
    "tennis ball": (6.4, 6.4, 6.4, 56, "radial", "rough", "medium", "fabric", "squeezable"),
    "wood piece": (3.7, 2.9, 1.9, 7, "compact", "rough", "sturdy", "wood", "rigid"),
    "plastic cap": (3.4, 3.4, 1.3, 5, "compact", "grippy", "medium", "plastic", "rigid"),
}
TABLE_II_COLUMNS = ("a_cm", "b_cm", "c_cm", "mass_g", "shape", "texture", "fragility", "material", "rigidity")

#: The paper's Table III, verbatim.
PAPER_TABLE_III = {
    "calculator": "A scientific calculator with plastic body. It is about fifteen and half centimeters long, "
    "8 centimeters wide and appears to be more than one and half centimeters thick.",
    "water bottle": "A metallic water bottle of about seven and quarter centimeters in diameter and twenty one "
    "and half centimeters long. It is filled with about half a liter of water and is heavy.",
    "wood cylinder": "A cylindrical wood block of about eight centimeters long and about three centimeters in "
    "diameter. It is light weight. It has a rough surface.",
    "cardboard box": "An empty cardboard box about fifteen centimeters in length, nine centimeters wide and "
    "about two centimeters thick. It is very light weight. It weighs about sixty grams.",
    "mini rubix cube": "A mini rubix cube of about three centimeters wide. It is made of plastic and has "
    "smooth texture.",
}

UNIT_TAGS = {"metric", "imperial", "mixed"}
NAMING_TAGS = {"named", "loose", "unnamed"}
OTHER_TAGS = {"words", "fraction", "range", "terse", "guess", "paper"}


def _read(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    with path.open(newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        return list(reader.fieldnames or []), list(reader)


def _record(row: dict[str, str]) -> ObjectRecord:
    row = dict(row)
    aliases = [a for a in row.pop("aliases").split(";") if a.strip()]
    source = row.pop("source")
    return ObjectRecord.create(row.pop("name"), aliases=aliases, source=source, **row)


@pytest.fixture(scope="module")
def seed_rows() -> list[dict[str, str]]:
    header, rows = _read(SEED_CSV)
    assert header == SEED_HEADER
    return rows


@pytest.fixture(scope="module")
def seed(seed_rows) -> dict[str, ObjectRecord]:
    return {rec.name: rec for rec in map(_record, seed_rows)}


@pytest.fixture(scope="module")
def dev_rows() -> list[dict[str, str]]:
    header, rows = _read(DEV_CSV)
    assert header == ["object", "description", "style"]
    return rows


def _mentions(text: str, phrase: str) -> bool:
    """Whether ``phrase`` occurs in ``text`` as whole words (case-insensitive)."""
    return re.search(rf"(?<![\w']){re.escape(phrase)}(?![\w'])", text.lower()) is not None


# --- seed catalog -------------------------------------------------------------------------------------


def test_every_seed_row_is_valid_and_there_are_enough(seed_rows, seed):
    assert len(seed_rows) >= 110
    assert len(seed) == len(seed_rows), "duplicate names"


def test_names_are_canonical_and_dimensions_written_largest_first(seed_rows):
    for row in seed_rows:
        assert row["name"] == normalize_name(row["name"]), row["name"]
        a, b, c = (float(row[k]) for k in ("a_cm", "b_cm", "c_cm"))
        assert a >= b >= c, row["name"]


def test_aliases_are_unique_and_never_another_objects_name(seed):
    owner: dict[str, str] = {}
    for rec in seed.values():
        for alias in rec.aliases:
            assert alias not in seed, f"alias {alias!r} of {rec.name!r} is a catalog name"
            assert alias not in owner, f"alias {alias!r} of {rec.name!r} also belongs to {owner[alias]!r}"
            owner[alias] = rec.name


def test_every_row_says_where_its_values_come_from(seed):
    assert all(rec.source and rec.source.strip() for rec in seed.values())
    prefixes = ("paper ", "YCB object set", "standard: ", "manufacturer spec: ", "typical value")
    assert all(rec.source.startswith(prefixes) for rec in seed.values())


@pytest.mark.parametrize("name", sorted(PAPER_TABLE_II))
def test_paper_table_ii_objects_have_the_papers_values(seed, name):
    rec = seed[name]
    assert tuple(getattr(rec, col) for col in TABLE_II_COLUMNS) == pytest.approx(PAPER_TABLE_II[name])
    assert rec.source.startswith("paper Table II")


def test_paper_tv_remote(seed):
    remote = seed["tv remote"]
    assert remote.dims_cm == (16.0, 3.5, 2.0)
    assert (remote.material, remote.shape) == ("plastic", "long")
    assert seed[normalize_name("tv remote")] is remote
    assert "remote control" in remote.aliases


def test_the_papers_open_set_orange_is_not_in_the_catalog(seed):
    words = set(seed) | {a for rec in seed.values() for a in rec.aliases}
    assert "orange" not in words


@pytest.mark.parametrize("feature", sorted(CATEGORIES))
def test_every_class_of_every_categorical_feature_occurs_several_times(seed, feature):
    counts = Counter(getattr(rec, feature) for rec in seed.values())
    assert set(counts) == set(CATEGORIES[feature])
    assert min(counts.values()) >= 3, counts


def test_every_object_is_fully_described(seed):
    for rec in seed.values():
        assert None not in rec.features().values(), rec.name


def test_density_over_the_bounding_box_is_physically_sane(seed):
    for rec in seed.values():
        density = rec.mass_g / (rec.a_cm * rec.b_cm * rec.c_cm)
        assert 0.01 <= density <= 25, f"{rec.name}: {density:.3f} g/cm3"


def test_near_confusable_pairs_are_present(seed):
    for pair in [
        ("tennis ball", "plastic ball"),
        ("aa battery", "aaa battery"),
        ("coffee mug", "plastic mug"),
        ("apple", "plastic apple"),
        ("wooden cutting board", "plastic cutting board"),
    ]:
        assert set(pair) <= set(seed)
    # objects that differ mainly by material
    assert seed["wooden cutting board"].material != seed["plastic cutting board"].material
    assert seed["apple"].material != seed["plastic apple"].material


def test_seed_imports_into_a_real_knowledge_base(tmp_path, seed):
    from kb.catalog import KnowledgeBase

    kb = KnowledgeBase.open(tmp_path / "seed.duckdb")
    kb.import_csv(SEED_CSV)
    names = {rec.name for rec in kb.list_objects()}
    assert names == set(seed)
    assert kb.get_object("Remote Control").name == "tv remote"
    assert kb.get_object("calculator").dims_cm == (15.4, 7.9, 1.5)


def test_sources_document_explains_every_source_kind_and_class_rule():
    text = SOURCES_MD.read_text(encoding="utf-8")
    for phrase in ("paper Table II", "YCB object set", "standard:", "manufacturer spec:", "typical value"):
        assert phrase in text
    for word in ("thin", "compact", "prism", "long", "radial", "squeezable", "floppy", "fragile", "grippy"):
        assert word in text


# --- development descriptions -------------------------------------------------------------------------


def test_dev_set_size_and_coverage(dev_rows, seed):
    assert len(dev_rows) >= 110
    objects = {row["object"] for row in dev_rows}
    assert objects <= set(seed), objects - set(seed)
    assert len(objects) >= 90
    assert all(row["description"].strip() for row in dev_rows)
    assert len({row["description"] for row in dev_rows}) == len(dev_rows), "duplicate descriptions"


@pytest.mark.parametrize("obj", sorted(PAPER_TABLE_III))
def test_paper_table_iii_descriptions_are_present_verbatim(dev_rows, obj):
    matches = [row for row in dev_rows if row["description"] == PAPER_TABLE_III[obj]]
    assert len(matches) == 1
    assert matches[0]["object"] == obj
    assert "paper" in matches[0]["style"].split(";")


def test_style_tags_are_from_the_documented_vocabulary(dev_rows):
    for row in dev_rows:
        tags = row["style"].split(";")
        assert tags[0] in UNIT_TAGS, row
        assert tags[1] in NAMING_TAGS, row
        assert set(tags[2:]) <= OTHER_TAGS, row


def test_style_mix_meets_the_brief(dev_rows):
    n = len(dev_rows)
    tags = [row["style"].split(";") for row in dev_rows]
    imperial = sum(t[0] in ("imperial", "mixed") for t in tags)
    words = sum("words" in t for t in tags)
    unnamed = sum(t[1] == "unnamed" for t in tags)
    assert imperial >= 0.25 * n
    assert words >= 0.20 * n
    assert unnamed >= 0.30 * n


def test_units_tag_matches_the_text(dev_rows):
    imperial = re.compile(r"\b(inch|inches|foot|feet|oz|ounces?|pounds?|lbs?)\b|\d\"", re.I)
    for row in dev_rows:
        has_imperial = bool(imperial.search(row["description"]))
        assert has_imperial == (row["style"].split(";")[0] in ("imperial", "mixed")), row


def test_naming_tag_matches_the_text(dev_rows, seed):
    for row in dev_rows:
        rec = seed[row["object"]]
        named = any(_mentions(row["description"], n) for n in (rec.name, *rec.aliases))
        assert named == (row["style"].split(";")[1] == "named"), row


def test_readme_style_counts_are_the_computed_ones(dev_rows):
    text = DATA_README.read_text(encoding="utf-8")
    block = text.split("<!-- style-counts")[1].split("<!-- end style-counts")[0]
    documented = {m[1]: int(m[2]) for m in re.finditer(r"^\| (\w+) \| (\d+) \|", block, re.M)}
    computed = Counter(tag for row in dev_rows for tag in row["style"].split(";"))
    assert documented == dict(computed)
    assert f"share of {len(dev_rows)}" in block


# --- open-set descriptions ----------------------------------------------------------------------------


def test_open_set_descriptions_name_things_outside_the_catalog(seed):
    header, rows = _read(OPEN_CSV)
    assert header == ["description", "nearest_expected", "note"]
    assert len(rows) >= 10
    assert rows[0]["description"] == "An orange of 7 cm diameter."
    assert "tennis ball" in rows[0]["nearest_expected"].split(";")
    for row in rows:
        nearest = row["nearest_expected"].split(";")
        assert nearest and set(nearest) <= set(seed), row
        assert row["note"].strip()
