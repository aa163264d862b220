"""Signs, absurd numbers and the catalog's limits in the description parser (issue 15 items 6 and 9):
a negative or absurd stated size is refused with a reason, never read as another number."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from kb.features import MAX_DIM_CM, MAX_MASS_G
from kb.measures.aliases import PARSER_LANGUAGES
from kb.measures.numbers import digits_value
from kb.measures.units import unit_table
from kb.service.cli import app
from recall.parser import parse

approx = pytest.approx
NUMERIC = ("a_cm", "b_cm", "c_cm", "mass_g")


def _numbers(text: str) -> dict[str, float]:
    return {k: v for k, v in parse(text).values().items() if k in NUMERIC}


def _refused(text: str) -> list[tuple[str, str]]:
    return [(r.words, r.reason) for r in parse(text).refused]


# ----------------------------------------------------------------------------------------- four extents
@pytest.mark.parametrize("text", ["3 x 2 x 1 x 7 cm", "a board 30 x 20 x 2 x 2 cm, 500 g", "1 x 2 x 3 x 4 x 5 in"])
def test_a_size_of_four_or_more_extents_is_refused_not_cut_to_three(text: str) -> None:
    """Which three of four extents were meant is a guess: the size is refused with its reason (the 7 of
    "3 x 2 x 1 x 7 cm" was silently dropped), and the other values stay."""
    numbers = _numbers(text)
    assert not {"a_cm", "b_cm", "c_cm"} & set(numbers)
    (words, reason), = _refused(text)
    assert reason.endswith("extents in one size: an object has three") and " x " in words
    assert numbers.get("mass_g") == (500 if "500 g" in text else None)


def test_three_extents_are_still_a_size() -> None:
    assert _numbers("a box 3 x 2 x 1 cm") == {"a_cm": 3, "b_cm": 2, "c_cm": 1} and _refused("3 x 2 x 1 cm") == []


# ------------------------------------------------------------------------------------------------ signs
@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("-10 kg", "-10 kg"),  # was 10,000 g
        ("-5 cm long", "-5 cm"),  # was 5 cm
        ("It weighs −2 kg.", "−2 kg"),  # the minus sign U+2212
        ("minus 5 cm", "minus 5 cm"),
        ("a ball -3 cm in diameter", "-3 cm"),
        ("size:-5 cm", "-5 cm"),
        ("from -3 to 4 cm", "-3 to 4 cm"),  # a range with a negative bound
        ("about -2.5 inches wide", "about -2.5 inches"),
        ("-half a pound", "-half a pound"),
    ],
)
def test_a_negative_value_is_refused_with_its_reason(text: str, words: str) -> None:
    assert _numbers(text) == {}
    assert _refused(text) == [(words, "negative: a size or a mass is more than zero")]


def test_a_negative_value_does_not_hide_the_others() -> None:
    p = parse("A box -3 cm thick, 20 cm long, 300 g")
    assert p.values()["a_cm"] == 20 and p.values()["mass_g"] == 300 and "c_cm" not in p.values()
    assert [r.words for r in p.refused] == ["-3 cm"]
    # an unlabelled value in a dimension is an extent: refused too, not only ignored
    assert _refused("15 cm long, -8 wide") == [("-8", "negative: a size or a mass is more than zero")]
    assert "shape" not in parse("-5 cm long").values()  # "long" was the dimension's word, not a shape


@pytest.mark.parametrize(
    ("text", "feature", "value"),
    [
        ("2-3 cm", "a_cm", 2.5),  # a range: the hyphen is no minus sign
        ("12-1/2 inches long", "a_cm", 12.5 * 2.54),  # a mixed number, not the range 1/2 to 12
        ("3-½ in long", "a_cm", 3.5 * 2.54),
        ("a 1-1/2 inch thick board, 30 cm long", "c_cm", 1.5 * 2.54),
        ("5-cm-long", "a_cm", 5.0),
        ("10 - 20 cm", "a_cm", 15.0),  # spaced: a range
        ("model X-5, 20 cm long", "a_cm", 20.0),  # glued to a word: no sign
        ("- 10 cm", "a_cm", 10.0),  # a dash with a space (a list bullet), not a sign
    ],
)
def test_hyphens_that_are_not_minus_signs(text: str, feature: str, value: float) -> None:
    assert parse(text).values()[feature] == approx(value)
    assert parse(text).refused == ()


def test_a_range_of_fractions_stays_a_range() -> None:
    ev = parse("1/2-3/4 inch thick").features["c_cm"]
    assert (ev.qualifier, ev.low, ev.high) == ("range", approx(1.27), approx(1.905))
    ev = parse("1-3/2 inches thick").features["c_cm"]  # 3/2 is no proper fraction: a range, 1 to 1.5
    assert (ev.qualifier, ev.low, ev.high) == ("range", approx(2.54), approx(3.81))
    assert parse("2-2/2 inches thick").features["c_cm"].qualifier == "range"  # 2/2 is no proper fraction
    assert parse("2-1/2 inches thick").features["c_cm"].qualifier == "exact"  # 2 1/2
    assert parse("2-3 cm").features["a_cm"].qualifier == "range"


# ------------------------------------------------------------------- scientific notation, powers, overflow
@pytest.mark.parametrize(
    ("token", "value"),
    [("1e308", 1e308), ("1.5e2", 150.0), ("5E-1", 0.5), ("10**3", 1000.0), ("10^3", 1000.0),
     ("10^-3", 0.001), ("2.5**2", 6.25), ("1e400", float("inf")), ("10**" + "9" * 5000, float("inf"))],
)  # fmt: skip
def test_the_number_grammar_reads_scientific_notation_and_powers(token: str, value: float) -> None:
    assert digits_value(token) == value


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("1e308 cm", "1e+308 cm: absurd for a household object (over 500 cm)"),  # was 308 cm
        ("10**100 g", "1e+100 g: absurd for a household object (over 500000 g)"),  # was 100 g
        ("10^9 mm long", "100000000 cm: absurd for a household object (over 500 cm)"),
        ("1e400 kg", "inf g: must be finite"),
        ("9" * 400 + " cm", "inf cm: must be finite"),
        ("1,000,000 g", "1000000 g: absurd for a household object (over 500000 g)"),
        ("0 cm", "zero: a size or a mass is more than zero"),
        ("0.00001 g", "1e-05 g: too small to state (under 0.0001)"),  # was 0.0 g
        ("a 1000 liter tank full of water", "1000000 g of contents: absurd for a household object (over 500000 g)"),
        ("a mug weighing a million grams", "1000000 g: absurd for a household object (over 500000 g)"),  # was dropped
        ("a pencil two million km long", "2e+11 cm: absurd for a household object (over 500 cm)"),
    ],
)
def test_absurd_values_are_refused_not_changed(text: str, reason: str) -> None:
    assert _numbers(text) == {}
    assert [r for _w, r in _refused(text)] == [reason]


def test_sensible_scientific_notation_and_powers_are_read() -> None:
    assert parse("1.5e2 cm long").values()["a_cm"] == 150
    assert parse("10^3 g").values()["mass_g"] == 1000
    assert parse("5e2 g").values()["mass_g"] == 500


def test_a_relation_past_the_limit_is_refused_with_its_words() -> None:
    p = parse("twenty times as long as it is wide, 30 cm wide")
    assert p.values()["b_cm"] == 30 and "a_cm" not in p.values()
    assert _refused("twenty times as long as it is wide, 30 cm wide") == [
        ("twenty times as long as it is wide", "600 cm: absurd for a household object (over 500 cm)")
    ]


# ------------------------------------------------------------------ the limits, pinned on both sides
# kb/features.py: "Values past these are refused" (5 m, 500 kg): the limit itself is accepted.
@pytest.mark.parametrize(
    ("text", "feature", "value"),
    [("500 cm long", "a_cm", 500.0), ("5 m long", "a_cm", 500.0), ("5000 mm", "a_cm", 500.0),
     ("500 kg", "mass_g", 500_000.0), ("500000 g", "mass_g", 500_000.0), ("0.0001 cm thick", "c_cm", 0.0001),
     ("0.1 mg", "mass_g", 0.0001)],
)  # fmt: skip
def test_the_limit_itself_is_accepted(text: str, feature: str, value: float) -> None:
    assert parse(text).values()[feature] == value
    assert parse(text).refused == ()


@pytest.mark.parametrize("text", ["500.0001 cm wide", "5.00001 m tall", "500.001 kg", "500000.1 g"])
def test_just_past_the_limit_is_refused(text: str) -> None:
    assert _numbers(text) == {}
    assert "absurd for a household object" in _refused(text)[0][1]


# A length in its own words past 5 m, up to 100 m, is a long flexible thing's ("a garden hose, 50 feet
# long"): read as at least the catalog's limit (recall.dimensions.MAX_STATED_LENGTH_CM).
@pytest.mark.parametrize(
    "text", ["500.0001 cm long", "5.00001 m long", "a garden hose, 50 feet long", "a rope, length 100 m"]
)
def test_a_length_past_the_limit_up_to_100_m_is_at_least_the_limit(text: str) -> None:
    from recall.dimensions import MAX_STATED_LENGTH_CM

    assert MAX_STATED_LENGTH_CM == 10_000.0
    p = parse(text)
    assert p.values()["a_cm"] == MAX_DIM_CM and p.features["a_cm"].qualifier == "at_least"
    assert p.refused == ()


@pytest.mark.parametrize(
    "text", ["100.001 m long", "a ball 10 m wide", "a 15 m hose", "twenty times as long as it is wide, 30 cm wide"]
)
def test_past_100_m_another_extent_or_a_derived_length_is_still_refused(text: str) -> None:
    assert not {"a_cm"} & set(_numbers(text))
    assert "absurd for a household object" in _refused(text)[0][1]


@pytest.mark.parametrize("text", ["0.00009 cm thick", "0.00005 g", "0.05 mg"])
def test_just_under_the_smallest_stated_value_is_refused(text: str) -> None:
    assert _numbers(text) == {}  # not rounded up to 0.0001
    assert "too small to state (under 0.0001)" in _refused(text)[0][1]


def test_the_parser_uses_the_catalogs_limits() -> None:
    assert (MAX_DIM_CM, MAX_MASS_G) == (500.0, 500_000.0)  # the figures the tests above pin


# ----------------------------------------------------------------- feet and inches, pounds and ounces
# A second unit states less than one of the first: "5' 11"" is 5 ft 11 in; "5' 12"" is refused (12 inches
# is a foot: a slip for 5' 1.2" or 6', the parser does not guess).
@pytest.mark.parametrize(
    ("text", "value"),
    [("5' 11\"", (5 * 12 + 11) * 2.54), ("5 ft 11 in", (5 * 12 + 11) * 2.54), ("6 ft 0 in", 72 * 2.54),
     ("5 ft 11.9 in", (5 * 12 + 11.9) * 2.54)],
)  # fmt: skip
def test_inches_under_a_foot_make_one_length(text: str, value: float) -> None:
    assert parse(text).values()["a_cm"] == approx(value)


@pytest.mark.parametrize(
    ("text", "reason"),
    [("5' 12\"", "12 inch is not less than 1 foot"), ("5 ft 12 in", "12 inch is not less than 1 foot"),
     ("5 ft 30 in", "30 inch is not less than 1 foot"), ("1 lb 16 oz", "16 ounce is not less than 1 pound")],
)  # fmt: skip
def test_a_second_unit_of_a_whole_first_unit_or_more_is_refused(text: str, reason: str) -> None:
    assert _numbers(text) == {}
    assert _refused(text) == [(text, reason)]


def test_pounds_and_ounces_at_the_boundary() -> None:
    assert parse("1 lb 15 oz").values()["mass_g"] == approx(453.59237 + 15 * 28.349523125)


# --------------------------------------------------------------------------------------- the faces
def test_json_and_the_cli_show_what_was_refused() -> None:
    d = parse("a 2 kg box, -5 cm wide").to_dict()
    assert d["mass_g"] == 2000 and d["b_cm"] is None
    assert d["refused"] == [
        {"words": "-5 cm", "start": 12, "end": 17, "reason": "negative: a size or a mass is more than zero"}
    ]
    assert parse("a 20 cm box").to_dict()["refused"] == []
    runner = CliRunner()
    shown = runner.invoke(app, ["parse", "--", "-10 kg, 1e308 cm"])
    assert shown.exit_code == 0, shown.output
    assert "refused: '-10 kg': negative" in shown.output
    assert "refused: '1e308 cm': 1e+308 cm: absurd for a household object (over 500 cm)" in shown.output
    as_json = runner.invoke(app, ["parse", "--json", "--", "-10 kg"])
    assert json.loads(as_json.output)["refused"][0]["words"] == "-10 kg"


# ----------------------------------------------------------------------------------- properties
_UNITS = sorted(unit_table(PARSER_LANGUAGES).items())
_LIMIT = {"length": MAX_DIM_CM, "mass": MAX_MASS_G, "volume": MAX_MASS_G}


def _stated(word: str, kind: str, number: str) -> tuple[str, str]:
    """A text stating ``number word`` and the feature it gives."""
    if kind == "volume":
        return f"a bottle filled with {number} {word} of water", "mass_g"
    return f"{number} {word}", "mass_g" if kind == "mass" else "a_cm"


@settings(max_examples=300, deadline=None)
@given(st.sampled_from(_UNITS), st.integers(min_value=1, max_value=10**7))
def test_any_number_in_range_parses_to_itself_in_the_catalog_unit(item, thousandths: int) -> None:
    word, unit = item
    x = thousandths / 1000
    text, feature = _stated(word, unit.kind, f"{x:.3f}")
    expected = x * unit.factor
    got = parse(text).values().get(feature)
    if 0.0001 <= expected <= _LIMIT[unit.kind]:
        assert got == approx(round(expected, 4), rel=1e-9, abs=1e-9), text
    else:
        assert got is None and parse(text).refused, text  # refused, with a reason


@settings(max_examples=300, deadline=None)
@given(
    st.sampled_from(_UNITS),
    st.integers(min_value=0, max_value=10**7),
    st.sampled_from(["-", "−", "minus "]),
    st.sampled_from(["", "A box ", "It is about ", "Weighs "]),
)
def test_a_negative_never_parses_to_a_positive(item, thousandths: int, sign: str, before: str) -> None:
    word, unit = item
    number = f"{sign}{thousandths / 1000:.3f}"
    text, _feature = _stated(word, unit.kind, number)
    p = parse(before + text)
    assert not any(f in p.values() for f in NUMERIC), p.values()
    assert p.refused  # and it says so


# ------------------------------------------------------------------ the parser's own documented limits
def test_a_text_of_exactly_the_longest_length_is_parsed() -> None:
    from kb.errors import DescriptionError
    from recall.parser import MAX_TEXT_CHARS

    text = ("a 20 cm box " * (MAX_TEXT_CHARS // 12 + 1))[:MAX_TEXT_CHARS]
    assert len(text) == MAX_TEXT_CHARS
    assert parse(text).values()["a_cm"] == 20
    with pytest.raises(DescriptionError, match=f"too long: {MAX_TEXT_CHARS + 1:,} characters"):
        parse(text + " ")


def test_sentences_are_cut_at_exactly_max_segment_tokens() -> None:
    from recall.chunks import MAX_SEGMENT_TOKENS, Chunker
    from recall.tokens import Token

    def tokens(n: int) -> list[Token]:
        return [Token("w", "w", i, i + 1) for i in range(n)]

    assert [len(s) for s in Chunker.segments(tokens(MAX_SEGMENT_TOKENS))] == [MAX_SEGMENT_TOKENS]
    assert [len(s) for s in Chunker.segments(tokens(MAX_SEGMENT_TOKENS + 1))] == [MAX_SEGMENT_TOKENS, 1]
    ends = tokens(3)
    ends[1].tag = "SEP"  # a sentence end closes its segment
    assert [len(s) for s in Chunker.segments(ends)] == [2, 1]


def test_the_tag_cache_stops_growing_at_its_size_and_tags_stay_right(monkeypatch) -> None:
    from recall import tags
    from recall.parser import DescriptionParser

    monkeypatch.setattr(tags, "TAG_CACHE_SIZE", 3)
    parser = DescriptionParser()
    parser.parse("zyx qwv ppq")  # under the size (0 < 3): all three remembered
    assert set(parser.tagger.cache) == {"zyx", "qwv", "ppq"}
    p = parser.parse("a metallic dddq bottle, 20 cm tall")  # at the size: tagged, not remembered
    assert set(parser.tagger.cache) == {"zyx", "qwv", "ppq"}
    assert p.values()["a_cm"] == 20 and p.values()["material"] == "metal"
