"""One grasp trial in MuJoCo: pre-shape, approach, close to the planned force, lift, hold, perturb.

Protocol (the phases and their constants are in sim/runner.py; sim/PHYSICS.md explains them):

1. Build a world for this object and plan (sim/world.py): a table (top at z = 0), the object resting on it with the
   grasped dimension along world y (the hand's opposition axis), the hand above it (``top``) or beside it
   (``side``), pre-shaped to the plan's aperture. If the pre-shaped hand, at its grasp pose, already
   overlaps the object by more than :data:`PENETRATION_TOL_M`, the trial is a failure: the hand would
   start inside the object.
2. Settle, then approach 6 cm along the approach direction to the grasp pose.
3. Close: digit targets ramp to beyond contact; each actuator's force limit is the torque for its share
   of the planned grip force (sim/hand.py: grasp_targets).
4. Lift the wrist 10 cm; hold; then push the object with a force of its own weight (m g) along +x, -x,
   +y, -y, +z, -z in turn (as DexGraspBench does; gravity stays on).
5. Success when, from the end of closing to the end of the perturbations, the object moved less than
   5 cm and turned less than 15 degrees relative to the palm, and it was lifted.

A diverged simulation (NaN or Inf in the state, or any MuJoCo warning counter) is an ``error`` outcome
(:class:`kb.errors.PhysicsError` inside), never a success. The seed only adds small noise to the wrist's
start (sigma 1 mm) and the pre-shape (sigma 0.01 rad); the same seed gives the same result.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Any

import mujoco
import numpy as np

from kb.errors import PhysicsError
from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import HAND_MAX_APERTURE_CM, GraspPlan
from sim.programs import program_for
from sim.protocols import DEFAULT_PROTOCOL, Protocol, protocol_named
from sim.runner import (  # noqa: F401 - re-exported
    LIFT_M,
    MAX_ROTATION_DEG,
    MAX_SLIP_CM,
    PERTURBATION_DIRECTIONS,
    Runner,
    beyond_limits,
    check_physics,
)
from sim.slide import slide_and_pinch, slides
from sim.world import PENETRATION_TOL_M, TrialWorld, build_world

__all__ = [
    "LIFT_M",
    "MAX_ROTATION_DEG",
    "MAX_SLIP_CM",
    "PERTURBATION_DIRECTIONS",
    "TrialResult",
    "TrialWorld",
    "beyond_limits",
    "build_world",
    "check_physics",
    "run_six_direction_trial",
    "run_trial",
]

#: The fraction of the lift (sim/runner.py LIFT_M) the object must follow to count as lifted.
LIFTED_FRACTION = 0.5
SIMULATOR = f"mujoco {mujoco.__version__}"


@dataclass
class TrialResult:
    """The outcome of one trial. Lengths in cm, angles in degrees, forces in N, times in s.

    ``outcome`` is 'success', 'failure' (the physics ran and the grasp did not hold) or 'error' (the
    simulation diverged or could not run; never counted as either). ``slip_cm`` and ``rotation_deg`` are
    the object's largest displacement and turn relative to the palm from the end of closing on;
    ``grip_force_n`` the measured squeeze: half the total normal force between hand and object (both
    sides of the opposition axis push), averaged over the hold, comparable to the plan's grip force;
    ``max_contact_force_n`` the largest normal force of a single contact over the trial;
    ``perturbation`` maps each direction pushed to the displacement (relative to the palm) it caused.
    """

    object_name: str
    grasp_type: str
    family: str
    seed: int
    outcome: str
    success: bool
    reason: str
    program: str = ""  # the hand program that ran (sim/programs.py); merged types share one
    slip_cm: float = 0.0
    rotation_deg: float = 0.0
    grip_force_n: float = 0.0
    max_contact_force_n: float = 0.0
    lifted: bool = False
    perturbation: dict[str, float] = field(default_factory=dict)
    closed_posture: tuple[float, ...] = ()  # digit joint angles (rad, ACTUATOR_NAMES order) after closing
    sim_time_s: float = 0.0
    wall_time_s: float = 0.0
    simulator: str = SIMULATOR
    hand_version: str = H.HAND_VERSION
    protocol: str = DEFAULT_PROTOCOL  # sim/protocols.py: the success rule this result was judged by
    failed_directions: list[str] = field(default_factory=list)  # six_direction: the directions not held

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def run_trial(
    obj: ObjectRecord,
    plan: GraspPlan,
    *,
    seed: int = 0,
    stop_after: str | None = None,
    world: TrialWorld | None = None,
    protocol: str | Protocol = DEFAULT_PROTOCOL,
) -> TrialResult:
    """Run one grasp trial of ``plan`` on ``obj`` (see the module docstring for the protocol).

    Returns a :class:`TrialResult`; a diverged simulation gives ``outcome='error'``. Raises
    :class:`SimulationError` only when the trial cannot be set up (an object without usable features)
    or the protocol is unknown. ``stop_after='hold'`` ends the trial after the hold (for rendering, with
    ``world`` given). ``protocol`` names the success rule (sim/protocols.py): ``lift_push`` (pushes in
    turn) or ``six_direction`` (each direction on its own from the held state).
    """
    rule = protocol_named(protocol)
    t0 = time.perf_counter()
    if world is None:
        world = build_world(obj, plan, seed=seed)
    runner = Runner(world)
    result = TrialResult(
        object_name=obj.name,
        grasp_type=plan.grasp_type,
        family=plan.family,
        seed=int(seed),
        outcome="failure",
        success=False,
        reason="",
        program=program_for(plan.grasp_type).name,
        protocol=rule.name,
        hand_version=H.HAND_VERSION + rule.version_tag,
    )

    def finish(outcome: str, reason: str) -> TrialResult:
        result.outcome, result.success, result.reason = outcome, outcome == "success", reason
        result.slip_cm = round(runner.slip, 3)
        result.rotation_deg = round(runner.turn, 2)
        result.max_contact_force_n = round(runner.max_force, 3)
        result.closed_posture = runner.closed_posture
        if runner.hold_forces:
            result.grip_force_n = round(float(np.mean(runner.hold_forces)), 3)
        result.sim_time_s = round(float(world.data.time), 4)
        result.wall_time_s = round(time.perf_counter() - t0, 4)
        return result

    try:
        depth = runner.start_penetration_m()
        if depth > PENETRATION_TOL_M:
            return finish("failure", _inside_reason(plan, depth))
        before = world.data.xpos[world.object_body].copy()
        if slides(world):  # too shallow to pinch where it lies: slid out over the edge first (sim/slide.py)
            slide_and_pinch(runner, world)
        else:
            runner.approach()
            before = world.data.xpos[world.object_body].copy()
            runner.close()
        if not world.hand_contacts()[0].size:
            return finish("failure", _no_contact_reason(world, before))
        rose = runner.lift()
        result.lifted = rose >= LIFTED_FRACTION * LIFT_M / H.CM
        if not result.lifted:
            return finish("failure", f"not lifted: the object rose {rose:.1f} cm of {LIFT_M / H.CM:.0f}")
        if rule.beyond(runner.slip, runner.turn):
            return finish("failure", _slip_reason(runner, "the lift", rule))
        runner.hold()
        if rule.beyond(runner.slip, runner.turn):
            return finish("failure", _slip_reason(runner, "the hold", rule))
        if stop_after == "hold":
            return finish("success", "stopped after the hold")
        if rule.raise_m:
            runner.lift(rule.raise_m, above_m=LIFT_M)
            if rule.beyond(runner.slip, runner.turn):
                return finish("failure", _slip_reason(runner, "the second rise", rule))
        if rule.independent:
            failed = _push_each(runner, result, rule)
            if failed:
                return finish("failure", failed)
        else:
            for direction in PERTURBATION_DIRECTIONS:
                result.perturbation[direction] = round(runner.perturb(direction), 3)
                if rule.beyond(runner.slip, runner.turn):
                    return finish("failure", _slip_reason(runner, f"the {direction} push", rule))
    except PhysicsError as exc:
        return finish("error", str(exc))
    each = " each on its own from the held state" if rule.independent else ""
    return finish(
        "success",
        f"held: moved {runner.slip:.2f} cm and turned {runner.turn:.1f} deg relative to the palm "
        f"under pushes of its weight ({world.obj.weight_n:.2f} N){each}",
    )


def run_six_direction_trial(obj: ObjectRecord, plan: GraspPlan, *, seed: int = 0) -> TrialResult:
    """:func:`run_trial` under the ``six_direction`` protocol (a module-level callable the validation
    worker can name: ``sim.trial:run_six_direction_trial``)."""
    return run_trial(obj, plan, seed=seed, protocol="six_direction")


def _push_each(runner: Runner, result: TrialResult, rule: Protocol) -> str:
    """Push along each direction on its own, each from the state after the hold (restored exactly: MuJoCo's
    full integration state), measuring from the end of closing. Records each direction's displacement in
    ``result.perturbation`` and the ones not held in ``result.failed_directions``; the largest translation
    and rotation over all directions become the runner's ``slip`` and ``turn``. Returns the failure reason,
    or "" when every direction held."""
    m, d = runner.m, runner.d
    spec = mujoco.mjtState.mjSTATE_INTEGRATION
    held = np.empty(mujoco.mj_stateSize(m, spec))
    mujoco.mj_getState(m, d, held, spec)
    slip0, turn0, force0 = runner.slip, runner.turn, runner.max_force
    worst_slip, worst_turn, worst_force = slip0, turn0, force0
    first = ""
    for direction in PERTURBATION_DIRECTIONS:
        mujoco.mj_setState(m, d, held, spec)
        mujoco.mj_forward(m, d)  # positions derived from the restored state, read before the first step
        runner.slip, runner.turn = slip0, turn0
        result.perturbation[direction] = round(runner.perturb(direction), 3)
        worst_slip, worst_turn = max(worst_slip, runner.slip), max(worst_turn, runner.turn)
        worst_force = max(worst_force, runner.max_force)
        if rule.beyond(runner.slip, runner.turn):
            result.failed_directions.append(direction)
            first = first or _slip_reason(runner, f"the {direction} push", rule)
    runner.slip, runner.turn, runner.max_force = worst_slip, worst_turn, worst_force
    if not first:
        return ""
    others = len(result.failed_directions) - 1
    return first + (f" (and {others} more of 6 directions)" if others else "")


def _inside_reason(plan: GraspPlan, depth_m: float) -> str:
    """The hand starts inside the object; when the plan says the hand cannot open round it (every side wider
    than its span, or this grasp's opening), the reason says so: an aperture problem, not a posture's."""
    reason = f"hand starts inside the object ({depth_m * 1000:.1f} mm deep at the grasp pose)"
    p = plan.params
    width = p.get("width_cm")
    if p.get("feasible") is False:
        return (
            f"{reason}: its smallest side ({width:g} cm) is wider than the hand's "
            f"{HAND_MAX_APERTURE_CM:g} cm span, it needs two hands"
        )
    if p.get("fits_aperture") is False:
        opening = p.get("opening_needed_cm")
        span = HAND_MAX_APERTURE_CM
        return f"{reason}: this grasp needs a {opening:g} cm opening round {width:g} cm; the hand opens {span:g}"
    return reason


#: An object that moved this far (cm) while the digits closed without holding it was pushed away by them.
PUSHED_AWAY_CM = 0.5


def _no_contact_reason(world: TrialWorld, before: np.ndarray) -> str:
    """Why no digit touches the object after closing: they closed past it, or they pushed it away (out of
    the pinch, and off the table when it fell below the table top)."""
    after = world.data.xpos[world.object_body]
    moved = float(np.linalg.norm(after - before)) / H.CM
    if moved < PUSHED_AWAY_CM:
        return "no contact after closing: the digits missed the object"
    if after[2] < 0.0:  # below the table top: it fell off the table's edge
        return "no contact after closing: the digits pushed the object out of the grasp and off the table"
    return f"no contact after closing: the digits pushed the object {moved:.1f} cm out of the grasp"


def _slip_reason(runner: Runner, phase: str, rule: Protocol) -> str:
    if runner.slip >= rule.max_translation_cm:
        limit = rule.max_translation_cm
        return f"slipped {runner.slip:.1f} cm (limit {limit:g}) relative to the palm during {phase}"
    limit = rule.max_rotation_deg
    return f"turned {runner.turn:.1f} deg (limit {limit:g}) relative to the palm during {phase}"
