"""The shortlist of a recall: the catalog rows that can rank in the first ``top`` (the pruned top-k of the
search plans, :mod:`recall.search`, plus the rows the text names; every row when vague words can reorder
them), their distances under the metric, their ranking scores (distance - name part + vague part) and
their :class:`~recall.results.Match` records, also for the closest objects of a described noun's kind.
The engine (:mod:`recall.engine`) ranks with it and judges the best match; rules: ``recall/RECALL.md``.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kb.features import FEATURES
from recall.catalog_kinds import KindIndex
from recall.confidence import COMPETITOR_POOL, JP_METRICS
from recall.distances import distances
from recall.metrics import FeatureQuery, feature_terms
from recall.name_index import NameEvidence
from recall.openset import DescribedNoun
from recall.results import Match
from recall.search import score_rows, select_top_k, top_k
from recall.snapshot import CatalogSnapshot
from recall.vague import SoftEvidence

__all__ = ["Shortlist", "ranking_scores"]


class Shortlist:
    """Candidate rows, distances and match records over one catalog snapshot (its k-d trees cached)."""

    def __init__(self, snapshot: CatalogSnapshot, kinds: KindIndex):
        self.snapshot = snapshot
        self.kinds = kinds
        self.kdtrees: dict = {}

    def distances_of(self, query: FeatureQuery, rows: np.ndarray, metric: str) -> np.ndarray:
        if metric == "jp":
            return score_rows(self.snapshot, query, rows)
        if metric == "jplog":
            return score_rows(self.snapshot.log_scaled, query.log_scaled(), rows)
        return distances(metric, self.snapshot.matrix, query, kdtree_cache=self.kdtrees)[rows]

    def candidates(
        self, query: FeatureQuery, named: list[int], top: int, metric: str, soft: SoftEvidence | None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Rows that can rank in the first ``top`` and their distances: the pruned top-k plus the named
        rows; every row when soft evidence can reorder them (vague words: one scan); for category
        alternatives alone the union of each variant's pruned top-k (``SoftEvidence.variants``)."""
        snap = self.snapshot
        if soft is not None and (soft.scan or metric not in JP_METRICS):
            rows = np.arange(len(snap), dtype=np.int64)
            return rows, self.distances_of(query, rows, metric) if len(query) else np.zeros(len(rows))
        want = min(len(snap), max(top + 1, COMPETITOR_POOL) + len(named))
        if soft is not None:
            found = [top_k(snap, v, want, metric=metric)[0] for v in soft.variants]
            rows = np.unique(np.concatenate([*found, np.asarray(named, dtype=np.int64)]))
            return rows, self.distances_of(query, rows, metric) if len(query) else np.zeros(len(rows))
        rows, dist = top_k(snap, query, want, metric=metric, kdtree_cache=self.kdtrees)
        extra = np.setdiff1d(np.asarray(named, dtype=np.int64), rows)
        if len(extra):
            rows = np.concatenate((rows, extra))
            dist = np.concatenate((dist, self.distances_of(query, extra, metric)))
        return rows, dist

    def matches(
        self,
        rows: np.ndarray,
        score: np.ndarray,
        parts: Mapping[int, tuple[float, float, float]],
        query: FeatureQuery,
        metric: str,
        named_exact: set[int],
    ) -> list[Match]:
        """:class:`Match` es of ``rows`` in order; ``parts``: row -> (distance, name part, vague part)."""
        snap = self.snapshot
        if metric == "jplog":
            terms = feature_terms(snap.log_scaled.num_rows(rows), snap.cat_rows(rows), query.log_scaled())
        else:  # the paper's JP terms (also shown for the baselines: why this object, in nats)
            terms = feature_terms(snap.num_rows(rows), snap.cat_rows(rows), query)
        out = []
        for i, row in enumerate(rows.tolist()):
            rec = snap.record(row)
            dist, name_part, vague_part = parts[row]
            out.append(
                Match(
                    name=snap.names[row],
                    distance=dist,
                    score=float(score[i]),
                    contributions={f: float(terms[f][i]) for f in query.stated},
                    matched_by_name=row in named_exact,
                    features={f: getattr(rec, f) for f in FEATURES},
                    name_part=name_part,
                    vague_part=vague_part,
                    kind=self.kinds.kind(row),
                )
            )
        return out

    def same_kind(
        self, noun: DescribedNoun, query: FeatureQuery, metric: str, k: int = 3
    ) -> tuple[str | None, list[Match]]:
        """The ``k`` objects of the described noun's kind (or nearest ancestor) closest by features."""
        kind, rows = self.kinds.rows_of_kind(noun.kind)
        if not rows:
            return None, []
        arr = np.asarray(rows, dtype=np.int64)
        dist = self.distances_of(query, arr, metric) if len(query) else np.zeros(len(arr))
        arr, dist = select_top_k(arr, dist, min(k, len(arr)))
        parts = {int(r): (float(d), 0.0, 0.0) for r, d in zip(arr, dist, strict=True)}
        return kind, self.matches(arr, dist, parts, query, metric, set())


def ranking_scores(
    rows: np.ndarray, dist: np.ndarray, names: NameEvidence, soft: SoftEvidence | None, metric: str
) -> tuple[np.ndarray, dict[int, tuple[float, float, float]]]:
    """The ranking score of each candidate row (distance - name part + vague part) and the parts by row:
    row -> (distance, name part, vague part)."""
    named = bool(names.exact or names.head or names.sorts)
    bonus = np.array([names.bonus(int(r)) for r in rows]) if named else np.zeros(len(rows))
    vague = soft.penalty[rows] if soft is not None else np.zeros(len(rows))
    if metric in JP_METRICS:
        score = dist - bonus + vague
    else:  # other metrics have no probabilistic scale: named objects rank first, by their evidence
        score = dist - (dist.max() + 1.0) * bonus + vague
    parts = {int(r): (float(d), float(b), float(v)) for r, d, b, v in zip(rows, dist, bonus, vague, strict=True)}
    return score, parts
