"""The column-wise name tables (recall.names) equal the name-by-name rules of recall.engine."""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from kb.csvio import read_catalog_csv
from recall.engine import GENERIC_NOUNS, NameIndex, _head, name_core, normalize_words
from recall.lexicon import MATERIAL_WORDS

ROOT = Path(__file__).resolve().parents[1]


def reference(names, aliases, materials):
    """The tables built one name at a time, by the rules (normalize_words, name_core, _head)."""
    generic, by_material, phrases, heads, head_materials = {}, {}, {}, {}, {}
    for row, mat in enumerate(materials):
        if mat:
            by_material.setdefault(mat, set()).add(row)
    for row, (name, alias) in enumerate(zip(names, aliases, strict=True)):
        for phrase in (name, *alias):
            words = tuple(normalize_words(phrase))
            core = name_core(phrase)
            if not words:
                continue
            phrases.setdefault(words, set()).add(row)
            phrases.setdefault(core, set()).add(row)
            head = _head(core)
            stated = {MATERIAL_WORDS[w] for w in core if w in MATERIAL_WORDS and w != head}
            if (
                len(stated) == 1
                and head in GENERIC_NOUNS
                and all(w in GENERIC_NOUNS or w in MATERIAL_WORDS or w == "of" for w in core)
            ):
                generic[core] = next(iter(stated))
            for key in (head, *(head[cut:] for cut in range(1, len(head) - NameIndex.MIN_SUFFIX + 1))):
                heads.setdefault(key, set()).add(row)
                known = head_materials.get((key, row), set())
                head_materials[(key, row)] = None if known is None or not stated else known | stated
    vocabulary = frozenset(w for p in phrases for w in p) | frozenset(heads)
    longest = max((len(p) for p in phrases), default=0)
    return generic, by_material, phrases, heads, head_materials, vocabulary, longest


def assert_same(names, aliases, materials):
    index = NameIndex(names, aliases, materials)
    generic, by_material, phrases, heads, head_materials, vocabulary, longest = reference(
        names, aliases, materials
    )
    assert index.generic == generic
    assert set(index.phrases) == set(phrases)
    assert all(index.phrases[p] == rows for p, rows in phrases.items())
    assert set(index.heads) == set(heads)
    assert all(index.heads[h] == rows for h, rows in heads.items())
    assert all(index.head_materials.get(key) == value for key, value in head_materials.items())
    assert index.head_materials.get(("no such head", 0)) is None
    assert all(index.by_material.get(m) == rows for m, rows in by_material.items())
    assert index.vocabulary == vocabulary and index.longest == longest


def test_the_real_catalogs_give_the_same_tables():
    for path in [ROOT / "recall" / "data" / "seed_catalog.csv", *sorted((ROOT / "tests" / "data").glob("*/catalog.csv"))]:
        if not path.exists():
            continue
        records = read_catalog_csv(path).records
        assert_same([r.name for r in records], [r.aliases for r in records], [r.material for r in records])


WORDS = st.sampled_from(
    ["ball", "balls", "tennis", "cup", "cups", "of", "water", "bottle", "wood", "wooden", "piece", "block",
     "2", "10", "b", "no", "v", "glass", "knives", "dice", "teaspoon", "spoon", "steel", "(small)", "[xl]",
     "box", "boxes", "it's", "rubik\u2019s", "caf\u00e9", "\u00c9cole", "x-ray", "ring", "  ", "", "thing",
     "ies", "berries", "glasses", "bus", "a", "metal", "plastic", "of of"]
)  # fmt: skip
PHRASES = st.lists(WORDS, min_size=0, max_size=5).map(" ".join)


@settings(max_examples=150, deadline=None)
@given(
    st.lists(
        st.tuples(PHRASES, st.lists(PHRASES, max_size=2), st.sampled_from([None, "wood", "metal", "glass"])),
        min_size=1,
        max_size=12,
    )
)
def test_random_names_give_the_same_tables(rows):
    names = [f"{name} #{i}" if i % 3 else name for i, (name, _, _) in enumerate(rows)]
    assert_same(names, [tuple(a) for _, a, _ in rows], [m for _, _, m in rows])

