"""The shape class from stated dimensions: when a description gives all three extents, the catalog's own
objects of those proportions say which of the paper's shape classes it is, and that beats a shape word.

The catalog's classes follow geometry (a can is ``compact``, a bottle ``prism``, a rod ``long``), while
people name shapes loosely ("a round wooden disc", "a metal block"). :class:`ShapeGeometry` places every
catalog object with three known extents and a known shape at (ln a/b, ln b/c), and classifies a
description's extents by its ``K`` nearest objects there; only a clear vote (at least ``MIN_VOTES`` of
``K``) counts. Proportions alone cannot tell a ball from a cube (both near (0, 0)): the geometry
overrides a word only with a proportion class (``thin``, ``long``, ``prism``) and never a ``radial``
word (roundness is no proportion; :func:`overrides`). Measured in ``recall/RECALL.md``.
"""

from __future__ import annotations

from collections import Counter

import numpy as np

from kb.features import CATEGORICAL_FEATURES, CATEGORIES

__all__ = ["K", "MIN_VOTES", "ShapeGeometry", "overrides"]

K = 7
MIN_VOTES = 6


class ShapeGeometry:
    """The shape classes of the catalog's proportions (see the module docstring)."""

    def __init__(self, num: np.ndarray, shape_codes: np.ndarray):
        a, b, c = (np.asarray(num[:, j], dtype=np.float64) for j in range(3))
        ok = np.isfinite(a) & np.isfinite(b) & np.isfinite(c) & (c > 0) & (shape_codes >= 0)
        self.points = np.stack([np.log(a[ok] / b[ok]), np.log(b[ok] / c[ok])], axis=1)
        names = CATEGORIES["shape"]
        self.labels = [names[int(s)] for s in shape_codes[ok]]

    @classmethod
    def of_snapshot(cls, snapshot) -> ShapeGeometry:
        num = np.stack([np.asarray(snapshot.num_cols[j]) for j in range(3)], axis=1)
        return cls(num, np.asarray(snapshot.cat_cols[CATEGORICAL_FEATURES.index("shape")]))

    def classify(self, a: float, b: float, c: float) -> str | None:
        """The shape class of extents a >= b >= c > 0 when the nearest catalog objects agree, else None."""
        if len(self.labels) < K or not (a >= b >= c > 0):
            return None
        x = np.array([np.log(a / b), np.log(b / c)])
        nearest = np.argsort(np.sum((self.points - x) ** 2, axis=1), kind="stable")[:K]
        label, votes = Counter(self.labels[i] for i in nearest).most_common(1)[0]
        return label if votes >= MIN_VOTES else None


#: The classes proportions decide (flat, elongated, in between); radial and compact need roundness.
PROPORTION_CLASSES = frozenset({"thin", "long", "prism"})


def overrides(geometric: str, worded: str) -> bool:
    """Whether the geometric class replaces the shape word's class."""
    return geometric in PROPORTION_CLASSES and worded != "radial"
