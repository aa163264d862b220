"""The fit rule (recall.fit.judge): one rule for the open-set verdict and the store lookup, pinned at
each threshold and each condition on its own."""

import pytest

from recall.fit import DISAGREE_FACTOR, THRESHOLDS, Trust, disagreeing_features, judge
from recall.metrics import relative_errors


@pytest.mark.parametrize("trust", [Trust.NAMED, Trust.PLAIN, Trust.DOUBTED])
def test_closeness_at_the_threshold_fits_and_just_above_does_not(trust):
    t = THRESHOLDS[trust]
    at = judge(t, {"a_cm": t}, trust)
    above = judge(t + 1e-6, {"a_cm": t + 1e-6}, trust)
    assert at.close and at.score == pytest.approx(1.0)
    assert not above.close and above.score > 1.0
    assert "fits" in at.reason and "does not fit" in above.reason and f"{t:.2f}" in above.reason


def test_thresholds_are_ordered_by_trust():
    assert THRESHOLDS[Trust.NAMED] > THRESHOLDS[Trust.PLAIN] > THRESHOLDS[Trust.DOUBTED]
    assert THRESHOLDS[Trust.FOREIGN] is None


def test_a_foreign_noun_never_fits_and_scores_above_every_misfit():
    fit = judge(0.0, {}, Trust.FOREIGN, noun="walkie talkie")
    assert not fit.close and "walkie talkie" in fit.reason
    far = judge(1.0, {"mass_g": 0.999}, Trust.PLAIN)
    assert fit.score > far.score


def test_a_feature_off_by_the_factor_disagrees_whatever_the_mean():
    limit = 1.0 - 1.0 / DISAGREE_FACTOR  # 4x off: d / max(v, x) = 0.75
    assert disagreeing_features({"mass_g": limit}) == ("mass_g",)
    assert disagreeing_features({"mass_g": limit - 1e-3}) == ()
    fit = judge(0.1, {"mass_g": limit, "a_cm": 0.0}, Trust.NAMED)  # mean well under every threshold
    assert not fit.close and "mass 4x off" in fit.reason and fit.score > 1.0
    assert judge(0.1, {"mass_g": limit - 1e-3, "a_cm": 0.0}, Trust.NAMED).close


def test_categorical_errors_never_disagree():
    assert disagreeing_features({"material": 1.0}) == ()


def test_refused_values_leave_nothing_to_compare():
    fit = judge(0.0, {}, Trust.PLAIN, unused=("56 kg",))
    assert not fit.close and "'56 kg'" in fit.reason and fit.score >= 2.0


def test_nothing_stated_is_a_fit_unless_foreign():
    assert judge(None, {}, Trust.PLAIN).close
    assert not judge(None, {}, Trust.FOREIGN).close


def test_lookup_and_open_set_share_the_threshold():
    from recall.lookup import FIT_CLOSENESS
    from recall.openset import OPEN_SET_NAMED_THRESHOLD, OPEN_SET_THRESHOLD, OPEN_SET_UNKNOWN_NOUN_THRESHOLD

    assert FIT_CLOSENESS == OPEN_SET_THRESHOLD == THRESHOLDS[Trust.PLAIN]
    assert OPEN_SET_NAMED_THRESHOLD == THRESHOLDS[Trust.NAMED]
    assert OPEN_SET_UNKNOWN_NOUN_THRESHOLD == THRESHOLDS[Trust.DOUBTED]


def _errors(stated_cm: float, catalog_cm: float, floors=None):
    import numpy as np

    from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
    from recall.metrics import FeatureQuery

    num = np.full(len(NUMERIC_FEATURES), np.nan)
    num[NUMERIC_FEATURES.index("a_cm")] = catalog_cm
    cat = np.full(len(CATEGORICAL_FEATURES), -1)
    query = FeatureQuery.from_values({"a_cm": stated_cm})
    return relative_errors(num, cat, query, floors)["a_cm"]


def test_a_floor_makes_the_catalog_value_a_lower_bound():
    floors = {"a_cm": 15.0}
    assert _errors(40.0, 15.0, floors) == 0.0  # "15 cm or more": 40 cm agrees
    assert _errors(10.0, 15.0, floors) == pytest.approx(5 / 15)  # below the floor still differs
    assert _errors(40.0, 14.99, floors) == pytest.approx((40 - 14.99) / 40)  # under the floor: a value
    assert _errors(40.0, 15.0) == pytest.approx(25 / 40)  # no floor: a value
