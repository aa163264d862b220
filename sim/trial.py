"""One grasp trial in MuJoCo: pre-shape, approach, close to the planned force, lift, hold, perturb.

Protocol (constants below; sim/PHYSICS.md explains them):

1. Build a world for this object and plan: a table (top at z = 0), the object resting on it with the
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

from kb.errors import PhysicsError, SimulationError
from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import GRASP_TYPES, GraspPlan, edge_grip_in_cm, edge_overhang_cm, is_flat_grasp
from sim.objects import ObjectModel, add_object, add_table, object_model
from sim.programs import program_for

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
#: The hand starts this far back along the approach direction.
APPROACH_M = 0.06
#: Gap between the palm face and the object above it in pinches (cm); a wrap's gap is its hand program's
#: ``palm_gap_cm`` (sim/programs.py: 0.4 cm pressed to the palm, 1 cm held in the fingers).
PRECISION_PALM_CLEARANCE_CM = 1.0
#: Deeper overlap than this at the pre-grasp pose means the hand starts inside the object.
PENETRATION_TOL_M = 0.002
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


# ---------------------------------------------------------------------------------------------------------
# The world
# ---------------------------------------------------------------------------------------------------------
@dataclass
class TrialWorld:
    """A compiled world for one (object, plan) and the indices the trial reads."""

    model: mujoco.MjModel
    data: mujoco.MjData
    obj: ObjectModel
    plan: GraspPlan
    targets: H.GraspTargets
    approach_dir: np.ndarray
    object_body: int
    palm_body: int
    is_hand: np.ndarray  # per geom: does it belong to the hand
    object_geom: int
    wrist_act: np.ndarray
    digit_act: np.ndarray
    wrist_qpos: np.ndarray
    approach: str = "top"  # as built: the plan's, or "edge" for a flat object grasped at a table edge
    geom_digit: dict[int, str] = field(default_factory=dict)  # hand geom id -> digit it belongs to
    digit_qpos: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))  # qpos index per digit joint

    def palm_pose(self) -> tuple[np.ndarray, np.ndarray]:
        return self.data.xpos[self.palm_body].copy(), self.data.xmat[self.palm_body].reshape(3, 3).copy()

    def object_in_palm(self) -> tuple[np.ndarray, np.ndarray]:
        """Object position and orientation matrix in the palm frame."""
        p, r = self.palm_pose()
        po = self.data.xpos[self.object_body]
        ro = self.data.xmat[self.object_body].reshape(3, 3)
        return r.T @ (po - p), r.T @ ro

    def digit_forces(self) -> dict[str, float]:
        """Total normal force (N) each digit presses on the object with (its fingertip sensors)."""
        d = self.data
        n = d.ncon
        out = dict.fromkeys(H.DIGITS, 0.0)
        if n == 0:
            return out
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        other = np.where(g1 == self.object_geom, g2, np.where(g2 == self.object_geom, g1, -1))
        ok = (other >= 0) & (d.contact.efc_address[:n] >= 0)
        for k in np.flatnonzero(ok):
            digit = self.geom_digit.get(int(other[k]))
            if digit is not None:
                out[digit] += float(d.efc_force[d.contact.efc_address[k]])
        return out

    def hand_contacts(self) -> tuple[np.ndarray, np.ndarray]:
        """Normal forces (N) and distances (m) of the active hand-object contacts.

        With elliptic cones a contact's first constraint row is its normal force (what
        ``mj_contactForce`` returns as force[0]); reading ``efc_force`` directly avoids a Python loop.
        """
        d = self.data
        n = d.ncon
        if n == 0:
            return _EMPTY, _EMPTY
        g1, g2 = d.contact.geom1[:n], d.contact.geom2[:n]
        mask = ((g1 == self.object_geom) & self.is_hand[g2]) | ((g2 == self.object_geom) & self.is_hand[g1])
        mask &= d.contact.efc_address[:n] >= 0
        if not mask.any():
            return _EMPTY, _EMPTY
        return d.efc_force[d.contact.efc_address[:n][mask]], d.contact.dist[:n][mask]


_EMPTY = np.zeros(0)


def _placement(obj: ObjectModel, plan: GraspPlan) -> dict[str, int]:
    """World axis of each catalog dimension: the grasped one along y (the opposition axis); of the other
    two, for a top approach the larger along x and the smaller up (lying on its broad side); for a side
    approach the larger up (standing, like a bottle) and the smaller along x, towards the palm."""
    rest = sorted((d for d in "abc" if d != plan.grasped_dim), key=obj.extent_cm, reverse=True)
    if plan.approach == "top":
        return {plan.grasped_dim: 1, rest[0]: 0, rest[1]: 2}
    return {plan.grasped_dim: 1, rest[0]: 2, rest[1]: 0}


def _is_flat(obj: ObjectModel, plan: GraspPlan) -> bool:
    """Does ``plan`` grasp a flat object across its thickness? Such objects lie flat, overhanging a table
    edge, and are grasped from the edge (thumb on top, fingers underneath), as people pick up a plate or
    a book; standing them on edge for a top or side grasp would be neither stable nor realistic."""
    dims = sorted("abc", key=obj.extent_cm)
    thin, middle = dims[0], dims[1]
    return plan.grasped_dim == thin and is_flat_grasp(obj.extent_cm(thin), obj.extent_cm(middle))


def _edge_placement(obj: ObjectModel, plan: GraspPlan) -> dict[str, int]:
    """Flat on the table (grasped thickness up), its longest side along the table edge (world y, where the
    fingers spread) and the other across it (world x, overhanging)."""
    rest = sorted((d for d in "abc" if d != plan.grasped_dim), key=obj.extent_cm, reverse=True)
    return {plan.grasped_dim: 2, rest[0]: 1, rest[1]: 0}


def build_world(obj: ObjectRecord | ObjectModel, plan: GraspPlan, *, seed: int = 0) -> TrialWorld:
    """Compile the trial's world with the hand at its start pose (pre-shaped, backed off the object)."""
    if plan.grasp_type not in GRASP_TYPES:
        raise SimulationError(f"unknown grasp type {plan.grasp_type!r}")
    if plan.approach not in H.APPROACH_QUAT:
        raise SimulationError(f"unknown approach {plan.approach!r}: expected top or side")
    model_obj = obj if isinstance(obj, ObjectModel) else object_model(obj)
    rng = np.random.default_rng(seed)
    flat = _is_flat(model_obj, plan)
    approach = "edge" if flat else plan.approach
    axes = _edge_placement(model_obj, plan) if flat else _placement(model_obj, plan)
    ext = np.zeros(3)
    for dim, ax in axes.items():
        ext[ax] = model_obj.extent_cm(dim)
    width = ext[2] if flat else ext[1]
    targets = H.grasp_targets(plan, width)
    program = program_for(plan.grasp_type)
    wrap = program.control == "wrap"

    depth = ext[2] if approach == "top" else ext[0]  # extent along the approach axis
    # Over the table's edge as far as the pads reach in (up to 6 cm), never by so much that the object's
    # centre of mass leaves the table (sim/grasps.py, shared with the planner's force).
    overhang = edge_overhang_cm(depth) if flat else 0.0
    center_cm, grip_depth = _object_in_hand_cm(program, targets, depth, flat)
    center_h = center_cm * H.CM

    obj_pos = np.array([0.0, 0.0, ext[2] / 2.0 * H.CM])
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, np.array(H.APPROACH_QUAT[approach]))
    rot = rot.reshape(3, 3)
    palm_pos = obj_pos - rot @ center_h
    if approach == "side":
        # Keep the palm's lower edge above the table: the fingers spread vertically from its centre.
        palm_pos[2] = max(palm_pos[2], (H.PALM_HALF_CM[0] + 0.3) * H.CM)
    approach_dir = np.array([0.0, 0.0, 1.0]) if approach == "top" else np.array([1.0, 0.0, 0.0])

    spec = mujoco.MjSpec()
    spec.modelname = "grasp_trial"
    H.configure_options(spec)
    spec.worldbody.add_light(pos=[0.3, -0.3, 0.8], dir=[-0.3, 0.3, -0.8], diffuse=[0.7, 0.7, 0.7])
    add_table(spec, (depth / 2.0 - overhang) * H.CM if flat else None)
    add_object(spec, model_obj, axes, obj_pos)
    H.add_hand(spec, approach=approach, mount_m=palm_pos, torque_limits=targets.closing_limits)
    try:
        model = spec.compile()
    except Exception as exc:
        raise SimulationError(f"could not compile the trial model: {exc}") from exc
    data = mujoco.MjData(model)

    wrist_act = np.array([model.actuator(n).id for n in H.WRIST_ACTUATOR_NAMES])
    digit_act = np.array([model.actuator(n).id for n in H.ACTUATOR_NAMES])
    wrist_qpos = np.array([model.jnt_qposadr[model.joint(n).id] for n in H.WRIST_JOINT_NAMES])
    digit_qpos = np.array([model.jnt_qposadr[model.joint(n).id] for n in H.JOINT_NAMES])
    object_body = model.body("object").id
    # Hand geoms: every geom on a body other than the world (the table) and the object.
    is_hand = (model.geom_bodyid != 0) & (model.geom_bodyid != object_body)

    noise = np.array([rng.normal(0, 0.001), rng.normal(0, 0.001), 0.0])
    open_q = targets.open + rng.normal(0, 0.01, size=targets.open.shape)
    data.qpos[digit_qpos] = open_q
    if not wrap:
        # Round objects bulge above their equator into the fingers that reach down to it: pinch higher,
        # in 5 mm steps up to 1 cm below the top, until the pre-shaped hand clears the object.
        backoff = _precision_backoff_m(
            model, data, is_hand, model.geom("object_geom").id, wrist_qpos, approach_dir, grip_depth - 1.0
        )
        noise = noise + backoff * approach_dir
    data.qpos[wrist_qpos] = noise
    data.ctrl[digit_act] = open_q
    data.ctrl[wrist_act] = noise
    world = TrialWorld(
        model=model,
        data=data,
        obj=model_obj,
        plan=plan,
        targets=targets,
        approach_dir=approach_dir,
        object_body=object_body,
        palm_body=model.body("palm").id,
        is_hand=is_hand,
        object_geom=model.geom("object_geom").id,
        wrist_act=wrist_act,
        digit_act=digit_act,
        wrist_qpos=wrist_qpos,
        digit_qpos=digit_qpos,
        approach=approach,
        geom_digit={
            g: model.geom(g).name.split("_")[0]
            for g in range(model.ngeom)
            if model.geom(g).name.split("_")[0] in H.DIGITS
        },
    )
    return world


def _object_in_hand_cm(program, targets: H.GraspTargets, depth: float, flat: bool) -> tuple[np.ndarray, float]:
    """Where the object's centre sits in the hand frame (cm) at the grasp pose, and how far below its near
    face the pads meet it (pinches; 0 for wraps). ``depth``: its extent along the approach axis."""
    palm_face = -H.PALM_HALF_CM[2]
    if program.control == "wrap":  # pressed to the palm, or held in the fingers by the program's gap
        return np.array([0.0, targets.center_y_cm, palm_face - program.palm_gap_cm - depth / 2.0]), 0.0
    x_c = float(np.mean([H.FINGER_BY_NAME[f].x_cm for f in targets.fingers]))
    # Pads meet the object's sides at its centre (no gravity torque about the pinch axis) when they reach
    # that far, else 3 cm below its near face; flat objects as near their centre of mass as the pads
    # reach under the overhang.
    grip_depth = edge_grip_in_cm(depth) if flat else min(depth / 2.0, 3.0)
    z_c = min(
        targets.contact_z_cm - depth / 2.0 + grip_depth,
        palm_face - PRECISION_PALM_CLEARANCE_CM - depth / 2,
    )
    return np.array([x_c, targets.center_y_cm, z_c]), grip_depth


def _precision_backoff_m(model, data, is_hand, object_geom, wrist_qpos, approach_dir, max_cm: float) -> float:
    """Smallest back-off (m, along the approach, 5 mm steps up to ``max_cm``) at which the pre-shaped hand
    does not overlap the object; 0 if none does (the trial then fails as starting inside)."""
    steps = int(max(0.0, max_cm) // 0.5)
    for k in range(steps + 1):
        offset = k * 0.005
        data.qpos[wrist_qpos] = offset * approach_dir
        mujoco.mj_forward(model, data)
        n = data.ncon
        g1, g2 = data.contact.geom1[:n], data.contact.geom2[:n]
        mine = ((g1 == object_geom) & is_hand[g2]) | ((g2 == object_geom) & is_hand[g1])
        if not (data.contact.dist[:n][mine] < -PENETRATION_TOL_M).any():
            return offset
    return 0.0


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
