"""Exact top-k for descriptions that state categories only, through the catalog's category combinations.

With only categories stated, a row's JP distance depends on its combination of category codes alone
(5 features, 4 320 combinations with "unknown"). The rows are kept grouped by combination (one int32
permutation, rows ascending within a group): a query scores the combinations, not the rows, takes whole
groups in order of distance and, at the k-th distance, the lowest row numbers of the groups tied there,
which is the brute force's order (distance, then row). About 0.1 ms at any catalog size.
"""

from __future__ import annotations

import math

import numpy as np

from kb.features import CATEGORICAL_FEATURES, CATEGORIES
from recall.metrics import FeatureQuery
from recall.ranking import CAT_INDEX, category_terms, select_top_k

__all__ = ["CombinationIndex"]

_WIDTHS = [len(CATEGORIES[f]) + 1 for f in CATEGORICAL_FEATURES]


class CombinationIndex:
    """Rows grouped by their combination of category codes."""

    def __init__(self, cat_cols: list[np.ndarray]):
        key = np.zeros(len(cat_cols[0]), dtype=np.int32)
        for col, width in zip(cat_cols, _WIDTHS, strict=True):
            key *= width
            key += col.astype(np.int32) + 1
        size = math.prod(_WIDTHS)
        self.perm = np.argsort(key, kind="stable").astype(np.int32)
        counts = np.bincount(key, minlength=size)
        self.starts = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
        used = np.flatnonzero(counts)
        self.used = used
        # the code (+1) of each feature in each used combination
        codes, rest = [], used.copy()
        for width in reversed(_WIDTHS):
            codes.append(rest % width)
            rest //= width
        self.codes = np.stack(codes[::-1]).astype(np.intp)  # (5, combinations used)

    @property
    def nbytes(self) -> int:
        return int(self.perm.nbytes + self.starts.nbytes + self.used.nbytes + self.codes.nbytes)

    def top_k(self, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Exact top-k (rows, distances) of a query with no numeric feature."""
        if query.numeric:
            raise ValueError("CombinationIndex answers category-only descriptions")
        score = None
        for feat, value in query.categorical:  # the same float64 sums, in the same order, as jp_scores
            term = category_terms(feat, value)[self.codes[CAT_INDEX[feat]]]
            score = term if score is None else np.add(score, term, out=score)
        if score is None:
            score = np.zeros(len(self.used))
        starts, stops = self.starts[self.used], self.starts[self.used + 1]
        order = np.argsort(score, kind="stable")
        total = np.cumsum(stops[order] - starts[order])
        kth = score[order[min(int(np.searchsorted(total, k)), len(order) - 1)]]
        groups = np.flatnonzero(score <= kth)
        # every row of the groups below the k-th distance, the first k rows of each group at it
        take = np.where(score[groups] < kth, stops[groups] - starts[groups], np.minimum(stops[groups] - starts[groups], k))
        first = starts[groups]
        pos = np.repeat(first - np.concatenate(([0], np.cumsum(take)[:-1])), take) + np.arange(take.sum())
        rows = self.perm[pos].astype(np.int64)
        return select_top_k(rows, np.repeat(score[groups], take), k)
