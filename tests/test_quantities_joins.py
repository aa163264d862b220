"""Adjacent chunks that state one quantity (recall/quantities_joins.py): a compound with a bare tail ("2 m
30", "5 ft 3") and a fraction of a scale word ("half a million grams"), as people write them."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from recall.parser import parse
from recall.quantities_joins import fraction_of

# (first unit word, its factor to cm or g, tail factor, how many tails make one first unit)
_TAILS = [("m", 100.0, 1.0, 100), ("kg", 1000.0, 1.0, 1000), ("ft", 30.48, 2.54, 12), ("lb", 453.59237, 28.349523125, 16)]


def _value(text: str, feature: str) -> float | None:
    ev = parse(text).features.get(feature)
    return None if ev is None else float(ev.value)


def _feature(unit: str) -> str:
    return "mass_g" if unit in ("kg", "lb") else "a_cm"


def _text(whole: int, unit: str, tail: int) -> str:
    return f"a thing weighing {whole} {unit} {tail}" if unit in ("kg", "lb") else f"a pole {whole} {unit} {tail} long"


@pytest.mark.parametrize(
    ("text", "feature", "expected"),
    [
        ("a pole 2 m 30 long", "a_cm", 230.0),
        ("a pole 1 m 20 long", "a_cm", 120.0),
        ("length 2 m 30", "a_cm", 230.0),  # the tail after a dimension chunk
        ("2 m 30 in length", "a_cm", 230.0),
        ("a 5 ft 3 lamp", "a_cm", 160.02),
        ("5 foot 3 tall", "a_cm", 160.02),
        ("1 kg 200 of flour", "mass_g", 1200.0),
        ("a 1 lb 4 bag", "mass_g", 567.0),
        ("about 2 m 30 long", "a_cm", 230.0),
        # the grammar's own compounds are unchanged
        ("a pole 1 m 20 cm long", "a_cm", 120.0),
        ("a 2 ft 3 in long broom handle", "a_cm", 68.58),
        ("5'3\" tall lamp", "a_cm", 160.02),
        ("a bag of 1 lb 4 oz", "mass_g", 567.0),
    ],
)
def test_compound_with_bare_tail_is_one_quantity(text, feature, expected):
    assert _value(text, feature) == pytest.approx(expected, rel=1e-3)


@pytest.mark.parametrize(("unit", "factor", "tail_factor", "per"), _TAILS)
def test_tail_boundary_one_less_than_a_whole_unit(unit, factor, tail_factor, per):
    """A tail of one less than a whole first unit joins; a whole unit or more does not (it is a second
    number, read as before: not the first value plus it)."""
    assert _value(_text(2, unit, per - 1), _feature(unit)) == pytest.approx(2 * factor + (per - 1) * tail_factor)
    joined = 2 * factor + per * tail_factor
    assert _value(_text(2, unit, per), _feature(unit)) != pytest.approx(joined)


@pytest.mark.parametrize(
    "text",
    [
        "a pole 2 m 30 cm long",  # the tail has its own unit: the grammar's SUB
        "a pole 2 m, 30 long",  # a comma: two statements
        "a pole 2.5 m 30 long",  # a first value not whole
        "a pole 2 cm 3 long",  # centimetres have no customary smaller unit here
    ],
)
def test_tail_not_joined(text):
    tree = parse(text).tree
    assert not list(tree.subtrees(lambda t: t.label() == "TAIL"))


@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=1, max_value=4), st.sampled_from(_TAILS), st.data())
def test_compound_equals_the_sum_of_its_parts(whole, spec, data):
    unit, factor, tail_factor, per = spec
    tail = data.draw(st.integers(min_value=1, max_value=per - 1))
    value = _value(_text(whole, unit, tail), _feature(unit))
    expected = whole * factor + tail * tail_factor
    assert value == pytest.approx(expected, rel=1e-4)


_FRACTIONS = [("half", 0.5), ("a half", 0.5), ("a quarter", 0.25), ("three quarters of", 0.75), ("a third of", 1 / 3),
              ("1/2", 0.5), ("\u00bd", 0.5), ("one and a half", 1.5)]  # fmt: skip
_SCALES = [("a hundred", 100), ("a thousand", 1000), ("a dozen", 12), ("hundred", 100), ("thousand", 1000)]


@pytest.mark.parametrize(
    ("text", "feature", "expected"),
    [
        ("half a million grams", "mass_g", 500_000.0),  # the limit itself: accepted
        ("a quarter million grams", "mass_g", 250_000.0),
        ("half a dozen centimetres long", "a_cm", 6.0),
        ("a third of a dozen cm long", "a_cm", 4.0),
        ("about half a thousand grams", "mass_g", 500.0),
        ("half a kilo", "mass_g", 500.0),  # a fraction of a unit: as before
        ("three quarters of a pound", "mass_g", 340.1943),
    ],
)
def test_fraction_word_scales_the_number(text, feature, expected):
    assert _value(text, feature) == pytest.approx(expected, rel=1e-4)


def test_fraction_of_past_the_limit_is_refused_with_its_own_words():
    p = parse("three quarters of a million kilograms")
    assert "mass_g" not in p.features
    assert [r.words for r in p.refused] == ["three quarters of a million kilograms"]
    assert "absurd" in p.refused[0].reason


def test_fraction_before_another_number_is_no_scale():
    """Only a scale word is scaled: "half a 2 kg bag" does not make a 1 kg one."""
    assert _value("half a 2 kg bag", "mass_g") != pytest.approx(1000.0)
    assert fraction_of(["half", "a", "2"]) is None
    assert fraction_of(["two", "million"]) is None  # no fraction: number_value's
    assert fraction_of(["half", "a", "million"]) == 500_000.0


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(_FRACTIONS), st.sampled_from(_SCALES), st.sampled_from([("g", "mass_g", 1.0), ("mm long", "a_cm", 0.1)]))
def test_a_fraction_word_scales(fraction, scale, unit):
    (fword, fvalue), (sword, svalue), (uword, feature, factor) = fraction, scale, unit
    if fword.endswith("of") and not sword.startswith("a "):
        sword = "a " + sword  # "three quarters of a thousand"
    value = _value(f"{fword} {sword} {uword}", feature)
    assert value == pytest.approx(fvalue * svalue * factor, rel=1e-4)
