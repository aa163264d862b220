"""Why the wrong object won: each miss of the evaluation explained from both objects' feature terms."""

from __future__ import annotations

from typing import Any

import numpy as np

from kb.features import CATEGORICAL_FEATURES
from recall.metrics import FeatureQuery, feature_terms

__all__ = ["explained_miss", "miss_reason"]


def miss_reason(
    recaller,
    query: FeatureQuery,
    true_name: str,
    got_name: str,
    *,
    metric: str = "jp",
    result=None,
) -> str:
    """Why ``got_name`` beat ``true_name`` under ``metric`` (``jp`` or ``jplog``): both ranking scores,
    the stated features that pulled the wrong object ahead (largest first, with the stated value, both
    catalog values and both terms), the ones that favoured the right object, the name evidence of the
    hybrid, and the unstated categories that would have told them apart."""
    snap = recaller.snapshot
    index = {n: i for i, n in enumerate(snap.names)}
    t, g = index[true_name], index[got_name]
    rows = np.array([t, g])
    if metric == "jplog":
        terms = feature_terms(snap.log_scaled.num_rows(rows), snap.cat_rows(rows), query.log_scaled())
    else:
        terms = feature_terms(snap.num_rows(rows), snap.cat_rows(rows), query)
    true_rec, got_rec = snap.record(t), snap.record(g)
    values = query.values()
    names = result.evidence if result is not None else None
    bonus = (names.bonus(t), names.bonus(g)) if names is not None else (0.0, 0.0)
    total_t = sum(float(v[0]) for v in terms.values()) - bonus[0]
    total_g = sum(float(v[1]) for v in terms.values()) - bonus[1]
    label = "jp" if metric == "jp" else metric
    parts = [f"{label} {got_name} {total_g:.2f} < {true_name} {total_t:.2f}"]

    def side(feat: str) -> str:
        return (
            f"{feat}: stated {_fmt(values.get(feat))}, {true_name} {_fmt(getattr(true_rec, feat))} "
            f"(+{terms[feat][0]:.2f}) vs {got_name} {_fmt(getattr(got_rec, feat))} (+{terms[feat][1]:.2f})"
        )

    diffs = sorted(((float(terms[f][0] - terms[f][1]), f) for f in terms), reverse=True)
    pulls = [side(f) for d, f in diffs if d > 1e-9][:3]
    if pulls:
        parts.append("pulled ahead by " + "; ".join(pulls))
    against = [f"{f} ({-d:.2f})" for d, f in sorted(diffs) if d < -1e-9][:3]
    if against:
        parts.append("the right object was closer on " + ", ".join(against))
    if bonus != (0.0, 0.0):
        parts.append(f"name evidence: {true_name} -{bonus[0]:.2f}, {got_name} -{bonus[1]:.2f}")
    if not query.stated:
        parts.append("no feature stated")
    unstated = [
        f"{f} ({getattr(true_rec, f)} vs {getattr(got_rec, f)})"
        for f in CATEGORICAL_FEATURES
        if f not in values and getattr(true_rec, f) != getattr(got_rec, f)
    ]
    if unstated:
        parts.append("not stated: " + ", ".join(unstated))
    if len(parts) == 1:
        parts.append("tie on every stated feature")
    return "; ".join(parts)


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    return "?" if v is None else str(v)


def explained_miss(recaller, key: tuple[str, bool], obj: str, text: str, query: FeatureQuery, res) -> tuple:
    """(mode, object, got, description, reason) of a miss of mode ``key`` (metric, features only), the
    reason from :func:`miss_reason` with the hybrid's name evidence first."""
    names = [m.name for m in res.matches]
    got = names[0] if names else "(nothing)"
    reason = miss_reason(recaller, query, obj, got, metric=key[0], result=res) if names else "nothing stated or named"
    if not key[1]:
        reason = (
            "named: " + ", ".join(res.named) + "; "
            if res.named
            else "head noun: " + ", ".join(res.evidence.heads) + "; "
            if res.evidence.heads
            else "no name found; "
        ) + reason
    return (key[0] if key[1] else f"{key[0]}+names", obj, got, text, reason)
