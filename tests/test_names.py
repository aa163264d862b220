"""The column-wise name tables (recall.names) equal the name-by-name rules of recall.engine."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.csvio import read_catalog_csv
from recall.engine import NameIndex
from recall.name_tables import NameTables
from recall.names import tables_by_rules

ROOT = Path(__file__).resolve().parents[1]


def assert_same(names, aliases, materials):
    """The column-wise tables equal the tables built by the rules, name by name."""
    cols = NameTables(names, aliases, materials, NameIndex.MIN_SUFFIX)
    rules = tables_by_rules(names, aliases, materials, NameIndex.MIN_SUFFIX)
    assert cols.generic == rules.generic
    assert set(cols.phrases) == set(rules.phrases)
    assert all(cols.phrases[p] == rows for p, rows in rules.phrases.items())
    assert set(cols.heads) == set(rules.heads)
    assert all(cols.heads[h] == rows for h, rows in rules.heads.items())
    assert all(cols.head_materials.get(key) == value for key, value in rules.head_materials.items())
    assert cols.head_materials.get(("no such head", 0)) is None
    assert all(cols.by_material.get(m) == rows for m, rows in rules.by_material.items())
    assert cols.vocabulary == rules.vocabulary and cols.longest == rules.longest
    assert_same_word_rows(cols.phrases, rules.phrases)


def assert_same_word_rows(phrases, by_rules):
    """rows_with_word over CSR phrases (built column-wise, and as read back from a stored index: its
    word -> phrases index) equals the scan of the rules' dict of phrases, for every word and others."""
    from recall.names import rows_with_word
    from recall.string_table import KeyRows, StringTable

    stored = KeyRows(StringTable.of(list(phrases.ids)), phrases.starts, phrases.rows, tuples=True)
    words = {w for p in by_rules for w in p} | {"", "zz", "bal", "balls ball", "caf", "\u00e9"}
    for word in sorted(words):
        expected = rows_with_word(by_rules, word)
        assert rows_with_word(phrases, word) == expected, word
        assert rows_with_word(stored, word) == expected, word


def test_small_catalogs_are_built_by_the_rules_large_ones_column_wise():
    from recall.name_tables import COLUMNWISE_FROM, name_tables

    for n, kind in ((COLUMNWISE_FROM - 1, SimpleNamespace), (COLUMNWISE_FROM, NameTables)):
        assert isinstance(name_tables([f"cup {i}" for i in range(n)], [()] * n, None, 4), kind)
    index = NameIndex(["wood block 2", "tennis ball (small)"], [(), ("ball",)], ["wood", "rubber"])
    assert list(index.find("a tennis ball").exact) == [1] and 0 in index.find("a wood block").head


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
     "ies", "berries", "glasses", "bus", "a", "metal", "plastic", "of of", "cm", "26", "750ml", "1,7", "l",
     "inch", "measuring"]
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



def test_a_size_at_the_end_of_a_store_name_is_no_head_noun():
    """Store names end in their size ("skillet 26 cm", "bottle 750 ml", "kettle 1.7l"): the unit is no noun
    (a blind test's "cm" recalled three such objects by name), and "measuring cup" keeps its noun."""
    from recall.names import name_core

    assert name_core("cast iron skillet 26 cm") == ("cast", "iron", "skillet")
    assert name_core("water bottle 750 ml") == ("water", "bottle")
    assert name_core("kettle 1.7l") == ("kettle",)
    assert name_core("tablet 10 inch") == ("tablet",)
    assert name_core("measuring cup") == ("measuring", "cup") and name_core("9v battery") == ("9v", "battery")
    names = ["cast iron skillet 26 cm", "porcelain dinner plate 27 cm", "water bottle 750 ml", "measuring cup"]
    index = NameIndex(names, [()] * 4, [None] * 4)
    for text in ("cm", "something in cm", "ml", "26 cm"):
        found = index.find(text)
        assert not found.exact and not found.head, (text, found)
    assert set(index.find("a skillet").head) == {0} and set(index.find("a bottle").head) == {2}
    assert set(index.find("a cup").head) == {3}


@pytest.mark.parametrize(
    ("text", "unknown"),
    [
        ("red, round, 7.5 cm across", None),  # colour words alone: adjectives, no object
        ("dark purple, round, 5 cm", None),
        ("bright yellow, squeezable, about 18 cm", None),
        ("an orange, 7 cm", "orange"),  # a colour that is a lexicon noun (fruit) still names an object
        ("a plum, 5 cm", "plum"),
        ("a red kettle, 20 cm", "kettle"),  # a colour before a noun: the noun
    ],
)
def test_a_subject_of_colour_words_alone_is_no_unknown_noun(text, unknown):
    index = NameIndex(["tennis ball", "mug"], [(), ()], [None, None])
    assert index.unknown_noun(text) == unknown
