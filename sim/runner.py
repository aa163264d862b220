"""The trial's phases (sim/trial.py runs them in order): a :class:`Runner` steps a TrialWorld through the
settle and approach, the force-limited close and the impedance hold with its grip-force loop, the lift,
the hold and the pushes, measuring as it goes how far the object moved and turned relative to the palm;
and the success rule's motion part (:func:`beyond_limits`). Constants and their reasons: sim/PHYSICS.md.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from kb.errors import PhysicsError
from sim import hand as H
from sim.programs import program_for
from sim.protocols import LIFT_PUSH
from sim.world import APPROACH_M, TrialWorld

__all__ = [
    "CONTROL_EVERY",
    "LIFT_M",
    "MAX_ROTATION_DEG",
    "MAX_SLIP_CM",
    "PERTURBATION_DIRECTIONS",
    "Runner",
    "beyond_limits",
    "check_physics",
]

#: Success thresholds of the default protocol, relative to the palm (sim/protocols.py LIFT_PUSH).
MAX_SLIP_CM = LIFT_PUSH.max_translation_cm
MAX_ROTATION_DEG = LIFT_PUSH.max_rotation_deg
#: Lift height and the fraction of it the object must follow to count as lifted.
LIFT_M = 0.10
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

def check_physics(model: mujoco.MjModel, data: mujoco.MjData, where: str = "") -> None:
    """Raise :class:`PhysicsError` if the state holds NaN/Inf or any MuJoCo warning fired (after
    dm_control's ``Physics.check_invalid_state``)."""
    qpos, qvel, qacc = data.qpos, data.qvel, data.qacc
    # A sum of squares is NaN or Inf whenever an element is (and may overflow: the loop then decides).
    if not math.isfinite(qpos.dot(qpos) + qvel.dot(qvel) + qacc.dot(qacc)):
        for arr, name in ((data.qpos, "qpos"), (data.qvel, "qvel"), (data.qacc, "qacc")):
            if not np.all(np.isfinite(arr)):
                raise PhysicsError(f"simulation diverged{where}: non-finite {name} at t={data.time:.3f} s")
    counts = data.warning.number
    if np.count_nonzero(counts):
        name = mujoco.mjtWarning(int(np.flatnonzero(counts)[0])).name
        raise PhysicsError(f"simulation diverged{where}: MuJoCo warning {name} at t={data.time:.3f} s")


def beyond_limits(slip_cm: float, turn_deg: float) -> bool:
    """The success rule's motion part: has the object moved :data:`MAX_SLIP_CM` or more, or turned
    :data:`MAX_ROTATION_DEG` or more, relative to the palm? (Either alone fails a trial.)"""
    return slip_cm >= MAX_SLIP_CM or turn_deg >= MAX_ROTATION_DEG


def _smooth(u: float) -> float:
    u = min(max(u, 0.0), 1.0)
    return u * u * (3.0 - 2.0 * u)


class Runner:
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
        # Read every control tick: views of MjData's own buffers (valid while the data lives), and the
        # hand-object geom pairs as a set, so the per-tick checks cost no numpy indexing.
        d = self.d
        self._state = (d.qpos, d.qvel, d.qacc)
        self._warnings = d.warning.number
        self._touching = frozenset(zip(*(a.tolist() for a in np.nonzero(world.touches)), strict=True))

    def _step(self, n_steps: int, where: str) -> None:
        mujoco.mj_step(self.m, self.d, nstep=n_steps)
        qpos, qvel, qacc = self._state
        # check_physics's two tests on the views taken once; it runs (and raises, naming why) when one fires.
        if not math.isfinite(qpos.dot(qpos) + qvel.dot(qvel) + qacc.dot(qacc)) or self._warnings.any():
            check_physics(self.m, self.d, where)

    def _largest_contact_force(self) -> float | None:
        """The largest normal force of the active hand-object contacts (None without one): the max of
        ``TrialWorld.contact_forces()``, by a loop over the few contacts instead of numpy indexing."""
        d = self.d
        if d.ncon == 0:
            return None
        c, force, touching, top = d.contact, d.efc_force, self._touching, None
        for g1, g2, row in zip(c.geom1.tolist(), c.geom2.tolist(), c.efc_address.tolist(), strict=True):
            if row >= 0 and (g1, g2) in touching:
                f = float(force[row])  # the contact's first row: its normal force (elliptic cones)
                if top is None or f > top:
                    top = f
        return top

    def _measure(self, record_force: bool = False) -> np.ndarray | None:
        """Record the contact forces and the object's motion relative to the palm since the reference;
        returns the object's position in the palm (None before the reference is taken)."""
        if record_force:
            forces = self.w.contact_forces()
            if forces.size:
                self.max_force = max(self.max_force, float(forces.max()))
            self.hold_forces.append(float(forces.sum()) / 2.0)  # the squeeze: both sides' forces, halved
        else:  # the total is read only while holding; the largest force by a cheaper loop
            top = self._largest_contact_force()
            if top is not None:
                self.max_force = max(self.max_force, top)
        if self.ref_pos is None:
            return None
        pos, rot = self.w.object_in_palm()
        self.slip = max(self.slip, _norm(pos - self.ref_pos) / H.CM)
        cos = min(1.0, max(-1.0, ((self.ref_rot.T @ rot).trace() - 1.0) / 2.0))
        self.turn = max(self.turn, math.degrees(math.acos(cos)))
        return pos

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
        self.latch_reference()

    def latch_reference(self) -> None:
        """End of any close: latch the impedance hold, record the closed posture, and take the object's
        pose in the palm as the reference the success rule measures from."""
        w, d = self.w, self.d
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

    def lift(self, height_m: float = LIFT_M, *, above_m: float = 0.0) -> float:
        """Raise the wrist by ``height_m`` over LIFT_S, from ``above_m`` over its grasp height (a second
        rise continues from the first's top); returns how far (cm) the object has risen since closing."""
        w, d = self.w, self.d
        base = self.wrist_base + np.array([0.0, 0.0, above_m])
        up = np.array([0.0, 0.0, height_m])
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
        where = f" while pushing {direction}"
        for _ in range(chunks):
            self._step(CONTROL_EVERY, where)
            pos = self._measure()
            if pos is None:
                pos, _ = w.object_in_palm()
            worst = max(worst, _norm(pos - before) / H.CM)
        d.xfrc_applied[w.object_body, :3] = 0.0
        return worst


def _norm(v: np.ndarray) -> float:
    """``np.linalg.norm`` of a 3-vector by its own operations (sqrt of the dot product), without its checks."""
    return math.sqrt(v.dot(v))
