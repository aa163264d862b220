"""The plans of :class:`recall.search.JPIndex` that read windows of rows from a packed row copy: the
**window** plan (the rows of the lead feature's window filtered by the product bound in growing chunks)
and the **ties at 0** (the k lowest row numbers at distance 0: the smallest zero window in row order, or a
row-order scan that stops at the k-th).

A mixin of the index (its columns, ``_window_rows``/``_window_size`` of
:class:`recall.columns.SortedColumns`, ``n``); the plan is chosen in :mod:`recall.search`.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
from recall.metrics import FeatureQuery
from recall.ranking import jp_scores, merge_top_k, survivors

__all__ = ["CHUNK", "MAX_CHUNK", "RECORD", "ZERO_SORT", "WindowPlans"]

#: Rows filtered per step of the window plan (the bound tightens between steps).
CHUNK = 1 << 14
MAX_CHUNK = 1 << 17
#: Zero windows up to this size are sorted into row order; larger ones are scanned in row order.
ZERO_SORT = 1 << 16

#: One row of :attr:`WindowPlans.records`.
RECORD = np.dtype(
    [(f, np.float32) for f in NUMERIC_FEATURES] + [(f, np.int8) for f in CATEGORICAL_FEATURES] + [("", "V3")]
)


class WindowPlans:
    """The window and zero-ties plans' methods and the packed rows they read (mixed into
    :class:`recall.search.JPIndex`)."""

    @cached_property
    def records(self) -> np.ndarray:
        """The columns packed row by row (24 B: 4 float32, 5 int8, padding), so that the plans reading
        scattered rows (windows) fetch one cache line per row, not one per column (measured: a take of
        50 000 scattered rows of 1M is ~5x faster than gathering the 9 columns)."""
        out = np.zeros(self.n, dtype=RECORD)
        for feat, col in zip(NUMERIC_FEATURES, self.num_cols, strict=True):
            out[feat] = col
        for feat, col in zip(CATEGORICAL_FEATURES, self.cat_cols, strict=True):
            out[feat] = col
        return out

    def _block(self, rows: np.ndarray) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """Columns (strided views) of ``rows`` taken from :attr:`records`."""
        block = self.records.take(rows)
        return [block[f] for f in NUMERIC_FEATURES], [block[f] for f in CATEGORICAL_FEATURES]

    def _window(self, query: FeatureQuery, items: list, lead: int, k: int, best_rows, best_scores):
        """Filter the rows of the lead feature's window in growing chunks (the bound tightens as better
        rows are found, so fewer of the later rows survive)."""
        s = float(best_scores[-1])
        source = self._window_rows(items[lead], s)
        order = [lead] + [i for i in range(len(items)) if i != lead]
        ordered = [items[i] for i in order]
        start, step = 0, CHUNK
        while start < len(source):
            chunk = source[start : start + step]
            num, cat = self._block(chunk)
            pos = survivors(ordered, num, cat, slice(0, len(chunk)), s)
            if len(pos):
                scores = jp_scores(num, cat, query, pos)
                best_rows, best_scores = merge_top_k(best_rows, best_scores, chunk[pos], scores, k)
                s = float(best_scores[-1])
            start, step = start + step, min(step * 2, MAX_CHUNK)
        return best_rows, best_scores

    def _zero_reads(self, items: list, k: int) -> tuple[float, int, bool]:
        """(rows the zero plan reads, the smallest window at 0, whether to read every row in row order):
        in row order until k rows at 0, estimated as if the features were independent, or the rows of
        the smallest window at 0 (sorted into row order up to ZERO_SORT numeric rows)."""
        sizes = [self._window_size(it, 0.0) for it in items]
        lead = min(range(len(items)), key=lambda i: sizes[i])
        zeros = self.n * math.prod(size / self.n for size in sizes)
        in_order = k * self.n / max(zeros, 1.0)
        if in_order < sizes[lead] or (items[lead][0] == "num" and sizes[lead] > ZERO_SORT):
            return in_order, lead, True
        return sizes[lead], lead, False

    def _zero_ties(self, query: FeatureQuery, items: list, k: int):
        """The k lowest rows at distance 0, given that at least k rows are at 0."""
        reads, lead, in_order = self._zero_reads(items, k)
        if in_order:
            return self._first_zeros(query, items, None, k, first=int(2 * reads))
        source = self._window_rows(items[lead], 0.0)
        if items[lead][0] == "num":
            source = np.sort(source)
        return self._first_zeros(query, items, source, k)

    def _first_zeros(self, query: FeatureQuery, items: list, source, k: int, first: int = CHUNK):
        """The first k rows of ``source`` (ascending; None: every row) at distance 0, read in chunks
        from ``first`` rows, doubling."""
        total = self.n if source is None else len(source)
        found, start, step = [], 0, max(64, min(first, CHUNK))
        while start < total and sum(len(f) for f in found) < k:
            stop = min(start + step, total)
            if source is None:
                rows = survivors(items, self.num_cols, self.cat_cols, slice(start, stop), 0.0)
                found.append(rows[self.score(query, rows) == 0.0])
            else:
                chunk = source[start:stop]
                num, cat = self._block(chunk)
                pos = survivors(items, num, cat, slice(0, len(chunk)), 0.0)
                found.append(chunk[pos[jp_scores(num, cat, query, pos) == 0.0]])
            start, step = stop, min(step * 2, MAX_CHUNK)
        rows = np.concatenate(found)[:k].astype(np.int64)
        return rows, np.zeros(len(rows))
