"""The one scored decision between a feature's candidate values (``scrapers.extract.fuse`` calls it).

Candidates that agree (within 2 %; a shorter size agreeing with part of a longer one) form a cluster: one
value the page states, perhaps several times and in several readers. Each cluster gets a score, the sum of
:data:`WEIGHTS` times its :func:`features` (each in 0..1, higher is more the product's):

* ``source``: how structured its best reader is (the adapters' priority order: JSON-LD 1, ... the title 0);
* ``direct``: how direct its best statement is (rank 0 an explicit field, 1 a labelled row, 2 a range bound,
  a title's size);
* ``support``: how many other readers state the same value (0, 1, 2 or more others: 0, 0.5, 1);
* ``repeats``: how many more times the page states it (capped at 3);
* ``complete``: for a size, how many extents its fullest member states (of 3);
* ``main``: the share of its statements read inside the page's main, shown content, not in a header,
  footer, navigation or aside (site-wide blocks: a store's size guide, a banner) nor in a hidden meta field
  (``Observation.hidden``: a shop system's postage weight in ``<meta>``).

The highest score wins (ties: the cluster holding the earliest candidate in the adapters' priority order);
its fullest member (sizes) or its best member (mass) is the value. A cluster stated **only** in site-wide
blocks or hidden meta fields (``main`` 0: a footer's shipping limits, an aside's size guide, an
``og:product:weight`` no shown line states) is never the product's: with no
other cluster, nothing is chosen. :func:`fit_weights` fits the weights on
samples of labelled pages (``benchmarks/corpus_bench.py --loso`` fits them on all development stores but
one and scores the one left out); :data:`WEIGHTS` are checked on the development stores only.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["FEATURES", "WEIGHTS", "Cluster", "choose", "cluster", "features", "fit_weights", "score"]

FEATURES = ("source", "direct", "support", "repeats", "complete", "main")
#: The weights in use (checked on the development stores: ``corpus_bench.py --loso``). ``source`` leads:
#: a structured field beats a line of text unless the text is stated by more readers, in full, in the
#: page's main content.
WEIGHTS: dict[str, float] = {"source": 4.0, "direct": 1.0, "support": 1.0, "repeats": 0.0, "complete": 0.5,
                             "main": 2.0}  # fmt: skip
#: The grid :func:`fit_weights` searches, per feature.
GRID: dict[str, tuple[float, ...]] = {
    "source": (2.0, 4.0, 8.0), "direct": (0.0, 0.5, 1.0, 2.0), "support": (0.0, 0.5, 1.0, 2.0, 4.0),
    "repeats": (0.0, 0.25, 1.0), "complete": (0.0, 0.5, 1.0), "main": (0.0, 1.0, 2.0, 4.0),
}  # fmt: skip


@dataclass
class Cluster:
    """Candidates stating one value; ``members`` in priority order (best first)."""

    members: list[Any]
    features: dict[str, float]
    score: float = 0.0

    @property
    def site_wide(self) -> bool:
        """Stated only in site-wide blocks: never the product's value."""
        return self.features["main"] == 0

    @property
    def value(self) -> Any:
        """The fullest member for a size (then the best), else the best member."""
        if self.members[0].feature == "dims":
            return min(self.members, key=lambda o: -len(o.value))
        return self.members[0]


def cluster(cands: Sequence[Any], agree: Callable[[Any, Any], bool]) -> list[list[Any]]:
    """``cands`` (already in priority order) grouped by agreement with each group's first member."""
    groups: list[list[Any]] = []
    for o in cands:
        for group in groups:
            if agree(group[0].value, o.value):
                group.append(o)
                break
        else:
            groups.append([o])
    return groups


def features(members: Sequence[Any], source_index: Callable[[Any], int], n_sources: int) -> dict[str, float]:
    """The :data:`FEATURES` of one cluster (module doc); ``source_index`` gives a member's adapter index."""
    best = min(source_index(o) for o in members)
    sources = {o.source for o in members}
    return {
        "source": 1.0 - best / max(n_sources - 1, 1),
        "direct": 1.0 - min(min(o.rank for o in members), 2) / 2,
        "support": min(len(sources) - 1, 2) / 2,
        "repeats": min(len(members) - 1, 3) / 3,
        "complete": max(len(o.value) for o in members) / 3 if members[0].feature == "dims" else 0.0,
        "main": sum(not (getattr(o, "site_wide", False) or getattr(o, "hidden", False)) for o in members) / len(members),
    }


def score(feats: dict[str, float], weights: dict[str, float] | None = None) -> float:
    w = WEIGHTS if weights is None else weights
    return sum(w.get(k, 0.0) * v for k, v in feats.items())


def choose(
    cands: Sequence[Any], agree: Callable[[Any, Any], bool], source_index: Callable[[Any], int], n_sources: int,
    weights: dict[str, float] | None = None,
) -> list[Cluster]:
    """The clusters of ``cands`` (in priority order), the winner first (module doc); [] for none. When every
    cluster is :attr:`Cluster.site_wide`, none wins: they keep their priority order."""
    clusters = []
    for members in cluster(cands, agree):
        feats = features(members, source_index, n_sources)
        clusters.append(Cluster(members, feats, score(feats, weights)))
    if not clusters:
        return []
    eligible = [i for i, c in enumerate(clusters) if not c.site_wide]
    if not eligible:
        return clusters
    # max() keeps the first of equal scores: the cluster of the earliest candidate in priority order
    win = max(eligible, key=lambda i: clusters[i].score)
    return [clusters[win]] + clusters[:win] + clusters[win + 1 :]


def pick(sample: list[tuple[dict[str, float], bool]], weights: dict[str, float]) -> bool:
    """Whether ``weights`` choose a right cluster among one sample's ``(features, right)`` clusters."""
    best = max(range(len(sample)), key=lambda i: score(sample[i][0], weights))
    return sample[best][1]


def fit_weights(samples: list[list[tuple[dict[str, float], bool]]]) -> dict[str, float]:
    """The :data:`GRID` weights that choose a right cluster in most ``samples`` (each: one page's
    clusters of one feature, as ``(features, right)``); ties keep the weights nearest :data:`WEIGHTS`.
    Samples whose clusters are all right or all wrong say nothing and are skipped."""
    useful = [s for s in samples if len({right for _, right in s}) == 2]
    best, best_key = dict(WEIGHTS), None
    for combo in itertools.product(*(GRID[k] for k in FEATURES)):
        w = dict(zip(FEATURES, combo, strict=True))
        right = sum(pick(s, w) for s in useful)
        distance = sum(abs(w[k] - WEIGHTS[k]) for k in FEATURES)
        key = (right, -distance)
        if best_key is None or key > best_key:
            best, best_key = w, key
    return best
