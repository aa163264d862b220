"""The AR10-like hand's postures for a grasp plan: pre-shape, touch and closing targets, and the torque
limits that give the plan's squeeze, from the grasp type's hand program (sim/programs.py).

The hand itself (geometry, joints, actuators, kinematics) is built in sim/hand_model.py; its names are
re-exported here, so ``from sim import hand as H`` reaches both.

Bump :data:`HAND_VERSION` whenever the model or the postures change: it is stored with every validation
result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from sim.bodies import GEOMETRY_VERSION
from sim.grasps import FINGER_LEAD_PARAM, FINGER_MAX_FORCE_N, GRASP_TYPES, THUMB_MAX_FORCE_N, GraspPlan
from sim.hand_kinematics import finger_tip, finger_tip_y_of, thumb_tip
from sim.hand_model import (
    ACTUATOR_NAMES,
    APPROACH_QUAT,
    CLOSING_FORCE_FLOOR_N,
    CM,
    DIGITS,
    FINGER_BY_NAME,
    FINGERS,
    HAND_BIT,
    HOLD_STIFFNESS_FACTOR,
    JOINT_NAMES,
    OBJECT_BIT,
    PALM_HALF_CM,
    RANGE_DEG,
    TABLE_BIT,
    THUMB,
    TIP_TAPER,
    UNUSED_TORQUE_NM,
    WRIST_ACTUATOR_NAMES,
    WRIST_JOINT_NAMES,
    Finger,
    Thumb,
    add_hand,
    configure_options,
    digit_length_cm,
    hand_spec,
    max_torques,
)
from sim.programs import PROGRAMS_VERSION, program_for

# The model's names (sim/hand_model.py, its kinematics sim/hand_kinematics.py) are re-exported: ``from sim
# import hand as H`` reaches them all.
__all__ = [
    "ACTUATOR_NAMES",
    "APPROACH_QUAT",
    "CM",
    "DIGITS",
    "FINGERS",
    "FINGER_BY_NAME",
    "FINGER_LEAD_PARAM",
    "FINGER_MAX_FORCE_N",
    "HAND_BIT",
    "HAND_VERSION",
    "HOLD_STIFFNESS_FACTOR",
    "JOINT_NAMES",
    "OBJECT_BIT",
    "PALM_HALF_CM",
    "PIP_PER_MCP",
    "TABLE_BIT",
    "THUMB_MAX_FORCE_N",
    "UNUSED_TORQUE_NM",
    "WRIST_ACTUATOR_NAMES",
    "WRIST_JOINT_NAMES",
    "Finger",
    "GraspTargets",
    "Thumb",
    "add_hand",
    "configure_options",
    "digit_length_cm",
    "finger_pinch_mcp",
    "finger_tip",
    "grasp_targets",
    "hand_spec",
    "max_torques",
    "thumb_flex_for",
    "thumb_tip",
]

# 6: one hand program per grasp type (sim/programs.py); g: object geometry (sim/bodies.py), same re-run rule
HAND_VERSION = f"ar10like-6.{PROGRAMS_VERSION}-g{GEOMETRY_VERSION}"


#: Precision finger posture: PIP follows MCP at this ratio, so the pad turns to face the thumb.
PIP_PER_MCP = 0.8
#: How far past the object's surface precision targets are placed (cm): far enough that the pads press
#: at their force limit, near enough that an object slipping out leaves them closed in the air instead
#: of sweeping it along (a thumb swinging on far past contact rolls the object up and out) or caging it.
PRECISION_OVERSHOOT_CM = 1.0
#: The fingers of an edge lever hold are nearly extended under the object (PIP 0.3 of MCP, the program's
#: 0.8 curls them): Feix 2016's parallel extension, fingers straight under a plate, the thumb on top.
EDGE_LEVER_PIP_PER_MCP = 0.3
#: A wrapped object keeps this far (cm) off the thumb's hanging metacarpal at the pre-shape.
WRAP_THUMB_CLEARANCE_CM = 0.5


def _solve(fn, target: float, lo: float, hi: float) -> float:
    """The x in [lo, hi] where the monotonic ``fn(x)`` reaches ``target`` (clamped to the ends)."""
    f_lo, f_hi = fn(lo) - target, fn(hi) - target
    if f_lo * f_hi > 0:
        return lo if abs(f_lo) < abs(f_hi) else hi
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        f_mid = fn(mid) - target
        if f_mid * f_lo > 0:
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def finger_pinch_mcp(finger: str, y_cm: float, pip_per_mcp: float = PIP_PER_MCP) -> float:
    """MCP angle (radians, PIP following at ``pip_per_mcp``) that puts ``finger``'s tip at hand-frame ``y_cm``."""
    lo, hi = 0.0, math.radians(RANGE_DEG["mcp"][1])
    pip_max = math.radians(RANGE_DEG["pip"][1])
    return _solve(finger_tip_y_of(finger, pip_per_mcp, pip_max), y_cm, lo, hi)


def thumb_flex_for(y_cm: float) -> float:
    """Thumb flexion (radians) that puts its tip at hand-frame ``y_cm``."""
    lo, hi = (math.radians(v) for v in RANGE_DEG["thumb_flex"])
    return _solve(lambda q: thumb_tip(q)[0], y_cm, lo, hi)


@dataclass(frozen=True)
class GraspTargets:
    """Joint targets (radians, in :data:`ACTUATOR_NAMES` order) and force limits for one grasp.

    ``open``: the pre-shape (hand opened to the plan's aperture around ``center_y_cm``). ``touch``
    (precision grasps; the pre-shape for power grasps): where each pad just meets the object, so that
    thumb and fingers can arrive together instead of one pushing the object into the other. ``close``: where
    the digits are driven to; they stop on the object and press at ``closing_limits`` (N m). Then the
    trial holds the ``squeezing`` joints with ``torque_limits``: the torques that give the plan's grip
    force. ``center_y_cm`` and ``contact_z_cm``: where (hand frame, y) the object's centre
    belongs and at which height (hand frame, z) the digits first meet a ``width_cm`` wide object.
    """

    open: np.ndarray
    close: np.ndarray
    touch: np.ndarray
    torque_limits: dict[str, float]
    closing_limits: dict[str, float]
    squeezing: tuple[str, ...]
    fingers: tuple[str, ...]
    center_y_cm: float
    contact_z_cm: float
    side_force_n: float


def grasp_targets(
    plan: GraspPlan,
    width_cm: float | None = None,
    *,
    align_pads: bool = False,
    overshoot_cm: float = PRECISION_OVERSHOOT_CM,
    ball: bool = False,
) -> GraspTargets:
    """Pre-shape and closing targets for ``plan``, for an object ``width_cm`` wide along the opposition axis.

    ``width_cm`` defaults to the plan's aperture less the planner's margin. Closing is force-limited
    position control: each used digit's target lies beyond contact (power: fully flexed; precision: the
    pads 1 cm past the object's surface), and its actuator's force limit is the torque that presses
    with its share of the planned grip force. The plan's ``grip_force_n`` is the squeeze: the normal
    force on each side of the opposition axis (the planner's F = m g SF / (2 mu) for a two-sided grip).
    The thumb presses with all of it and the fingers share it, so forces balance across the object;
    the squeeze is capped by the weaker side's strength (:data:`FINGER_MAX_FORCE_N` per finger,
    :data:`THUMB_MAX_FORCE_N`). While closing, a floor of :data:`CLOSING_FORCE_FLOOR_N` keeps light
    grips from closing too slowly (speed is torque over damping). Unused fingers stay straight and, in
    precision grasps, above the object. ``align_pads``: a pinch's used fingers each get the PIP-per-MCP
    ratio that puts their pads at the thumb's height (off a table edge; sim/world.py asks for it).
    ``ball``: the object is a sphere ``width_cm`` across (sim/world.py says so): a wrap places it as near
    the thumb as its curved side clears the thumb's metacarpal (:func:`ball_center_y_cm`), not its widest
    part.
    """
    if plan.grasp_type not in GRASP_TYPES:
        raise ValueError(f"unknown grasp type {plan.grasp_type!r}")
    program = program_for(plan.grasp_type)
    aperture = max(float(plan.aperture_cm), 0.5)
    width = float(width_cm) if width_cm is not None else max(0.5, aperture - 1.5)
    fingers = program.fingers
    side = min(max(plan.grip_force_n, 0.1), THUMB_MAX_FORCE_N, FINGER_MAX_FORCE_N * len(fingers))
    limits, closing, squeezing = _force_limits(program, side)
    if program.control == "wrap":
        open_q, close_q, touch_q, center, contact_z, reach = _wrap_posture(program, aperture, width, ball)
    else:
        lead = float(plan.params.get(FINGER_LEAD_PARAM, 0.0))
        if lead:
            program = replace(program, pip_per_mcp=EDGE_LEVER_PIP_PER_MCP)
        open_q, close_q, touch_q, center, contact_z, reach = _pinch_posture(
            program, aperture, width, align_pads, overshoot_cm, lead
        )
    open_q["thumb_rot"] = close_q["thumb_rot"] = _thumb_rotation(program, reach)
    return GraspTargets(
        open=np.array([open_q[n] for n in ACTUATOR_NAMES]),
        close=np.array([close_q[n] for n in ACTUATOR_NAMES]),
        touch=np.array([touch_q.get(n, open_q[n]) for n in ACTUATOR_NAMES]),
        torque_limits=limits,
        closing_limits=closing,
        squeezing=squeezing,
        fingers=fingers,
        center_y_cm=center,
        contact_z_cm=contact_z,
        side_force_n=side,
    )


def _force_limits(program, side: float) -> tuple[dict[str, float], dict[str, float], tuple[str, ...]]:
    """Holding torque limits (the thumb presses with the squeeze ``side``, the fingers share it), closing
    limits (at least the closing floor) and the squeezing joints."""
    fingers, lever = program.fingers, program.lever
    per_finger = side / len(fingers)
    limits = dict.fromkeys(ACTUATOR_NAMES, UNUSED_TORQUE_NM)
    limits["thumb_rot"] = THUMB_MAX_FORCE_N * digit_length_cm("thumb", "rot") * CM
    limits["thumb_flex"] = side * lever * digit_length_cm("thumb", "flex") * CM
    for f in fingers:
        limits[f"{f}_mcp"] = per_finger * lever * digit_length_cm(f, "mcp") * CM
        limits[f"{f}_pip"] = per_finger * lever * digit_length_cm(f, "pip") * CM
    squeezing = ("thumb_flex", *(f"{f}_{j}" for f in fingers for j in ("mcp", "pip")))
    closing = dict(limits)
    for name in squeezing:
        digit, joint = name.split("_", 1)
        floor = CLOSING_FORCE_FLOOR_N * lever * digit_length_cm(digit, joint) * CM
        closing[name] = max(limits[name], floor)
    return limits, closing, squeezing


def ball_center_y_cm(diameter_cm: float, palm_gap_cm: float) -> float:
    """The nearest hand-frame y (cm) to the thumb at which a ball ``diameter_cm`` across, its top
    ``palm_gap_cm`` under the palm face, clears the thumb's metacarpal (a capsule hanging
    :data:`THUMB` ``metacarpal_cm`` from the CMC) by :data:`WRAP_THUMB_CLEARANCE_CM`. A box's near face is
    as wide at the palm as below it; a ball's near side curves away under the metacarpal's end, so it can
    sit that much nearer the thumb, whose phalanges then reach round its near side to its equator."""
    radius = diameter_cm / 2.0
    centre_z = -PALM_HALF_CM[2] - palm_gap_cm - radius
    end_z = THUMB.base_cm[2] - THUMB.metacarpal_cm  # the metacarpal's lower end (the ball's centre is below)
    reach = radius + THUMB.radius_cm + WRAP_THUMB_CLEARANCE_CM
    dz = max(0.0, end_z - centre_z)
    return THUMB.base_cm[1] + math.sqrt(max(0.0, reach * reach - dz * dz))


def _wrap_posture(program, aperture: float, width: float, ball: bool = False):
    """A wrap's (open, close, touch, centre y, contact z, thumb reach): the object sits under the palm
    between the hanging thumb and the knuckles, centred between them when it fits; a wider one overhangs
    the knuckles (never the thumb, which hangs from the palm), and the fingers wrap down over its far
    side, driven to the program's closing targets. A ``ball`` sits as near the thumb as its curved side
    clears the metacarpal (:func:`ball_center_y_cm`)."""
    open_q = dict.fromkeys(ACTUATOR_NAMES, 0.0)
    close_q = dict.fromkeys(ACTUATOR_NAMES, 0.0)
    thumb_clear = THUMB.base_cm[1] + THUMB.radius_cm + WRAP_THUMB_CLEARANCE_CM
    knuckle_clear = PALM_HALF_CM[1] - FINGER_BY_NAME["middle"].radius_cm - 0.3
    near = ball_center_y_cm(width, program.palm_gap_cm) if ball else thumb_clear + width / 2.0
    center = max(0.5 * (thumb_clear + knuckle_clear), near)
    # Thumb open: its pad (one radius in front of the tip's axis) at least 5 mm off the near side.
    open_q["thumb_flex"] = thumb_flex_for(min(center - aperture / 2.0, center - width / 2.0 - 0.5) - THUMB.radius_cm)
    close_q["thumb_flex"] = math.radians(RANGE_DEG["thumb_flex"][1] + 30.0)
    for f in program.fingers:
        open_q[f"{f}_pip"] = math.radians(10.0)
        close_q[f"{f}_mcp"] = math.radians(program.mcp_close_deg)
        close_q[f"{f}_pip"] = math.radians(program.pip_close_deg)
    reach = THUMB.metacarpal_cm + sum(THUMB.lengths_cm)
    return open_q, close_q, {}, center, -PALM_HALF_CM[2], reach


def _pinch_posture(
    program,
    aperture: float,
    width: float,
    align_pads: bool = False,
    overshoot: float = PRECISION_OVERSHOOT_CM,
    lead: float = 0.0,
):
    """A pinch's (open, close, touch, centre y, contact z, thumb reach): the pads press on opposite sides
    at one height (else the squeeze is a couple that turns the object), so the pinch centre is where, for
    this width, the thumb tip and the finger tips touch the object at the same depth below the palm (an edge
    lever hold: the finger tips ``lead`` cm deeper). Tip positions are capsule axis ends: the pads'
    surfaces lie one radius closer to the object."""
    fingers, ratio = program.fingers, program.pip_per_mcp
    pip_max = math.radians(RANGE_DEG["pip"][1])

    def pip_of(q: float) -> float:
        return min(pip_max, ratio * q)

    r_t = THUMB.radius_cm * TIP_TAPER
    half_open = aperture / 2.0

    def height_gap(c: float) -> float:
        thumb_z = thumb_tip(thumb_flex_for(c - width / 2.0 - r_t))[1]
        zs = []
        for f in fingers:
            q = finger_pinch_mcp(f, c + width / 2.0 + FINGER_BY_NAME[f].radius_cm * TIP_TAPER, ratio)
            zs.append(finger_tip(f, q, pip_of(q))[1])
        return thumb_z - float(np.mean(zs))

    center = _solve(height_gap, lead, -2.0, 8.0)  # the fingers ``lead`` cm deeper than the thumb
    open_q = dict.fromkeys(ACTUATOR_NAMES, 0.0)
    close_q = dict.fromkeys(ACTUATOR_NAMES, 0.0)
    touch_q: dict[str, float] = {}
    open_q["thumb_flex"] = thumb_flex_for(center - half_open - r_t)
    close_q["thumb_flex"] = thumb_flex_for(center - width / 2.0 - r_t + overshoot)
    touch_q["thumb_flex"] = thumb_flex_for(center - width / 2.0 - r_t)
    thumb_contact = thumb_tip(touch_q["thumb_flex"])[1]
    finger_contacts = []
    for f in fingers:
        r_f = FINGER_BY_NAME[f].radius_cm * TIP_TAPER
        y_touch = center + width / 2.0 + r_f
        f_ratio = _aligned_ratio(f, y_touch, thumb_contact, ratio) if align_pads else ratio
        q_open = finger_pinch_mcp(f, center + half_open + r_f, f_ratio)
        q_close = finger_pinch_mcp(f, center + width / 2.0 + r_f - overshoot, f_ratio)
        q_touch = finger_pinch_mcp(f, y_touch, f_ratio)
        for q_map, q in ((open_q, q_open), (close_q, q_close), (touch_q, q_touch)):
            q_map[f"{f}_mcp"], q_map[f"{f}_pip"] = q, min(pip_max, f_ratio * q)
        finger_contacts.append(finger_tip(f, q_touch, min(pip_max, f_ratio * q_touch))[1])
    contact_z = 0.5 * (thumb_contact + float(np.mean(finger_contacts)))
    # The thumb's rotation is about the palm's y axis: its lateral reach is the tip's depth below the CMC.
    return open_q, close_q, touch_q, center, contact_z, max(2.0, THUMB.base_cm[2] - thumb_contact)


def _aligned_ratio(finger: str, y_cm: float, z_cm: float, ratio: float) -> float:
    """The PIP-per-MCP ratio that puts ``finger``'s tip at (``y_cm``, ``z_cm``), searched between half and
    twice the program's ``ratio`` (at most 1.6) and clamped to that range: the fingers differ in length, so
    at one ratio their tips reach a pinch's far side at different heights (sim/PHYSICS.md, pads aligned)."""
    pip_max = math.radians(RANGE_DEG["pip"][1])

    def z_of(r: float) -> float:
        q = finger_pinch_mcp(finger, y_cm, r)
        return -finger_tip(finger, q, min(pip_max, r * q))[1]

    return _solve(z_of, -z_cm, 0.5 * ratio, min(1.6, 2.0 * ratio))


def _thumb_rotation(program, reach: float) -> float:
    """Thumb rotation (radians) aiming its tip at the program's target x (default: the centre of the
    fingers it opposes), ``reach`` cm from the CMC; clamped to the joint's range."""
    x_target = (
        program.thumb_aim
        if program.thumb_aim is not None
        else float(np.mean([FINGER_BY_NAME[f].x_cm for f in program.fingers]))
    )
    rot = math.asin(max(-1.0, min(1.0, (x_target - THUMB.base_cm[0]) / reach)))
    return max(math.radians(RANGE_DEG["thumb_rot"][0]), min(math.radians(RANGE_DEG["thumb_rot"][1]), rot))
