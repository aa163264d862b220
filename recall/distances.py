"""Distances of every catalog row to a description over the one-hot catalog matrix
(:data:`kb.features.VECTOR_COLUMNS`, NaN = unknown), for each metric of :data:`recall.metrics.METRICS`:
the paper's JP (also in log units, ``jplog``) and the baselines (Euclidean, Minkowski p=4, Cosine,
scikit-learn's k-d tree), all over the masked columns of the stated features with the unknown-value rules
of :mod:`recall.metrics` (:meth:`~recall.metrics.NumericCondition.differences`).

* Cosine and the k-d tree need a catalog *vector*, not a difference: they use the stated point value,
  impute an unknown numeric value as ``v · (1 + 0.5)`` (cosine) or the column median (k-d tree, whose tree
  is built once per mask), and an unknown category as zeros.
"""

from __future__ import annotations

import numpy as np

from kb.errors import RecallError
from kb.features import NUMERIC_FEATURES, VECTOR_COLUMNS
from recall.metrics import METRICS, MINKOWSKI_P, UNKNOWN_NUMERIC_FRACTION, FeatureQuery, log_units

__all__ = ["distances", "kdtree_query"]


def _masked_columns(query: FeatureQuery) -> list[int]:
    stated = set(query.stated)
    return [i for i, col in enumerate(VECTOR_COLUMNS) if col.split("=")[0] in stated]


def _column_differences(matrix: np.ndarray, query: FeatureQuery) -> np.ndarray:
    """(n, p) absolute per-column differences over the masked one-hot columns, with the unknown rules."""
    cols = _masked_columns(query)
    conds = {c.feature: c for c in query.numeric}
    cats = dict(query.categorical)
    out = np.empty((matrix.shape[0], len(cols)))
    for k, i in enumerate(cols):
        col = VECTOR_COLUMNS[i]
        x = matrix[:, i]
        if col in conds:
            out[:, k] = conds[col].differences(x)
        else:
            feat, val = col.split("=")
            q = 1.0 if cats[feat] == val else 0.0
            out[:, k] = np.abs(np.where(np.isnan(x), 0.0, x) - q)
    return out


def _vectors(matrix: np.ndarray, query: FeatureQuery, impute: str) -> tuple[np.ndarray, np.ndarray]:
    """Masked catalog matrix (unknowns imputed) and the query's point vector, for cosine and the k-d tree."""
    cols = _masked_columns(query)
    conds = {c.feature: c for c in query.numeric}
    cats = dict(query.categorical)
    x = matrix[:, cols].copy()
    q = np.empty(len(cols))
    for k, i in enumerate(cols):
        col = VECTOR_COLUMNS[i]
        missing = np.isnan(x[:, k])
        if col in conds:
            q[k] = conds[col].value
            if missing.any():
                if impute == "median":
                    known = x[~missing, k]
                    fill = float(np.median(known)) if known.size else 0.0
                else:
                    fill = q[k] * (1.0 + UNKNOWN_NUMERIC_FRACTION)
                x[missing, k] = fill
        else:
            feat, val = col.split("=")
            q[k] = 1.0 if cats[feat] == val else 0.0
            x[missing, k] = 0.0
    return x, q


def distances(
    metric: str, matrix: np.ndarray, query: FeatureQuery, kdtree_cache: dict | None = None
) -> np.ndarray:
    """Distance of every catalog row to the description under ``metric`` (smaller = closer).

    ``matrix`` is the catalog over :data:`kb.features.VECTOR_COLUMNS` (NaN = unknown). With no stated
    feature every distance is 0. ``kdtree`` returns the k-d tree's Euclidean distances for all rows (the
    tree is queried for every row so that the ranking is complete); trees are cached in ``kdtree_cache``
    by mask.
    """
    if metric not in METRICS:
        raise RecallError(f"unknown metric {metric!r}; expected one of {', '.join(METRICS)}")
    n = matrix.shape[0]
    if len(query) == 0 or n == 0:
        return np.zeros(n)
    if metric == "jp":
        return np.log1p(_column_differences(matrix, query)).sum(axis=1)
    if metric == "jplog":
        scaled = matrix.copy()
        scaled[:, : len(NUMERIC_FEATURES)] = log_units(matrix[:, : len(NUMERIC_FEATURES)])
        return np.log1p(_column_differences(scaled, query.log_scaled())).sum(axis=1)
    if metric == "euclidean":
        return np.sqrt((_column_differences(matrix, query) ** 2).sum(axis=1))
    if metric == "minkowski":
        return ((_column_differences(matrix, query) ** MINKOWSKI_P).sum(axis=1)) ** (1.0 / MINKOWSKI_P)
    if metric == "cosine":
        x, q = _vectors(matrix, query, impute="inflate")
        denom = np.linalg.norm(x, axis=1) * np.linalg.norm(q)
        with np.errstate(invalid="ignore", divide="ignore"):
            sim = np.where(denom > 0, (x @ q) / np.where(denom > 0, denom, 1.0), 0.0)
        return 1.0 - sim
    # kdtree
    idx, dist = kdtree_query(matrix, query, n, kdtree_cache)
    out = np.empty(n)
    out[idx] = dist
    return out


def kdtree_query(matrix: np.ndarray, query: FeatureQuery, k: int, kdtree_cache: dict | None = None):
    """The k nearest rows (indices, Euclidean distances) by scikit-learn's KDTree over the stated columns;
    one tree per mask, kept in ``kdtree_cache``."""
    from sklearn.neighbors import KDTree

    key = tuple(_masked_columns(query))
    cache = kdtree_cache if kdtree_cache is not None else {}
    if key not in cache:
        x, _ = _vectors(matrix, query, impute="median")
        cache[key] = KDTree(x)
    _, q = _vectors(matrix[:1], query, impute="median")
    dist, idx = cache[key].query(q.reshape(1, -1), k=k)
    return idx[0], dist[0]
