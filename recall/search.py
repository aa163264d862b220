"""Exact top-k search over a :class:`~recall.snapshot.CatalogSnapshot`, with a plan chosen per query.

:func:`brute_force_top_k` scores every row (the reference). :class:`JPIndex` returns the *same* answer
(rows and distances bit for bit, ties by row number) for the Joint Probability distance, choosing for
each query the cheapest of these plans from counts it can take before scoring anything:

* **categories only** (:meth:`recall.combinations.CombinationIndex.search`): "zero" when k of the first
  rows are at distance 0, else a pass of uint8 levels over the rows (small catalogs) or the category
  combinations scored instead of the rows (~0.3 ms at any size);
* **column**: one number and nothing else, read off its sorted column
  (:meth:`recall.columns.SortedColumns.one_column`, O(k) but for ties; up to COLUMN_FROM objects only
  when k rows hold the value, or from the column's Python lists, else brute);
* **window**: argmin Σ log(1 + d_j) = argmin Π (1 + d_j) and every term is >= 0, so a row can only
  score <= S if each stated feature has ``d_j <= e^S − 1``: for a numeric feature the rows of one window
  of the column sorted by value (NaN last), for a category its row list. S starts as the k-th best of a
  small pool (rows nearest the description in each stated column), then of the rows of the cells of
  smallest bound; the smallest window's rows, read from a packed row copy (:attr:`JPIndex.records`),
  are filtered by the product bound in float32 (``recall.ranking.survivors``) and the survivors scored;
* **cells**: a best-first search over cells of neighbouring objects (``recall.cells``), when the
  rows of the cells within the bound are fewer than those of any window;
* **ties at 0**: when the k-th best is already 0, the answer is the k lowest row numbers at distance 0:
  the smallest zero window in row order, or a row-order scan that stops at the k-th;
* **brute**: up to :data:`BRUTE_BELOW` objects, every row scored in float64 (the brute force itself);
* **scan**: every row's float32 product in few passes (:meth:`JPIndex.products`), then the rows within
  the k-th product (widened by ``FILTER_SLACK``) scored exactly: used below :data:`SCAN_BELOW` objects
  and whenever the cost model (:mod:`recall.costs`) estimates the others dearer.

The cost model's figures and the thresholds were measured on this machine (plans forced on the same
queries in one process; ``recall/RECALL.md``); ``tests/test_search.py`` pins each threshold and rule at
its boundary.
"""

from __future__ import annotations

import functools
import math
import threading
import weakref
from functools import cached_property

import numpy as np

from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
from recall.cells import CellIndex
from recall.columns import LIST_BELOW, SortedColumns
from recall.combinations import CombinationIndex
from recall.costs import PlanCosts, after_probe, before_probe
from recall.distances import distances, kdtree_query
from recall.metrics import FeatureQuery
from recall.ranking import (
    CAT_INDEX,
    FILTER_SLACK,
    NUM_INDEX,
    WideColumns,
    category_terms,
    factors,
    jp_scores,
    merge_top_k,
    select_top_k,
    survivors,
)
from recall.snapshot import CatalogSnapshot

__all__ = ["JPIndex", "brute_force_top_k", "index_for", "score_rows", "select_top_k", "top_k"]

#: Catalogs up to this size are scored whole in float64 (the brute force itself): below, the scan's
#: second step (the rows within the k-th product scored exactly, ~25 NumPy calls of fixed cost for 8
#: features) costs more than scoring every row (measured, see RECALL.md).
BRUTE_BELOW = 3072
#: Catalogs up to this size are always scanned, and so is any query of at most SCAN_WORK row-features
#: (below that, the fixed costs of the other plans exceed the scan; measured, see RECALL.md).
SCAN_BELOW = 32768
SCAN_WORK = 40_000
#: One number and nothing else is read off its sorted column by NumPy above this many objects (below,
#: ~12 NumPy calls of fixed cost cost more than a pass over every row; measured): up to it only when k
#: rows hold the value (two binary searches), or from Python lists (``recall.columns.LIST_BELOW``).
COLUMN_FROM = 1024
#: Rows taken around the description in each stated column for the first bound.
FIRST_POOL = 64
#: The scan's first bound: the k-th of a sample of SAMPLE_PER_ROW_K * sqrt(n k) rows (n k / sample
#: rows then pass it, ~sqrt(n k) / SAMPLE_PER_ROW_K: a few dozen to a few hundred).
SAMPLE_PER_ROW_K = 4.0
#: Cells of smallest bound whose rows are scored to tighten the first bound before choosing a plan:
#: 1 024 rows up to 4M objects (64 a cell; against 2 048: 8 % less CPU on described and 14 % on
#: sizes-only descriptions at 1M, 6 % at 100k, in interleaved A/Bs, synthetic), more above, where the
#: cells grow (at 10M 1 024 rows were 7 cells and a jplog description's weak bound cost 51 ms).
PROBE_CELLS = 16
#: Rows filtered per step of the window plan (the bound tightens between steps).
CHUNK = 1 << 14
MAX_CHUNK = 1 << 17
#: Zero windows up to this size are sorted into row order; larger ones are scanned in row order.
ZERO_SORT = 1 << 16


def score_rows(snap: CatalogSnapshot, query: FeatureQuery, rows: np.ndarray | None = None) -> np.ndarray:
    """JP distance of ``rows`` (all rows when None), summed in the query's feature order (float64)."""
    return jp_scores(snap.num_cols, snap.cat_cols, query, rows)


def brute_force_top_k(snap: CatalogSnapshot, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Exact top-k JP by scoring every row (the reference for :class:`JPIndex`)."""
    k = min(k, len(snap))
    if k <= 0:
        return np.empty(0, dtype=np.int64), np.empty(0)
    return select_top_k(None, score_rows(snap, query), k)


def top_k(
    snap: CatalogSnapshot, query: FeatureQuery, k: int, metric: str = "jp", kdtree_cache: dict | None = None
):
    """Exact top-k rows and distances under ``metric`` (JP and JP in log units through the index)."""
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


#: One row of :attr:`JPIndex.records`.
RECORD = np.dtype(
    [(f, np.float32) for f in NUMERIC_FEATURES] + [(f, np.int8) for f in CATEGORICAL_FEATURES] + [("", "V3")]
)

_INDEXES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_INDEX_LOCK = threading.Lock()


def index_for(snap: CatalogSnapshot) -> JPIndex:
    """The :class:`JPIndex` of ``snap``, built on first use and kept while the snapshot lives."""
    with _INDEX_LOCK:
        index = _INDEXES.get(snap)
        if index is None:
            index = _INDEXES[snap] = JPIndex(snap)
        return index


class JPIndex(SortedColumns):
    """Sorted numeric columns, per-category row lists, category combinations and cells of a snapshot's
    columns, for exact JP top-k. Holds the columns, not the snapshot (:func:`index_for` caches weakly)."""

    def __init__(self, snap: CatalogSnapshot):
        self.num_cols, self.cat_cols = snap.num_cols, snap.cat_cols
        self.n = len(snap)
        SortedColumns.__init__(self, self.num_cols, self.cat_cols)

    @cached_property
    def cells(self) -> CellIndex:
        return CellIndex(self.num_cols, self.cat_cols)

    @cached_property
    def wide(self) -> WideColumns:
        """The columns widened for the brute plan (up to BRUTE_BELOW rows: +33 B a row numeric, +40 B categories)."""
        return WideColumns(self.num_cols, self.cat_cols)

    @cached_property
    def combinations(self) -> CombinationIndex:
        return CombinationIndex(self.cat_cols)

    def warm(self) -> JPIndex:
        """Build the parts built on first use (cells, combinations) now, and run one query (NumPy's
        first call of some routines imports modules: ~40 ms, not to be paid by the first description)."""
        _ = self.cells, self.combinations, self.records
        if self.n <= BRUTE_BELOW:
            _ = self.wide
        if self.n <= LIST_BELOW:
            _ = self._key_lists, self._order_lists
        self.plan_and_search(FeatureQuery.from_values({"a_cm": 10.0, "material": "wood"}), 1)
        return self

    @property
    def nbytes(self) -> int:
        """Bytes of the index (the parts built so far; the columns themselves not included)."""
        parts = [self.__dict__.get(p) for p in ("cells", "combinations", "records", "wide")]
        return self.sorted_nbytes + sum(p.nbytes for p in parts if p is not None)

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

    def score(self, query: FeatureQuery, rows=None) -> np.ndarray:
        """JP distances of ``rows`` (all when None), as :func:`score_rows`."""
        return jp_scores(self.num_cols, self.cat_cols, query, rows)

    # -- plans -----------------------------------------------------------------------------------
    def top_k(self, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Exact top-k (rows, JP distances), identical to :func:`brute_force_top_k`."""
        return self.plan_and_search(query, k)[1:]

    def plan_and_search(
        self, query: FeatureQuery, k: int, force: str | None = None
    ) -> tuple[str, np.ndarray, np.ndarray]:
        """(plan, rows, distances), the plan one of categories, window, cells, zero, scan (see the
        module docstring). ``force`` runs one plan whatever it costs (tests and benchmarks: "scan",
        "window", "cells"; "zero" only where the first bound is 0, "categories" without numbers)."""
        k = min(k, self.n)
        if k <= 0:
            return "empty", np.empty(0, dtype=np.int64), np.empty(0)
        if len(query) == 0:
            return "empty", np.arange(k, dtype=np.int64), np.zeros(k)
        if not query.numeric:
            if force == "categories":
                return "categories", *self.combinations.top_k(query, k)
            if force == "scan":
                return "scan", *self.combinations.scan(query, k)
            if force is None:
                return self.combinations.search(query, k)
        if force == "column" or (force is None and len(query) == 1):
            wide = force == "column" or self.n > COLUMN_FROM  # else only k rows in the interval (at 0)
            found = self.one_column(self.num_cols, self.cat_cols, query, k, general=wide)
            if found is not None:
                return "column", *found
            if force == "column":
                raise ValueError("the column plan found more rows near the value, or ties, than it reads")
            if wide:
                (cond,) = query.numeric
                exact = float(np.float32(cond.low)) == cond.low and float(np.float32(cond.high)) == cond.high
                if exact and self._window_size(("num", cond), 0.0) >= k:
                    return "zero", *self._zero_ties(query, [("num", cond)], k)  # k rows in the interval: at 0
        if force == "brute" or (force is None and self.n <= BRUTE_BELOW):
            return "brute", *select_top_k(None, jp_scores(None, self.cat_cols, query, wide=self.wide), k)
        items = [("num", c) for c in query.numeric] + [("cat", c) for c in query.categorical]
        small = self.n <= SCAN_BELOW or self.n * len(items) <= SCAN_WORK
        if force == "scan" or (force is None and small):
            return "scan", *self._scan(query, items, k)
        pool = np.unique(np.concatenate([self._nearest(it, FIRST_POOL) for it in items] + [np.arange(k)]))
        best_rows, best_scores = select_top_k(pool, self.score(query, pool), k)
        s = float(best_scores[-1])
        if force == "window":
            sizes = [self._window_size(it, s) for it in items]
            lead = min(range(len(items)), key=lambda i: sizes[i])
            return "window", *self._window(query, items, lead, k, best_rows, best_scores)
        if force == "cells":
            return "cells", *self.cells.top_k(query, k, best_rows, best_scores)
        if force == "zero" and s != 0.0:
            raise ValueError("the zero plan needs k rows at distance 0 in the first pool")
        if s == 0.0:
            return "zero", *self._zero_ties(query, items, k)
        return self._costed(query, items, k, best_rows, best_scores)

    def costs(self, query: FeatureQuery) -> PlanCosts:
        """The cost model's figures for ``query`` (:mod:`recall.costs`)."""
        m = len(query.numeric) + len(query.categorical)
        return PlanCosts(self.n, self.cells.cmin.shape[1], len(query.numeric), m, bool(query.categorical))

    def _costed(self, query: FeatureQuery, items: list, k: int, best_rows, best_scores):
        """The plan of least estimated cost (:mod:`recall.costs`), given a first top-k whose k-th
        distance is above 0: :func:`~recall.costs.before_probe`, else the probe of the nearest cells
        tightens the bound and :func:`~recall.costs.after_probe` picks the plan."""
        costs = self.costs(query)
        sizes = [self._window_size(it, float(best_scores[-1])) for it in items]
        lead = min(range(len(items)), key=lambda i: sizes[i])
        plan = before_probe(costs, sizes[lead])
        if plan == "window":
            return "window", *self._window(query, items, lead, k, best_rows, best_scores)
        if plan == "scan":
            return "scan", *self._scan(query, items, k)
        lb = self.cells.bounds(query)
        rows = PROBE_CELLS * self.n // len(lb)
        best_rows, best_scores = self.cells.probe(query, k, best_rows, best_scores, lb, rows)
        s = float(best_scores[-1])
        sizes = [self._window_size(it, s) for it in items]
        lead = min(range(len(items)), key=lambda i: sizes[i])
        zero = self._zero_reads(items, k)[0] if s == 0.0 else None
        plan, trial = after_probe(costs, sizes[lead], self.cells.rows_within(lb, s), zero)
        if plan == "zero":
            return "zero", *self._zero_ties(query, items, k)
        if plan == "window":
            return "window", *self._window(query, items, lead, k, best_rows, best_scores)
        if plan == "scan":
            return "scan", *self._scan(query, items, k)
        selective = [items[i] for i in sorted(range(len(items)), key=lambda i: sizes[i])]
        give_up = costs.give_up_rows if trial else None
        found = self.cells.top_k(query, k, best_rows, best_scores, lb, selective, give_up=give_up)
        if found is None:
            return "scan", *self._scan(query, items, k)
        return "cells", *found

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
