"""Amounts stated without a number (recall/quantities_unnumbered.py): refused with the reason, not dropped
silently."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from recall.parser import parse
from recall.quantities_unnumbered import NONFINITE_REASON, VAGUE_REASON


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("NaN cm long stick", "NaN cm"),
        ("a stick of nan kg", "nan kg"),
        ("-inf kg", "inf kg"),
        ("a stick inf kg", "inf kg"),
        ("a box of infinity grams", "infinity grams"),
    ],
)
def test_non_finite_word_before_a_unit_is_refused(text, words):
    p = parse(text)
    assert [(r.words, r.reason) for r in p.refused] == [(words, NONFINITE_REASON)]
    assert not {"a_cm", "b_cm", "c_cm", "mass_g"} & p.features.keys()


def test_non_finite_length_gives_no_long_shape():
    """"NaN cm long" states no length, so "long" is the refused value's dimension word, not a shape."""
    assert "shape" not in parse("NaN cm long").features
    assert parse("a long stick").features["shape"].value == "long"  # the shape word alone still is one


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("a few kilograms", "a few kilograms"),
        ("several inches long", "several inches"),
        ("many grams", "many grams"),
        ("some kilos of stuff", "some kilos"),
        ("a few cm long thing", "a few cm"),
        # before a scale word: not one hundred, one thousand
        ("a few hundred grams", "a few hundred grams"),
        ("several thousand grams", "several thousand grams"),
        ("a few hundred mm long", "a few hundred mm"),
    ],
)
def test_vague_count_is_refused(text, words):
    p = parse(text)
    assert [(r.words, r.reason) for r in p.refused] == [(words, VAGUE_REASON)]
    assert not {"a_cm", "b_cm", "c_cm", "mass_g"} & p.features.keys()


@pytest.mark.parametrize(
    ("text", "feature", "value"),
    [
        ("some 20 cm long", "a_cm", 20.0),  # a hedge before a number: about 20
        ("a few 10 cm long pieces", "a_cm", 10.0),  # a count of things, then their size
        ("a few 200 g weights", "mass_g", 200.0),
        ("a couple of kilos", "mass_g", 2000.0),  # a couple is two
        ("a hundred grams", "mass_g", 100.0),
    ],
)
def test_a_number_after_the_vague_word_is_read(text, feature, value):
    p = parse(text)
    assert p.features[feature].value == pytest.approx(value)
    assert not [r for r in p.refused if r.reason == VAGUE_REASON]


def test_common_word_units_are_not_taken():
    """"in" is a unit word and a preposition: "a few in the box" states nothing."""
    assert parse("a few in the box").refused == ()


@settings(max_examples=40, deadline=None)
@given(
    st.sampled_from(["nan", "NaN", "inf", "Inf", "infinity", "few", "several", "many"]),
    st.sampled_from(["cm", "mm", "inches", "kg", "grams", "pounds", "metres"]),
    st.sampled_from(["", "a stick of ", "it is "]),
)
def test_never_a_value_and_always_a_reason(word, unit, prefix):
    p = parse(f"{prefix}{word} {unit}")
    assert not {"a_cm", "b_cm", "c_cm", "mass_g"} & p.features.keys()
    assert [r.reason for r in p.refused] in ([NONFINITE_REASON], [VAGUE_REASON])
