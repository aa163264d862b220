"""The confidence model (recall.confidence) and its constrained fit (recall.calibration.fit_confidence)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from recall.calibration import calibration, fit_confidence, pooled
from recall.confidence import (
    FEATURES_ONLY_CONFIDENCE,
    HYBRID_CONFIDENCE,
    UNKNOWN_NOUN_WEIGHT,
    capped_confidence,
    confidence_of,
)

MODES = (True, False)  # features only, hybrid


@pytest.mark.parametrize("model", [FEATURES_ONLY_CONFIDENCE, HYBRID_CONFIDENCE])
def test_the_fitted_weights_have_the_known_signs(model):
    assert model.margin >= 0 and model.closeness <= 0 and model.competitors <= 0 and model.tie_slope >= 1
    assert UNKNOWN_NOUN_WEIGHT < 0  # a rule, outside the fit


@pytest.mark.parametrize("features_only", MODES)
def test_a_tie_is_at_most_a_half_and_more_margin_more_confidence(features_only):
    def conf(m, **kw):
        return confidence_of(
            m, kw.get("c", 0.0), kw.get("u", False), "jplog", kw.get("k", 1.0), features_only
        )

    assert conf(0.0) <= 0.5
    values = [conf(m) for m in (0.0, 0.25, 0.5, 1.0, 2.0, 4.0)]
    assert values == sorted(values) and values[0] < values[-1]
    assert conf(4.0, c=0.2) < conf(4.0)  # a worse fit
    assert conf(4.0, k=6.0) < conf(4.0)  # a near tie of six
    assert conf(4.0, u=True) < conf(4.0)  # an unknown named noun


def test_the_hybrid_trusts_a_clear_margin_more_than_features_alone():
    # names make a given margin mean more (fitted): 2 nats, a close match, one clear first
    assert confidence_of(2.0, 0.02, False, "jplog", 1.1, False) > confidence_of(
        2.0, 0.02, False, "jplog", 1.1, True
    )


@pytest.mark.parametrize("features_only", MODES)
def test_vague_words_only_get_the_rankings_own_posterior(features_only):
    args = (0.05, 0.0, False, "jplog", 60.0, False, False, features_only)
    assert capped_confidence(*args, soft_only=True) <= 1 / 60
    assert capped_confidence(*args, soft_only=False) > 1 / 60
    clear = (6.0, 0.0, False, "jplog", 1.0, False, False, features_only)  # one candidate: the cap is 1
    assert capped_confidence(*clear, soft_only=True) == capped_confidence(*clear)


@pytest.mark.parametrize("features_only", MODES)
def test_open_set_and_not_in_catalog_caps(features_only):
    args = (6.0, 0.0, False, "jplog", 1.0)
    assert capped_confidence(*args, False, False, features_only) > 0.9
    assert capped_confidence(*args, True, False, features_only) == 0.5
    assert capped_confidence(*args, True, True, features_only) == 0.05


def _result(margin, closeness, unknown, competitors, open_set=False):
    matches = [SimpleNamespace(score=0.0), SimpleNamespace(score=margin)]
    return SimpleNamespace(
        matches=matches, closeness=closeness, unknown_noun="widget" if unknown else None,
        competitors=competitors, metric="jplog", open_set=open_set, not_in_catalog=False,
    )  # fmt: skip


def test_the_fit_keeps_the_signs_when_the_data_points_the_other_way():
    rng = np.random.default_rng(0)
    points = []
    for _ in range(300):
        m, c = float(rng.uniform(0, 4)), float(rng.uniform(0, 0.3))
        # right more often with a larger margin, and (perversely) with a worse closeness and an unknown noun
        p = 1 / (1 + math.exp(-(-1.0 + 1.5 * m + 8.0 * c)))
        unknown = bool(rng.uniform() < 0.2)
        points.append(
            (_result(m, c, unknown, 1.0 + float(rng.uniform(0, 2))), bool(rng.uniform() < p) or unknown)
        )
    model, n = fit_confidence(points)
    assert n == 300
    assert (
        model.margin >= 0.0 and model.closeness == 0.0 and model.competitors <= 0.0
    )  # held at 0, not flipped
    assert 1.0 <= model.tie_slope <= 5.0

    def fitted(m: float) -> float:  # the model's confidence at margin m, closeness 0, one candidate
        z = model.intercept + model.margin * m
        return min(1 / (1 + math.exp(-z)), 1 / (1 + math.exp(-model.tie_slope * m)))

    assert fitted(0.0) <= 0.5 < fitted(1.0) < fitted(3.0)  # the margin's real effect is found


def test_results_not_in_the_catalog_are_left_out_of_the_fit():
    points = [(_result(2.0, 0.0, False, 1.0), True), (_result(0.1, 0.2, False, 3.0), False)] * 5
    nic = _result(3.0, 0.0, True, 1.0)
    nic.not_in_catalog = True
    assert fit_confidence(points + [(nic, False)])[1] == 10


def test_pooled_calibration_is_the_calibration_of_the_union():
    a = ([0.05, 0.55, 0.95, 0.97], [False, True, True, True])
    b = ([0.15, 0.55, 0.65, 0.99, 1.0], [False, False, True, True, False])
    union = calibration(a[0] + b[0], a[1] + b[1])
    got = pooled([calibration(*a), calibration(*b)])
    assert got.n == union.n == 9
    assert got.brier == pytest.approx(union.brier) and got.ece == pytest.approx(union.ece)
    for g, u in zip(got.bins, union.bins, strict=True):
        assert (g.n, g.mean_confidence, g.accuracy) == pytest.approx((u.n, u.mean_confidence, u.accuracy))
    assert pooled([]).n == 0
