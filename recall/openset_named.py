"""Name evidence before feature distance: a named object that fits ranks first.

The hybrid ranking lowers a named object's distance by its name's information (``recall/RECALL.md``, "The
hybrid"), and a different-kind object a little nearer in every stated value could still beat it: "a bowl
about 25 cm wide, 600 g" recalled the basketball (24 cm, 600 g) at 0.96 although the seed catalog's ceramic
bowl (15 cm, 350 g) is within a factor 2 of both values. The rule (issue 23): when the text names catalog
objects (a whole name or alias, a head noun, a sort of a catalog head) and one of them **fits** by the
open-set rule (:func:`recall.fit.judge` of its own closeness: mean relative error at most 0.45 for a whole
name or alias the subject's material does not contradict, 0.30 for a head noun or a sort, and no stated value
past the disagreement factor), the best such object ranks first; a different-kind object beats a named one
only when no named object fits. Among the named objects, and behind the first, the ranking is unchanged.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from recall.fit import Trust, judge
from recall.name_index import NameEvidence

__all__ = ["FIRST_MARGIN", "fits_by", "named_first"]

#: The margin (nats) by which the fitting named object is put before the nearest unnamed one: a tie in
#: all but the order, so the confidence says how close the two were.
FIRST_MARGIN = 1e-3


def named_first(
    rows: np.ndarray,
    score: np.ndarray,
    parts: Mapping[int, tuple[float, float, float]],
    names: NameEvidence,
    fits: Callable[[int, Trust], bool],
) -> tuple[np.ndarray, dict[int, tuple[float, float, float]]]:
    """``score`` (one per row of ``rows``) and ``parts`` (row -> distance, name part, vague part) with the
    named rows lowered together, when the best-scoring row is unnamed and a named row fits (``fits(row,
    trust)``: the open-set rule on that row, :attr:`Trust.NAMED` for a whole name, else
    :attr:`Trust.PLAIN`), so that the best fitting named row ranks :data:`FIRST_MARGIN` before the best
    unnamed one; the shift is added to their name parts. Unchanged otherwise."""
    named = set(names.exact)
    if not named or len(rows) == 0:
        return score, dict(parts)
    order = np.argsort(score, kind="stable")
    if int(rows[order[0]]) in set(names.rows()):  # the best is named already
        return score, dict(parts)
    is_named = np.array([int(r) in named for r in rows])
    fitting = [
        i for i in order.tolist()
        if is_named[i] and fits(int(rows[i]), Trust.NAMED)
    ]  # fmt: skip
    if not fitting:
        return score, dict(parts)
    shift = float(score[fitting[0]] - score[order[0]]) + FIRST_MARGIN
    out = score.copy()
    out[is_named] -= shift
    new_parts = dict(parts)
    for i in np.flatnonzero(is_named).tolist():
        dist, name_part, vague_part = parts[int(rows[i])]
        new_parts[int(rows[i])] = (dist, name_part + shift, vague_part)
    return out, new_parts


def fits_by(closeness: float | None, errors: Mapping[str, float], trust: Trust) -> bool:
    """The open-set rule on one object (:func:`recall.fit.judge`): whether it is a close match."""
    return closeness is not None and judge(closeness, errors, trust).close
