"""The one unit table (kb/measures/units.py): built with pint from kb/measures/aliases.py, stored as package
data, read by both the description parser (English and language-neutral words) and the extractor (every
language)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.measures import units
from kb.measures.aliases import ALIASES, KINDS, PARSER_LANGUAGES
from kb.measures.units import combine, length_unit, lookup, mass_unit, unit_table, volume_unit
from recall import lexicon


def test_stored_unit_table_equals_a_fresh_pint_build() -> None:
    fresh = units.build_unit_table()
    stored = units._read_stored(units.STORED_TABLE)
    assert stored is not None, f"{units.STORED_TABLE} is stale: run python -m kb.measures.units --write"
    assert list(stored) == list(fresh)  # same words, same order
    assert stored == fresh  # same kind, pint name, factor and language, exactly
    assert dict(units.unit_table()) == fresh


def test_stored_unit_table_is_what_the_writer_writes() -> None:
    text = units.table_to_json(units.build_unit_table(), units.build_unit_table(description=True))
    assert units.STORED_TABLE.read_text(encoding="utf-8") == text


def test_stored_description_units_equal_a_fresh_pint_build() -> None:
    fresh = units.build_unit_table(description=True)
    stored = units._read_description(units.STORED_TABLE)
    assert stored == fresh and list(stored) == list(fresh)
    assert (fresh["t"].factor, fresh["km"].factor, fresh["yd"].factor) == (1e6, 1e5, 91.44)


def _stored() -> dict:
    return json.loads(units.STORED_TABLE.read_text(encoding="utf-8"))


def _edit(data: dict, word: str, row) -> dict:
    data["units"][word] = row
    return data


@pytest.mark.parametrize(
    "change",
    [
        lambda d: d["units"].pop("cm") and d,  # an alias missing
        lambda d: _edit(d, "parsec", ["length", "parsec", 3.0857e18, ""]),  # a word the aliases lack
        lambda d: _edit(d, "cm", ["length", "meter", 1.0, ""]),  # another pint name
        lambda d: _edit(d, "cm", ["mass", "centimeter", 1.0, ""]),  # another kind
        lambda d: _edit(d, "cm", ["length", "centimeter", 1.0, "en"]),  # another language
        lambda d: _edit(d, "cm", ["length", "centimeter", 0.0, ""]),  # not positive
        lambda d: _edit(d, "cm", ["length", "centimeter", -1.0, ""]),
        lambda d: _edit(d, "cm", ["length", "centimeter", math.inf, ""]),
        lambda d: _edit(d, "cm", ["length", "centimeter", "1.0", ""]),  # not a number
    ],
)
def test_a_stale_or_damaged_stored_table_is_not_used(change, tmp_path: Path) -> None:
    path = tmp_path / "units.json"
    path.write_text(json.dumps(change(_stored())), encoding="utf-8")
    assert units._read_stored(path) is None  # unit_table() then builds it with pint


def test_a_missing_or_unreadable_stored_table_is_not_used(tmp_path: Path) -> None:
    assert units._read_stored(tmp_path / "absent.json") is None
    (tmp_path / "bad.json").write_text("{not json", encoding="utf-8")
    assert units._read_stored(tmp_path / "bad.json") is None
    (tmp_path / "short.json").write_text(json.dumps({"units": {"cm": ["length", "centimeter"]}}), "utf-8")
    assert units._read_stored(tmp_path / "short.json") is None


def test_the_parser_reads_every_language_but_the_english_homographs_and_the_description_units() -> None:
    table = units.description_units()
    assert table is units.description_units()  # built once
    for kind, words in (("length", lexicon.LENGTH_UNITS), ("mass", lexicon.MASS_UNITS),
                        ("volume", lexicon.VOLUME_UNITS)):  # fmt: skip
        for word, name in words.items():
            assert (table[word].kind, table[word].pint_name) == (kind, name)
    assert set(table) == {*lexicon.LENGTH_UNITS, *lexicon.MASS_UNITS, *lexicon.VOLUME_UNITS}
    assert set(unit_table(PARSER_LANGUAGES)) <= set(table)
    # English words that are units elsewhere are not the parser's units; the other languages' words are
    for word in ("once", "pies", "libra", "metro"):
        assert word not in table and word in unit_table()
    for word, name in (("gramm", "gram"), ("zentimeter", "centimeter"), ("gramos", "gram"), ("pouce", "inch")):
        assert table[word].pint_name == name
    # the description-only units are no page's: the extractor's table does not hold them
    for word, name in (("t", "tonne"), ("km", "kilometer"), ("µm", "micrometer"), ("yd", "yard"),
                       ("mi", "mile"), ("stone", "stone")):  # fmt: skip
        assert table[word].pint_name == name and word not in unit_table()


def test_no_word_names_two_units_even_without_its_accents() -> None:
    seen: dict[str, str] = {}
    for name, by_lang in ALIASES.items():
        assert name in KINDS
        for words in by_lang.values():
            for word in words.split():
                for key in (word, units.strip_accents(word)):
                    assert seen.setdefault(key, name) == name, (key, seen[key], name)


def test_a_word_naming_two_units_is_refused_at_build(monkeypatch) -> None:
    monkeypatch.setitem(ALIASES, "inch", {**ALIASES["inch"], "xx": "cm"})
    units._alias_rows.cache_clear()  # the aliases are read once per process
    try:
        with pytest.raises(ValueError, match="'cm' names both centimeter and inch"):
            units.build_unit_table()
    finally:
        monkeypatch.undo()
        units._alias_rows.cache_clear()


def test_factors_are_the_definitions_exact_decimals() -> None:
    table = unit_table()
    assert table["ft"].factor == 30.48  # pint alone gives 30.479999999999997
    assert table["lb"].factor == 453.59237
    assert table["oz"].factor == 28.349523125
    assert table["inches"].factor == 2.54
    assert table["mm"].factor == 0.1
    assert table["fl oz"].factor == 29.5735295625


@pytest.mark.parametrize(
    ("token", "cm"),
    [("cm", 1.0), ("CM.", 1.0), ("centímetros", 1.0), ("centimetros", 1.0), ("millimètres", 0.1), ("MMT", 0.1),
     ('"', 2.54), ("''", 2.54), ("″", 2.54), ("zoll", 2.54), ("fuß", 30.48), ("fuss", None), ("см", 1.0),
     ("センチ", 1.0), ("cms", 1.0), ("kg", None), ("l", None), ("", None), (None, None), ("x", None)],
)  # fmt: skip
def test_length_lookup_as_pages_write_units(token, cm) -> None:
    assert length_unit(token) == cm


@pytest.mark.parametrize(
    ("token", "g"),
    [("g", 1.0), ("Gramm", 1.0), ("KGM", 1000.0), ("kilogramos", 1000.0), ("lb.", 453.59237), ("LBS", 453.59237),
     ("onzas", 28.349523125), ("гр", 1.0), ("公斤", 1000.0), ("gms", 1.0), ("ml", None), ("cm", None)],
)  # fmt: skip
def test_mass_lookup_as_pages_write_units(token, g) -> None:
    assert mass_unit(token) == g


def test_volume_words_are_neither_lengths_nor_masses() -> None:
    for word in ("ml", "Milliliter", "l", "litros", "cc", "cups", "литр"):
        assert volume_unit(word) is not None, word
        assert length_unit(word) is None and mass_unit(word) is None, word


_WORDS = st.sampled_from(sorted(unit_table()))


@settings(max_examples=200, deadline=None)
@given(_WORDS, st.floats(min_value=1e-3, max_value=1e4))
def test_conversion_agrees_with_the_lookup_and_the_table(word: str, value: float) -> None:
    unit = unit_table()[word]
    kind, converted = units.convert(value, word)
    assert kind == unit.kind and converted == pytest.approx(value * unit.factor)
    found = lookup(word.upper() if word.isascii() else word)
    assert found is not None and found.factor == unit.factor
    by_kind = {"length": length_unit, "mass": mass_unit, "volume": volume_unit}
    for k, fn in by_kind.items():
        assert (fn(word) is not None) == (k == unit.kind)


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(sorted({u.pint_name for u in unit_table().values()})))
def test_every_word_of_a_unit_has_one_factor(name: str) -> None:
    factors = {u.factor for u in unit_table().values() if u.pint_name == name}
    assert len(factors) == 1 and 0 < factors.pop() < math.inf


def _u(word: str):
    return unit_table()[word]


def test_combine_two_units_of_one_quantity_at_its_boundary() -> None:
    assert combine(1, _u("lb"), 2, _u("oz")) == pytest.approx(1.125)
    assert combine(5, _u("ft"), 3, _u("in")) == pytest.approx(5.25)
    assert combine(1, _u("kg"), 450, _u("g")) == pytest.approx(1.45)
    assert combine(5, _u("ft"), 11.99, _u("in")) == pytest.approx(5 + 11.99 / 12)
    assert "not less than 1 foot" in combine(5, _u("ft"), 12, _u("in"))  # the exact limit: a whole foot
    assert "not less than 1 kilogram" in combine(1, _u("kg"), 1000, _u("g"))
    assert "not a smaller unit" in combine(1, _u("in"), 2, _u("ft"))  # the second unit is larger
    assert "not a smaller unit" in combine(1, _u("cm"), 2, _u("cm"))  # the same unit
    assert "not a smaller unit" in combine(1, _u("kg"), 2, _u("cm"))  # another kind
