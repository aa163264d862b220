"""Confidence: the calibrated probability that a recall's first match is the described object.

A logistic model per mode (:data:`FEATURES_ONLY_CONFIDENCE`, :data:`HYBRID_CONFIDENCE`; fitted with
constrained signs on the development sets, ``python -m recall.scoreboard --fit-confidence``) of the
ranking-score margin, the best match's closeness and the ranking's effective number of candidates
(:func:`competitors_of`), lowered by rule for an unknown subject noun (:data:`UNKNOWN_NOUN_WEIGHT`) and
capped by the ranking's own two-candidate posterior; open-set and "not in the catalog" results are
capped further by rule. Figures: ``recall/RECALL.md``, "Open set and confidence".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "COMPETITOR_POOL",
    "CONFIDENCE_COEF",
    "FEATURES_ONLY_CONFIDENCE",
    "HYBRID_CONFIDENCE",
    "UNKNOWN_NOUN_WEIGHT",
    "ConfidenceModel",
    "JP_METRICS",
    "MAX_LOOSE_FEATURES",
    "MAX_MARGIN",
    "NOT_IN_CATALOG_CONFIDENCE",
    "OPEN_SET_CONFIDENCE_CAP",
    "REFUSED_CONFIDENCE_CAP",
    "capped_confidence",
    "competitors_of",
    "confidence_from_margin",
    "confidence_of",
]

#: Confidence = min(σ(a + b * margin + c * closeness + d * unknown_noun + e * ln competitors), σ(k * margin)):
#: margin = second-best minus best ranking score (nats, capped at MAX_MARGIN), closeness the best match's
#: mean relative error, unknown_noun 1 when the subject is a noun the catalog does not know, competitors
#: the ranking's effective number of candidates (1 / its softmax posterior of the first) and k the
#: tie slope (:class:`ConfidenceModel`). One model per mode (features only, hybrid): the hybrid's names
#: make a given margin mean more than the features' alone.


@dataclass(frozen=True)
class ConfidenceModel:
    """The fitted part of the confidence (``recall.calibration.fit_confidence``): intercept ``a``, the
    weights of margin (>= 0), closeness (<= 0) and ln competitors (<= 0), and the tie slope ``k`` (>= 1)
    of the cap σ(k · margin): a tie (margin 0) is at most 0.5 whatever the rest. The unknown noun's
    weight is not fitted (:data:`UNKNOWN_NOUN_WEIGHT`)."""

    intercept: float
    margin: float
    closeness: float
    competitors: float
    tie_slope: float = 1.0


#: Features only (``jp`` and the baselines): fitted on the development set and its open set (RECALL.md,
#: "Confidence: the ranking's own number of candidates"); a sign-constrained refit on the four
#: development sets did not lower the held-out ECE (0.079 -> 0.081-0.087), so these stay.
FEATURES_ONLY_CONFIDENCE = ConfidenceModel(3.69, 0.39, -10.54, -1.61, 1.0)
#: The hybrid (features + names): sign-constrained fit on the development sets dev, catalog2,
#: sparse_dev and blind_openset (RECALL.md, "Confidence refit per mode"); held-out Brier 0.034 -> 0.026,
#: ECE 0.043 -> 0.026 (hold-out, hold-out 2, blind_openset3, blind2_sparse, blind2_full).
HYBRID_CONFIDENCE = ConfidenceModel(2.77, 2.30, -7.52, -0.89, 3.21)
#: The weight of an unknown subject noun: a rule, kept outside the fit (a plain refit gives it +0.31, the
#: wrong sign: the open-set cap already absorbs most unknown nouns, leaving the few right ones in the fit).
#: The value of the last unconstrained fit on the development set (RECALL.md).
UNKNOWN_NOUN_WEIGHT = -1.73
#: (a, b, c, d, e) of the features-only model, d = :data:`UNKNOWN_NOUN_WEIGHT` (the old tuple's layout).
CONFIDENCE_COEF: tuple[float, float, float, float, float] = (
    FEATURES_ONLY_CONFIDENCE.intercept,
    FEATURES_ONLY_CONFIDENCE.margin,
    FEATURES_ONLY_CONFIDENCE.closeness,
    UNKNOWN_NOUN_WEIGHT,
    FEATURES_ONLY_CONFIDENCE.competitors,
)
MAX_MARGIN = 10.0
#: Candidates always scored, whatever ``top``, so that ``competitors`` (and the confidence) does not
#: depend on how many matches are shown.
COMPETITOR_POOL = 16
#: A description stating at most this many features and naming no object by a whole name or alias ("red",
#: "a red one", "something small and round") pins little down: its confidence is at most the ranking's own
#: posterior of the first, 1 / competitors (the number of catalog objects it leaves about tied; ``soft_only``
#: of :func:`capped_confidence`). 1 ("10 cm", "wooden": already at most 0.5 by the tie and open-set caps)
#: raised the development set's Brier 0.010 -> 0.014 (hybrid), so it stays 0 (RECALL.md).
MAX_LOOSE_FEATURES = 0
#: An open-set result's confidence is at most this.
OPEN_SET_CONFIDENCE_CAP = 0.5
#: ... and so is a result whose description states a value that is not used (refused as absurd, negative,
#: zero, or not read: "a 40 tonne mug", "a 10 cm mug of 40 blorps"): what it said was not all compared.
REFUSED_CONFIDENCE_CAP = 0.5
#: ... and a description naming a noun the catalog does not have at most this (its first match is the
#: physically closest object, never the described one; measured in RECALL.md).
NOT_IN_CATALOG_CONFIDENCE = 0.05
#: Metrics in nats (a name bonus can be subtracted; the margin is a log-likelihood ratio).
JP_METRICS = ("jp", "jplog")


def confidence_of(
    margin: float,
    closeness: float | None,
    unknown_noun: bool,
    metric: str = "jp",
    competitors: float = 1.0,
    features_only: bool = True,
) -> float:
    """The calibrated probability that the first match is the described object: the mode's
    :class:`ConfidenceModel` of the ranking-score margin (nats, capped at :data:`MAX_MARGIN`), the
    closeness, ln(``competitors``), the ranking's effective number of candidates (1 / its own posterior of
    the first: k near-tied objects give about k), plus :data:`UNKNOWN_NOUN_WEIGHT` for an unknown noun;
    never above σ(k · margin), so a tie is at most 0.5 (see RECALL.md)."""
    model = FEATURES_ONLY_CONFIDENCE if features_only else HYBRID_CONFIDENCE
    if metric not in JP_METRICS:  # the baselines' distances are on other scales: rescale the margin to nats
        margin = math.log1p(max(margin, 0.0))
    margin = min(max(margin, 0.0), MAX_MARGIN)
    z = (
        model.intercept
        + model.margin * margin
        + model.closeness * (closeness or 0.0)
        + UNKNOWN_NOUN_WEIGHT * float(unknown_noun)
        + model.competitors * math.log(max(competitors, 1.0))
    )
    return float(min(_sigmoid(z), _sigmoid(model.tie_slope * margin)))


def _sigmoid(z: float) -> float:
    return 1.0 / (1.0 + math.exp(-max(min(z, 50.0), -50.0)))


def confidence_from_margin(margin: float, metric: str = "jp") -> float:
    """The confidence of a result with this margin, a perfect closeness and a known subject."""
    return confidence_of(margin, 0.0, False, metric)


def competitors_of(score: np.ndarray) -> float:
    """The ranking's effective number of candidates: sum of exp(-(s - s_best)) over the candidates scored
    (nats), i.e. 1 / the softmax posterior of the best; k tied objects and nothing else give k. A lower
    bound when not every row was scored."""
    if len(score) < 2:
        return 1.0
    rel = np.asarray(score, dtype=np.float64) - float(np.min(score))
    return float(np.sum(np.exp(-np.minimum(rel, 50.0))))


def capped_confidence(
    margin: float,
    closeness: float | None,
    unknown_noun: bool,
    metric: str,
    competitors: float,
    open_set: bool,
    not_in_catalog: bool,
    features_only: bool = True,
    soft_only: bool = False,
    refused: bool = False,
) -> float:
    """:func:`confidence_of`, capped at :data:`OPEN_SET_CONFIDENCE_CAP` for an open-set result, at
    :data:`NOT_IN_CATALOG_CONFIDENCE` for a noun the catalog does not have and, when ``soft_only`` (at
    most :data:`MAX_LOOSE_FEATURES` stated feature and no whole name or alias named: "something small and
    round", "red", "10 cm"), at the ranking's own posterior of the first, 1 / ``competitors``: the
    fitted model has next to nothing of that kind to say about them; at :data:`REFUSED_CONFIDENCE_CAP`
    when ``refused`` (a stated value was not used)."""
    confidence = confidence_of(margin, closeness, unknown_noun, metric, competitors, features_only)
    if soft_only:
        confidence = min(confidence, 1.0 / max(competitors, 1.0))
    if refused:
        confidence = min(confidence, REFUSED_CONFIDENCE_CAP)
    if open_set:
        confidence = min(confidence, OPEN_SET_CONFIDENCE_CAP)
    if not_in_catalog:
        confidence = min(confidence, NOT_IN_CATALOG_CONFIDENCE)
    return confidence
