"""Sliding a small flat object out over the table edge before pinching it (an experiment; no trial uses it).

A coin or a paper clip at the table edge can overhang only as far as its centre of mass allows (0.45 of its
depth, sim/grasps.py ``edge_overhang_cm``), so the edge pinch's pads press nearer its rim than their own
radius and squeeze it out (sim/PHYSICS.md, "Narrow flat things"). People first slide it out under a
fingertip. This module holds what was measured of that idea with this hand (sim/PHYSICS.md, "Sliding a
coin to the edge"): the class of objects it is for (:func:`needs_slide`), the geometry it needs
(:func:`overhang_needed_cm`, :func:`rim_push_ratio`) and two slide phases on a built trial world, a press
and drag (:func:`press_drag`: a light press does not move it, the object's own friction governing both its
contacts; a firmer one tips it over the edge) and a hook behind the inner rim (:func:`hook_pull`: slides
it, the thumb holding it down). No re-grip from there into a pinch held, so the trial (sim/trial.py) does
not call these.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from sim import hand as H
from sim.diagnosis import PAD_TIP_RADIUS_CM
from sim.grasps import EDGE_PAD_CLEAR_CM, edge_grip_in_cm
from sim.runner import Runner, _smooth
from sim.world import TrialWorld

__all__ = [
    "HOOK_CLEARANCE_CM",
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
#: Phase durations (s): the thumb lowered behind the rim, then the wrist's pull.
LOWER_S = 0.3
PULL_S = 0.6
LOWER_FROM_CM = 3.0
#: An object whose centre ends this far (cm) below the table top has fallen off it.
FELL_CM = 1.0


def pad_radius_cm() -> float:
    """The smallest pad radius (cm) of the digits every pinch uses (sim/diagnosis.py ``PAD_TIP_RADIUS_CM``)."""
    return PAD_TIP_RADIUS_CM


def needs_slide(depth_cm: float) -> bool:
    """Does a flat object ``depth_cm`` deep across the table edge need sliding out before an edge pinch?
    Yes when the pads, laid where its centre of mass lets it overhang, would press nearer its rim than a
    pad's radius plus :data:`SLIDE_MARGIN_CM` (a coin: 0.3 cm; a paper clip: 0.585 cm)."""
    return edge_grip_in_cm(depth_cm) < pad_radius_cm() + SLIDE_MARGIN_CM


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


def _tip_m(world: TrialWorld, geom: str) -> np.ndarray:
    """World position (m) of the lower end of a digit capsule's axis."""
    m, d = world.model, world.data
    g = m.geom(geom).id
    axis = d.geom_xmat[g].reshape(3, 3)[:, 2] * m.geom_size[g][1]
    ends = (d.geom_xpos[g] - axis, d.geom_xpos[g] + axis)
    return min(ends, key=lambda e: e[2]).copy()


def _ramp(runner: Runner, duration: float, where: str, start: np.ndarray, end: np.ndarray) -> None:
    d, w = runner.d, runner.w
    runner._phase(
        duration, where, lambda u: d.ctrl.__setitem__(w.wrist_act, start + (end - start) * _smooth(u))
    )


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


def hook_pull(world: TrialWorld, depth_cm: float, pull_cm: float) -> Slide:
    """The thumb tip lowered just behind the object's inner rim (the table side, ``depth_cm`` from its outer
    one), the wrist pulls ``pull_cm`` along +x, over the edge. Call on a freshly built edge world."""
    radius = float(world.model.geom("thumb_distal_geom").size[0]) / H.CM
    _straighten_fingers(world)
    inner = _object_x_m(world) / H.CM - depth_cm / 2.0
    goal = np.array([inner - radius - HOOK_BEHIND_CM, 0.0, radius + HOOK_CLEARANCE_CM]) * H.CM
    return _lower_and_move(world, goal, pull_cm)


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


def _lower_and_move(world: TrialWorld, goal_m: np.ndarray, pull_cm: float) -> Slide:
    runner = Runner(world)
    wrist = _start_above(world, goal_m)
    before = _object_x_m(world)
    above = world.data.ctrl[world.wrist_act].copy()
    _ramp(runner, LOWER_S, " while lowering the thumb", above, wrist)
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
