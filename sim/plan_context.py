"""What every grasp candidate of one object shares, and the per-plan params the trial and diagnosis read.

:func:`plan_context` decides whether a one-hand grasp across ``c`` is feasible, the notes that explain it, and
the object's force bounds (friction, the edge moment of a flat object, a side wrap's moment, a ball held over
its top: sim/PLANNER.md, rule 3). :func:`planned_force` turns them into a candidate's squeeze with its
rationale. The ``*_params`` functions give the geometry a plan carries for the trial and sim/diagnosis.py: a
round side's diameter, a draping sheet's held strip, a table edge's depths, an edge lever's finger lead.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sim.grasps import (
    BALL_MAX_ONE_HAND_CM,
    FINGER_LEAD_PARAM,
    HAND_MAX_APERTURE_CM,
    drapes,
    edge_depth_cm,
    edge_grip_in_cm,
    edge_lever_lead_cm,
    edge_overhang_cm,
    is_flat_grasp,
    sheet_held_cm,
)
from sim.grip_force import (
    BALL_FINGER_CONTACT_DEG,
    MIN_GRIP_FORCE_N,
    SAFETY_FACTOR,
    WRAP_REACH_CM,
    ball_over_top_force,
    edge_grip_force,
    required_grip_force,
    wrap_moment_force,
)
from sim.planned_object import PlannedObject
from sim.programs import HandProgram

__all__ = [
    "TYPICAL_MAX_WIDTH_CM",
    "PlanContext",
    "edge_params",
    "lever_params",
    "over_top_ball_force",
    "plan_context",
    "planned_force",
    "round_across_params",
    "sheet_params",
]

#: Feix et al. 2014: 96 % of grasp locations are 7 cm wide or less; beyond this the hand wraps or spans.
TYPICAL_MAX_WIDTH_CM = 7.0


@dataclass(frozen=True)
class PlanContext:
    """What every candidate of one object shares: the object, its width notes and its two force bounds."""

    o: PlannedObject
    feasible: bool
    notes: tuple[str, ...]
    base_force: float
    edge_force: float
    wrap_force: float
    ball_force: float = 0.0  # a wrap from above of a ball wider than the span, held over its top


def over_top_ball_force(o: PlannedObject) -> float | None:
    """The squeeze of a wrap from above holding ``o`` over its top (sim/grip_force.py ball_over_top_force)
    when it is a ball (a sphere body) wider than the hand's span and at most :data:`BALL_MAX_ONE_HAND_CM`,
    whose friction lets a squeeze lift it; else None."""
    if not HAND_MAX_APERTURE_CM < o.c_cm <= BALL_MAX_ONE_HAND_CM or o.shape != "radial":
        return None
    if o.body().form != "sphere":
        return None
    return ball_over_top_force(o.mass_g, o.friction, o.fragility)


def plan_context(o: PlannedObject) -> PlanContext:
    """Feasibility of a one-hand grasp across ``c``, the notes it gives, and the force bounds."""
    width = o.c_cm
    notes = list(o.assumptions)
    ball_force = over_top_ball_force(o)
    feasible = width <= HAND_MAX_APERTURE_CM or ball_force is not None
    if ball_force is not None:
        notes.append(
            f"a ball wider than the hand's {HAND_MAX_APERTURE_CM:g} cm span (up to {BALL_MAX_ONE_HAND_CM:g} cm): "
            "held from above over its top, the thumb at its near side, the fingers curled over its far side"
        )
    if not feasible:
        notes.append(
            f"every side is wider than the hand's {HAND_MAX_APERTURE_CM:g} cm span (smallest {width:g} cm): "
            "needs two hands; the best one-hand option is listed but flagged infeasible"
        )
    elif width > TYPICAL_MAX_WIDTH_CM:
        notes.append(
            f"grasped width {width:g} cm is over 7 cm, wider than 96 % of human grasp locations (Feix 2014)"
        )
    base_force = required_grip_force(o.mass_g, o.friction, o.fragility)
    flat = is_flat_grasp(o.c_cm, o.b_cm)  # across the table edge: its middle side, or its length (a key)
    edge_force = edge_grip_force(o.mass_g, edge_depth_cm(o.a_cm, o.b_cm), o.fragility) if flat else 0.0
    # A side wrap of a deep object (not a flat one: that is taken at a table edge) holds the weight's moment.
    wrap_force = 0.0 if edge_force else wrap_moment_force(
        o.mass_g, o.b_cm, o.friction, o.fragility, squeezable=o.rigidity == "squeezable"
    )
    return PlanContext(o, feasible, tuple(notes), base_force, edge_force, wrap_force, ball_force or 0.0)


def planned_force(ctx: PlanContext, program: HandProgram, rationale: list[str]) -> tuple[float, float]:
    """The squeeze to plan (before the capacity check), with the rationale lines that explain it, and the
    squeeze the ranking judges: without the side wrap's moment term, which only wraps are given (a pinch
    from above hangs the weight under the grip), so that a heavy deep object's wraps are not ranked below
    grasps whose moment was never counted."""
    o = ctx.o
    force = ctx.base_force
    if o.rigidity == "squeezable":
        force = round(max(MIN_GRIP_FORCE_N, force * 0.8), 2)
        rationale.append("squeezable: a softer grip (it deforms to the fingers, more contact area)")
    if ctx.edge_force > force:
        force = ctx.edge_force
        depth = edge_depth_cm(o.a_cm, o.b_cm)
        rationale.append(
            f"flat: picked up at its edge, the pads {edge_grip_in_cm(depth):.3g} cm in and its centre of mass "
            f"{depth / 2:.3g} cm in; the squeeze must hold the moment of its weight: {ctx.edge_force:g} N"
        )
    if program.control == "wrap" and program.approach == "top" and ctx.ball_force > force:
        force = ctx.ball_force
        rationale.append(
            f"over its top: the fingers press {BALL_FINGER_CONTACT_DEG:g} deg above its far equator, pushing it "
            f"down, and the thumb at its near one; the squeeze must carry its weight at both friction limits: "
            f"{ctx.ball_force:g} N"
        )
    ranked = force
    if program.control == "wrap" and program.approach == "side" and ctx.wrap_force > force:
        force = ctx.wrap_force
        rationale.append(
            f"deep: {o.b_cm:g} cm along the approach, its centre of mass beyond the wrap's {WRAP_REACH_CM:g} cm; "
            f"the squeeze must hold the moment of its weight: {ctx.wrap_force:g} N"
        )
    rationale.append(
        f"grip {force:g} N = m g SF / (2 mu) with m = {o.mass_g:.0f} g, mu = {o.friction:g} ({o.material or 'unknown'}, "
        f"{o.texture or 'unknown'} texture), SF = {SAFETY_FACTOR.get(o.fragility, 2.4):g} ({o.fragility})"
    )
    return force, ranked


def round_across_params(o: PlannedObject, hold: dict[str, Any] | None) -> dict[str, float]:
    """``{"round_across_cm": diameter}`` when the grasped side is round (a cylinder lying on its side,
    grasped across its diameter: a battery, a marker), else {}; sim/diagnosis.py reads it to tell a rod
    pressed into the table from a slip (grasp-small)."""
    if hold:
        return {}
    body = o.body()
    if body.form != "cylinder" or "c" not in body.round_dims:
        return {}
    return {"round_across_cm": round(o.c_cm, 3)}


def sheet_params(ctx: PlanContext, hold: dict[str, Any] | None) -> dict[str, float]:
    """For a floppy sheet the trial drapes (sim/sheet.py ``is_sheet``: floppy, flat at a table edge, a plain
    box body): the held strip's depth behind the edge, where the pads press, and the grams that hang from
    it; sim/diagnosis.py reads them instead of the rigid plate's edge moment (grasp-small)."""
    o = ctx.o
    if hold or not ctx.edge_force or not drapes(o.rigidity, o.material):
        return {}
    body = o.body()
    if not (len(body.parts) == 1 and body.parts[0].geom == "box"):
        return {}
    depth = edge_depth_cm(o.a_cm, o.b_cm)
    held = sheet_held_cm(depth, edge_overhang_cm(depth))
    return {
        "sheet_held_cm": round(held, 3),
        "sheet_grip_in_cm": round(edge_grip_in_cm(depth), 3),
        "sheet_hanging_g": round(o.mass_g * (depth - held) / depth, 1),
    }


def edge_params(ctx: PlanContext, hold: dict[str, Any] | None) -> dict[str, float]:
    """For a flat object picked up at a table edge (rule 3): the depth that lies across the edge, how far it
    overhangs and how far in from its rim the pads press (sim/grasps.py, the trial's geometry);
    sim/diagnosis.py reads them to say why a pinch there closed without holding a coin (grasp-odd)."""
    o = ctx.o
    if hold or not ctx.edge_force:
        return {}
    depth = edge_depth_cm(o.a_cm, o.b_cm)
    return {
        "edge_depth_cm": round(depth, 3),
        "edge_overhang_cm": round(edge_overhang_cm(depth), 3),
        "edge_grip_in_cm": round(edge_grip_in_cm(depth), 3),
    }


def lever_params(
    ctx: PlanContext, program: HandProgram, hold: dict[str, Any] | None, force_ok: bool, squeeze: float
) -> dict[str, float]:
    """An edge lever hold (rule 3): a pinch of a rigid flat object whose moment at the table edge needs more
    than the pinch can squeeze (the pads at one depth carry it only by their patches, ``2 F r``) puts the
    finger pads under it deeper than the thumb on top, by the lead whose couple ``F L`` carries that moment
    at the planned squeeze (sim/grasps.py ``edge_lever_lead_cm``; sim/hand.py extends the fingers)."""
    o = ctx.o
    if hold or force_ok or not ctx.edge_force or program.control != "pinch" or drapes(o.rigidity, o.material):
        return {}
    return {FINGER_LEAD_PARAM: edge_lever_lead_cm(o.mass_g, edge_depth_cm(o.a_cm, o.b_cm), squeeze)}
