"""How well an open-set score separates objects not in the catalog from objects in it, as the field
reports it: AUROC and the false-flag rate at 95 % of unknown objects flagged (FPR95).

Scores are :attr:`recall.fit.Fit.score` (above 1: "not in the catalog"; larger: farther from a fit).
``unknown`` are the scores of descriptions of objects the catalog lacks (positives), ``known`` those of
objects it holds (negatives). Both functions are pure and need at least one score on each side.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from kb.errors import RecallError

__all__ = ["auroc", "fpr_at_tpr"]


def _sides(unknown: Sequence[float], known: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    pos, neg = np.asarray(unknown, dtype=float), np.asarray(known, dtype=float)
    if pos.size == 0 or neg.size == 0:
        raise RecallError("open-set scores need at least one unknown and one known description")
    if np.isnan(pos).any() or np.isnan(neg).any():
        raise RecallError("an open-set score is NaN")
    return pos, neg


def auroc(unknown: Sequence[float], known: Sequence[float]) -> float:
    """The probability that an unknown object's score is above a known one's (ties count one half):
    1.0 separates perfectly, 0.5 is chance."""
    pos, neg = _sides(unknown, known)
    greater = (pos[:, None] > neg[None, :]).sum()
    ties = (pos[:, None] == neg[None, :]).sum()
    return float((greater + 0.5 * ties) / (pos.size * neg.size))


def fpr_at_tpr(unknown: Sequence[float], known: Sequence[float], tpr: float = 0.95) -> float:
    """The share of known objects flagged when the threshold is the highest that still flags at least
    ``tpr`` of the unknown ones (flagged: score at or above the threshold)."""
    if not 0.0 < tpr <= 1.0:
        raise RecallError(f"tpr must be in (0, 1], not {tpr}")
    pos, neg = _sides(unknown, known)
    ranked = np.sort(pos)[::-1]
    need = int(np.ceil(tpr * pos.size - 1e-9))
    threshold = ranked[need - 1]
    return float((neg >= threshold).mean())
