"""What a grasp is planned for, from a recall result: the recalled catalog object when it is a close match,
else the object *as described* (the paper's point: a physically similar object serves the grasp).

:func:`grasp_target` is used by ``objrecall grasp plan`` and ``POST /grasp/plan`` alike, so both say the
same thing: ``planned_for``, ``hint`` and a one-line ``why``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from kb.features import FEATURES, NUMERIC_FEATURES, ObjectRecord, sort_dims
from recall.verdict import verdict

__all__ = ["grasp_target"]


def grasp_target(result: Any, get_object: Callable[[str], ObjectRecord]) -> tuple[ObjectRecord, dict[str, Any]]:
    """The object to plan for and how it was chosen (``recalled`` of the grasp plan's JSON).

    A close match: the catalog object itself (``get_object(name)``). Not in the catalog or not a close
    match (``result.open_set``): the stated features, with the values of a hint object (the closest of
    the described kind when there is one, else the nearest) only for what the description leaves out."""
    best = result.best
    info: dict[str, Any] = {
        "method": "recall",
        "confidence": round(result.confidence, 4),
        "open_set": result.open_set,
        "not_in_catalog": result.not_in_catalog,
        "distance": best.distance,
        "alternatives": [m.name for m in result.matches[1:]],
        "verdict": verdict(result).to_dict(),  # the recall's own line, as in `objrecall recall` and POST /recall
    }
    if not result.open_set:
        info["planned_for"] = best.name
        info["why"] = f"planned for {best.name}: recalled with {info['verdict']['text']}"
        return get_object(best.name), info
    hint = get_object(result.same_kind[0].name if result.same_kind else best.name)
    stated = dict(result.query["values"])
    values = {f: stated.get(f, getattr(hint, f)) for f in FEATURES}
    values.update(_fill_sides(stated, [getattr(hint, f) for f in NUMERIC_FEATURES[:3]]))
    noun = result.described.noun if result.not_in_catalog and result.described else None
    name = f"described {noun}" if noun else "described object"
    from_hint = [f for f in FEATURES if f not in stated and values[f] is not None]
    reason = f"not in the catalog (no {noun!r})" if noun else f"no close match (confidence {result.confidence:.2f})"
    why = f"planned for the {name}: {reason}; from its stated {', '.join(sorted(stated)) or 'nothing'}"
    if from_hint:
        why += f"; the rest ({', '.join(from_hint)}) from {hint.name}, as a hint"
    info.update(planned_for=name, hint=hint.name, stated=sorted(stated), from_hint=from_hint, why=why)
    return ObjectRecord.create(name, plausible=False, **{k: v for k, v in values.items() if v is not None}), info


def _fill_sides(stated: dict[str, Any], hint: list[float | None]) -> dict[str, float | None]:
    """The sides a >= b >= c of the object planned for: a stated side keeps its place and value ("a spoon
    1 cm long": a = 1 cm); a side left out takes the hint's, clamped between the sides around it so the
    order holds (b, c <= 1 cm there; "a bottle 40 cm wide": a >= 40 cm). When no side is stated, the
    hint's sides, sorted."""
    names = NUMERIC_FEATURES[:3]
    if not any(f in stated for f in names):
        return dict(zip(names, sort_dims(*hint), strict=True))
    sides: list[float | None] = [stated.get(f) for f in names]
    for i, f in enumerate(names):
        if f in stated or hint[i] is None:
            continue
        above = [v for v in sides[:i] if v is not None]  # sides before: filled or stated, all >= this one
        below = [stated[g] for g in names[i + 1 :] if g in stated]  # stated sides after: <= this one
        value = max([hint[i], *below])
        sides[i] = min([value, *above])
    return dict(zip(names, sides, strict=True))
