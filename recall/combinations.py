"""Exact top-k for descriptions that state categories only, through the catalog's category combinations.

With only categories stated, a row's JP distance depends on its combination of category codes alone
(5 features, 4 320 combinations with "unknown"). The rows are kept grouped by combination (one int32
permutation, rows ascending within a group): a query scores the combinations, not the rows, takes whole
groups in order of distance and, at the k-th distance, the lowest row numbers of the groups tied there,
which is the brute force's order (distance, then row). About 0.1 ms at any catalog size.
"""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np

from kb.features import CATEGORICAL_FEATURES, CATEGORIES
from recall.metrics import CATEGORY_CODES, MISMATCH_TERM, UNKNOWN_CATEGORY_TERM, FeatureQuery
from recall.ranking import CAT_INDEX, category_terms, jp_scores, select_top_k

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
        # each row's combination, as its position among the used ones (int16: < 4 320)
        self.group = np.empty(len(key), dtype=np.int16)
        self.group[self.perm] = np.repeat(np.arange(len(used), dtype=np.int16), counts[used])
        self.cat_cols = cat_cols

    @property
    def nbytes(self) -> int:
        return int(self.perm.nbytes + self.starts.nbytes + self.used.nbytes + self.codes.nbytes + self.group.nbytes)

    def search(self, query: FeatureQuery, k: int) -> tuple[str, np.ndarray, np.ndarray]:
        """(plan, rows, distances) of a category-only query, the plan chosen from a cheap look first:
        "zero" when k of the rows 0..FIRST_ROWS are at distance 0 (no row is closer, ties go to the
        lowest rows), else a pass over the rows ("scan") up to :data:`SCAN_ROWS` rows, else the
        combinations (:meth:`top_k`, a fixed cost of about SCAN_ROWS rows' pass)."""
        table = self._levels_of(query)
        level = table.take(self.group[:FIRST_ROWS])
        zeros = (level == 0).nonzero()[0]
        if len(zeros) >= k:
            return "zero", zeros[:k].astype(np.int64), np.zeros(k)
        if len(self.group) > SCAN_ROWS:
            return "categories", *self.top_k(query, k)
        return "scan", *self._ranked(query, k, level if len(self.group) <= FIRST_ROWS else table.take(self.group))

    def scan(self, query: FeatureQuery, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Exact top-k of a category-only query by a pass over the rows: each combination's level
        h = Σ 0/1/2 (the value / unknown / another category) is looked up for every row (one gather,
        whatever the number of stated categories); levels order the rows (:func:`_levels`), so a stable
        sort of the row levels (a radix sort of uint8) is the brute force's order, ties by row number.
        Rows are scored when a level up to the k-th holds two distances."""
        return self._ranked(query, k, self._levels_of(query).take(self.group))

    def _levels_of(self, query: FeatureQuery) -> np.ndarray:
        """The level of each used combination (uint8)."""
        if query.numeric or not query.categorical:
            raise ValueError("CombinationIndex answers descriptions that state categories only")
        table = None
        for feat, value in query.categorical:
            state = _states(feat, value).take(self.codes[CAT_INDEX[feat]])
            table = state if table is None else np.add(table, state, out=table)
        return table

    def _ranked(self, query: FeatureQuery, k: int, level: np.ndarray):
        single, distance = _levels(len(query.categorical))
        rows = level.argsort(kind="stable")[:k]
        at = level[rows]
        if not single[: int(at[-1]) + 1].all():  # a level of two distances: score the rows up to it
            rows = (level <= at[-1]).nonzero()[0]
            return select_top_k(rows, jp_scores(None, self.cat_cols, query, rows), k)
        return rows.astype(np.int64), distance[at]

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
        groups = (score <= kth).nonzero()[0]
        # every row of the groups below the k-th distance, the first k rows of each group at it
        take = np.where(score[groups] < kth, stops[groups] - starts[groups], np.minimum(stops[groups] - starts[groups], k))
        first = starts[groups]
        pos = np.repeat(first - np.concatenate(([0], np.cumsum(take)[:-1])), take) + np.arange(take.sum())
        rows = self.perm[pos].astype(np.int64)
        return select_top_k(rows, np.repeat(score[groups], take), k)


#: Rows looked at first by :meth:`CombinationIndex.search` (most answers are k rows at distance 0 there).
FIRST_ROWS = 4096
#: Above this many rows the combinations beat a pass over the rows (measured: ~11 ns per row for the
#: pass, ~0.25 ms for the combinations, on this machine under load; tests pin the boundary).
SCAN_ROWS = 20_000


@functools.cache
def _levels(m: int) -> tuple[np.ndarray, np.ndarray]:
    """For m stated categories, by level h = Σ states (0 the value, 1 unknown, 2 another; h in 0..2m):
    whether every order of states at that level sums to one float64 distance (summed as ``jp_scores``
    does), and the largest distance of the level. Levels are strictly ordered (checked), so a row's level
    orders it against the rows of every other level."""
    terms = np.array([0.0, UNKNOWN_CATEGORY_TERM, MISMATCH_TERM])
    values: dict[int, set[float]] = {}
    for combo in itertools.product(range(3), repeat=m):
        total = terms[combo[0]]
        for st in combo[1:]:
            total = total + terms[st]
        values.setdefault(sum(combo), set()).add(float(total))
    levels = [values[h] for h in range(2 * m + 1)]
    if any(max(a) >= min(b) for a, b in itertools.pairwise(levels)):
        raise AssertionError("category distances are not ordered by level")  # pragma: no cover
    return np.array([len(v) == 1 for v in levels]), np.array([max(v) for v in levels])


@functools.cache
def _states(feature: str, value: str) -> np.ndarray:
    """By code + 1 (0 = unknown): the state 0 (the value), 1 (unknown) or 2 (another category)."""
    states = np.full(len(CATEGORIES[feature]) + 1, 2, dtype=np.uint8)
    states[CATEGORY_CODES[feature][value] + 1] = 0
    states[0] = 1
    states.flags.writeable = False
    return states
