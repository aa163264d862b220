"""A negated value ("a mug, not 10 cm") is not stated; a negated bound flips ("not over 10 cm" is at most
10); the rule's reach (recall/PARSER.md, "Negated values")."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from recall.parser import parse

approx = pytest.approx
NEGATED = "negated: the description says it is not this value"


@pytest.mark.parametrize(
    "text",
    [
        "a mug, not 10 cm",
        "a mug, not 10 cm long",
        "a mug that is not 10 cm tall",
        "the length is not 10 cm",
        "it isn't about 10 cm long",
        "it is not really 10 cm",  # one gap word
        "it is not the 10 cm one",  # BE words between
        "not 10 x 5 x 2 cm",
        "not between 3 and 4 cm long",
        "never 10 cm long",
        "a bag, no 10 cm",
    ],
)
def test_a_negated_length_is_not_stated_and_is_listed_as_refused(text: str) -> None:
    parsed = parse(text)
    assert not {"a_cm", "b_cm", "c_cm"} & set(parsed.features), parsed.values()
    assert [r.reason for r in parsed.refused] == [NEGATED]


@pytest.mark.parametrize(
    ("text", "grams"),
    [
        ("it weighs not 300 g but 500 g", 500),
        ("it does not weigh 300 g, it weighs 500 g", 500),
        ("it doesn't weigh 300 g; 500 g", 500),
        ("without the 200 g lid, 500 g", 500),
    ],
)
def test_the_value_not_negated_is_the_one_read(text: str, grams: float) -> None:
    assert parse(text).values()["mass_g"] == approx(grams)


def test_negated_contents_give_no_lower_bound() -> None:
    assert "mass_g" not in parse("a bottle, not filled with 500 ml of water").features
    assert parse("a bottle filled with 500 ml of water").features["mass_g"].qualifier == "at_least"


@pytest.mark.parametrize(
    ("text", "qualifier", "low", "high"),
    [
        ("not over 10 cm", "at_most", None, 10),
        ("it isn't more than 10 cm long", "at_most", None, 10),
        ("never longer than 10 cm", "at_most", None, 10),
        ("not under 10 cm", "at_least", 10, None),
        ("it isn't less than 10 cm", "at_least", 10, None),
        ("not exactly 10 cm", "about", None, None),
        ("not quite 10 cm long", "about", None, None),
        ("it is not even 10 cm long", "at_most", None, 10),
        # merged hedges read as before
        ("not more than 10 cm", "at_most", None, 10),
        ("no less than 10 cm", "at_least", 10, None),
    ],
)
def test_a_negated_hedge_changes_the_qualifier(text: str, qualifier: str, low, high) -> None:
    ev = parse(text).features["a_cm"]
    assert (ev.value, ev.qualifier, ev.low, ev.high) == (approx(10), qualifier, low, high)


@pytest.mark.parametrize(
    "text",
    [
        "not fragile, 10 cm long",  # a comma ends the negation
        "not plastic and 10 cm long",  # so does any other word between
        "a mug not made of glass 10 cm tall",
        "not only 10 cm long",
        "hardly 10 cm long",  # barely 10 cm: stated
        "10 cm long, not heavy",  # a negation after the value
        "it is not, I think, 10 cm",
    ],
)
def test_a_negation_out_of_reach_leaves_the_value(text: str) -> None:
    assert parse(text).values()["a_cm"] == approx(10), text


def test_three_gap_words_are_out_of_reach_two_are_not() -> None:
    assert "mass_g" not in parse("it does not really weigh 300 g").features  # two gaps
    assert parse("it does not actually really weigh 300 g").values()["mass_g"] == approx(300)  # three


def test_a_negated_dimension_is_not_a_long_shape() -> None:
    assert "shape" not in parse("a thing, not 10 cm long").features
    assert parse("a long thing, not 10 cm").values()["shape"] == "long"


@settings(max_examples=80, deadline=None)
@given(
    st.integers(1, 400),
    st.integers(1, 400),
    st.sampled_from(["not", "isn't", "never", "not really", "does not measure"]),
    st.sampled_from(["{v} cm long", "{v} cm tall", "{v} cm", "about {v} cm wide", "{v} x {v} cm"]),
)
def test_only_the_value_not_negated_is_kept(told: int, negated: int, neg: str, form: str) -> None:
    """Whatever the numbers, a negated value is never read and the other one always is."""
    stated, wrong = told / 10, negated / 10
    text = f"a thing {neg} {form.format(v=f'{wrong:g}')}, but {stated:g} cm long"
    got = parse(text).values()
    assert got.get("a_cm") == approx(stated), text
    assert got.get("b_cm") is None and got.get("c_cm") is None, text
