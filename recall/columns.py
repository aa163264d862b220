"""The catalog's columns sorted by value (numeric) and grouped by code (categories), for the plans of
``recall.search`` that read windows of rows: the rows whose term of one stated feature can be <= s.

Numeric columns are argsorted stably with NaN (unknown) last, so that rows of equal value are in
ascending row order; a category's rows are ascending too.
"""

from __future__ import annotations

import bisect
import math
import sys
from functools import cached_property

import numpy as np

from kb.features import CATEGORICAL_FEATURES
from recall.metrics import CATEGORY_CODES, MISMATCH_TERM, UNKNOWN_CATEGORY_TERM
from recall.ranking import CAT_INDEX, NUM_INDEX, jp_scores, select_top_k

__all__ = ["SortedColumns", "radius"]

#: Catalogs up to this size keep their sorted values as Python lists too (:attr:`SortedColumns._key_lists`:
#: 32 B a value, 128 KB at 1 024 rows), and read one number off them (:meth:`SortedColumns._one_listed`)
#: when at most LISTED_INSIDE rows are in its interval (each costs a Python float operation).
LIST_BELOW = 1024
LISTED_INSIDE = 64


def radius(s: float) -> float:
    """Largest difference whose term can be <= s, widened a little against rounding."""
    return math.expm1(s) * (1.0 + 1e-9) + 1e-12


class SortedColumns:
    """Sorted orders and keys of the numeric columns, row lists of each category code."""

    def __init__(self, num_cols: list[np.ndarray], cat_cols: list[np.ndarray]):
        self.n = len(num_cols[0])
        self.num_order: list[np.ndarray] = []
        self.num_keys: list[np.ndarray] = []
        self.num_known: list[int] = []
        for col in num_cols:
            order = np.argsort(col, kind="stable").astype(np.int32)  # NaN (unknown) last
            self.num_order.append(order)
            self.num_keys.append(col[order])
            self.num_known.append(int(len(col) - np.isnan(col).sum()))
        self.cat_order: list[np.ndarray] = []
        self.cat_starts: list[np.ndarray] = []
        for feat, col in zip(CATEGORICAL_FEATURES, cat_cols, strict=True):
            self.cat_order.append(np.argsort(col, kind="stable").astype(np.int32))
            counts = np.bincount(col.astype(np.intp) + 1, minlength=len(CATEGORY_CODES[feat]) + 1)
            self.cat_starts.append(np.concatenate(([0], np.cumsum(counts))))

    @cached_property
    def _key_lists(self) -> list[list[float]]:
        """The known sorted values of each numeric column as Python floats (up to LIST_BELOW rows: two
        binary searches by :mod:`bisect` take ~0.3 µs, NumPy's ~1.5 µs, of a ~10 µs query at 1k)."""
        return [keys[:known].tolist() for keys, known in zip(self.num_keys, self.num_known, strict=True)]

    @cached_property
    def _order_lists(self) -> list[list[int]]:
        """:attr:`num_order` as Python lists (up to LIST_BELOW rows, as :attr:`_key_lists`)."""
        return [order.tolist() for order in self.num_order]

    def _one_listed(self, cond, k: int, start: int, end: int) -> tuple[np.ndarray, np.ndarray]:
        """Exact top-k of one numeric condition from the Python lists (up to LIST_BELOW rows; at 1k a
        NumPy pass over every row costs ~10 fixed calls, this ~3 and a few dozen float operations).

        The distance is V-shaped along the sorted column, so the k-th smallest difference D is among
        the rows in the interval, k on each side and the first k unknown rows; every row whose term
        can equal the k-th term has a difference within D (1 + 1e-9) (log1p of differences further
        apart differs), so those rows (walking outwards), with the first k unknown rows (later ones
        lose every tie to them), are scored exactly (the differences as NumPy computes them, the same
        IEEE operations; one log1p) and ranked by (term, row). ``start``, ``end``: the positions of
        the interval's rows (its ends rounded to float32)."""
        j = NUM_INDEX[cond.feature]
        keys, order = self._key_lists[j], self._order_lists[j]
        known, low, high = len(keys), cond.low, cond.high
        first, last = max(0, start - k), min(known, end + k)
        rows = order[first:last] + order[known : known + k]
        diff = [_difference(x, low, high) for x in keys[first:last]]
        diff += [cond.unknown_difference] * (len(rows) - len(diff))
        limit = sorted(diff)[k - 1] * (1.0 + 1e-9) + 1e-300 if len(diff) >= k else math.inf
        while first > 0 and _difference(keys[first - 1], low, high) <= limit:
            first -= 1
            diff.append(_difference(keys[first], low, high))
            rows.append(order[first])
        while last < known and _difference(keys[last], low, high) <= limit:
            diff.append(_difference(keys[last], low, high))
            rows.append(order[last])
            last += 1
        ranked = sorted(zip(np.log1p(np.array(diff)).tolist(), rows, strict=True))[:k]
        return np.array([r for _, r in ranked], dtype=np.int64), np.array([t for t, _ in ranked])

    @property
    def sorted_nbytes(self) -> int:
        """Bytes of the sorted arrays, and of the Python lists once built (their objects counted)."""
        arrays = [*self.num_order, *self.num_keys, *self.cat_order, *self.cat_starts]
        lists = [*self.__dict__.get("_key_lists", ()), *self.__dict__.get("_order_lists", ())]
        held = sum(sys.getsizeof(x) + sum(map(sys.getsizeof, x)) for x in lists)
        return int(sum(a.nbytes for a in arrays) + held)

    def _group(self, feat: str, code: int) -> np.ndarray:
        """Rows (ascending) whose code of ``feat`` is ``code`` (-1 = unknown)."""
        j = CAT_INDEX[feat]
        starts = self.cat_starts[j]
        return self.cat_order[j][starts[code + 1] : starts[code + 2]]

    def _numeric_window(self, cond, s: float) -> tuple[int, int, bool]:
        """Positions [start, end) among the known values of the sorted column of the rows whose term
        can be <= s, and whether the unknown rows (at the end of the order) can be too."""
        j = NUM_INDEX[cond.feature]
        r = radius(s) if s > 0.0 else 0.0
        keys = self.num_keys[j][: self.num_known[j]]
        lo = np.float32(cond.low - r) if math.isfinite(cond.low - r) else np.float32(-np.inf)
        hi = np.float32(cond.high + r) if math.isfinite(cond.high + r) else np.float32(np.inf)
        start = int(np.searchsorted(keys, lo, "left"))
        end = int(np.searchsorted(keys, hi, "right"))
        return start, end, math.log1p(cond.unknown_difference) <= s + 1e-12

    def _window_size(self, item, s: float) -> int:
        kind, obj = item
        if kind == "num":
            start, end, unknown = self._numeric_window(obj, s)
            return end - start + (self.n - self.num_known[NUM_INDEX[obj.feature]] if unknown else 0)
        feat, value = obj
        if MISMATCH_TERM <= s + 1e-12:
            return self.n
        size = len(self._group(feat, CATEGORY_CODES[feat][value]))
        if UNKNOWN_CATEGORY_TERM <= s + 1e-12:
            size += len(self._group(feat, -1))
        return size

    def _window_rows(self, item, s: float) -> np.ndarray:
        kind, obj = item
        if kind == "num":
            j = NUM_INDEX[obj.feature]
            start, end, unknown = self._numeric_window(obj, s)
            order, known = self.num_order[j], self.num_known[j]
            if not unknown:
                return order[start:end]
            return order[start:] if end == known else np.concatenate((order[start:end], order[known:]))
        feat, value = obj
        if MISMATCH_TERM <= s + 1e-12:
            return np.arange(self.n, dtype=np.int32)
        rows = self._group(feat, CATEGORY_CODES[feat][value])
        if UNKNOWN_CATEGORY_TERM <= s + 1e-12:
            rows = np.concatenate((rows, self._group(feat, -1)))
        return rows

    def _nearest(self, item, m: int) -> np.ndarray:
        """About ``m`` rows nearest the description in one column (both sides of the stated interval)."""
        kind, obj = item
        if kind == "cat":
            feat, value = obj
            return self._group(feat, CATEGORY_CODES[feat][value])[:m]
        j = NUM_INDEX[obj.feature]
        keys, order, known = self.num_keys[j][: self.num_known[j]], self.num_order[j], self.num_known[j]
        lo = np.float32(obj.low) if math.isfinite(obj.low) else np.float32(-np.inf)
        hi = np.float32(obj.high) if math.isfinite(obj.high) else np.float32(np.inf)
        start = int(np.searchsorted(keys, lo, "left"))
        end = int(np.searchsorted(keys, hi, "right"))
        half = max(1, m // 2)
        if end - start <= m:
            return order[max(0, start - half) : min(end + half, known)]
        return np.concatenate(
            (order[max(0, start - half) : start + half], order[max(0, end - half) : min(end + half, known)])
        )

    def one_column(self, num_cols, cat_cols, query, k: int, most: int = 4096, general: bool = True):
        """Exact top-k (rows, distances) of a description that states one number and nothing else, read
        off its sorted column; None when more than ``most`` rows of several values are in the stated
        interval or a tie at the k-th distance spans two values beyond the rows read (the caller then
        takes another plan). At least k rows in the interval (its ends exact in float32, as a
        FeatureQuery's are) are at distance 0: the k lowest of them (the first k of one value).

        The distance is V-shaped along the sorted column (falling to the interval, 0 in it, rising
        after), so the k positions on each side of the interval, the rows in it and the first k unknown
        rows hold every row closer than the k-th best S of them; rows at exactly S can lie beyond, in the
        run of the value at either end (rows of one value are in ascending row order) or among the
        unknown rows (ascending too): the lowest of each are enough. ``general`` False: only the
        cheap cases (k rows in the interval; up to LIST_BELOW rows, :meth:`_one_listed`), else None."""
        (cond,) = query.numeric
        j = NUM_INDEX[cond.feature]
        order, known = self.num_order[j], self.num_known[j]
        lo, hi = float(np.float32(cond.low)), float(np.float32(cond.high))  # (infinite ends stay infinite)
        if self.n <= LIST_BELOW:  # the same positions (float32 values compared exactly as floats)
            keys = self._key_lists[j]
            start, end = bisect.bisect_left(keys, lo), bisect.bisect_right(keys, hi)
        else:
            keys = self.num_keys[j][:known]
            start = int(np.searchsorted(keys, np.float32(lo)))
            end = int(np.searchsorted(keys, np.float32(hi), "right"))
        if end - start >= k and lo == cond.low and hi == cond.high and cond.unknown_difference > 0.0:
            # k rows in it, all at 0 (and unknown rows not at 0: a stated 0 charges them 0)
            inside, one_value = order[start:end], keys[start] == keys[end - 1]
            if one_value:  # rows of one value are in ascending order
                return inside[:k].astype(np.int64), np.zeros(k)
            if end - start > most:
                return None
            return np.sort(np.partition(inside, k - 1)[:k]).astype(np.int64), np.zeros(k)
        if self.n <= LIST_BELOW and end - start <= LISTED_INSIDE:
            return self._one_listed(cond, k, start, end)
        if end - start > most or not general:
            return None
        keys = self.num_keys[j][:known]
        c0, c1 = max(0, start - k), min(known, end + k)
        rows = np.concatenate((order[c0:c1], order[known : known + k]))
        scores = jp_scores(num_cols, cat_cols, query, rows)
        s = np.partition(scores, k - 1)[k - 1]
        parts = [rows[scores == s]]
        if c0 > 0 and c1 > c0 and scores[0] == s:  # the run of the value at the left end may go on
            a = int(np.searchsorted(keys, keys[c0], "left"))
            if a > 0 and jp_scores(num_cols, cat_cols, query, order[a - 1 : a])[0] == s:
                return None
            parts.append(order[a:c0][:k])
        if c1 < known and c1 > c0 and scores[c1 - c0 - 1] == s:
            b = int(np.searchsorted(keys, keys[c1 - 1], "right"))
            if b < known and jp_scores(num_cols, cat_cols, query, order[b : b + 1])[0] == s:
                return None
            parts.append(order[c1:b][:k])
        if known + k < self.n and scores[-1] == s and len(rows) > c1 - c0:  # unknown rows at s
            parts.append(order[known + k : known + 2 * k])
        below = rows[scores < s]
        tied = np.unique(np.concatenate(parts))[: k - len(below)]
        return select_top_k(np.concatenate((below, tied)), np.concatenate((scores[scores < s], np.full(len(tied), s))), k)


def _difference(x: float, low: float, high: float) -> float:
    """:meth:`recall.metrics.NumericCondition.differences` of one known value, in Python floats (the
    same IEEE double operations: |x - v| for a point, else max(low - x, x - high, 0), zero as +0)."""
    if low == high:
        return abs(x - low)
    return max(low - x, x - high, 0.0) or 0.0
