"""Grasp planner: ranked candidate grasps for an object, from its features, with the rules that chose them.

The rules, and the published findings they rest on, are written down in ``sim/PLANNER.md``. In short:

1. **Grasped dimension.** Grasp across the smallest dimension ``c`` (Feix et al. 2014: the smallest major
   dimension is grasped in 94 % of grasps), unless it is wider than the hand can open.
2. **Family first** (power, intermediate, precision), from mass and grasped width, the strongest object
   predictors of grasp type (Feix et al. 2014, 2014b): heavy or wide objects get power grasps, small light
   ones precision grasps; thin small flat objects (keys, cards) the lateral pinch.
3. **Type within the family** from shape (Cutkosky 1989: prismatic versus circular; disk versus sphere)
   and size (wrap diameter; how many fingers fit along the object).
4. **Force**: the normal force a two-sided grip needs to hold the weight against friction,
   ``F >= m g SF / (2 mu)``, with friction from material and texture (sim/friction.py) and a safety factor
   lowered for fragile objects (Johansson & Westling 1984).
5. **Feasibility**: the aperture is capped by the hand's span; a plan the hand cannot open for, or whose
   force exceeds what its fingers can give, is kept but flagged and ranked down.

Unknown features get documented defaults (:data:`DEFAULTS`) and every assumption is named in the plan's
rationale, so that ``plan_grasps`` always answers for any valid feature set.
"""


from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from kb.features import ObjectRecord
from sim.grasp_rules import HEAVY_MASS_G, candidates
from sim.grasps import (
    FINGER_LEAD_PARAM,
    GRASP_TYPES,
    HAND_MAX_APERTURE_CM,
    GraspPlan,
    edge_grip_in_cm,
    side_force_capacity,
)
from sim.grip_force import (
    EDGE_PAD_LEVER_CM,
    GRAVITY,
    MIN_GRIP_FORCE_N,
    SAFETY_FACTOR,
    edge_grip_force,
    required_grip_force,
)
from sim.plan_context import (
    PlanContext,
    edge_params,
    lever_params,
    plan_context,
    planned_force,
    round_across_params,
    sheet_params,
)
from sim.planned_object import DEFAULTS, PlannedObject, resolve_features
from sim.programs import HandProgram, program_for

# The planner's parts, re-exported here: the object it sees (sim/planned_object.py), the rules
# (sim/grasp_rules.py) and the grip force (sim/grip_force.py); this module ranks and explains.
__all__ = [
    "DEFAULTS",
    "EDGE_PAD_LEVER_CM",
    "GRAVITY",
    "HAND_MAX_APERTURE_CM",
    "HEAVY_MASS_G",
    "PLANNER_VERSION",
    "SAFETY_FACTOR",
    "PlannedObject",
    "best_grasp",
    "plan_grasps",
    "edge_grip_force",
    "required_grip_force",
    "resolve_features",
]

#: Stored with every validation result; bump when the rules change what they choose.
PLANNER_VERSION = "17"  # 17: a thin rod of 50-250 g in the lateral pinch; 16: a light paper sheet pinched flat by thumb and two fingers; 15: a flat object laid by its length across the edge gets fingers by its width; 14: a squeezable deep object's side wrap squeezed for half the friction lever; 13: a ball up to 15 cm held over its top from above; 12: an edge lever hold for heavy flat objects; 11: a peaked cap by its brim; 10: no power sphere for a heavy box; 9: a pan held by its handle first; 8: unfit ranked down

#: Fingertip grasps open at least this much wider than the object (cm): people's maximum grip aperture
#: during the reach exceeds the object by a few centimetres (Jeannerod 1984, "The timing of natural
#: prehension movements"). 1 cm left the pads' capsules brushing round objects and boxes on the way down
#: (pinched higher, they squeezed them out); 2 cm: 127 instead of 124 of the seed catalog's best plans held.
PRECISION_APERTURE_MARGIN_CM = 2.0
#: Score factors of a candidate whose needed squeeze exceeds its grasp's capacity, and of one the hand cannot
#: open round (needed opening over the span). The order does not rest on them: plan_grasps ranks every
#: candidate that fits above every one that does not, then those within capacity above those beyond it.
FORCE_PENALTY = 0.4
APERTURE_PENALTY = 0.2
#: A pan (an object whose kind has a long handle, sim/bodies.py) is picked up by its handle in a
#: small-diameter wrap from above (Feix 2016 type 2; what people do with a frying pan: PLANNER.md).
HANDLE_GRASP = "heavy_wrap_small_diameter"
#: A pan at least this heavy is held at the middle of its handle, nearer its centre of mass (people choke up
#: on a heavy pan); a lighter one near the handle's end (sim/placement.py ``HANDLE_END_MARGIN_CM``).
HANDLE_MIDDLE_MIN_MASS_G = HEAVY_MASS_G
#: A peaked cap is picked up by its brim: thumb on top, four fingers under it (Feix 2016 type 6, prismatic
#: 4 finger; the brim is 17 cm wide), the strongest pinch (60 N) against its crown's moment.
BRIM_GRASP = "thumb_4_finger"


def opening_needed(grasp_type: str, width_cm: float) -> float:
    """The opening a grasp needs before closing: the grasped width plus a margin (more for wraps, which
    close around). A candidate fits the hand when this is at most :data:`HAND_MAX_APERTURE_CM`."""
    margin = (
        max(1.5, 0.25 * width_cm)
        if GRASP_TYPES[grasp_type] == "power"
        else max(PRECISION_APERTURE_MARGIN_CM, 0.2 * width_cm)
    )
    return round(width_cm + margin, 2)


def _aperture(grasp_type: str, width_cm: float) -> float:
    """Opening before closing, capped by the hand's span."""
    return round(min(HAND_MAX_APERTURE_CM, opening_needed(grasp_type, width_cm)), 2)


def _plan(
    ctx: PlanContext, rank: int, grasp_type: str, reason: str, program: HandProgram, hold: dict[str, Any] | None = None
) -> GraspPlan:
    """One candidate as a plan: its score from its rank, force and feasibility, and why. ``hold``: the plan
    params of a grasp of a part (a handle: its ``width_cm`` replaces the object's smallest side)."""
    o = ctx.o
    width = float(hold["width_cm"]) if hold else o.c_cm
    rationale = [reason]
    if program.merged:
        others = ", ".join(t.replace("_", " ") for t in program.grasp_types if t != grasp_type)
        rationale.append(
            f"simulated by the {program.name.replace('_', ' ')} hand program, shared with {others}: "
            "this hand (no finger abduction) cannot make them differently (sim/programs.py)"
        )
    if rank == 0 and not hold:
        rationale.append(f"grasped across its smallest side c = {width:g} cm (Feix 2014: 94 % of grasps)")
    # Score: rule order (1.0 down to 0.5), times the two penalties, so that scores fall in the order of
    # _rank_key (fit, then force, then rule order), which the ranking itself uses.
    score = max(0.5, 1.0 - 0.2 * rank)
    capacity = side_force_capacity(grasp_type)
    force, _ranked = planned_force(ctx, program, rationale)
    needed = force
    force_ok = force <= capacity
    if not force_ok:
        score *= FORCE_PENALTY
        rationale.append(f"force: needs {force:g} N, more than a {grasp_type} grasp's {capacity:g} N: ranked down")
        force = capacity
    opening = opening_needed(grasp_type, width)
    fits = opening <= HAND_MAX_APERTURE_CM
    if not fits:
        score *= APERTURE_PENALTY
        rationale.append(
            f"aperture: needs a {opening:g} cm opening round {width:g} cm, more than the hand's "
            f"{HAND_MAX_APERTURE_CM:g} cm: ranked down"
        )
    lever = lever_params(ctx, program, hold, force_ok, force)
    if lever:
        rationale.append(
            f"lever: the finger pads {lever[FINGER_LEAD_PARAM]:g} cm deeper under it than the thumb on top, so "
            f"the squeeze's couple carries the moment of its weight at the edge (fingers extended, Feix 2016's "
            f"parallel extension)"
        )
    return GraspPlan(
        grasp_type=grasp_type,
        family=GRASP_TYPES[grasp_type],
        grasped_dim=str(hold["grasped_dim"]) if hold else "c",
        aperture_cm=_aperture(grasp_type, width),
        approach=str(hold["approach"]) if hold else program.approach,  # type: ignore[arg-type]
        grip_force_n=force,
        score=round(score, 3),
        rationale=tuple(rationale) + ctx.notes,
        params={
            "width_cm": round(width, 3),
            "friction": o.friction,
            "safety_factor": SAFETY_FACTOR.get(o.fragility, 2.4),
            "required_force_n": ctx.base_force,
            "needed_force_n": needed,
            "force_within_capacity": force_ok,
            "feasible": ctx.feasible,
            "opening_needed_cm": opening,
            "fits_aperture": fits,
            "two_hands": not ctx.feasible,
            "assumed_mass_g": round(o.mass_g, 1),
            "planner_version": PLANNER_VERSION,
            "program": program.name,
            **round_across_params(o, hold),
            **sheet_params(ctx, hold),
            **edge_params(ctx, hold),
            **lever,
            **{k: v for k, v in (hold or {}).items() if k not in ("grasped_dim", "approach")},
        },
    )


def _handle_hold(ctx: PlanContext) -> dict[str, Any] | None:
    """The hold params of a pan's handle (the one the simulator builds, sim/bodies.py), or None when the
    object's kind has no long handle. A loop handle (mug, pitcher) is not held: this hand's fingers cannot
    pass through the loop without abduction (PHYSICS.md), and its body is wrapped instead."""
    from sim.bodies import HOLD_HANDLE

    body = ctx.o.body()
    handle = body.handle
    if handle is None or handle.style != "long" or body.up is None:
        return None
    across = next(d for d in "abc" if d not in (body.up, handle.dim))
    where = "middle" if ctx.o.mass_g >= HANDLE_MIDDLE_MIN_MASS_G else "end"
    # A long handle is wrapped from above (sim/world.py places the hand on it so).
    return {
        "hold": HOLD_HANDLE,
        "handle_grip": where,
        "width_cm": round(handle.width_cm, 3),
        "grasped_dim": across,
        "approach": "top",
    }


def _handle_noun(o: PlannedObject) -> str:
    """The kind noun that gave the object its long handle (sim/bodies.py HANDLE_NOUNS: a frying pan, a ladle)."""
    from sim.bodies import handle_style

    style = handle_style(o.name, o.aliases)
    return style[1] if style else "long-handled object"


def _handle_plan(ctx: PlanContext, hold: dict[str, Any]) -> GraspPlan:
    """The handle hold as a plan: the friction bound on the handle, not the body's edge or wrap moment
    (the pan hangs under the wrap; the trial's pushes test the moment)."""
    hctx = PlanContext(ctx.o, True, ctx.notes, ctx.base_force, 0.0, 0.0)
    where = "at its middle, nearer its heavy end (it is heavy)" if hold["handle_grip"] == "middle" else "near its end"
    reason = (
        f"a {_handle_noun(ctx.o)}: held by its handle ({hold['width_cm']:g} cm wide) {where}, in a small-diameter "
        "wrap from above, as people pick up a frying pan or a ladle (Feix 2016 type 2; its heavy end, the pan or "
        "the bowl, hangs beyond the grip)"
    )
    plan = _plan(hctx, 0, HANDLE_GRASP, reason, program_for(HANDLE_GRASP), hold)
    capacity = side_force_capacity(HANDLE_GRASP)
    if plan.grip_force_n >= capacity:
        return plan
    # The pan hangs beyond the grip: its weight's moment about the handle, and a push's, which the friction
    # bound does not count, are held by squeezing the handle as hard as the wrap can (measured: a 1.2 kg pan
    # held at its friction bound, 47.8 N, turned 17 deg in the sideways push; at the wrap's 60 N it holds).
    line = (
        f"handle: its heavy end's weight acts beyond the grip, so the handle is squeezed at the wrap's full "
        f"{capacity:g} N (its friction bound: {plan.grip_force_n:g} N)"
    )
    return dataclasses.replace(plan, grip_force_n=capacity, rationale=(*plan.rationale, line))


def _brim_plan(ctx: PlanContext) -> GraspPlan | None:
    """A peaked cap (sim/bodies.py ``peaked``) is picked up by its brim, a thin plate: thumb on top, four
    fingers under it, at a table edge like any flat object (rule 3). The crown hangs beyond the pads, so the
    squeeze must hold its weight's moment about them: ``F = SF m g d / (2 r)``, ``d`` from the pads to the
    body's centre of mass (the edge bound's lever ``r``, sim/grip_force.py)."""
    from sim.bodies import HOLD_PART

    o = ctx.o
    body = o.body()
    if body.form != "cap":
        return None
    brim = next(p for p in body.parts if p.name == "brim")
    length = brim.extent_cm("a")
    grip_a = brim.pos_cm[0] + length / 2.0 - edge_grip_in_cm(length)
    com_a = sum(p.mass_kg * p.pos_cm[0] for p in body.parts) / sum(p.mass_kg for p in body.parts)
    lever = max(0.0, grip_a - com_a)
    sf = SAFETY_FACTOR.get(o.fragility, SAFETY_FACTOR["medium"])
    moment = round(max(MIN_GRIP_FORCE_N, sf * o.mass_g / 1000.0 * GRAVITY * lever / (2 * EDGE_PAD_LEVER_CM)), 2)
    hold = {"hold": HOLD_PART, "part": "brim", "width_cm": round(brim.extent_cm("c"), 3), "grasped_dim": "c",
            "approach": "top", "brim_lever_cm": round(lever, 2)}  # fmt: skip
    reason = (
        f"a peaked cap: pinched by its brim ({hold['width_cm']:g} cm thin plate), thumb on top and four fingers "
        "under it, as people pick a cap up by the peak"
    )
    plan = _plan(PlanContext(o, True, o.assumptions, ctx.base_force, 0.0, 0.0), 0, BRIM_GRASP, reason,
                 program_for(BRIM_GRASP), hold)  # fmt: skip
    if moment <= plan.grip_force_n:
        return plan
    capacity = side_force_capacity(BRIM_GRASP)
    line = (
        f"brim: its crown's weight acts {lever:.3g} cm beyond the pads (its centre of mass); the squeeze must "
        f"hold that moment: {moment:g} N (F = SF m g d / (2 r), r = {EDGE_PAD_LEVER_CM:g} cm)"
    )
    params = {**plan.params, "needed_force_n": moment, "force_within_capacity": moment <= capacity}
    return dataclasses.replace(plan, grip_force_n=min(moment, capacity), rationale=(*plan.rationale, line),
                               params=params)  # fmt: skip


def _rank_key(p: GraspPlan) -> tuple[bool, bool, float]:
    """Candidates the hand can open round first, then those it can squeeze enough, then by score."""
    return (not p.params["fits_aperture"], not p.params["force_within_capacity"], -p.score)


def plan_grasps(
    obj: ObjectRecord | Mapping[str, Any], *, top: int | None = None, experience: Any = None
) -> list[GraspPlan]:
    """Ranked candidate grasps for ``obj`` (an ObjectRecord or a features mapping), best first.

    Every plan carries its rationale (the rules that chose it and the assumptions made for unknown
    features). ``top`` keeps only the first ``top`` plans. Raises InvalidFeature for invalid features.
    Each hand program is listed once: a merged type the rules reach later is dropped. ``experience`` (a
    sim.experience ``Experience``) may move a later one of the first three to the front, where the trials
    of its object class say so; None keeps the rules' order.
    """
    ctx = plan_context(resolve_features(obj))
    hold = _handle_hold(ctx)
    brim = _brim_plan(ctx)
    plans: list[GraspPlan] = [_handle_plan(ctx, hold)] if hold else [brim] if brim else []
    # Hand programs already listed (the handle hold's too): a merged type is simulated once, and results,
    # grouped by grasp type, never mix a handle hold with a grasp of the body.
    seen: set[str] = {program_for(p.grasp_type).name for p in plans}
    for rank, (grasp_type, reason) in enumerate(candidates(ctx.o), start=len(plans)):
        program = program_for(grasp_type)
        if program.name in seen:
            continue
        seen.add(program.name)
        plans.append(_plan(ctx, rank, grasp_type, reason, program))
    plans.sort(key=_rank_key)  # stable: rule order breaks ties
    if experience is not None:
        plans = experience.order(plans, ctx.o)
    return plans[:top] if top else plans


def best_grasp(obj: ObjectRecord | Mapping[str, Any]) -> GraspPlan:
    """The planner's first choice for ``obj``."""
    return plan_grasps(obj, top=1)[0]
