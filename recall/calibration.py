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


# ---------------------------------------------------------------------- fitting the confidence model
def confidence_inputs(result) -> list[float]:
    """The confidence model's inputs of a result: margin (capped), closeness, unknown noun (0/1)."""
    from recall.confidence import MAX_MARGIN

    margin = result.matches[1].score - result.matches[0].score if len(result.matches) > 1 else MAX_MARGIN
    return [
        min(max(margin, 0.0), MAX_MARGIN),
        result.closeness or 0.0,
        float(result.unknown_noun is not None),
        math.log(max(result.competitors, 1.0)),
    ]


def fit_confidence(cases, open_set=()) -> tuple[tuple[float, ...], int]:
    """Logistic fit of P(first match right) on :func:`confidence_inputs`, over the features-only and the
    hybrid results of the development set (``cases``: :class:`recall.evaluation.Case` s) and the results of the open set (never right). Returns the
    coefficients (a, b, c, d, e) of ``recall.confidence.CONFIDENCE_COEF`` and the number of points.
    Results reported not in the catalog are left out: their confidence is capped by rule."""
    from sklearn.linear_model import LogisticRegression

    x, y = [], []
    for case in cases:
        for res in (case.features_only, case.hybrid):
            if res.matches and not res.not_in_catalog:  # those are capped by rule, not by the model
                x.append(confidence_inputs(res))
                y.append(int(res.matches[0].name == case.object))
    for res in open_set:
        if res.matches and not res.not_in_catalog:
            x.append(confidence_inputs(res))
            y.append(0)
    model = LogisticRegression(C=10.0).fit(np.array(x), np.array(y))
    return (float(model.intercept_[0]), *(float(c) for c in model.coef_[0])), len(x)
