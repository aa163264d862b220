"""Confidence: the calibrated probability that a recall's first match is the described object.

A logistic model (:data:`CONFIDENCE_COEF`, fitted on the development sets by
``python -m recall.evaluation --fit``) of the ranking-score margin, the best match's closeness, whether
the subject is an unknown noun and the ranking's effective number of candidates
(:func:`competitors`), capped by the ranking's own two-candidate posterior; open-set and "not in the
catalog" results are capped further by rule. Figures: ``recall/RECALL.md``, "Open set and confidence".
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "COMPETITOR_POOL",
    "CONFIDENCE_COEF",
    "JP_METRICS",
    "MAX_MARGIN",
    "NOT_IN_CATALOG_CONFIDENCE",
    "OPEN_SET_CONFIDENCE_CAP",
    "capped_confidence",
    "competitors_of",
    "confidence_from_margin",
    "confidence_of",
]

#: Confidence = 1 / (1 + exp(-(a + b * margin + c * closeness + d * unknown_noun + e * ln competitors))):
#: margin = second-best minus best ranking score (nats, capped at MAX_MARGIN), closeness the best match's
#: mean relative error, unknown_noun 1 when the subject is a noun the catalog does not know, competitors
#: the ranking's effective number of candidates (1 / its softmax posterior of the first). Fitted by logistic regression on
#: the development set and its open set (``python -m recall.evaluation --fit``; RECALL.md).
CONFIDENCE_COEF: tuple[float, float, float, float, float] = (3.69, 0.39, -10.54, -1.73, -1.61)
MAX_MARGIN = 10.0
#: Candidates always scored, whatever ``top``, so that ``competitors`` (and the confidence) does not
#: depend on how many matches are shown.
COMPETITOR_POOL = 16
#: An open-set result's confidence is at most this.
OPEN_SET_CONFIDENCE_CAP = 0.5
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
) -> float:
    """The calibrated probability that the first match is the described object: a logistic model of the
    ranking-score margin (nats, capped at :data:`MAX_MARGIN`), the closeness, whether the subject is an
    unknown noun and ln(``competitors``), the ranking's effective number of candidates (1 / its own
    posterior of the first: k near-tied objects give about k; :data:`CONFIDENCE_COEF`, fitted on the
    development sets; see RECALL.md)."""
    a, b, c, d, e = CONFIDENCE_COEF
    if metric not in JP_METRICS:  # the baselines' distances are on other scales: rescale the margin to nats
        margin = math.log1p(max(margin, 0.0))
    margin = min(max(margin, 0.0), MAX_MARGIN)
    z = a + b * margin + c * (closeness or 0.0) + d * float(unknown_noun) + e * math.log(max(competitors, 1.0))
    # never above the two-candidate posterior of the ranking itself, e^m / (1 + e^m): a tie is at most 0.5
    return float(min(_sigmoid(z), _sigmoid(margin)))


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
) -> float:
    """:func:`confidence_of`, capped at :data:`OPEN_SET_CONFIDENCE_CAP` for an open-set result and at
    :data:`NOT_IN_CATALOG_CONFIDENCE` for a noun the catalog does not have."""
    confidence = confidence_of(margin, closeness, unknown_noun, metric, competitors)
    if open_set:
        confidence = min(confidence, OPEN_SET_CONFIDENCE_CAP)
    if not_in_catalog:
        confidence = min(confidence, NOT_IN_CATALOG_CONFIDENCE)
    return confidence
