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
from dataclasses import dataclass
from typing import Any

from kb.features import ObjectRecord
from sim.grasp_rules import HEAVY_MASS_G, candidates
from sim.grasps import (
    BALL_MAX_ONE_HAND_CM,
    FINGER_LEAD_PARAM,
    GRASP_TYPES,
    HAND_MAX_APERTURE_CM,
    GraspPlan,
    drapes,
    edge_depth_cm,
    edge_grip_in_cm,
    edge_lever_lead_cm,
    edge_overhang_cm,
    is_flat_grasp,
    sheet_held_cm,
    side_force_capacity,
)
from sim.grip_force import (
    BALL_FINGER_CONTACT_DEG,
    EDGE_PAD_LEVER_CM,
    GRAVITY,
    MIN_GRIP_FORCE_N,
    SAFETY_FACTOR,
    WRAP_REACH_CM,
    ball_over_top_force,
    edge_grip_force,
    required_grip_force,
    wrap_moment_force,
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
PLANNER_VERSION = "15"  # 15: a flat object laid by its length across the edge gets fingers by its width; 14: a squeezable deep object's side wrap squeezed for half the friction lever; 13: a ball up to 15 cm held over its top from above; 12: an edge lever hold for heavy flat objects; 11: a peaked cap by its brim; 10: no power sphere for a heavy box; 9: a pan held by its handle first; 8: unfit ranked down

#: Feix et al. 2014: 96 % of grasp locations are 7 cm wide or less; beyond this the hand wraps or spans.
TYPICAL_MAX_WIDTH_CM = 7.0
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
#: on a heavy pan); a lighter one near the handle's end (sim/world.py ``HANDLE_END_MARGIN_CM``).
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


@dataclass(frozen=True)
class _Context:
    """What every candidate of one object shares: the object, its width notes and its two force bounds."""

    o: PlannedObject
    feasible: bool
    notes: tuple[str, ...]
    base_force: float
    edge_force: float
    wrap_force: float
    ball_force: float = 0.0  # a wrap from above of a ball wider than the span, held over its top


def _over_top_ball_force(o: PlannedObject) -> float | None:
    """The squeeze of a wrap from above holding ``o`` over its top (sim/grip_force.py ball_over_top_force)
    when it is a ball (a sphere body) wider than the hand's span and at most :data:`BALL_MAX_ONE_HAND_CM`,
    whose friction lets a squeeze lift it; else None."""
    if not HAND_MAX_APERTURE_CM < o.c_cm <= BALL_MAX_ONE_HAND_CM or o.shape != "radial":
        return None
    if o.body().form != "sphere":
        return None
    return ball_over_top_force(o.mass_g, o.friction, o.fragility)


def _context(o: PlannedObject) -> _Context:
    """Feasibility of a one-hand grasp across ``c``, the notes it gives, and the force bounds."""
    width = o.c_cm
    notes = list(o.assumptions)
    ball_force = _over_top_ball_force(o)
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
    return _Context(o, feasible, tuple(notes), base_force, edge_force, wrap_force, ball_force or 0.0)


def _planned_force(ctx: _Context, program: HandProgram, rationale: list[str]) -> tuple[float, float]:
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


def _plan(
    ctx: _Context, rank: int, grasp_type: str, reason: str, program: HandProgram, hold: dict[str, Any] | None = None
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
    force, _ranked = _planned_force(ctx, program, rationale)
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
    lever = _lever(ctx, program, hold, force_ok, force)
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
            **_round_across(o, hold),
            **_sheet(ctx, hold),
            **_edge(ctx, hold),
            **lever,
            **{k: v for k, v in (hold or {}).items() if k not in ("grasped_dim", "approach")},
        },
    )


def _round_across(o: PlannedObject, hold: dict[str, Any] | None) -> dict[str, float]:
    """``{"round_across_cm": diameter}`` when the grasped side is round (a cylinder lying on its side,
    grasped across its diameter: a battery, a marker), else {}; sim/diagnosis.py reads it to tell a rod
    pressed into the table from a slip (grasp-small)."""
    if hold:
        return {}
    body = o.body()
    if body.form != "cylinder" or "c" not in body.round_dims:
        return {}
    return {"round_across_cm": round(o.c_cm, 3)}


def _sheet(ctx: _Context, hold: dict[str, Any] | None) -> dict[str, float]:
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


def _edge(ctx: _Context, hold: dict[str, Any] | None) -> dict[str, float]:
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


def _lever(
    ctx: _Context, program: HandProgram, hold: dict[str, Any] | None, force_ok: bool, squeeze: float
) -> dict[str, float]:
    """An edge lever hold (rule 3): a pinch of a rigid flat object whose moment at the table edge needs more
    than the pinch can squeeze (the pads at one depth carry it only by their patches, ``2 F r``) puts the
    finger pads under it deeper than the thumb on top, by the lead whose couple ``F L`` carries that moment
    at the planned squeeze (sim/grasps.py ``edge_lever_lead_cm``; sim/hand.py extends the fingers)."""
    o = ctx.o
    if hold or force_ok or not ctx.edge_force or program.control != "pinch" or drapes(o.rigidity, o.material):
        return {}
    return {FINGER_LEAD_PARAM: edge_lever_lead_cm(o.mass_g, edge_depth_cm(o.a_cm, o.b_cm), squeeze)}


def _handle_hold(ctx: _Context) -> dict[str, Any] | None:
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


def _handle_plan(ctx: _Context, hold: dict[str, Any]) -> GraspPlan:
    """The handle hold as a plan: the friction bound on the handle, not the body's edge or wrap moment
    (the pan hangs under the wrap; the trial's pushes test the moment)."""
    hctx = _Context(ctx.o, True, ctx.notes, ctx.base_force, 0.0, 0.0)
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


def _brim_plan(ctx: _Context) -> GraspPlan | None:
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
    plan = _plan(_Context(o, True, o.assumptions, ctx.base_force, 0.0, 0.0), 0, BRIM_GRASP, reason,
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
    ctx = _context(resolve_features(obj))
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
