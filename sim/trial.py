"""One grasp trial in MuJoCo: pre-shape, approach, close to the planned force, lift, hold, perturb.

Protocol (constants below; sim/PHYSICS.md explains them):

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

import math
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import mujoco
import numpy as np

from kb.errors import PhysicsError
from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import GraspPlan
from sim.programs import program_for
from sim.world import APPROACH_M, PENETRATION_TOL_M, TrialWorld, build_world

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
    "run_trial",
]

GRAVITY = 9.81
#: Success thresholds, relative to the palm (the issue's; DexGraspBench uses similar ones).
MAX_SLIP_CM = 5.0
MAX_ROTATION_DEG = 15.0
#: Lift height and the fraction of it the object must follow to count as lifted.
LIFT_M = 0.10
LIFTED_FRACTION = 0.5
#: Phase durations (s). Closing ramps for CLOSE_RAMP_S then settles; each perturbation lasts PUSH_S.
SETTLE_S = 0.04
APPROACH_S = 0.3
TOUCH_S = 0.2  # precision grasps only: pads travel to the object's sides together
CLOSE_RAMP_S = 0.25
CLOSE_HOLD_S = 0.15
LIFT_S = 0.5
HOLD_S = 0.3
PUSH_S = 0.2
#: After closing, the grip-force loop runs alone for this many control ticks before the lift, and then
#: every tick until the end; each tick changes a digit's torque by at most this fraction.
REGULATE_TICKS = 4
REGULATE_STEP = 0.25
#: A digit pressing with less than this (N) does not feel the object: its torque stays as planned.
CONTACT_SENSED_N = 0.2
#: Steps between control updates and measurements (20 ms at the 2 ms step).
CONTROL_EVERY = 10
PERTURBATION_DIRECTIONS: dict[str, tuple[float, float, float]] = {
    "+x": (1.0, 0.0, 0.0),
    "-x": (-1.0, 0.0, 0.0),
    "+y": (0.0, 1.0, 0.0),
    "-y": (0.0, -1.0, 0.0),
    "+z": (0.0, 0.0, 1.0),
    "-z": (0.0, 0.0, -1.0),
}
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

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def check_physics(model: mujoco.MjModel, data: mujoco.MjData, where: str = "") -> None:
    """Raise :class:`PhysicsError` if the state holds NaN/Inf or any MuJoCo warning fired (after
    dm_control's ``Physics.check_invalid_state``)."""
    if not np.isfinite(data.qpos.sum() + data.qvel.sum() + data.qacc.sum()):
        for arr, name in ((data.qpos, "qpos"), (data.qvel, "qvel"), (data.qacc, "qacc")):
            if not np.all(np.isfinite(arr)):
                raise PhysicsError(f"simulation diverged{where}: non-finite {name} at t={data.time:.3f} s")
    counts = data.warning.number
    if counts.any():
        name = mujoco.mjtWarning(int(np.flatnonzero(counts)[0])).name
        raise PhysicsError(f"simulation diverged{where}: MuJoCo warning {name} at t={data.time:.3f} s")


def beyond_limits(slip_cm: float, turn_deg: float) -> bool:
    """The success rule's motion part: has the object moved :data:`MAX_SLIP_CM` or more, or turned
    :data:`MAX_ROTATION_DEG` or more, relative to the palm? (Either alone fails a trial.)"""
    return slip_cm >= MAX_SLIP_CM or turn_deg >= MAX_ROTATION_DEG


def _smooth(u: float) -> float:
    u = min(max(u, 0.0), 1.0)
    return u * u * (3.0 - 2.0 * u)


class _Runner:
    """Steps a TrialWorld through the protocol, measuring as it goes."""

    def __init__(self, world: TrialWorld):
        self.w = world
        self.m, self.d = world.model, world.data
        self.ref_pos: np.ndarray | None = None
        self.ref_rot: np.ndarray | None = None
        self.slip = 0.0
        self.turn = 0.0
        self.max_force = 0.0
        self.hold_forces: list[float] = []
        self.wrist_base = self.d.ctrl[world.wrist_act].copy()
        self.hold_joints: list[list] = []  # filled by _latch: the grip-force loop runs from then on
        self.closed_posture: tuple[float, ...] = ()

    def _step(self, n_steps: int, where: str) -> None:
        mujoco.mj_step(self.m, self.d, nstep=n_steps)
        check_physics(self.m, self.d, where)

    def _measure(self, record_force: bool = False) -> float:
        forces, _ = self.w.hand_contacts()
        total = float(forces.sum())
        if forces.size:
            self.max_force = max(self.max_force, float(forces.max()))
        if record_force:
            self.hold_forces.append(total / 2.0)  # the squeeze: contact forces from both sides, halved
        if self.ref_pos is not None:
            pos, rot = self.w.object_in_palm()
            self.slip = max(self.slip, float(np.linalg.norm(pos - self.ref_pos)) / H.CM)
            rel = self.ref_rot.T @ rot
            cos = min(1.0, max(-1.0, (np.trace(rel) - 1.0) / 2.0))
            self.turn = max(self.turn, math.degrees(math.acos(cos)))
        return total

    def _phase(self, duration: float, where: str, control=None, record_force: bool = False) -> None:
        chunks = max(1, int(round(duration / (self.m.opt.timestep * CONTROL_EVERY))))
        for k in range(chunks):
            if control is not None:
                control((k + 1) / chunks)
            self._step(CONTROL_EVERY, where)
            self._measure(record_force)

    def failed(self) -> bool:
        return beyond_limits(self.slip, self.turn)

    def start_penetration_m(self) -> float:
        """Deepest hand-object overlap with the pre-shaped hand placed at its grasp pose."""
        d, w = self.d, self.w
        saved = d.qpos[w.wrist_qpos].copy()
        mujoco.mj_forward(self.m, d)
        _, dists = w.hand_contacts()
        depth = max(0.0, float(-dists.min())) if dists.size else 0.0
        d.qpos[w.wrist_qpos] = saved + APPROACH_M * w.approach_dir
        mujoco.mj_forward(self.m, d)
        return depth

    def approach(self) -> None:
        w, d = self.w, self.d
        start = self.wrist_base + APPROACH_M * w.approach_dir
        d.ctrl[w.wrist_act] = start
        self._phase(SETTLE_S, " while settling")
        self._phase(
            APPROACH_S,
            " during the approach",
            lambda u: d.ctrl.__setitem__(w.wrist_act, start - APPROACH_M * _smooth(u) * w.approach_dir),
        )

    def close(self) -> None:
        w, d = self.w, self.d
        open_q = d.ctrl[w.digit_act].copy()
        touch_q, close_q = w.targets.touch, w.targets.close
        if program_for(w.plan.grasp_type).control != "wrap":
            # Pads first travel to where they meet the object, all arriving together, then press on.
            self._phase(
                TOUCH_S,
                " while closing",
                lambda u: d.ctrl.__setitem__(w.digit_act, open_q + _smooth(u) * (touch_q - open_q)),
            )
            open_q = touch_q
        self._phase(
            CLOSE_RAMP_S,
            " while closing",
            lambda u: d.ctrl.__setitem__(w.digit_act, open_q + _smooth(u) * (close_q - open_q)),
        )
        self._phase(CLOSE_HOLD_S, " while closing")
        self._latch()
        self.closed_posture = tuple(round(float(q), 4) for q in d.qpos[w.digit_qpos])
        self.ref_pos, self.ref_rot = self.w.object_in_palm()
        self.obj_z0 = float(d.xpos[w.object_body][2])

    def _latch(self) -> None:
        """Hold the closed posture as a stiff spring that squeezes with the planned force.

        While closing, each used digit presses at its force limit (pure force control). Holding that way
        is unstable along the opposition axis: a push towards one side finds both sides saturated and
        the whole pinch drifts. So, like a robot hand switching to an impedance hold on contact, each
        target becomes the current angle plus the offset that gives the holding torque (tau / kp), the
        force limit rises to the digit's strongest and kp to HOLD_STIFFNESS_FACTOR times the closing one:
        a push is resisted by that stiffness up to the digit's strength.

        The holding torque is regulated on the measured contact forces (the hand's fingertip sensors, as a
        person scales grip force to what the fingers feel; Johansson & Westling 1984): each squeezing
        digit's torque is scaled by (its share of the planned squeeze) / (the normal force it presses
        with now), so the thumb presses with the planned squeeze and the fingers share it. Open-loop
        torques fell 20-40 % short, because a digit touches the object wherever the object is, not at the
        assumed lever arm. Friction still only scales with the squeeze, so a heavy, slippery object slides
        out of a light pinch as it should.
        """
        m, d, w = self.m, self.d, self.w
        strongest = H.max_torques()
        self.hold_joints = []  # (actuator, reference angle, direction, torque, strongest, digit)
        for k, name in enumerate(H.ACTUATOR_NAMES):
            if name not in w.targets.squeezing and name != "thumb_rot":
                continue
            a = int(w.digit_act[k])
            q = float(d.qpos[m.jnt_qposadr[m.actuator_trnid[a, 0]]])
            direction = float(np.sign(w.targets.close[k] - w.targets.open[k]))
            if name in w.targets.squeezing:
                digit = name.split("_")[0]
                torque = min(abs(float(d.actuator_force[a])), strongest[name])
            else:
                digit, torque = "", 0.0
            self.hold_joints.append([a, q, direction, torque, strongest[name], digit])
            m.actuator_forcerange[a] = (-strongest[name], strongest[name])
            # A stiffer hold than closing (sim/hand.py HOLD_STIFFNESS_FACTOR): position actuator, kp in the
            # gain and -kp in the bias.
            m.actuator_gainprm[a, 0] *= H.HOLD_STIFFNESS_FACTOR
            m.actuator_biasprm[a, 1] *= H.HOLD_STIFFNESS_FACTOR
        self._regulate(gain=1.0)
        for _ in range(REGULATE_TICKS):
            self._step(CONTROL_EVERY, " while closing")
            self._regulate(gain=1.0)

    def _regulate(self, gain: float) -> None:
        """One tick of the grip-force loop: scale each squeezing digit's holding torque towards (its share
        of the planned squeeze) / (the normal force it feels), by at most REGULATE_STEP per tick, and hold
        the joints at their latched angles plus torque / kp (the stiffness stays kp)."""
        if not self.hold_joints:
            return
        m, d, w = self.m, self.d, self.w
        side = w.targets.side_force_n
        share = {"thumb": side, **{f: side / len(w.targets.fingers) for f in w.targets.fingers}}
        felt = w.digit_forces()
        for joint in self.hold_joints:
            a, q_ref, direction, torque, strongest, digit = joint
            if digit and felt[digit] > CONTACT_SENSED_N:
                ratio = (share[digit] / felt[digit]) ** gain
                ratio = min(1.0 + REGULATE_STEP, max(1.0 / (1.0 + REGULATE_STEP), ratio))
                torque = min(strongest, torque * ratio)
                joint[3] = torque
            d.ctrl[a] = q_ref + direction * torque / m.actuator_gainprm[a, 0]

    def lift(self) -> float:
        w, d = self.w, self.d
        base = self.wrist_base.copy()
        up = np.array([0.0, 0.0, LIFT_M])
        self._phase(
            LIFT_S, " during the lift", lambda u: d.ctrl.__setitem__(w.wrist_act, base + _smooth(u) * up)
        )
        return (float(d.xpos[w.object_body][2]) - self.obj_z0) / H.CM

    def hold(self) -> None:
        self._phase(HOLD_S, " during the hold", record_force=True)

    def perturb(self, direction: str) -> float:
        w, d = self.w, self.d
        before, _ = w.object_in_palm()
        force = w.obj.weight_n * np.array(PERTURBATION_DIRECTIONS[direction])
        d.xfrc_applied[w.object_body, :3] = force
        worst = 0.0
        chunks = max(1, int(round(PUSH_S / (self.m.opt.timestep * CONTROL_EVERY))))
        for _ in range(chunks):
            self._step(CONTROL_EVERY, f" while pushing {direction}")
            self._measure()
            pos, _ = w.object_in_palm()
            worst = max(worst, float(np.linalg.norm(pos - before)) / H.CM)
        d.xfrc_applied[w.object_body, :3] = 0.0
        return worst


def run_trial(
    obj: ObjectRecord,
    plan: GraspPlan,
    *,
    seed: int = 0,
    stop_after: str | None = None,
    world: TrialWorld | None = None,
) -> TrialResult:
    """Run one grasp trial of ``plan`` on ``obj`` (see the module docstring for the protocol).

    Returns a :class:`TrialResult`; a diverged simulation gives ``outcome='error'``. Raises
    :class:`SimulationError` only when the trial cannot be set up (an object without usable features).
    ``stop_after='hold'`` ends the trial after the hold (for rendering, with ``world`` given).
    """
    t0 = time.perf_counter()
    if world is None:
        world = build_world(obj, plan, seed=seed)
    runner = _Runner(world)
    result = TrialResult(
        object_name=obj.name,
        grasp_type=plan.grasp_type,
        family=plan.family,
        seed=int(seed),
        outcome="failure",
        success=False,
        reason="",
        program=program_for(plan.grasp_type).name,
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
            return finish(
                "failure", f"hand starts inside the object ({depth * 1000:.1f} mm deep at the grasp pose)"
            )
        runner.approach()
        runner.close()
        if not world.hand_contacts()[0].size:
            return finish("failure", "no contact after closing: the digits missed the object")
        rose = runner.lift()
        result.lifted = rose >= LIFTED_FRACTION * LIFT_M / H.CM
        if not result.lifted:
            return finish("failure", f"not lifted: the object rose {rose:.1f} cm of {LIFT_M / H.CM:.0f}")
        if runner.failed():
            return finish("failure", _slip_reason(runner, "the lift"))
        runner.hold()
        if runner.failed():
            return finish("failure", _slip_reason(runner, "the hold"))
        if stop_after == "hold":
            return finish("success", "stopped after the hold")
        for direction in PERTURBATION_DIRECTIONS:
            result.perturbation[direction] = round(runner.perturb(direction), 3)
            if runner.failed():
                return finish("failure", _slip_reason(runner, f"the {direction} push"))
    except PhysicsError as exc:
        return finish("error", str(exc))
    return finish(
        "success",
        f"held: moved {runner.slip:.2f} cm and turned {runner.turn:.1f} deg relative to the palm "
        f"under pushes of its weight ({world.obj.weight_n:.2f} N)",
    )


def _slip_reason(runner: _Runner, phase: str) -> str:
    if runner.slip >= MAX_SLIP_CM:
        return f"slipped {runner.slip:.1f} cm (limit {MAX_SLIP_CM:g}) relative to the palm during {phase}"
    return f"turned {runner.turn:.1f} deg (limit {MAX_ROTATION_DEG:g}) relative to the palm during {phase}"
