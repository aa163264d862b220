"""How honest a confidence is: Brier score, expected calibration error and a reliability plot.

Each point is a (confidence, right) pair: the confidence a result gave its first match, and whether that
match was the described object (an out-of-catalog description is never right). ``objrecall evaluate``
reports them per development set (``recall.evaluation``); definitions:

* Brier score: mean of (confidence − right)², 0 for perfect, 0.25 for always 0.5.
* ECE: the confidence range [0, 1] cut into ``bins`` equal bins; the mean over points of
  |accuracy of its bin − mean confidence of its bin| (weights = bin sizes).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

__all__ = [
    "Calibration",
    "ReliabilityBin",
    "brier_score",
    "calibration",
    "confidence_inputs",
    "expected_calibration_error",
    "fit_confidence",
    "pooled",
]


@dataclass(frozen=True)
class ReliabilityBin:
    low: float
    high: float
    n: int
    mean_confidence: float
    accuracy: float


@dataclass(frozen=True)
class Calibration:
    n: int
    brier: float
    ece: float
    bins: tuple[ReliabilityBin, ...]

    def to_dict(self) -> dict[str, object]:
        return {"n": self.n, "brier": self.brier, "ece": self.ece, "bins": [asdict(b) for b in self.bins]}

    def plot(self, width: int = 40) -> list[str]:
        """A text reliability plot: per non-empty bin, the accuracy bar (#) with the mean confidence
        marked (|), and the numbers."""
        lines = ["confidence    n   mean  accuracy"]
        for b in self.bins:
            if not b.n:
                continue
            bar = ["#" if i < round(b.accuracy * width) else " " for i in range(width)]
            mark = min(width - 1, int(b.mean_confidence * width))
            bar[mark] = "|"
            lines.append(
                f"{b.low:.1f}-{b.high:.1f} {b.n:5d}  {b.mean_confidence:.2f}  {b.accuracy:.2f}  {''.join(bar)}"
            )
        return lines


def _arrays(confidence: Sequence[float], right: Sequence[bool]) -> tuple[np.ndarray, np.ndarray]:
    c = np.asarray(confidence, dtype=np.float64)
    y = np.asarray(right, dtype=np.float64)
    if c.shape != y.shape:
        raise ValueError(f"{len(c)} confidences for {len(y)} outcomes")
    if np.any((c < 0) | (c > 1)) or not np.all(np.isfinite(c)):
        raise ValueError("confidences must lie in [0, 1]")
    return c, y


def brier_score(confidence: Sequence[float], right: Sequence[bool]) -> float:
    c, y = _arrays(confidence, right)
    return float(np.mean((c - y) ** 2)) if len(c) else 0.0


def _bin_index(c: np.ndarray, bins: int) -> np.ndarray:
    return np.minimum((c * bins).astype(np.int64), bins - 1)  # 1.0 falls in the last bin


def expected_calibration_error(confidence: Sequence[float], right: Sequence[bool], bins: int = 10) -> float:
    return calibration(confidence, right, bins).ece


def calibration(confidence: Sequence[float], right: Sequence[bool], bins: int = 10) -> Calibration:
    """Brier score, ECE and the reliability bins of the points (see the module docstring)."""
    if bins < 1:
        raise ValueError(f"bins must be at least 1, not {bins}")
    c, y = _arrays(confidence, right)
    n = len(c)
    idx = _bin_index(c, bins)
    out = []
    ece = 0.0
    for b in range(bins):
        sel = idx == b
        k = int(sel.sum())
        mean_c = float(c[sel].mean()) if k else 0.0
        acc = float(y[sel].mean()) if k else 0.0
        ece += k / n * abs(acc - mean_c) if n else 0.0
        out.append(ReliabilityBin(b / bins, (b + 1) / bins, k, mean_c, acc))
    return Calibration(n, brier_score(c, y), float(ece), tuple(out))


def pooled(calibrations: Sequence[Calibration]) -> Calibration:
    """The calibration of the union of the points of ``calibrations`` (all with the same bins): bin
    counts added, means weighted by them, Brier weighted by the point counts, ECE of the merged bins."""
    if not calibrations:
        return calibration([], [])
    n = sum(c.n for c in calibrations)
    bins = []
    for parts in zip(*(c.bins for c in calibrations), strict=True):
        k = sum(b.n for b in parts)
        mean_c = sum(b.n * b.mean_confidence for b in parts) / k if k else 0.0
        acc = sum(b.n * b.accuracy for b in parts) / k if k else 0.0
        bins.append(ReliabilityBin(parts[0].low, parts[0].high, k, mean_c, acc))
    brier = sum(c.n * c.brier for c in calibrations) / n if n else 0.0
    ece = sum(b.n / n * abs(b.accuracy - b.mean_confidence) for b in bins) if n else 0.0
    return Calibration(n, float(brier), float(ece), tuple(bins))


# ---------------------------------------------------------------------- fitting the confidence model
def confidence_inputs(result) -> list[float]:
    """The confidence model's inputs of a result: margin (capped; the baselines' rescaled to nats),
    closeness, unknown noun (0/1), ln competitors."""
    from recall.confidence import JP_METRICS, MAX_MARGIN

    margin = result.matches[1].score - result.matches[0].score if len(result.matches) > 1 else MAX_MARGIN
    if result.metric not in JP_METRICS:
        margin = math.log1p(max(margin, 0.0))
    return [
        min(max(margin, 0.0), MAX_MARGIN),
        result.closeness or 0.0,
        float(result.unknown_noun is not None),
        math.log(max(result.competitors, 1.0)),
    ]


def fit_confidence(points) -> tuple[object, int]:
    """The :class:`recall.confidence.ConfidenceModel` minimising the log loss of the *final* confidence
    (with its caps: σ(k · margin), the open-set cap) over ``points``, (result, right) pairs of one mode
    (results reported not in the catalog are left out: their confidence is a rule). Signs constrained:
    margin weight >= 0, closeness and ln-competitors weights <= 0, tie slope k in [1, 5]; the unknown
    noun's weight is the rule ``UNKNOWN_NOUN_WEIGHT``, not fitted. Returns the model and the number of
    points."""
    from scipy.optimize import minimize

    from recall.confidence import OPEN_SET_CONFIDENCE_CAP, UNKNOWN_NOUN_WEIGHT, ConfidenceModel

    kept = [(r, y) for r, y in points if r.matches and not r.not_in_catalog]
    x = np.array([confidence_inputs(r) for r, _ in kept])
    flagged = np.array([r.open_set for r, _ in kept])
    y = np.array([float(y) for _, y in kept])

    def loss(w: np.ndarray) -> float:
        z = w[0] + w[1] * x[:, 0] + w[2] * x[:, 1] + UNKNOWN_NOUN_WEIGHT * x[:, 2] + w[3] * x[:, 3]
        p = np.minimum(_logistic(z), _logistic(w[4] * x[:, 0]))
        p = np.clip(np.where(flagged, np.minimum(p, OPEN_SET_CONFIDENCE_CAP), p), 1e-6, 1 - 1e-6)
        return float(-np.mean(y * np.log(p) + (1 - y) * np.log(1 - p)) + 0.01 * np.sum(w[1:4] ** 2) / len(y))

    bounds = [(None, None), (0.0, None), (None, 0.0), (None, 0.0), (1.0, 5.0)]
    starts = ((3.69, 0.39, -10.54, -1.61, 1.0), (2.0, 0.5, -3.0, -1.0, 1.5), (1.0, 1.0, -5.0, -0.5, 2.0))
    fits = [minimize(loss, np.array(s), bounds=bounds, method="Powell") for s in starts]
    best = min(fits, key=lambda f: f.fun)
    return ConfidenceModel(*(round(float(v), 2) for v in best.x)), len(kept)


def _logistic(z: np.ndarray) -> np.ndarray:
    return 1.0 / (1.0 + np.exp(-np.clip(z, -50.0, 50.0)))
