"""Why a grasp did not hold, in the hand's terms: aperture, mass, friction, the weight's moment, or size.

A trial says *what* happened (``not lifted``, ``slipped 9.6 cm``, ``turned 26 deg``, ``hand starts inside
the object``, ``no contact``: sim/trial.py); :func:`diagnose` says *why*, from that reason and the plan's
numbers (stored with every result: its ``params`` and grip force, sim/planner.py):

| cause | when | what it means |
|---|---|---|
| ``aperture`` | the plan is infeasible (every side wider than the hand's span), its grasp needs a wider opening than the span (``fits_aperture`` false: width plus the planner's margin), or the hand, opened for this grasp, starts inside the object | the hand cannot open round it: a setup problem, counted apart from grasp failures in the report |
| ``mass`` | the squeeze its weight needs (against friction, or against the moment of its weight at a table edge) is more than this grasp can give | too heavy for this grasp: a stronger grasp, or two hands |
| ``size`` | the digits closed without touching it | too small or thin for the pads; at a table edge, pads that press nearer its rim than their radius (the plan's ``edge_grip_in_cm``: a coin, a paper clip, whose centre of mass lets them overhang only about 1 cm) pushed it out of the pinch |
| ``pressed`` | a pinch from above did not lift a rod lying on the table (``round_across_cm`` in the plan) thinner than twice the fingertip pad's radius (:data:`PAD_TIP_RADIUS_CM`) | pads that meet it a millimetre or two above its centre line (the hand passes through the table, so nothing stops them lower; the fingers' pads are aligned at the thumb's height since programs version 3, and the AA battery's thumb-3 finger still touched 1-2 mm high) push it down into the table instead of squeezing it up |
| ``friction`` | not lifted, or slipped past the limit, with a squeeze within the grasp's strength | squeeze times friction did not carry its weight and the push |
| ``moment`` | turned past the limit with a squeeze within the grasp's strength | the weight's moment about the grip, or a push, turned it out of the pads |

A draping sheet (the plan's ``sheet_held_cm``: floppy, flat at a table edge, sim/sheet.py) is no ``mass``
cause for the rigid plate's edge moment the planner computes: only its friction bound can be; turned, it
is a ``moment`` of the hanging part's weight at the held strip's inner edge, with those numbers.

The checks run in that order: the first that applies is the cause. Report and ``grasp validate`` show it
beside the trial's reason, never instead of it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from sim.grasps import EDGE_PAD_CLEAR_CM, GRASP_TYPES, HAND_MAX_APERTURE_CM, side_force_capacity
from sim.grip_force import GRAVITY
from sim.hand_model import FINGER_BY_NAME, THUMB, TIP_TAPER
from sim.programs import program_for
from sim.task import row_details

__all__ = ["CAUSES", "PAD_TIP_RADIUS_CM", "Cause", "diagnose", "failure_cause", "is_setup_failure"]

CAUSES = ("aperture", "mass", "size", "pressed", "friction", "moment")
#: A measured squeeze under this fraction of the planned one is named in a ``moment`` cause: the turn may
#: be the hand's shortfall (a wide wrap's fingers press less than planned: the ladle's box 55 %, the
#: baseball cap 74 %), not the plan's force.
SHORT_SQUEEZE_FRACTION = 0.9
#: The smallest fingertip pad radius (cm) of the digits every pinch uses (thumb and index: the distal
#: capsule's radius, sim/hand_model.py). A pad resting on the table has its centre this high; a rod lying
#: there whose radius is smaller is touched above its centre line.
PAD_TIP_RADIUS_CM = round(min(THUMB.radius_cm, FINGER_BY_NAME["index"].radius_cm) * TIP_TAPER, 3)


@dataclass(frozen=True)
class Cause:
    """A failed grasp's cause (one of :data:`CAUSES`) and a sentence with the numbers behind it."""

    kind: str
    text: str

    def __str__(self) -> str:
        return f"{self.kind}: {self.text}"


def _num(value: Any, default: float = 0.0) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def diagnose(row: Mapping[str, Any]) -> Cause | None:
    """The cause of a failed trial row (``reason``, ``grip_force_n``, ``details.plan``), or None when it held.

    An ``error`` row (the simulation diverged) has no physical cause: its reason is returned as it is.
    """
    reason = str(row.get("reason") or "")
    outcome = row.get("outcome") or ("success" if row.get("success") else "failure")
    if outcome == "success":
        return None
    if outcome == "error":
        return Cause("error", reason or "the simulation could not run")
    plan = row_details(row).get("plan") or {}
    params = plan.get("params") or {}
    grasp = str(plan.get("grasp_type") or row.get("grasp_type") or "")
    width = _num(params.get("width_cm"))
    mass = _num(params.get("assumed_mass_g"))
    mu = _num(params.get("friction"), 0.45)
    capacity = side_force_capacity(grasp) if grasp else _num(plan.get("grip_force_n"))
    setup = _setup(params, reason, grasp, width)
    if setup is not None:
        return setup
    sheet = _sheet(params, reason, mass, capacity, grasp)
    if sheet is not None:
        return sheet
    if params.get("force_within_capacity") is False and "sheet_held_cm" not in params:
        needed = _num(params.get("needed_force_n"), _num(params.get("required_force_n")))
        return Cause(
            "mass",
            f"holding {f'its {mass:.0f} g' if mass else 'it'} needs a squeeze of {needed:g} N, more than the {capacity:g} N a "
            f"{grasp.replace('_', ' ')} gives",
        )
    if "no contact" in reason:
        return _edge_size(params, width) or Cause(
            "size", f"the digits closed past it ({width:g} cm across): too small or thin for the pads"
        )
    pressed = _pressed(plan, params, reason)
    if pressed is not None:
        return pressed
    return _held_badly(row, plan, params, reason, mass, mu, capacity)


def _setup(params: Mapping[str, Any], reason: str, grasp: str, width: float) -> Cause | None:
    """An ``aperture`` cause when the trial could not start as planned: no one-hand grasp, an opening wider
    than the hand's span, or the hand inside the object."""
    if params.get("feasible") is False:
        return Cause(
            "aperture", f"its smallest side ({width:g} cm) is wider than the hand's {HAND_MAX_APERTURE_CM:g} cm span: it needs two hands"
        )
    if params.get("fits_aperture") is False:
        opening = _num(params.get("opening_needed_cm"))
        return Cause(
            "aperture",
            f"a {grasp.replace('_', ' ')} round {width:g} cm needs a {opening:g} cm opening, more than the hand's "
            f"{HAND_MAX_APERTURE_CM:g} cm: a setup problem, not a grasp that slipped",
        )
    if "inside" in reason:
        return Cause("aperture", f"the hand, opened for a {grasp.replace('_', ' ')}, cannot get round it ({width:g} cm across)")
    return None


def _held_badly(
    row: Mapping[str, Any], plan: Mapping[str, Any], params: Mapping[str, Any], reason: str, mass: float, mu: float,
    capacity: float,
) -> Cause:
    """The cause of a grasp that closed on the object and lost it: its crown's moment (a cap by its brim),
    a moment that turned it, else friction."""
    squeeze = _num(row.get("grip_force_n")) or _num(plan.get("grip_force_n"))
    weight = mass / 1000.0 * GRAVITY
    lever = _num(params.get("brim_lever_cm"))
    if lever and reason.startswith(("slipped", "turned")):  # the crown swung down about the pinch
        return Cause(
            "moment",
            f"held by its brim, its crown's weight acts {lever:g} cm beyond the pads ({weight * lever:.3g} N cm, "
            "doubled by the downward push); the pads' couple did not hold it and the crown swung down about the "
            f"pinch (so far out, a turn of {math.degrees(5.0 / lever):.0f} deg moves the cap's centre the 5 cm slip "
            "limit: a slip here is that swing); a "
            "person lets a cap hang from its brim, which the trial's 15 deg limit does not allow",
        )
    if reason.startswith("turned"):
        planned = _num(plan.get("grip_force_n"))
        short = (
            f"; the hand gave {squeeze:.3g} N of the {planned:g} N planned"
            if planned and _num(row.get("grip_force_n")) and squeeze < SHORT_SQUEEZE_FRACTION * planned
            else ""
        )
        return Cause(
            "moment",
            f"its weight's moment about the grip or a push turned it out of the pads (squeeze {squeeze:.3g} N, "
            f"friction {mu:g}, within the grasp's {capacity:g} N{short})",
        )
    return Cause(
        "friction",
        f"a squeeze of {squeeze:.3g} N at friction {mu:g} carries about {2 * mu * squeeze:.3g} N; its weight is "
        f"{weight:.3g} N and the pushes add as much again",
    )


def _edge_size(params: Mapping[str, Any], width: float) -> Cause | None:
    """A flat object at a table edge whose pads could reach in from its rim less than their own radius (the
    plan's ``edge_*`` params, sim/planner.py): its centre of mass must stay on the table, so a coin overhangs
    about 1 cm and the pads, kept clear of the table's edge, press within a few millimetres of its rim."""
    grip_in = _num(params.get("edge_grip_in_cm"), -1.0)
    if not 0.0 <= grip_in < PAD_TIP_RADIUS_CM:
        return None
    depth, overhang = _num(params.get("edge_depth_cm")), _num(params.get("edge_overhang_cm"))
    return Cause(
        "size",
        f"at the table edge its centre of mass lets it overhang only {overhang:.3g} cm of its {depth:g} cm, "
        f"so the pads, kept {EDGE_PAD_CLEAR_CM:g} cm off the table's edge, press {grip_in:.3g} cm in from its "
        "rim, "
        f"less than their own {PAD_TIP_RADIUS_CM:g} cm radius: closing that near the rim of a {width:g} cm "
        "thin plate, they pushed it out of the pinch. A person slides it out over the edge under a fingertip "
        "first, or lifts it by its rim with the nails; this hand has no nails, and its fixed wrist and the "
        "trial's one approach do not slide it",
    )


def _sheet(params: Mapping[str, Any], reason: str, mass: float, capacity: float, grasp: str) -> Cause | None:
    """A draping sheet (the plan's ``sheet_held_cm``, sim/sheet.py): the planner's edge moment is a rigid
    plate's, which the trial's sheet does not have, so it is no ``mass`` cause; the friction bound is.
    A turn is the hanging part's pull at the held strip's inner edge, behind the pads."""
    if "sheet_held_cm" not in params:
        return None
    bound = _num(params.get("required_force_n"))
    if bound > capacity:
        return Cause("mass", f"holding its {mass:.0f} g needs a squeeze of {bound:g} N against friction, more than the "
                     f"{capacity:g} N a {grasp.replace('_', ' ')} gives")  # fmt: skip
    if not reason.startswith("turned"):
        return None
    held, grip_in = _num(params.get("sheet_held_cm")), _num(params.get("sheet_grip_in_cm"))
    hanging = _num(params.get("sheet_hanging_g"))
    lever = held - grip_in
    return Cause(
        "moment",
        f"a draping sheet: {hanging:.0f} g of it hang from the held strip's inner edge, {lever:.3g} cm behind the "
        f"pads ({grip_in:.3g} cm in from its edge): {hanging / 1000 * GRAVITY * lever:.3g} N cm, that turned the "
        f"strip in the pads (the "
        f"planner's {_num(params.get('needed_force_n')):g} N is a rigid plate's edge moment, which a sheet does "
        "not have); a person gathers it into the fist, which this fixed-wrist hand at the table edge does not do",
    )


def _pressed(plan: Mapping[str, Any], params: Mapping[str, Any], reason: str) -> Cause | None:
    """A pinch from above that did not lift a rod lying on the table, thinner than two pad radii."""
    diameter = _num(params.get("round_across_cm"))
    grasp = str(plan.get("grasp_type") or "")
    pinch = bool(grasp) and grasp in GRASP_TYPES and program_for(grasp).control != "wrap"
    if not (reason.startswith("not lifted") and pinch and plan.get("approach") == "top" and diameter):
        return None
    if diameter / 2.0 >= PAD_TIP_RADIUS_CM:
        return None
    return Cause(
        "pressed",
        f"lying on the table, its {diameter:g} cm round side is thinner than two fingertip pads' radius "
        f"({2 * PAD_TIP_RADIUS_CM:g} cm): on so small a curve, pads that meet it even a millimetre or two "
        "above its centre line push it down into the table instead of squeezing it up (a person rolls it or "
        "slides a nail under it)",
    )


def failure_cause(row: Mapping[str, Any]) -> str:
    """:func:`diagnose` as one line (``"mass: ..."``); the reason itself for a held or unexplained row."""
    cause = diagnose(row)
    return str(cause) if cause is not None else str(row.get("reason") or "held")


def is_setup_failure(row: Mapping[str, Any]) -> bool:
    """Did the trial fail because the hand could not be set up round the object (cause ``aperture``)?
    Such a trial says nothing about how well the grasp holds: the report counts it apart."""
    cause = diagnose(row)
    return cause is not None and cause.kind == "aperture"
