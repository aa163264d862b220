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

import functools
import math

import numpy as np

from recall.metrics import CATEGORY_CODES, FeatureQuery
from recall.ranking import CAT_INDEX, FILTER_SLACK, NUM_INDEX, jp_scores, merge_top_k, survivors

__all__ = ["CellIndex"]

#: Objects per cell the split aims at.
CELL_ROWS = 64
#: Split order; a parent is split into about (rows / rows per cell)^(1 / levels left) parts, at most
#: MAX_SPLIT; rows per cell are CELL_ROWS, or more above 2^MAX_BITS cells.
CELL_ORDER = ("a_cm", "mass_g", "b_cm", "c_cm")
MAX_BITS = 16
MAX_SPLIT = 256
#: Rows scored per step of the best-first search (the bound tightens between steps).
CELL_BATCH = 4096
MAX_BATCH = 32768


class CellIndex:
    """The cells of one snapshot's columns (see the module docstring)."""

    def __init__(self, num_cols: list[np.ndarray], cat_cols: list[np.ndarray], groups: np.ndarray | None = None):
        n = len(num_cols[0])
        per_cell = max(CELL_ROWS, n >> MAX_BITS)
        cell = np.zeros(n, dtype=np.int64) if groups is None else groups.astype(np.int64)
        for depth, feat in enumerate(CELL_ORDER):
            col = num_cols[NUM_INDEX[feat]]
            order = np.lexsort((col, cell))  # NaN sorts last within the cell
            sorted_cell = cell[order]
            starts = np.searchsorted(sorted_cell, sorted_cell, "left")
            size = np.searchsorted(sorted_cell, sorted_cell, "right") - starts
            left = len(CELL_ORDER) - depth
            split = np.ceil(size / per_cell) if left == 1 else np.rint((size / per_cell) ** (1.0 / left))
            split = np.clip(split, 1, MAX_SPLIT)
            part = ((np.arange(n) - starts) * split.astype(np.int64)) // size
            new = np.empty(n, dtype=np.int64)
            new[order] = sorted_cell * MAX_SPLIT + part
            cell = new
        perm = np.argsort(cell, kind="stable")
        ids, first = np.unique(cell[perm], return_index=True)
        self.perm = perm.astype(np.int32)
        self.starts = np.append(first, n).astype(np.int64)
        m = len(ids)
        self.num_cols = [np.ascontiguousarray(c[perm]) for c in num_cols]
        self.cat_cols = [np.ascontiguousarray(c[perm]) for c in cat_cols]
        self.sizes = np.diff(self.starts)
        self.cmin = np.empty((len(self.num_cols), m), dtype=np.float32)
        self.cmax = np.empty((len(self.num_cols), m), dtype=np.float32)
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
        arrays = [self.perm, self.starts, self.sizes, self.cmin, self.cmax, self.cnan, self.present]
        return int(sum(a.nbytes for a in (*arrays, *self.num_cols, *self.cat_cols)))

    def bounds(self, query: FeatureQuery) -> np.ndarray:
        """A lower bound of Π (1 + d_j) over the rows of each cell (float32, the product form of the JP
        distance: a cell can hold a row at distance <= s only if its bound is <= e^s · (1 + FILTER_SLACK)).

        float32 rounding is monotone and the query's ends are widened to float32 outwards, so a cell's
        bound never exceeds the float32 product that :func:`recall.ranking.survivors` computes for its
        rows; no logarithm is taken (it cost ~20 ns per cell)."""
        m = self.cmin.shape[1]
        prod = None
        for cond in query.numeric:
            j = NUM_INDEX[cond.feature]
            low, high = _outward(cond.low, -np.inf), _outward(cond.high, np.inf)
            gap = np.subtract(low, self.cmax[j]) if math.isfinite(low) else np.full(m, -np.inf, np.float32)
            if math.isfinite(high):
                np.maximum(gap, self.cmin[j] - high, out=gap)
            np.maximum(gap, np.float32(0.0), out=gap)  # a cell with no known value: gap = inf
            gap += np.float32(1.0)
            np.minimum(gap, np.float32(1.0 + cond.unknown_difference), out=gap, where=self.cnan[j])
            prod = gap if prod is None else np.multiply(prod, gap, out=prod)
        for feat, value in query.categorical:
            f = _present_factors(feat, value).take(self.present[CAT_INDEX[feat]])
            prod = f if prod is None else np.multiply(prod, f, out=prod)
        return np.ones(m, dtype=np.float32) if prod is None else prod

    def rows_within(self, lb: np.ndarray, s: float) -> int:
        """Rows of the cells whose bound allows a distance <= s: at most what a search with bound s scores."""
        return int(self.sizes[lb <= _limit(s)].sum())

    def probe(self, query: FeatureQuery, k: int, best_rows, best_scores, lb: np.ndarray, rows: int):
        """Merge into a top-k the rows of the cells with the smallest bounds, about ``rows`` of them (all
        scored: a first bound, not the answer)."""
        cells = max(1, min(len(lb), -(-rows // CELL_ROWS)))
        pick = np.argpartition(lb, cells - 1)[:cells] if cells < len(lb) else np.arange(len(lb))
        pos = self._positions(pick)
        scores = jp_scores(self.num_cols, self.cat_cols, query, pos)
        return merge_top_k(best_rows, best_scores, self.perm[pos].astype(np.int64), scores, k)

    def _positions(self, cells: np.ndarray) -> np.ndarray:
        """Positions (in the cell-sorted columns) of the rows of ``cells``."""
        starts, sizes = self.starts[cells], self.sizes[cells]
        if len(cells) == 1:
            return np.arange(starts[0], starts[0] + sizes[0])
        return np.repeat(starts - np.concatenate(([0], np.cumsum(sizes)[:-1])), sizes) + np.arange(sizes.sum())

    def top_k(
        self,
        query: FeatureQuery,
        k: int,
        best_rows: np.ndarray,
        best_scores: np.ndarray,
        lb: np.ndarray | None = None,
        items: list | None = None,
        give_up: float | None = None,
    ):
        """Improve a top-k (rows, scores) whose k-th score bounds the answer (none: every cell), visiting
        the cells within the bound best first, in batches of CELL_BATCH / 4 rows growing to MAX_BATCH
        (the bound tightens between batches). ``items``: the stated features in the order to filter
        by (the most selective first; default the query's order). ``give_up`` (rows): None when, once
        a quarter of that many rows are read, the rows read and those of the cells left within the
        bound are still more (the caller then scans)."""
        lb = self.bounds(query) if lb is None else lb
        if items is None:
            items = [("num", c) for c in query.numeric] + [("cat", c) for c in query.categorical]
        s = float(best_scores[-1]) if len(best_scores) >= k else math.inf
        order = np.flatnonzero(lb <= _limit(s)) if math.isfinite(s) else np.arange(len(lb))
        order = order[np.argsort(lb[order])]  # not stable: ~6x faster, and any order of equal bounds is exact
        ends = np.cumsum(self.sizes[order])
        sorted_lb = lb[order] if give_up is not None else None
        i, budget = 0, CELL_BATCH // 4
        while i < len(order):
            done = int(ends[i - 1]) if i else 0
            limit = _limit(s)
            if sorted_lb is not None and 4 * done >= give_up:  # a quarter done: is the whole still more?
                if int(ends[int(np.searchsorted(sorted_lb, limit, "right")) - 1]) > give_up:
                    return None
            j = max(i + 1, int(np.searchsorted(ends, done + budget, "right")))
            batch = order[i:j]
            i, budget = j, min(max(budget * 2, CELL_BATCH), MAX_BATCH)
            if lb[batch[0]] > limit:
                break
            pos = self._positions(batch[lb[batch] <= limit])
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


@functools.cache
def _present_factors(feature: str, value: str) -> np.ndarray:
    """The bound factor (e^term: 1, 2, 4, exact) of a cell by its set of codes present (bit c + 1 for
    code c, bit 0 unknown): 1 when it holds the value, else 2 when it holds an unknown, else 4; one
    gather per stated category (at most 2^9 sets: the widest feature has 8 values)."""
    sets = np.arange(1 << (len(CATEGORY_CODES[feature]) + 1))
    bit = 1 << (CATEGORY_CODES[feature][value] + 1)
    table = np.where(sets & bit, 1.0, np.where(sets & 1, 2.0, 4.0)).astype(np.float32)
    table.flags.writeable = False
    return table


def _outward(x: float, toward: float) -> np.float32:
    """``x`` in float32, rounded away from the interval's inside (toward ``toward``) when not exact."""
    y = np.float32(x) if math.isfinite(x) else np.float32(toward)
    if math.isfinite(x) and float(y) != x and (float(y) > x) == (toward < 0):
        y = np.nextafter(y, np.float32(toward))
    return y


def _limit(s: float) -> np.float32:
    """The largest cell bound that can hold a row at distance <= s (as in ``survivors``)."""
    return np.float32(math.exp(s) * (1.0 + FILTER_SLACK)) if math.isfinite(s) else np.float32(np.inf)
