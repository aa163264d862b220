"""The scan plan of :class:`recall.search.JPIndex`: every row's product Π (1 + d_j) in float32 in few
passes, then the rows within the k-th product (widened by ``FILTER_SLACK``) scored exactly.

A mixin of the index (its columns ``num_cols``/``cat_cols``, sorted orders ``num_order``/``num_known``,
``combinations`` and ``n``); the plan is chosen in :mod:`recall.search`.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from kb.features import NUMERIC_FEATURES
from recall.metrics import FeatureQuery
from recall.ranking import (
    CAT_INDEX,
    FILTER_SLACK,
    NUM_INDEX,
    category_terms,
    factors,
    jp_scores,
    select_top_k,
)

__all__ = ["SAMPLE_PER_ROW_K", "ScanPlan"]

#: The scan's first bound: the k-th of a sample of SAMPLE_PER_ROW_K * sqrt(n k) rows (n k / sample
#: rows then pass it, ~sqrt(n k) / SAMPLE_PER_ROW_K: a few dozen to a few hundred).
SAMPLE_PER_ROW_K = 4.0


class ScanPlan:
    """The scan plan's methods (mixed into :class:`recall.search.JPIndex`)."""

    def _scan(self, query: FeatureQuery, items: list, k: int):
        """Every row's product Π (1 + d_j) in float32 (:meth:`products`); the rows within the k-th
        (widened) scored."""
        prod = self.products(query)
        return select_top_k(*self._within_kth(prod, k, query), k)

    def _within_kth(self, prod: np.ndarray, k: int, query: FeatureQuery):
        """The rows whose product is within the k-th smallest (widened by FILTER_SLACK) and their exact
        distances. The k-th of a strided sample of ~SAMPLE_PER_ROW_K * sqrt(n k) rows bounds the k-th
        from above (a selection over the sample, not over every row); should more than 32 k rows fall
        within it, the k-th among those (the true k-th: they hold every row below the bound) is taken."""
        slack = np.float32(1.0 + FILTER_SLACK)
        step = max(1, int(self.n / max(4 * k, SAMPLE_PER_ROW_K * math.sqrt(self.n * k))))
        sample = prod[::step]
        rows = (prod <= np.partition(sample, k - 1)[k - 1] * slack).nonzero()[0] if step > 1 else None
        if rows is None or len(rows) > 4 * k:
            within = prod if rows is None else prod[rows]
            keep = (within <= np.partition(within, k - 1)[k - 1] * slack).nonzero()[0]
            rows = keep if rows is None else rows[keep]
        num, cat = self._block(rows)  # one gather of the packed rows, not one per column
        return rows, jp_scores(num, cat, query)

    def products(self, query: FeatureQuery) -> np.ndarray:
        """Π (1 + d_j) of every row in float32, in as few passes as the mask allows (the scan's work;
        the same factors as :func:`recall.ranking.factors`, multiplied in another order, so within
        ``FILTER_SLACK`` of the exact product): a numeric feature's ``1 + d`` takes 3 passes for a
        point, 5 for an interval (no NaN-aware fmax: 5x slower than an add), then its unknown rows
        (the tail of its sorted order, ~3 %) are set to the unknown factor; every stated category
        together is one gather of a table over the category combinations (:attr:`combinations`),
        whose factors 1 / 2 / 4 are exact."""
        prod = None
        for cond in query.numeric:
            j = NUM_INDEX[cond.feature]
            d = _one_plus_distance(cond, self.num_cols[j])
            unknown = self.num_order[j][self.num_known[j] :]
            if len(unknown):
                d[unknown] = np.float32(1.0 + cond.unknown_difference)
            prod = d if prod is None else np.multiply(prod, d, out=prod)
        if query.categorical:
            comb = self.combinations
            table = None
            for feat, value in query.categorical:
                f = _category_factors(feat, value).take(comb.codes[CAT_INDEX[feat]])
                table = f if table is None else np.multiply(table, f, out=table)
            f = table.take(comb.group)
            prod = f if prod is None else np.multiply(prod, f, out=prod)
        return np.ones(self.n, dtype=np.float32) if prod is None else prod


_ONE = np.float32(1.0)


def _one_plus_distance(cond, x: np.ndarray) -> np.ndarray:
    """``1 + d`` of a numeric condition for a float32 column (a new array; NaN where unknown, or 1)."""
    low, high = np.float32(cond.low), np.float32(cond.high)
    if float(low) != cond.low or float(high) != cond.high:  # bounds not held in float32: float64
        d = factors(("num", cond), [x] * len(NUMERIC_FEATURES), None, optimistic=True)
        return d.astype(np.float32) if d.dtype != np.float32 else d
    if cond.low == cond.high:
        d = np.subtract(x, low)
        np.abs(d, out=d)
        d += _ONE
        return d
    if math.isinf(cond.high):
        d = np.subtract(low, x)
    elif math.isinf(cond.low):
        d = np.subtract(x, high)
    else:
        d = np.subtract(low, x)
        np.maximum(d, np.subtract(x, high), out=d)
    d += _ONE
    return np.maximum(d, _ONE, out=d)  # inside the interval (1 + d < 1): 1


@functools.cache
def _category_factors(feature: str, value: str) -> np.ndarray:
    """e^term of a category by code + 1 (0 = unknown): 1, 2 or 4 (float32, exact)."""
    table = np.exp(category_terms(feature, value)).round().astype(np.float32)
    table.flags.writeable = False
    return table
