"""Cells of neighbouring catalog objects, for a best-first exact JP search when no single column window
is small (``recall.search`` chooses the plan).

The catalog is split by quantiles of the largest extent, then mass, middle and smallest extent, each
within its parent cell, into about one cell per :data:`CELL_ROWS` objects (at most 2^16 cells). A cell
keeps its value ranges and the categories it holds, which give a cheap lower bound of the JP distance of
every row in it (the distance from the description to the ranges; 0 / log 2 / 2 log 2 for a category
the cell holds / holds unknown / lacks). Cells are visited in order of that bound, their rows filtered by
the product bound and the survivors scored, until the next bound exceeds the k-th best distance.
Rows of a cell are contiguous in copies of the columns sorted by cell.
"""

from __future__ import annotations

import math

import numpy as np

from recall.metrics import CATEGORY_CODES, MISMATCH_TERM, UNKNOWN_CATEGORY_TERM, FeatureQuery
from recall.ranking import CAT_INDEX, NUM_INDEX, jp_scores, merge_top_k, survivors

__all__ = ["CellIndex", "cell_levels"]

#: Objects per cell the split aims at.
CELL_ROWS = 64
#: Split order and the most bits of the cell number each level may take (2^16 cells at most).
CELL_ORDER = ("a_cm", "mass_g", "b_cm", "c_cm")
MAX_BITS = 16
#: Rows scored per step of the best-first search (the bound tightens between steps).
CELL_BATCH = 4096


def cell_levels(n: int) -> tuple[tuple[str, int], ...]:
    """(feature, parts) of each split for a catalog of ``n`` objects: bits dealt round-robin."""
    bits = max(2, min(MAX_BITS, int(math.log2(max(n, 1) / CELL_ROWS) + 0.5)))
    per = [0] * len(CELL_ORDER)
    for i in range(bits):
        per[i % len(CELL_ORDER)] += 1
    return tuple((f, 1 << b) for f, b in zip(CELL_ORDER, per, strict=True) if b)


class CellIndex:
    """The cells of one snapshot's columns (see the module docstring)."""

    def __init__(self, num_cols: list[np.ndarray], cat_cols: list[np.ndarray]):
        n = len(num_cols[0])
        cell = np.zeros(n, dtype=np.int64)
        for feat, split in cell_levels(n):
            col = num_cols[NUM_INDEX[feat]]
            order = np.lexsort((col, cell))  # NaN sorts last within the cell
            sorted_cell = cell[order]
            starts = np.searchsorted(sorted_cell, sorted_cell, "left")
            ends = np.searchsorted(sorted_cell, sorted_cell, "right")
            part = ((np.arange(n) - starts) * split) // np.maximum(ends - starts, 1)
            new = np.empty(n, dtype=np.int64)
            new[order] = sorted_cell * split + part
            cell = new
        perm = np.argsort(cell, kind="stable")
        ids, first = np.unique(cell[perm], return_index=True)
        self.perm = perm.astype(np.int32)
        self.starts = np.append(first, n).astype(np.int64)
        m = len(ids)
        self.num_cols = [np.ascontiguousarray(c[perm]) for c in num_cols]
        self.cat_cols = [np.ascontiguousarray(c[perm]) for c in cat_cols]
        self.cmin = np.empty((len(self.num_cols), m))
        self.cmax = np.empty((len(self.num_cols), m))
        self.cnan = np.empty((len(self.num_cols), m), dtype=bool)
        with np.errstate(invalid="ignore"):
            for j, col in enumerate(self.num_cols):
                missing = np.isnan(col)
                self.cmin[j] = np.minimum.reduceat(np.where(missing, np.inf, col), first)
                self.cmax[j] = np.maximum.reduceat(np.where(missing, -np.inf, col), first)
                self.cnan[j] = np.logical_or.reduceat(missing, first)
        self.present = np.empty((len(self.cat_cols), m), dtype=np.uint16)
        for j, col in enumerate(self.cat_cols):
            bits = (np.uint16(1) << (col.astype(np.uint16) + 1).astype(np.uint16)).astype(np.uint16)
            self.present[j] = np.bitwise_or.reduceat(bits, first)

    @property
    def nbytes(self) -> int:
        arrays = [self.perm, self.starts, self.cmin, self.cmax, self.cnan, self.present]
        return int(sum(a.nbytes for a in (*arrays, *self.num_cols, *self.cat_cols)))

    def bounds(self, query: FeatureQuery) -> np.ndarray:
        """A lower bound of the JP distance of the rows of each cell."""
        lb = np.zeros(self.cmin.shape[1])
        with np.errstate(invalid="ignore"):
            for cond in query.numeric:
                j = NUM_INDEX[cond.feature]
                gap = np.maximum(np.maximum(cond.low - self.cmax[j], self.cmin[j] - cond.high), 0.0)
                term = np.log1p(gap)  # a cell with no known value: gap = inf
                term = np.where(self.cnan[j], np.minimum(term, math.log1p(cond.unknown_difference)), term)
                lb += term
        for feat, value in query.categorical:
            j = CAT_INDEX[feat]
            bit = np.uint16(1 << (CATEGORY_CODES[feat][value] + 1))
            has = (self.present[j] & bit) != 0
            unknown = (self.present[j] & np.uint16(1)) != 0
            lb += np.where(has, 0.0, np.where(unknown, UNKNOWN_CATEGORY_TERM, MISMATCH_TERM))
        return lb

    def rows_within(self, lb: np.ndarray, s: float) -> int:
        """Rows of the cells whose bound is <= s: at most what a search with bound s scores."""
        inside = lb <= s + 1e-12
        return int(((self.starts[1:] - self.starts[:-1]) * inside).sum())

    def top_k(
        self,
        query: FeatureQuery,
        k: int,
        best_rows: np.ndarray,
        best_scores: np.ndarray,
        lb: np.ndarray | None = None,
        stop_at_zero: bool = False,
        max_rows: int | None = None,
    ):
        """Improve a top-k (rows, scores) whose k-th score bounds the answer, visiting cells best first.
        ``stop_at_zero``: return as soon as the k-th best is 0 (the caller settles ties at 0);
        ``max_rows``: return after about this many rows (a probe for a better bound, not the answer)."""
        lb = self.bounds(query) if lb is None else lb
        items = [("num", c) for c in query.numeric] + [("cat", c) for c in query.categorical]
        s = float(best_scores[-1]) if len(best_scores) >= k else math.inf
        order = np.flatnonzero(lb <= s + 1e-12) if math.isfinite(s) else np.arange(len(lb))
        order = order[np.argsort(lb[order], kind="stable")]
        ends = np.cumsum(self.starts[order + 1] - self.starts[order])
        i, budget = 0, min(CELL_BATCH // 4, max_rows or CELL_BATCH)
        while i < len(order) and not (stop_at_zero and s == 0.0):
            if max_rows is not None and i and ends[i - 1] >= max_rows:
                break
            j = max(i + 1, int(np.searchsorted(ends, (ends[i - 1] if i else 0) + budget, "right")))
            batch = order[i:j]
            i, budget = j, CELL_BATCH
            if lb[batch[0]] > s + 1e-12:
                break
            batch = batch[lb[batch] <= s + 1e-12]
            starts, stops = self.starts[batch], self.starts[batch + 1]
            sizes = stops - starts
            pos = np.repeat(starts - np.concatenate(([0], np.cumsum(sizes)[:-1])), sizes) + np.arange(
                sizes.sum()
            )
            if math.isfinite(s):
                pos = survivors(items, self.num_cols, self.cat_cols, pos, s)
            scores = jp_scores(self.num_cols, self.cat_cols, query, pos)
            keep = scores <= s + 1e-12 if math.isfinite(s) else np.ones(len(scores), dtype=bool)
            if keep.any():
                rows = self.perm[pos[keep]].astype(np.int64)
                best_rows, best_scores = merge_top_k(best_rows, best_scores, rows, scores[keep], k)
                if len(best_scores) >= k:
                    s = float(best_scores[-1])
        return best_rows, best_scores
