"""Sliding a small flat object out over the table edge before pinching it (programs version 8).

A coin or a paper clip at the table edge can overhang only as far as its centre of mass allows (0.45 of its
depth, sim/grasps.py ``edge_overhang_cm``), so the edge pinch's pads press nearer its rim than their own
radius and squeeze it out (sim/PHYSICS.md, "Narrow flat things"). People first slide it out under a
fingertip. Here (sim/PHYSICS.md, "Sliding a coin to the edge"): the class of objects it is for
(:func:`needs_slide`, :func:`slides`), the geometry it needs (:func:`overhang_needed_cm`,
:func:`rim_push_ratio`), two measured slide phases (:func:`press_drag`: a light press does not move a coin,
the object's own friction governing both its contacts, a firmer one tips it over the edge;
:func:`hook_pull`: a thumb hook behind the inner rim slides it, holding it down) and the program the trial
runs in place of the approach and the close (:func:`slide_and_pinch`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from sim import hand as H
from sim.diagnosis import PAD_TIP_RADIUS_CM
from sim.grasps import EDGE_PAD_CLEAR_CM, edge_grip_in_cm
from sim.programs import program_for
from sim.runner import Runner, _smooth
from sim.world import TrialWorld

__all__ = [
    "HOOK_CLEARANCE_CM",
    "HOOK_RIM_FRACTION",
    "hook_clearance_cm",
    "SLIDE_MARGIN_CM",
    "Slide",
    "hook_pull",
    "needs_slide",
    "overhang_needed_cm",
    "pad_radius_cm",
    "press_drag",
    "rim_push_ratio",
]

#: The pads must press at least their radius plus this in from the rim to hold it (cm).
SLIDE_MARGIN_CM = 0.3
#: The hooking thumb tip hangs this far above the table top (cm), and starts this far behind the rim.
HOOK_CLEARANCE_CM = 0.05
HOOK_BEHIND_CM = 0.1
#: ... but never higher than this fraction of the rim's height: a round tip must meet a low rim well below
#: its top to push it along rather than down (programs version 10). At 0.5 mm a paper clip's 1 mm wire met
#: the tip half-way up (forward over downward push 0.35 against its friction 0.32) and did not move; at a
#: third of its height (0.33 mm, 0.46: 1.45 times its friction, as the quarter's 0.59 against 0.4) it slides.
HOOK_RIM_FRACTION = 0.25
#: Phase durations (s): the thumb lowered behind the rim, then the wrist's pull.
LOWER_S = 0.3
PULL_S = 0.6
LOWER_FROM_CM = 3.0
#: An object whose centre ends this far (cm) below the table top has fallen off it.
FELL_CM = 1.0


def pad_radius_cm() -> float:
    """The smallest pad radius (cm) of the digits every pinch uses (sim/diagnosis.py ``PAD_TIP_RADIUS_CM``)."""
    return PAD_TIP_RADIUS_CM


def needs_slide(depth_cm: float, thickness_cm: float) -> bool:
    """Does a flat object ``depth_cm`` deep across the table edge and ``thickness_cm`` thick need sliding out
    before an edge pinch? Yes when the pads, laid where its centre of mass lets it overhang, would press
    nearer its rim than a pad's radius plus :data:`SLIDE_MARGIN_CM` (a coin: 0.3 cm; a paper clip: 0.585
    cm) and it is thinner than a pad's radius (a plate the pads' curvature squeezes out; the teaspoon,
    1 cm thick, holds in the plain edge pinch at 0.45 cm from its rim)."""
    return edge_grip_in_cm(depth_cm) < pad_radius_cm() + SLIDE_MARGIN_CM and thickness_cm < pad_radius_cm()


def overhang_needed_cm() -> float:
    """How far (cm) the object must overhang so that the pads, clear of the table edge, press a pad radius
    plus the margin in from its rim. More than half a coin's 2.3 cm: its centre of mass is then off the
    table, so it must be held down until the pinch closes."""
    return EDGE_PAD_CLEAR_CM + pad_radius_cm() + SLIDE_MARGIN_CM


def rim_push_ratio(
    thickness_cm: float, tip_radius_cm: float, clearance_cm: float = HOOK_CLEARANCE_CM
) -> float:
    """Horizontal over downward part of the force a round tip, hanging ``clearance_cm`` above the table,
    exerts on the top corner of a rim ``thickness_cm`` high. The object slides when this exceeds its
    friction on the table (the downward part adds to the load); a rim as high as the tip's centre: inf."""
    below = tip_radius_cm + clearance_cm - thickness_cm
    if below <= 0.0:
        return math.inf
    if below >= tip_radius_cm:
        return 0.0
    return math.sqrt(tip_radius_cm**2 - below**2) / below


def _axis_ends(world: TrialWorld, g: int) -> tuple[np.ndarray, np.ndarray]:
    """World positions (m) of the two ends of capsule geom ``g``'s axis."""
    axis = world.data.geom_xmat[g].reshape(3, 3)[:, 2] * world.model.geom_size[g][1]
    return world.data.geom_xpos[g] - axis, world.data.geom_xpos[g] + axis


def _tip_m(world: TrialWorld, geom: str) -> np.ndarray:
    """World position (m) of the lower end of a digit capsule's axis."""
    return min(_axis_ends(world, world.model.geom(geom).id), key=lambda e: e[2]).copy()


def _ctrl_to(runner: Runner, act: np.ndarray, target: np.ndarray, duration: float, where: str) -> None:
    """Ramp the controls ``act`` (the wrist's or the digits') smoothly from where they are to ``target``."""
    d = runner.d
    start = d.ctrl[act].copy()
    runner._phase(duration, where, lambda u: d.ctrl.__setitem__(act, start + (target - start) * _smooth(u)))


def _straighten_fingers(world: TrialWorld) -> None:
    """Fingers straight (pointing down at the edge, out of the table); the thumb keeps its pre-shape."""
    q = world.data.ctrl[world.digit_act].copy()
    q[2:] = 0.0
    world.data.ctrl[world.digit_act] = q
    world.data.qpos[world.digit_qpos] = q


def _start_above(world: TrialWorld, goal_m: np.ndarray) -> np.ndarray:
    """Place the wrist so the thumb tip's centre will be at ``goal_m`` once lowered; returns that wrist pose
    (the hand starts :data:`LOWER_FROM_CM` above it)."""
    d = world.data
    mujoco.mj_forward(world.model, d)
    wrist = d.qpos[world.wrist_qpos] + (goal_m - _tip_m(world, "thumb_distal_geom"))
    above = wrist + np.array([0.0, 0.0, LOWER_FROM_CM * H.CM])
    d.qpos[world.wrist_qpos] = above
    d.ctrl[world.wrist_act] = above
    mujoco.mj_forward(world.model, d)
    return wrist


def _object_x_m(world: TrialWorld) -> float:
    return float(world.data.xpos[world.object_body][0])


def hook_clearance_cm(thickness_cm: float) -> float:
    """How high (cm) the hooking thumb tip hangs above the table behind a rim ``thickness_cm`` high:
    :data:`HOOK_CLEARANCE_CM`, at most :data:`HOOK_RIM_FRACTION` of the rim's height."""
    return min(HOOK_CLEARANCE_CM, HOOK_RIM_FRACTION * thickness_cm)


def hook_pull(world: TrialWorld, depth_cm: float, pull_cm: float, runner: Runner | None = None) -> Slide:
    """The thumb tip lowered just behind the object's inner rim (the table side, ``depth_cm`` from its outer
    one; :func:`hook_clearance_cm` above the table), the wrist pulls ``pull_cm`` along +x, over the edge.
    Call on a freshly built edge world (the hand starts above the hook point); ``runner``: the trial's, so
    that it measures as it goes."""
    radius = float(world.model.geom("thumb_distal_geom").size[0]) / H.CM
    _straighten_fingers(world)
    inner = _object_x_m(world) / H.CM - depth_cm / 2.0
    thickness = 2.0 * float(world.data.xpos[world.object_body][2]) / H.CM
    goal = np.array([inner - radius - HOOK_BEHIND_CM, 0.0, radius + hook_clearance_cm(thickness)]) * H.CM
    return _lower_and_move(world, goal, pull_cm, runner)


def press_drag(world: TrialWorld, pull_cm: float, press_cm: float, inward_cm: float = 0.0) -> Slide:
    """The thumb tip lowered ``press_cm`` into the object's top, ``inward_cm`` from its centre towards the
    table side, then the wrist drags it ``pull_cm`` along +x (a fingertip pressing and sliding it)."""
    radius = float(world.model.geom("thumb_distal_geom").size[0]) / H.CM
    _straighten_fingers(world)
    top = 2.0 * float(world.data.xpos[world.object_body][2]) / H.CM
    centre = _object_x_m(world) / H.CM
    goal = np.array([centre - inward_cm, 0.0, top + radius - press_cm]) * H.CM
    return _lower_and_move(world, goal, pull_cm)


@dataclass(frozen=True)
class Slide:
    """What a slide phase did: how far (cm) the object moved along +x, the thumb's mean normal force on it
    during the pull (N), its tilt at the end (deg) and whether it fell off the table (:data:`FELL_CM`)."""

    slid_cm: float
    thumb_n: float
    tilt_deg: float
    fell: bool


def _lower_and_move(
    world: TrialWorld, goal_m: np.ndarray, pull_cm: float, runner: Runner | None = None
) -> Slide:
    runner = runner or Runner(world)
    wrist = _start_above(world, goal_m)
    before = _object_x_m(world)
    _ctrl_to(runner, world.wrist_act, wrist, LOWER_S, " while lowering the thumb")
    forces: list[float] = []
    end = wrist + np.array([pull_cm * H.CM, 0.0, 0.0])

    def pull(u: float) -> None:
        world.data.ctrl[world.wrist_act] = wrist + (end - wrist) * _smooth(u)
        forces.append(world.digit_forces()["thumb"])

    runner._phase(PULL_S, " while sliding", pull)
    d = world.data
    tilt = math.degrees(math.acos(min(1.0, float(d.xmat[world.object_body][8]))))
    return Slide(
        slid_cm=round((_object_x_m(world) - before) / H.CM, 3),
        thumb_n=round(float(np.mean(forces)), 3),
        tilt_deg=round(tilt, 2),
        fell=bool(d.xpos[world.object_body][2] < -FELL_CM * H.CM),
    )


# ---------------------------------------------------------------------------------------------------------
# The slide-and-pinch program: hook it out, catch it from below, then pinch it across its thickness
# ---------------------------------------------------------------------------------------------------------
#: The thumb's flexion (rad) while it hooks the rim: at this flexion the wrist sits low enough that the
#: index pad reaches the object's underside 1.7-2.1 cm from the hooked rim (a kinematic scan of 0.3-0.55
#: rad; the pre-shape's 0.59 reaches only 1.4 cm: inside a coin's centre of mass).
HOOK_THUMB_FLEX = 0.48
#: The pull is the slide needed plus what the hook's gap and the thumb's give take up (cm, measured: a
#: 1.5 cm pull slides the euro coin 0.93 cm).
PULL_SLACK_CM = 0.6
#: The finger pads catch the object this far (cm) beyond its centre of mass and this far below it.
CATCH_BEYOND_CM = 0.7
CATCH_BELOW_CM = 0.05
#: After the catch the thumb lifts by this (rad) and the wrist rises by RISE_CM, the fingers holding their
#: pads where they caught it (inverse kinematics), then it shifts until the thumb is over them.
THUMB_LIFT_RAD = 0.35
RISE_CM = 1.0
IK_STEPS = 10
IK_STEP_S = 0.04
#: Once the thumb touches the top, thumb and fingers press on past it (rad), force-limited like the plain
#: pinch's 1 cm overshoot (sim/hand.py: each digit presses at the plan's torque limit).
PRESS_PAST_RAD = (0.2, 0.15)


def slide_overhang_cm(depth_cm: float) -> float:
    """How far (cm) the slide pulls the object's outer rim past the table edge: :func:`overhang_needed_cm`,
    and at least so far that its centre of mass is past the edge (the catching pads hold it there)."""
    return max(overhang_needed_cm(), depth_cm / 2.0 + HOOK_BEHIND_CM)


def slides(world: TrialWorld) -> bool:
    """Does this trial slide the object out first? An edge pinch (a pinch program; not a sheet, not a lever
    hold) of a flat object too shallow for the plain edge pinch (:func:`needs_slide`)."""
    plan = world.plan
    return (
        world.approach == "edge"
        and program_for(plan.grasp_type).control == "pinch"
        and plan.params.get("edge_depth_cm") is not None
        and needs_slide(float(plan.params["edge_depth_cm"]), float(plan.params.get("width_cm", math.inf)))
        and not plan.params.get(H.FINGER_LEAD_PARAM)
        and not plan.params.get("sheet_held_cm")
    )


def _finger_rows(world: TrialWorld) -> list[tuple[int, int, list[int]]]:
    """Per used finger: its MCP and PIP actuator indices and its middle and distal geoms."""
    rows = []
    for f in world.targets.fingers:
        k = H.ACTUATOR_NAMES.index(f"{f}_mcp")
        geoms = [world.model.geom(f"{f}_{s}_geom").id for s in ("middle", "distal")]
        rows.append((k, k + 1, geoms))
    return rows


def _top_point(world: TrialWorld, geoms: list[int]) -> tuple[float, float]:
    """(z, x) in m of the highest end of a finger's middle and distal capsules, plus their radius."""
    best = (-np.inf, 0.0)
    for g in geoms:
        for end in _axis_ends(world, g):
            z = float(end[2] + world.model.geom_size[g][0])
            if z > best[0]:
                best = (z, float(end[0]))
    return best


def _catch_posture(world: TrialWorld, wrist: np.ndarray, x_m: float, z_m: float) -> np.ndarray:
    """Digit targets with each used finger's highest pad point nearest (x_m, z_m) with the wrist at
    ``wrist`` (a grid over MCP and the PIP-per-MCP ratio; z weighs 3 times x)."""
    d, m = world.data, world.model
    saved = d.qpos.copy()
    out = d.ctrl[world.digit_act].copy()
    d.qpos[world.wrist_qpos] = wrist
    for mcp_k, pip_k, geoms in _finger_rows(world):
        best = None
        for mcp in np.linspace(0.6, 1.57, 60):
            for ratio in np.linspace(0.4, 1.3, 19):
                pip = min(1.74, ratio * mcp)
                d.qpos[world.digit_qpos[mcp_k]], d.qpos[world.digit_qpos[pip_k]] = mcp, pip
                mujoco.mj_kinematics(m, d)
                z, x = _top_point(world, geoms)
                err = 3.0 * abs(z - z_m) + abs(x - x_m)
                if best is None or err < best[0]:
                    best = (err, mcp, pip)
        out[mcp_k], out[pip_k] = best[1], best[2]
    d.qpos[:] = saved
    mujoco.mj_kinematics(m, d)
    return out


def _thumb_touch(world: TrialWorld, top_m: float) -> tuple[float, float]:
    """The thumb flexion at which its tip's lowest point reaches ``top_m`` with the wrist where it is
    commanded, and that point's x (m)."""
    d, m = world.data, world.model
    saved = d.qpos.copy()
    radius = float(m.geom("thumb_distal_geom").size[0])
    d.qpos[world.wrist_qpos] = d.ctrl[world.wrist_act]

    def low(flex: float) -> tuple[float, float]:
        d.qpos[world.digit_qpos[1]] = flex
        mujoco.mj_kinematics(m, d)
        tip = _tip_m(world, "thumb_distal_geom")
        return float(tip[2]) - radius, float(tip[0])

    lo, hi = float(d.ctrl[world.digit_act][1]), float(m.jnt_range[m.actuator_trnid[world.digit_act[1], 0]][1])
    for _ in range(30):
        mid = (lo + hi) / 2.0
        lo, hi = (mid, hi) if low(mid)[0] > top_m else (lo, mid)
    x = low(lo)[1]
    d.qpos[:] = saved
    mujoco.mj_kinematics(m, d)
    return lo, x


def _ik_move(runner: Runner, world: TrialWorld, start: np.ndarray, end: np.ndarray, catch: tuple) -> None:
    """Move the wrist from ``start`` to ``end`` in IK_STEPS steps, the fingers keeping their pads at
    ``catch`` (x, z in m)."""
    d = world.data
    for k in range(IK_STEPS):
        wrist = start + (end - start) * (k + 1) / IK_STEPS
        target = _catch_posture(world, wrist, *catch)
        w0, q0 = d.ctrl[world.wrist_act].copy(), d.ctrl[world.digit_act].copy()

        def step(u: float, w0=w0, q0=q0, wrist=wrist, target=target) -> None:
            d.ctrl[world.wrist_act] = w0 + (wrist - w0) * u
            d.ctrl[world.digit_act] = q0 + (target - q0) * u

        runner._phase(IK_STEP_S, " while re-gripping", step)


def slide_and_pinch(runner: Runner, world: TrialWorld) -> None:
    """The slide program's approach and close (instead of Runner.approach and Runner.close): the thumb hooks
    the table-side rim and pulls the object out past the edge (:func:`slide_overhang_cm`), the fingers catch
    it from below beyond its centre of mass, the thumb lifts, the wrist rises and shifts until the thumb is
    over the fingers (the fingers holding their pads under it), the thumb touches its top and both press on,
    force-limited; then the plain pinch's impedance hold latches. The lift, hold and pushes follow as ever."""
    d, m = world.data, world.model
    depth = float(world.plan.params["edge_depth_cm"])
    thickness = 2.0 * float(d.xpos[world.object_body][2]) / H.CM
    table = m.geom("table")
    edge_cm = float(table.pos[0] + table.size[0]) / H.CM  # the table's +x edge (sim/objects.py add_table)
    _straighten_fingers(world)
    q = d.ctrl[world.digit_act].copy()
    q[1] = HOOK_THUMB_FLEX
    d.ctrl[world.digit_act] = q
    d.qpos[world.digit_qpos] = q
    outer = _object_x_m(world) / H.CM + depth / 2.0
    pull = slide_overhang_cm(depth) - (outer - edge_cm) + PULL_SLACK_CM
    hook_pull(world, depth, pull, runner=runner)
    wrist = d.ctrl[world.wrist_act].copy()
    centre = _object_x_m(world)
    catch = (centre + CATCH_BEYOND_CM * H.CM, -CATCH_BELOW_CM * H.CM)
    _ctrl_to(runner, world.digit_act, _catch_posture(world, wrist, *catch), 0.3, " while catching")
    lifted = d.ctrl[world.digit_act].copy()
    lifted[1] -= THUMB_LIFT_RAD
    _ctrl_to(runner, world.digit_act, lifted, 0.15, " while lifting the thumb")
    risen = wrist + np.array([0.0, 0.0, RISE_CM * H.CM])
    _ik_move(runner, world, wrist, risen, catch)
    _, thumb_x = _thumb_touch(world, thickness * H.CM)
    over = risen + np.array([catch[0] - thumb_x, 0.0, 0.0])
    _ik_move(runner, world, risen, over, catch)
    flex, _ = _thumb_touch(world, thickness * H.CM)
    touch = d.ctrl[world.digit_act].copy()
    touch[1] = flex
    _ctrl_to(runner, world.digit_act, touch, 0.25, " while closing")
    press = touch.copy()
    press[1] += PRESS_PAST_RAD[0]
    for mcp_k, pip_k, _ in _finger_rows(world):
        press[mcp_k] += PRESS_PAST_RAD[1]
        press[pip_k] += PRESS_PAST_RAD[1]
    _ctrl_to(runner, world.digit_act, press, 0.25, " while closing")
    runner._phase(0.15, " while closing")
    runner.wrist_base = d.ctrl[world.wrist_act].copy()
    runner.latch_reference()
