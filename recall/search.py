"""Exact top-k search over a :class:`~recall.snapshot.CatalogSnapshot`.

:func:`brute_force_top_k` scores every row. :class:`JPIndex` returns the *same* answer for the Joint
Probability distance while scoring only a small part of the catalog:

* argmin Σ log(1 + d_j) = argmin Π (1 + d_j), and every term is >= 0, so a row can only score <= S if
  *each* stated feature has term <= S, i.e. ``d_j <= e^S − 1``.
* For a numeric feature those rows form one window of the column sorted by value (``searchsorted`` on
  float32 keys: rounding to float32 is monotonic, so the window is conservative), plus the rows whose
  value is unknown when the unknown penalty is <= S. For a categorical feature they are the rows of the
  stated category (precomputed row lists per value), plus unknown ones when log 2 <= S, plus every row
  when 2 log 2 <= S.
* S starts as the k-th best score of a small pool (rows nearest the description in each stated column)
  and is tightened by scoring more rows near it in the most selective column. Then the rows of the
  smallest window are filtered by the other features' windows (comparisons only) and the survivors are
  scored exactly with the same float64 code as the brute force. Ties are broken by row number, as in the
  brute force, so results are identical (tested on random queries).
"""

from __future__ import annotations

import math
import threading
import weakref
from functools import cached_property

import numpy as np

from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
from recall.metrics import (
    CATEGORY_CODES,
    MISMATCH_TERM,
    UNKNOWN_CATEGORY_TERM,
    FeatureQuery,
    distances,
    kdtree_query,
)
from recall.snapshot import CatalogSnapshot

__all__ = ["JPIndex", "brute_force_top_k", "index_for", "score_rows", "select_top_k", "top_k"]

#: Catalogs up to this size are simply scanned.
SCAN_BELOW = 2048
#: Rows taken around the description in each stated column for the first bound.
FIRST_POOL = 64
#: Growth of the pool while the best window is much larger than the pool.
POOL_GROWTH = 8
MAX_POOL = 1 << 16
#: Rows filtered per step of the final scan (the bound tightens between steps).
CHUNK = 1 << 14
MAX_CHUNK = 1 << 17
#: Rows of the fixed random sample used to order the filter.
SAMPLE = 512
_NUM_INDEX = {f: j for j, f in enumerate(NUMERIC_FEATURES)}
_CAT_INDEX = {f: j for j, f in enumerate(CATEGORICAL_FEATURES)}


def _category_table(feature: str, value: str) -> np.ndarray:
    """Term by (code + 1): index 0 is unknown (-1)."""
    table = np.full(len(CATEGORY_CODES[feature]) + 1, MISMATCH_TERM)
    table[0] = UNKNOWN_CATEGORY_TERM
    table[CATEGORY_CODES[feature][value] + 1] = 0.0
    return table


def score_rows(snap: CatalogSnapshot, query: FeatureQuery, rows: np.ndarray | None = None) -> np.ndarray:
    """JP distance of ``rows`` (all rows when None), summed in the query's feature order (float64)."""
    return _score(snap.num_cols, snap.cat_cols, query, rows)


def _score(num_cols, cat_cols, query: FeatureQuery, rows) -> np.ndarray:
    """The one scoring routine (the brute force, the pruned search and the cells all use it, so their
    distances are equal bit for bit): numeric terms then categorical ones, in the query's order."""
    total = None
    for cond in query.numeric:
        col = num_cols[_NUM_INDEX[cond.feature]]
        x = (col if rows is None else col[rows]).astype(np.float64)  # float32 values, float64 arithmetic
        term = np.log1p(cond.differences(x))
        total = term if total is None else np.add(total, term, out=total)
    for feat, value in query.categorical:
        col = cat_cols[_CAT_INDEX[feat]]
        codes = col if rows is None else col[rows]
        term = _category_table(feat, value)[codes.astype(np.intp) + 1]
        total = term if total is None else np.add(total, term, out=total)
    if total is None:
        return np.zeros(len(num_cols[0]) if rows is None else len(rows))
    return total


def select_top_k(rows: np.ndarray, scores: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The k smallest (score, row) pairs, ordered by score then row number."""
    if len(scores) > k:
        kth = np.partition(scores, k - 1)[k - 1]
        keep = scores <= kth
        rows, scores = rows[keep], scores[keep]
    order = np.lexsort((rows, scores))[:k]
    return rows[order].astype(np.int64), scores[order]


def brute_force_top_k(snap: CatalogSnapshot, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Exact top-k JP by scoring every row (the reference for :class:`JPIndex`)."""
    k = min(k, len(snap))
    if k <= 0:
        return np.empty(0, dtype=np.int64), np.empty(0)
    return select_top_k(np.arange(len(snap)), score_rows(snap, query), k)


def top_k(
    snap: CatalogSnapshot, query: FeatureQuery, k: int, metric: str = "jp", kdtree_cache: dict | None = None
):
    """Exact top-k rows and distances under ``metric`` (JP and JP in log units through the pruned index)."""
    if metric == "jp":
        return index_for(snap).top_k(query, k)
    if metric == "jplog":
        return index_for(snap.log_scaled).top_k(query.log_scaled(), k)
    k = min(k, len(snap))
    if k <= 0:
        return np.empty(0, dtype=np.int64), np.empty(0)
    if metric == "kdtree" and len(query):
        rows, dist = kdtree_query(snap.matrix, query, k, kdtree_cache)
        return rows.astype(np.int64), dist
    d = distances(metric, snap.matrix, query, kdtree_cache=kdtree_cache)
    return select_top_k(np.arange(len(snap)), d, k)


def _merge(rows_a, scores_a, rows_b, scores_b, k: int):
    """Top-k of two scored row sets that may share rows."""
    rows, first = np.unique(np.concatenate((rows_a, rows_b)), return_index=True)
    return select_top_k(rows, np.concatenate((scores_a, scores_b))[first], k)


def _radius(s: float) -> float:
    """Largest difference whose term can be <= s, widened a little against rounding."""
    return math.expm1(s) * (1.0 + 1e-9) + 1e-12


_INDEXES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_INDEX_LOCK = threading.Lock()


def index_for(snap: CatalogSnapshot) -> JPIndex:
    """The :class:`JPIndex` of ``snap``, built on first use and kept while the snapshot lives."""
    with _INDEX_LOCK:
        index = _INDEXES.get(snap)
        if index is None:
            index = _INDEXES[snap] = JPIndex(snap)
        return index


class JPIndex:
    """Sorted numeric columns and per-category row lists of a snapshot, for exact pruned JP top-k.
    Holds the snapshot's columns (not the snapshot, so :func:`index_for` can cache it weakly)."""

    def __init__(self, snap: CatalogSnapshot):
        self.num_cols, self.cat_cols = snap.num_cols, snap.cat_cols
        self.n = len(snap)
        self.num_order: list[np.ndarray] = []
        self.num_keys: list[np.ndarray] = []
        self.num_unknown: list[np.ndarray] = []
        for col in self.num_cols:
            missing = np.isnan(col)
            known = np.flatnonzero(~missing)
            order = known[np.argsort(col[known], kind="stable")].astype(np.int32)
            self.num_order.append(order)
            self.num_keys.append(col[order])
            self.num_unknown.append(np.flatnonzero(missing).astype(np.int32))
        self.cat_order: list[np.ndarray] = []
        self.cat_starts: list[np.ndarray] = []
        for feat, col in zip(CATEGORICAL_FEATURES, self.cat_cols, strict=True):
            self.cat_order.append(np.argsort(col, kind="stable").astype(np.int32))
            counts = np.bincount(col.astype(np.intp) + 1, minlength=len(CATEGORY_CODES[feat]) + 1)
            self.cat_starts.append(np.concatenate(([0], np.cumsum(counts))))

        self.sample = np.sort(
            np.random.default_rng(0).choice(self.n, size=min(SAMPLE, self.n), replace=False)
        )

    @cached_property
    def cells(self) -> CellIndex:
        return CellIndex(self.num_cols, self.cat_cols)

    @property
    def nbytes(self) -> int:
        """Bytes of the index (the cells counted once built)."""
        arrays = [*self.num_order, *self.num_keys, *self.num_unknown, *self.cat_order, *self.cat_starts]
        cells = self.__dict__.get("cells")
        return int(sum(a.nbytes for a in arrays)) + (cells.nbytes if cells is not None else 0)

    def score(self, query: FeatureQuery, rows=None) -> np.ndarray:
        """JP distances of ``rows`` (all when None), as :func:`score_rows`."""
        return _score(self.num_cols, self.cat_cols, query, rows)

    # -- category groups -------------------------------------------------------------------------
    def _group(self, feat: str, code: int) -> np.ndarray:
        """Rows (ascending) whose code of ``feat`` is ``code`` (-1 = unknown)."""
        j = _CAT_INDEX[feat]
        starts = self.cat_starts[j]
        return self.cat_order[j][starts[code + 1] : starts[code + 2]]

    # -- windows ---------------------------------------------------------------------------------
    def _numeric_window(self, cond, s: float) -> tuple[int, int, bool]:
        j = _NUM_INDEX[cond.feature]
        r = _radius(s)
        keys = self.num_keys[j]
        lo = np.float32(cond.low - r) if math.isfinite(cond.low - r) else np.float32(-np.inf)
        hi = np.float32(cond.high + r) if math.isfinite(cond.high + r) else np.float32(np.inf)
        start = int(np.searchsorted(keys, lo, "left"))
        end = int(np.searchsorted(keys, hi, "right"))
        with_unknown = math.log1p(cond.unknown_difference) <= s + 1e-12
        return start, end, with_unknown

    def _window_size(self, item, s: float) -> int:
        kind, obj = item
        if kind == "num":
            start, end, with_unknown = self._numeric_window(obj, s)
            return end - start + (len(self.num_unknown[_NUM_INDEX[obj.feature]]) if with_unknown else 0)
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
            j = _NUM_INDEX[obj.feature]
            start, end, with_unknown = self._numeric_window(obj, s)
            rows = self.num_order[j][start:end]
            return np.concatenate((rows, self.num_unknown[j])) if with_unknown else rows
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
        j = _NUM_INDEX[obj.feature]
        keys, order = self.num_keys[j], self.num_order[j]
        lo = np.float32(obj.low) if math.isfinite(obj.low) else np.float32(-np.inf)
        hi = np.float32(obj.high) if math.isfinite(obj.high) else np.float32(np.inf)
        start = int(np.searchsorted(keys, lo, "left"))
        end = int(np.searchsorted(keys, hi, "right"))
        half = max(1, m // 2)
        if end - start <= m:
            return order[max(0, start - half) : end + half]
        return np.concatenate(
            (order[max(0, start - half) : start + half], order[max(0, end - half) : end + half])
        )

    def _factor(self, item, rows: np.ndarray | None) -> np.ndarray:
        """A lower bound of ``1 + d`` (= e^term) per row for one stated feature (an unknown numeric value
        counts as 1: optimistic, so the filter never drops a row it should keep)."""
        kind, obj = item
        if kind == "num":
            col = self.num_cols[_NUM_INDEX[obj.feature]]
            x = (col if rows is None else col[rows]).astype(np.float64)
            d = np.maximum(obj.low - x, x - obj.high)
            np.fmax(d, 0.0, out=d)
            d += 1.0
            return d
        feat, value = obj
        col = self.cat_cols[_CAT_INDEX[feat]]
        codes = col if rows is None else col[rows]
        return np.where(codes == CATEGORY_CODES[feat][value], 1.0, np.where(codes < 0, 2.0, 4.0))

    def _survivors(self, items: list, order: list[int], rows, s: float) -> np.ndarray:
        """Rows (of an index array or a slice) whose product Π(1 + d_j) can be <= e^s: multiply in the
        features from the most selective one and drop rows as soon as the bound is passed."""
        bound = math.exp(s) * (1.0 + 1e-9) + 1e-12
        prod = None
        for i in order:
            f = self._factor(items[i], rows)
            prod = f if prod is None else np.multiply(prod, f, out=prod)
            keep = prod <= bound
            if isinstance(rows, slice):
                rows = np.flatnonzero(keep) + rows.start
            else:
                rows = rows[keep]
            prod = prod[keep]
            if not len(rows):
                break
        return rows

    # -- search ----------------------------------------------------------------------------------
    def top_k(self, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Exact top-k (rows, JP distances), identical to :func:`brute_force_top_k`."""
        k = min(k, self.n)
        if k <= 0:
            return np.empty(0, dtype=np.int64), np.empty(0)
        if len(query) == 0:
            return np.arange(k, dtype=np.int64), np.zeros(k)
        if self.n <= SCAN_BELOW:
            return select_top_k(np.arange(self.n), self.score(query), k)
        items = [("num", c) for c in query.numeric] + [("cat", c) for c in query.categorical]
        pool = np.unique(np.concatenate([self._nearest(it, FIRST_POOL) for it in items] + [np.arange(k)]))
        best_rows, best_scores = select_top_k(pool, self.score(query, pool), k)
        s = float(best_scores[-1])
        sizes = [self._window_size(it, s) for it in items]
        lead = min(range(len(items)), key=lambda i: sizes[i])
        if s > 0.0 and sizes[lead] > CELL_WINDOW:
            return self.cells.top_k(query, k, best_rows, best_scores)
        if s == 0.0 or sizes[lead] > self.n // 2:
            # ties at 0 are decided by row number: scan in row order and stop early
            source, total, ascending = None, self.n, True
        else:
            source = self._window_rows(items[lead], s)
            total = len(source)
            # a category's own rows are in row order (not once the unknown ones are appended)
            ascending = items[lead][0] == "cat" and not UNKNOWN_CATEGORY_TERM <= s + 1e-12
        # filter order: the feature that typically adds the most to the distance first
        sample = self.sample
        weight = [float(np.mean(np.log(self._factor(it, sample)))) for it in items]
        order = sorted(range(len(items)), key=lambda i: (i != lead or source is None, -weight[i]))
        start, step = 0, CHUNK
        while start < total:
            stop = min(start + step, total)
            chunk = slice(start, stop) if source is None else source[start:stop]
            first = start if source is None else int(chunk[0])
            if ascending and s == 0.0 and int(best_rows.max()) < first:
                break  # only a score below 0, or 0 at a lower row number, could still enter
            rows = self._survivors(items, order, chunk, s)
            if len(rows):
                best_rows, best_scores = _merge(
                    best_rows, best_scores, rows, self.score(query, rows), k
                )
                s = float(best_scores[-1])
            start, step = stop, min(step * 2, MAX_CHUNK)
        return best_rows, best_scores


#: Cells of the best-first search: the catalog is split 4 times (largest extent, mass, middle, smallest
#: extent), each time into this many quantile parts within the parent cell (16384 cells).
CELL_LEVELS = (("a_cm", 16), ("mass_g", 16), ("b_cm", 8), ("c_cm", 8))
#: Rows scored per step of the best-first search (the bound tightens between steps).
CELL_BATCH = 4096
#: Use the cells once the smallest window holds more rows than this.
CELL_WINDOW = 8192


class CellIndex:
    """The catalog cut into about 4096 cells of neighbouring objects, with each cell's value ranges.

    A lower bound of the JP distance of every row of a cell is cheap (the distance from the description
    to the cell's ranges, and 0 / log 2 / 2 log 2 for a category the cell holds / holds unknown / lacks),
    so cells are visited in order of their bound and the search stops once the next bound exceeds the
    k-th best distance found. Rows of a cell are contiguous in copies of the columns sorted by cell.
    """

    def __init__(self, num_cols: list[np.ndarray], cat_cols: list[np.ndarray]):
        n = len(num_cols[0])
        cell = np.zeros(n, dtype=np.int64)
        for feat, split in CELL_LEVELS:
            col = num_cols[_NUM_INDEX[feat]]
            key = np.where(np.isnan(col), np.inf, col)
            order = np.lexsort((key, cell))
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
        arrays = [
            self.perm,
            self.starts,
            self.cmin,
            self.cmax,
            self.cnan,
            self.present,
            *self.num_cols,
            *self.cat_cols,
        ]
        return int(sum(a.nbytes for a in arrays))

    def bounds(self, query: FeatureQuery) -> np.ndarray:
        """A lower bound of the JP distance of the rows of each cell."""
        lb = np.zeros(self.cmin.shape[1])
        with np.errstate(invalid="ignore"):
            for cond in query.numeric:
                j = _NUM_INDEX[cond.feature]
                gap = np.maximum(np.maximum(cond.low - self.cmax[j], self.cmin[j] - cond.high), 0.0)
                term = np.log1p(gap)  # a cell with no known value: gap = inf
                term = np.where(self.cnan[j], np.minimum(term, math.log1p(cond.unknown_difference)), term)
                lb += term
        for feat, value in query.categorical:
            j = _CAT_INDEX[feat]
            bit = np.uint16(1 << (CATEGORY_CODES[feat][value] + 1))
            has = (self.present[j] & bit) != 0
            unknown = (self.present[j] & np.uint16(1)) != 0
            lb += np.where(has, 0.0, np.where(unknown, UNKNOWN_CATEGORY_TERM, MISMATCH_TERM))
        return lb

    def top_k(self, query: FeatureQuery, k: int, best_rows: np.ndarray, best_scores: np.ndarray):
        """Improve a top-k (rows, scores) whose k-th score bounds the answer, visiting cells best first."""
        lb = self.bounds(query)
        s = float(best_scores[-1]) if len(best_scores) >= k else math.inf
        order = np.flatnonzero(lb <= s + 1e-12) if math.isfinite(s) else np.arange(len(lb))
        order = order[np.argsort(lb[order], kind="stable")]
        counts = self.starts[order + 1] - self.starts[order]
        ends = np.cumsum(counts)
        i, budget = 0, CELL_BATCH // 4
        while i < len(order):
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
            scores = _score(self.num_cols, self.cat_cols, query, pos)
            keep = scores <= s + 1e-12 if math.isfinite(s) else np.ones(len(scores), dtype=bool)
            if keep.any():
                rows = self.perm[pos[keep]].astype(np.int64)
                best_rows, best_scores = _merge(best_rows, best_scores, rows, scores[keep], k)
                if len(best_scores) >= k:
                    s = float(best_scores[-1])
        return best_rows, best_scores
