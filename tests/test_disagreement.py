"""A stated feature far from the named match's (blind-test findings): "a tennis ball 6.4 cm 56 kg" (the mass
1000x off) was a close match at confidence 1.00, and "a ball 10 m wide" (its only value refused) a "close
match (mean relative error 0.00)"."""

from __future__ import annotations

import pytest
from recallers import seed

from recall.openset import DISAGREE_FACTOR, disagreeing_features, nothing_compared
from recall.parser import RefusedQuantity
from recall.verdict import verdict

LIMIT = 1 - 1 / DISAGREE_FACTOR


@pytest.mark.parametrize(
    ("errors", "expected"),
    [
        ({"mass_g": 0.999, "a_cm": 0.0}, ("mass_g",)),
        ({"mass_g": LIMIT}, ("mass_g",)),  # exactly DISAGREE_FACTOR off
        ({"mass_g": LIMIT - 0.01}, ()),  # a little less
        ({"a_cm": 0.9, "c_cm": 0.8, "b_cm": 0.1}, ("a_cm", "c_cm")),  # in feature order
        ({"mass_g": 1 / 3}, ()),  # an unknown catalog value counts 1/3: never a disagreement
        ({"material": 1.0, "shape": 1.0}, ()),  # categories are the open-set rule's, not this one's
    ],
)
def test_disagreeing_features_each_condition(errors, expected):
    assert disagreeing_features(errors) == expected


def test_nothing_compared_each_condition():
    absurd = RefusedQuantity("10 m", 7, 11, "1000 cm: absurd for a household object (over 500 cm)")
    negated = RefusedQuantity("10 cm", 11, 16, "negated: the description says it is not this value")
    assert nothing_compared((absurd,), numeric_stated=False) == ("10 m",)
    assert nothing_compared((absurd,), numeric_stated=True) == ()  # another value is left to compare
    assert nothing_compared((negated,), numeric_stated=False) == ()  # a negated value was never stated
    assert nothing_compared((), numeric_stated=False) == ()


def test_a_mass_1000x_off_is_not_a_close_match_and_the_verdict_says_which_feature():
    result = seed().recall_text("a tennis ball 6.4 cm 56 kg")
    assert result.matches[0].name == "tennis ball"
    assert result.disagrees == ("mass_g",)
    assert result.open_set and result.confidence <= 0.5
    said = verdict(result)
    assert said.label == "not a close match"
    assert "mass" in said.text and "1000x" in said.text and "56 g" in said.text


def test_the_same_ball_with_its_own_mass_is_a_close_match():
    result = seed().recall_text("a tennis ball 6.4 cm 56 g")
    assert result.disagrees == () and not result.open_set and result.confidence > 0.9
    assert verdict(result).label == "close match"


@pytest.mark.parametrize("text", ["a ball 10 m wide", "a tennis ball 10 m wide"])
def test_when_every_stated_value_is_refused_the_verdict_claims_no_close_match(text):
    result = seed().recall_text(text)
    assert result.unused == ("10 m",)
    said = verdict(result)
    assert said.label != "close match" and "close match (" not in said.text
    assert "mean relative error" not in said.text and "'10 m' refused" in said.text


def test_a_negated_value_leaves_the_close_match():
    result = seed().recall_text("a mug, not 10 cm")
    assert result.unused == () and verdict(result).label == "close match"
