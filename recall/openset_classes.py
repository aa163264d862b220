"""The ranking reads a binned catalog's classes as the verdict does: past the part measured, mass is open above.

A catalog that declares its sizes a part's (``bins.csv``, the largest size's class open above) and an open
top size class (``floors.csv``) records, for an object whose part already reaches the top class, the mass
of what the hand bore (Yale: the garden hose 240 g, the wardrobe door 750 g); the verdict reads that mass
class as open above (:func:`recall.metrics.past_the_part`, helper yale4). The ranking read the closed
class: "a garden hose, 5/8 inch diameter, 50 feet long, rubber, about 8 pounds" ranked the cleaning
supplies basket over the hose, whose 240 g class the 8 pounds are 10x over. Here the rows past the part are
ranked by the query whose mass class is open above (every such row scored, so the pruned search misses
none), the other rows as before (issue 23, helper openset6; ``recall/RECALL.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np

from recall.metrics import FeatureQuery, past_the_part
from recall.snapshot import CatalogSnapshot

__all__ = ["past_part_rows", "with_open_mass"]


def past_part_rows(snapshot: CatalogSnapshot, floors: Mapping[str, float], bins) -> np.ndarray:
    """The rows whose recorded mass class is open above (:func:`recall.metrics.past_the_part`)."""
    if not floors or not bins:
        return np.zeros(0, dtype=np.int64)
    return np.asarray(
        [i for i in range(len(snapshot)) if past_the_part(snapshot.num_rows(i), floors, bins)], dtype=np.int64
    )


def with_open_mass(
    rows: np.ndarray,
    dist: np.ndarray,
    query: FeatureQuery,
    ranked: FeatureQuery,
    past: np.ndarray,
    mass: np.ndarray,
    bins,
    metric: str,
    distances_of: Callable[[FeatureQuery, np.ndarray], np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """``rows`` and their distances ``dist`` (under ``ranked``, the query of the catalog's classes) with
    every row of ``past`` added, and those whose class the stated mass (of ``query``) is above scored as
    when the catalog's mass is unknown: ``ranked`` without its mass, plus the metric's unknown-value term
    (``mass``: the catalog's masses by row; ``distances_of(query, rows)``: the shortlist's metric).
    Unchanged when no mass is stated or the metric is no JP."""
    cond = next((c for c in query.numeric if c.feature == "mass_g"), None)
    if len(past) == 0 or cond is None or metric not in ("jp", "jplog"):
        return rows, dist
    above = bins.get("mass_g", (1.0, 1.0))[1]
    over = past[cond.low > mass[past] * above]  # the stated mass above the recorded class
    if len(over) == 0:
        return rows, dist
    rows = np.concatenate((rows, np.setdiff1d(over, rows)))
    dist = np.concatenate((dist, np.zeros(len(rows) - len(dist))))
    mask = np.isin(rows, over)
    rest = FeatureQuery(tuple(c for c in ranked.numeric if c.feature != "mass_g"), ranked.categorical)
    unknown = (cond.log_scaled() if metric == "jplog" else cond).unknown_difference
    dist = dist.copy()
    dist[mask] = (distances_of(rest, rows[mask]) if len(rest) else 0.0) + math.log1p(unknown)
    return rows, dist
