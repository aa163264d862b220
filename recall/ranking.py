"""Scoring and ranking primitives shared by every search plan (``recall.search``, ``recall.cells``,
``recall.combinations``): one float64 JP routine, so that all plans and the brute force give the same
distances bit for bit, and the top-k selection with ties broken by row number.

Two helpers give the product form used to *filter* before scoring: argmin Σ log(1 + d_j) =
argmin Π (1 + d_j). :func:`factors` computes a feature's ``1 + d`` in float32 (NaN = unknown counts as the
unknown penalty, or as 1 when ``optimistic``); products of up to 9 float32 factors are within
:data:`FILTER_SLACK` of the exact ones, so a filter ``Π ≤ e^S · (1 + FILTER_SLACK)`` never drops a row
whose exact distance is ≤ S.
"""

from __future__ import annotations

import functools

import numpy as np

from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
from recall.metrics import CATEGORY_CODES, MISMATCH_TERM, UNKNOWN_CATEGORY_TERM, FeatureQuery

__all__ = ["FILTER_SLACK", "factors", "jp_scores", "merge_top_k", "select_top_k", "survivors"]

NUM_INDEX = {f: j for j, f in enumerate(NUMERIC_FEATURES)}
CAT_INDEX = {f: j for j, f in enumerate(CATEGORICAL_FEATURES)}
#: Relative slack of a float32 product filter: 3 roundings of 2^-24 per factor, 9 factors, times 20.
FILTER_SLACK = 1e-5


@functools.cache
def category_terms(feature: str, value: str) -> np.ndarray:
    """JP term by (code + 1): index 0 is an unknown category (-1). Read-only, built once."""
    table = np.full(len(CATEGORY_CODES[feature]) + 1, MISMATCH_TERM)
    table[0] = UNKNOWN_CATEGORY_TERM
    table[CATEGORY_CODES[feature][value] + 1] = 0.0
    table.flags.writeable = False
    return table


@functools.cache
def byte_table(feature: str, value: str, factor: bool) -> np.ndarray:
    """The term (float64) or factor e^term (float32: 1, 2, 4, exact) of a category indexed by the code's
    byte (0..127 codes, 255 = unknown -1), so that int8 codes index it without a conversion."""
    terms = category_terms(feature, value)
    table = np.zeros(256)
    table[: len(terms) - 1] = terms[1:]
    table[255] = terms[0]
    table = np.exp(table).round().astype(np.float32) if factor else table
    table.flags.writeable = False
    return table


def _category_lookup(feature: str, value: str, codes: np.ndarray, factor: bool) -> np.ndarray:
    return byte_table(feature, value, factor).take(codes.view(np.uint8))  # (take: half a [] gather's time)


def jp_scores(num_cols, cat_cols, query: FeatureQuery, rows=None, wide=None) -> np.ndarray:
    """JP distance of ``rows`` (an index array, a slice, or all when None) of float32 / int8 columns,
    in float64, summed in the query's order (numeric terms, then categorical ones). ``wide``: the
    numeric columns already in float64 and their unknown rows (:class:`WideColumns`; every row)."""
    total = None
    for cond in query.numeric:
        j = NUM_INDEX[cond.feature]
        if wide is not None:
            term = wide.term(cond, j)
        else:
            x = (num_cols[j] if rows is None else num_cols[j][rows]).astype(np.float64)
            term = np.log1p(cond.differences(x))
        total = term if total is None else np.add(total, term, out=total)
    for feat, value in query.categorical:
        if wide is not None:
            term = byte_table(feat, value, False).take(wide.codes[CAT_INDEX[feat]])
        else:
            col = cat_cols[CAT_INDEX[feat]]
            term = _category_lookup(feat, value, col if rows is None else col[rows], factor=False)
        total = term if total is None else np.add(total, term, out=total)
    if total is None:
        size = len(num_cols[0]) if rows is None else len(np.arange(len(num_cols[0]))[rows])
        return np.zeros(size)
    return total


class WideColumns:
    """Numeric columns in float64 with their unknown rows (~8 B per value) and the category codes as
    indices (8 B per value), for scoring every row of a
    small catalog without converting them at each query (the same float64 values: exact)."""

    def __init__(self, num_cols, cat_cols):
        self.codes = [c.view(np.uint8).astype(np.intp) for c in cat_cols]  # byte_table's index (0.4 µs less)
        self.values = [c.astype(np.float64) for c in num_cols]
        self.unknown = [np.isnan(c).nonzero()[0] for c in self.values]  # rows (a set by index: 0.4 µs
        # less than a masked copy at 1k rows)

    def term(self, cond, j: int) -> np.ndarray:
        """``log1p(cond.differences(...))`` of column ``j``, computed in place in one new array (the
        same operations on the same values as :meth:`recall.metrics.NumericCondition.differences`, so
        the same float64 terms: |x - v| for a point, max(low - x, x - high, 0) otherwise, the unknown
        rows set to the penalty)."""
        x = self.values[j]
        if cond.low == cond.high:
            d = np.subtract(x, cond.low)
            np.abs(d, out=d)
        else:
            d = np.subtract(cond.low, x)
            np.maximum(d, np.subtract(x, cond.high), out=d)
            np.maximum(d, 0.0, out=d)
        d[self.unknown[j]] = cond.unknown_difference
        return np.log1p(d, out=d)

    @property
    def nbytes(self) -> int:
        return int(sum(a.nbytes for a in (*self.values, *self.unknown, *self.codes)))


def factors(item, num_cols, cat_cols, rows=None, optimistic: bool = False) -> np.ndarray:
    """``1 + d`` of one stated feature (``("num", condition)`` or ``("cat", (feature, value))``) for
    ``rows`` (index array, slice or None), float32. ``optimistic``: an unknown numeric value counts 1 (a
    lower bound), else its penalty (the exact factor, within rounding)."""
    kind, obj = item
    if kind == "cat":
        feat, value = obj
        codes = cat_cols[CAT_INDEX[feat]]
        codes = codes if rows is None else codes[rows]
        return _category_lookup(feat, value, codes, factor=True)
    col = num_cols[NUM_INDEX[obj.feature]]
    x = col if rows is None else col[rows]
    low, high = np.float32(obj.low), np.float32(obj.high)
    if float(low) != obj.low or float(high) != obj.high:  # bounds not held in float32 (not from FeatureQuery): float64
        x, low, high = x.astype(np.float64), obj.low, obj.high
    d = np.maximum(low - x, x - high)
    np.fmax(d, 0.0, out=d)  # NaN (unknown) -> 0
    d += 1.0
    if not optimistic:
        np.copyto(d, 1.0 + obj.unknown_difference, where=np.isnan(x))
    return d


def survivors(items, num_cols, cat_cols, rows, s: float) -> np.ndarray:
    """Of ``rows`` (an index array, or a slice whose rows are returned as indices), those whose product
    Π (1 + d_j) can be <= e^s (unknown numeric values optimistic): factors multiplied in the order of
    ``items``, rows dropped as soon as the bound is passed."""
    bound = np.float32(np.exp(s) * (1.0 + FILTER_SLACK))
    prod = None
    for item in items:
        f = factors(item, num_cols, cat_cols, rows, optimistic=True)
        prod = f if prod is None else np.multiply(prod, f, out=f)
        keep = prod <= bound
        rows = keep.nonzero()[0] + rows.start if isinstance(rows, slice) else rows[keep]
        prod = prod[keep]
        if not len(rows):
            break
    return rows


def select_top_k(rows: np.ndarray | None, scores: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The k smallest (score, row) pairs, ordered by score then row number (``rows`` None: the rows
    are 0..n-1, the scores of every row)."""
    if len(scores) > k:
        kth = np.partition(scores, k - 1)[k - 1]
        keep = (scores <= kth).nonzero()[0]  # (np.flatnonzero: +0.7 µs of Python)
        if len(keep) > k:  # more rows at the k-th distance than needed: the lowest row numbers win
            below, tied = keep[scores[keep] < kth], keep[scores[keep] == kth]
            need = k - len(below)
            tied = tied[:need] if rows is None else tied[np.argpartition(rows[tied], need - 1)[:need]]
            keep = np.concatenate((below, tied))
        scores = scores[keep]
        if rows is None:  # keep ascends (or below, then tied, each ascending): a stable sort breaks ties
            order = np.argsort(scores, kind="stable")  # by row, as the lexsort below (fewer calls)
            return keep[order].astype(np.int64, copy=False), scores[order]
        rows = rows[keep]
    elif rows is None:
        rows = np.arange(len(scores))
    order = np.lexsort((rows, scores))[:k]
    return rows[order].astype(np.int64), scores[order]


def merge_top_k(rows_a, scores_a, rows_b, scores_b, k: int):
    """Top-k of two scored row sets that may share rows."""
    rows, first = np.unique(np.concatenate((rows_a, rows_b)), return_index=True)
    return select_top_k(rows, np.concatenate((scores_a, scores_b))[first], k)
