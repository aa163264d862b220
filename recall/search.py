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

import threading
import weakref
from functools import cached_property

import numpy as np

from recall.cells import CellIndex
from recall.columns import LIST_BELOW, SortedColumns
from recall.combinations import CombinationIndex
from recall.costs import PlanCosts, after_probe, before_probe
from recall.distances import distances, kdtree_query
from recall.metrics import FeatureQuery
from recall.ranking import WideColumns, jp_scores, select_top_k
from recall.search_scan import ScanPlan
from recall.search_windows import WindowPlans
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
#: Cells of smallest bound whose rows are scored to tighten the first bound before choosing a plan:
#: 1 024 rows up to 4M objects (64 a cell; against 2 048: 8 % less CPU on described and 14 % on
#: sizes-only descriptions at 1M, 6 % at 100k, in interleaved A/Bs, synthetic), more above, where the
#: cells grow (at 10M 1 024 rows were 7 cells and a jplog description's weak bound cost 51 ms).
PROBE_CELLS = 16


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


_INDEXES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_INDEX_LOCK = threading.Lock()


def index_for(snap: CatalogSnapshot) -> JPIndex:
    """The :class:`JPIndex` of ``snap``, built on first use and kept while the snapshot lives."""
    with _INDEX_LOCK:
        index = _INDEXES.get(snap)
        if index is None:
            index = _INDEXES[snap] = JPIndex(snap)
        return index


class JPIndex(ScanPlan, WindowPlans, SortedColumns):
    """Sorted numeric columns, per-category row lists, category combinations and cells of a snapshot's
    columns, for exact JP top-k. Holds the columns, not the snapshot (:func:`index_for` caches weakly).
    The scan plan is :class:`recall.search_scan.ScanPlan`'s, the window and zero-ties plans (and the packed
    rows they read) :class:`recall.search_windows.WindowPlans`'."""

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
