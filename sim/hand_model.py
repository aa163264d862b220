"""A five-fingered, AR10-like anthropomorphic hand built in code with :class:`mujoco.MjSpec`.

The paper's hand (Active8 AR10) has a thumb and four fingers with two actuated joints per digit, ten in
all. This model keeps that: each finger has an actuated MCP (knuckle) and PIP (middle) flexion joint, the
distal phalanx fused to the middle one at a fixed bend (the AR10 couples it through a linkage); the thumb
has an actuated rotation at its base (swinging its tip across the palm, towards the finger it opposes) and
an actuated flexion towards the fingers. Proportions are those of an adult human hand (see the
constants). Units inside MuJoCo are SI (m, kg, s, N); the tables below are in cm for readability.

Hand frame ``H`` (the ``palm`` body): origin at the palm's centre; ``+y`` points from the wrist to the
fingers; the palm's grasping face looks along ``-z`` (``+z`` is the back of the hand); ``+x`` is the index
side. Fingers flex from ``+y`` towards ``-z``; the thumb hangs along ``-z`` from the proximal palm and
flexes towards ``+y``, so an object between them is grasped along ``y`` (the opposition axis).

The hand hangs from a wrist that slides along the world x, y and z axes (three position actuators: an
arm's end effector, without its orientation control). Its orientation is fixed per approach: ``top``
(palm down, opposition axis along world y) or ``side`` (palm facing world ``-x``, opposition axis along
world y). Every hand body has gravity compensation (``gravcomp`` 1: a real arm carries the hand's weight),
so the wrist actuators carry only what the hand holds, and the slip we measure is the object's.

Bump ``sim.hand.HAND_VERSION`` whenever the model changes (geometry, constants, control): it is stored
with every validation result. The hand's postures for a grasp (pre-shape, closing targets, force
limits) are in sim/hand.py, which re-exports this module's names; the planar kinematics of the digits (the
tips' positions at given joint angles) are in sim/hand_kinematics.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from sim.grasps import FINGER_MAX_FORCE_N, THUMB_MAX_FORCE_N, active_fingers

__all__ = [
    "ACTUATOR_NAMES",
    "APPROACH_QUAT",
    "DIGITS",
    "FINGERS",
    "JOINT_NAMES",
    "WRIST_ACTUATOR_NAMES",
    "Finger",
    "Thumb",
    "active_fingers",
    "digit_length_cm",
    "max_torques",
    "configure_options",
    "add_hand",
    "hand_spec",
]

CM = 0.01  # metres per centimetre

# ---------------------------------------------------------------------------------------------------------
# Geometry (cm). Adult hand, length ~19 cm, breadth ~8.5 cm (ANSUR II medians: hand length 19.1 cm,
# breadth 8.6 cm). Phalanx lengths after Buchholz, Armstrong & Goldstein (1992), "Anthropometric data
# for describing the kinematics of the human hand", Ergonomics 35(3): segment lengths as fractions of hand
# length (index P/M/D 0.245/0.143/0.097 of 18.9 cm ...), rounded to 1 mm.
# ---------------------------------------------------------------------------------------------------------
PALM_HALF_CM = (4.25, 4.5, 1.25)  # palm 8.5 cm wide (x), 9 cm long (y), 2.5 cm thick (z)
#: Fused distal bend of the fingers: the DIP joint at about 2/3 of a mid-range PIP flexion (the AR10
#: linkage and human tendon coupling both make DIP follow PIP); fixed here, 20 degrees.
DISTAL_BEND_DEG = 20.0
#: Distal phalanges taper: their capsule radius is this fraction of the digit's.
TIP_TAPER = 0.9
#: Fused bend between thumb proximal and distal phalanx (IP joint), towards the fingers.
THUMB_IP_BEND_DEG = 15.0


@dataclass(frozen=True)
class Finger:
    name: str
    x_cm: float  # knuckle position across the palm (+x = index side)
    lengths_cm: tuple[float, float, float]  # proximal, middle, distal phalanx
    radius_cm: float  # capsule radius: half the finger's thickness at the middle phalanx
    mass_g: tuple[float, float]  # proximal body, middle+distal body (about 1.1 g/cm^3 tissue + bone)


@dataclass(frozen=True)
class Thumb:
    name: str
    base_cm: tuple[float, float, float]  # CMC joint on the palm face (H frame)
    metacarpal_cm: float  # part of the metacarpal that stands out of the palm
    lengths_cm: tuple[float, float]  # proximal, distal phalanx
    radius_cm: float
    mass_g: tuple[float, float]


#: Knuckles 2.1 cm apart (finger breadth ~1.8-2 cm plus a gap), the index on +x.
FINGERS: tuple[Finger, ...] = (
    Finger("index", 3.15, (3.9, 2.3, 1.8), 0.85, (18.0, 14.0)),
    Finger("middle", 1.05, (4.4, 2.7, 1.9), 0.9, (21.0, 16.0)),
    Finger("ring", -1.05, (4.1, 2.6, 1.9), 0.85, (18.0, 14.0)),
    Finger("little", -3.15, (3.3, 1.8, 1.7), 0.75, (11.0, 9.0)),
)
#: The thumb's CMC sits on the palm face towards the index side, 1 cm from the palm's wrist end (the
#: thenar eminence), so an object of up to ~5 cm fits under the palm between thumb and knuckles.
THUMB = Thumb("thumb", (2.6, -3.5, -PALM_HALF_CM[2]), 2.5, (3.2, 2.6), 1.0, (30.0, 22.0))
DIGITS: tuple[str, ...] = ("thumb", *(f.name for f in FINGERS))
FINGER_BY_NAME = {f.name: f for f in FINGERS}

# ---------------------------------------------------------------------------------------------------------
# Joints and actuators
# ---------------------------------------------------------------------------------------------------------
#: Joint ranges (degrees). Human active ranges: MCP 0..90, PIP 0..110 (we stop at 100: the fused distal
#: phalanx would otherwise fold into the palm); thumb flexion here spans from swung back 50 degrees (wide
#: opening) to 85 degrees across the palm; thumb rotation +-35 degrees covers index to little finger.
RANGE_DEG = {
    "mcp": (-10.0, 90.0),
    "pip": (0.0, 100.0),
    "thumb_rot": (-35.0, 35.0),
    "thumb_flex": (-50.0, 85.0),
}
#: Position gains (N m / rad): 0.5 rad of error already asks for 1 N m, more than any finger's force
#: limit, so a digit driven past contact presses at its limit. The grip force is not set by kp but by the force
#: limit (see grasp_targets): targets are placed beyond contact, so the actuator saturates.
KP = {"mcp": 2.0, "pip": 1.0, "thumb_rot": 3.0, "thumb_flex": 3.0}
#: Holding is stiffer than closing: once the digits have closed on the object, their position gains rise
#: by this factor (sim/trial.py _latch), as a servo hand switches to a stiff hold and as people stiffen
#: their fingers by co-contraction, more the harder they grip (Hajian & Howe 1997, fingertip impedance).
#: Closing stays compliant (a light grip must not knock the object away); holding with the closing gains
#: let the pads' preload (about 1 N over 4 mm at the fingertips) vanish whenever the object shifted a few
#: millimetres. 4x gives fingertip stiffnesses of about 1.2 N/mm (index) and 3.5 N/mm (thumb); measured
#: on the seed catalog: 1x 112, 3x 120, 4x 124, 5x 123 of 169 best plans held.
HOLD_STIFFNESS_FACTOR = 4.0
#: Reflected rotor inertia of the geared servo behind each joint (kg m^2): AR10 drives each joint through
#: a geared linear servo; 3e-4 dominates the phalanges' own ~5e-5 and keeps the joints well conditioned
#: (sqrt(kp / I) ~ 80 rad/s for kp = 2: 0.16 rad per 2 ms step, well inside implicitfast's comfort).
ARMATURE = 3e-4
#: Joint damping (N m s / rad), about 0.4 of critical (2 sqrt(kp I) ~ 0.05). Kept low on purpose: when the
#: grip force is small the actuator saturates at a small torque, and the closing speed is that torque over
#: the damping (0.06 N m / 0.02 = 3 rad/s: a light grip still closes in ~0.3 s). Integrated implicitly.
DAMPING = {"mcp": 0.02, "pip": 0.01, "thumb_rot": 0.05, "thumb_flex": 0.03}
#: Strongest normal force each digit can press with (N): shared with the planner, see sim/grasps.py for
#: the human values and the choice (15 N per finger, 60 N for the thumb).
#: Torque limit of an unused finger (N m): enough to hold its pose (gravity is compensated), too weak to
#: take part in the grasp.
UNUSED_TORQUE_NM = 0.05
#: While closing, each used digit presses with at least this force (N): the closing speed is the torque
#: over the joint damping, and a 1 N grip would take a second to close. The hold then returns to the plan.
CLOSING_FORCE_FLOOR_N = 2.0
# The lever arm from a joint to where the digit presses (a fraction of the digit beyond the joint: 0.6
# mid-finger in wraps, 0.8 lateral pinch, 0.85 near the tip in precision grasps) is each hand program's
# ``lever`` (sim/programs.py).

#: Wrist slides: kp 5000 N/m sags 3 mm under a 1.5 kg load; critically damped (dampratio 1) against the
#: hand's own mass; +-200 N is a strong arm's payload (~20 kg), so even heavy objects are the fingers'
#: problem, not the arm's.
WRIST_KP = 5000.0
WRIST_FORCE_N = 200.0
#: Wrist slide range (m) around the mount point: enough to approach and lift anywhere on the table.
WRIST_RANGE_M = 0.5

JOINT_NAMES: tuple[str, ...] = (
    "thumb_rot",
    "thumb_flex",
    *(f"{f.name}_{j}" for f in FINGERS for j in ("mcp", "pip")),
)
#: The ten digit actuators, in ctrl order (each drives the joint of the same name).
ACTUATOR_NAMES: tuple[str, ...] = JOINT_NAMES
WRIST_JOINT_NAMES: tuple[str, ...] = ("wrist_x", "wrist_y", "wrist_z")
WRIST_ACTUATOR_NAMES: tuple[str, ...] = WRIST_JOINT_NAMES

#: Orientation of the palm per approach (w, x, y, z): top = identity (palm down); side = 90 degrees
#: about world y (palm's -z turned to world -x, fingers still along world y, their spread vertical).
APPROACH_QUAT: dict[str, tuple[float, float, float, float]] = {
    "top": (1.0, 0.0, 0.0, 0.0),
    "side": (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0),
    # Table-edge grasp of a flat object (sim/trial.py): palm facing world -x, fingers pointing down
    # (opposition axis vertical: thumb on top, fingers under the overhang), spread along world y.
    # Hand axes in world: x_H = -y, y_H = -z, z_H = +x.
    "edge": (0.5, -0.5, 0.5, -0.5),
}

#: Collision bits: hand geoms touch only the object; the table touches only the object (the hand may
#: pass through the table: its wrist orientation is fixed, so without this a wrap planned around an
#: object's lower half would stall on the table top instead of tilting as a real arm would).
HAND_BIT, OBJECT_BIT, TABLE_BIT = 1, 2, 4

HAND_RGBA = (0.85, 0.72, 0.62, 1.0)
PALM_RGBA = (0.78, 0.64, 0.55, 1.0)


def _joint_kind(name: str) -> str:
    return name if name.startswith("thumb") else name.split("_")[1]


def _capsule(body, name: str, start, end, radius_cm: float, mass_g: float, rgba=HAND_RGBA) -> None:
    body.add_geom(
        name=name,
        type=mujoco.mjtGeom.mjGEOM_CAPSULE,
        fromto=[*(v * CM for v in start), *(v * CM for v in end)],
        size=[radius_cm * CM, 0, 0],
        mass=mass_g / 1000.0,
        contype=HAND_BIT,
        conaffinity=OBJECT_BIT,
        condim=4,
        priority=0,  # the object's geom has priority 1: its friction and softness decide each contact
        rgba=list(rgba),
    )


def _hinge(body, name: str, axis) -> None:
    kind = _joint_kind(name)
    lo, hi = RANGE_DEG[kind]
    body.add_joint(
        name=name,
        type=mujoco.mjtJoint.mjJNT_HINGE,
        axis=list(axis),
        range=[math.radians(lo), math.radians(hi)],
        limited=mujoco.mjtLimited.mjLIMITED_TRUE,
        armature=ARMATURE,
        damping=DAMPING[kind],
    )


def add_hand(spec: mujoco.MjSpec, *, approach: str = "top", mount_m=(0.0, 0.0, 0.3), torque_limits=None):
    """Add the hand, its wrist slides and its 13 position actuators (3 wrist, 10 digits) to ``spec``.

    ``mount_m`` is the world position of the wrist at zero slide; ``torque_limits`` maps actuator names to
    their force limits (N m) -- by default each digit's strongest (see :func:`max_torques`). Returns the
    palm body.
    """
    if approach not in APPROACH_QUAT:
        raise ValueError(f"approach must be one of {', '.join(APPROACH_QUAT)}, not {approach!r}")
    limits = max_torques()
    limits.update(torque_limits or {})
    wrist = spec.worldbody.add_body(name="wrist", pos=list(mount_m), gravcomp=1.0)
    for axis, name in zip(np.eye(3), WRIST_JOINT_NAMES, strict=True):
        wrist.add_joint(
            name=name,
            type=mujoco.mjtJoint.mjJNT_SLIDE,
            axis=list(axis),
            range=[-WRIST_RANGE_M, WRIST_RANGE_M],
            limited=mujoco.mjtLimited.mjLIMITED_TRUE,
        )
    # A light wrist body so the slides have mass of their own (the palm carries the rest).
    wrist.add_geom(
        name="wrist_geom",
        type=mujoco.mjtGeom.mjGEOM_SPHERE,
        size=[0.01, 0, 0],
        mass=0.05,
        contype=0,
        conaffinity=0,
        rgba=[0.3, 0.3, 0.3, 1.0],
    )
    palm = wrist.add_body(name="palm", quat=list(APPROACH_QUAT[approach]), gravcomp=1.0)
    palm.add_geom(
        name="palm_geom",
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[v * CM for v in PALM_HALF_CM],
        mass=0.25,  # AR10's palm and servos weigh more (~1 kg in all); 250 g is a human palm
        contype=HAND_BIT,
        conaffinity=OBJECT_BIT,
        condim=4,
        rgba=list(PALM_RGBA),
    )
    palm.add_site(name="palm_center", pos=[0, 0, -PALM_HALF_CM[2] * CM], size=[0.004, 0, 0])
    palm.add_camera(name="palm_cam", pos=[0.0, -0.35, 0.12], xyaxes=[1, 0, 0, 0, 0.3, 1])

    for f in FINGERS:
        p1, p2, p3 = f.lengths_cm
        base_z = -PALM_HALF_CM[2] + f.radius_cm  # pads flush with the palm face
        prox = palm.add_body(
            name=f"{f.name}_proximal", pos=[f.x_cm * CM, PALM_HALF_CM[1] * CM, base_z * CM], gravcomp=1.0
        )
        _hinge(prox, f"{f.name}_mcp", (-1.0, 0.0, 0.0))  # +angle turns +y towards -z: flexion
        _capsule(prox, f"{f.name}_proximal_geom", (0, 0, 0), (0, p1, 0), f.radius_cm, f.mass_g[0])
        mid = prox.add_body(name=f"{f.name}_middle", pos=[0, p1 * CM, 0], gravcomp=1.0)
        _hinge(mid, f"{f.name}_pip", (-1.0, 0.0, 0.0))
        # The middle+distal body's mass splits 60/40 by length; the distal pad tapers to 0.9 of the radius.
        _capsule(mid, f"{f.name}_middle_geom", (0, 0, 0), (0, p2, 0), f.radius_cm, f.mass_g[1] * 0.6)
        bend = math.radians(DISTAL_BEND_DEG)
        tip = (0, p2 + p3 * math.cos(bend), -p3 * math.sin(bend))
        _capsule(mid, f"{f.name}_distal_geom", (0, p2, 0), tip, f.radius_cm * TIP_TAPER, f.mass_g[1] * 0.4)
        mid.add_site(name=f"{f.name}_tip", pos=[v * CM for v in tip], size=[0.003, 0, 0])

    t = THUMB
    base = palm.add_body(name="thumb_base", pos=[v * CM for v in t.base_cm], gravcomp=1.0)
    _hinge(base, "thumb_rot", (0.0, -1.0, 0.0))  # +angle swings the tip towards +x (the index)
    _capsule(base, "thumb_metacarpal_geom", (0, 0, 0), (0, 0, -t.metacarpal_cm), t.radius_cm, t.mass_g[0])
    prox = base.add_body(name="thumb_proximal", pos=[0, 0, -t.metacarpal_cm * CM], gravcomp=1.0)
    _hinge(prox, "thumb_flex", (1.0, 0.0, 0.0))  # +angle turns -z towards +y: towards the fingers
    q1, q2 = t.lengths_cm
    bend = math.radians(THUMB_IP_BEND_DEG)
    tip = (0, q2 * math.sin(bend), -q1 - q2 * math.cos(bend))
    _capsule(prox, "thumb_proximal_geom", (0, 0, 0), (0, 0, -q1), t.radius_cm, t.mass_g[1] * 0.6)
    _capsule(prox, "thumb_distal_geom", (0, 0, -q1), tip, t.radius_cm * TIP_TAPER, t.mass_g[1] * 0.4)
    prox.add_site(name="thumb_tip", pos=[v * CM for v in tip], size=[0.003, 0, 0])

    for name in WRIST_ACTUATOR_NAMES:
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=WRIST_KP, dampratio=1.0)
        act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.forcerange = [-WRIST_FORCE_N, WRIST_FORCE_N]
    for name in ACTUATOR_NAMES:
        kind = _joint_kind(name)
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=KP[kind])
        lo, hi = RANGE_DEG[kind]
        act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
        # Targets may lie 30 degrees beyond the joint range: that is how a digit keeps pressing (at its
        # force limit) against an object that stops it, or against its own joint limit.
        act.ctrlrange = [math.radians(lo - 30.0), math.radians(hi + 30.0)]
        act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        lim = limits[name]
        act.forcerange = [-lim, lim]
    return palm


def digit_length_cm(digit: str, joint: str) -> float:
    if digit == "thumb":
        q1, q2 = THUMB.lengths_cm
        return q1 + q2 + (THUMB.metacarpal_cm if joint == "rot" else 0.0)
    p1, p2, p3 = FINGER_BY_NAME[digit].lengths_cm
    return p1 + p2 + p3 if joint == "mcp" else p2 + p3


def max_torques() -> dict[str, float]:
    """Each digit actuator's strongest torque (N m): its maximal force at the tip times the digit length."""
    out = {}
    for name in ACTUATOR_NAMES:
        digit, joint = name.split("_", 1)
        force = THUMB_MAX_FORCE_N if digit == "thumb" else FINGER_MAX_FORCE_N
        out[name] = force * digit_length_cm(digit, joint) * CM
    return out


def hand_spec(approach: str = "top") -> mujoco.MjSpec:
    """A spec with only the hand (and a floor light): for smoke tests and inspection."""
    spec = mujoco.MjSpec()
    configure_options(spec)
    spec.worldbody.add_light(pos=[0, 0, 1.0], dir=[0, 0, -1])
    add_hand(spec, approach=approach)
    return spec


def configure_options(spec: mujoco.MjSpec) -> None:
    """Simulator options shared by every hand model (see sim/PHYSICS.md)."""
    spec.compiler.degree = False  # every angle in this code is in radians (MJCF's default is degrees)
    opt = spec.option
    opt.timestep = 0.002  # 2 ms: contacts at solref 10 ms time constant need >= 2 steps per constant
    opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST  # implicit joint damping, stable stiff PDs
    opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC  # exact friction cone: no pyramid facets leaking grip
    opt.impratio = 10.0  # frictional stiffer than normal: holding without creeping slip (MuJoCo docs)
    opt.iterations = 50
    opt.ls_iterations = 20
    # opt.jacobian stays MuJoCo's auto, dense at these sizes: sparse changes a verdict (sim/PHYSICS.md)
