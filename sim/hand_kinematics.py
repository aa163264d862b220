"""Planar kinematics of the hand's digits (sim/hand_model.py): where a finger's or the thumb's tip is, in the
hand's y-z plane (cm, hand frame ``H``), at given joint angles. The posture solvers of sim/hand.py call these
thousands of times per trial, so the chains are unrolled over constants taken once from the model.
"""

from __future__ import annotations

import math

from sim.hand_model import DISTAL_BEND_DEG, FINGERS, PALM_HALF_CM, THUMB, THUMB_IP_BEND_DEG

__all__ = ["finger_tip", "finger_tip_y_of", "thumb_tip"]


def finger_tip(finger: str, mcp: float, pip: float) -> tuple[float, float]:
    """(y, z) in cm, hand frame, of ``finger``'s tip at joint angles ``mcp``, ``pip`` (radians).

    The posture solvers call this some 3000 times per pinch trial, so the chain is unrolled over constants
    taken once (:data:`_TIP_CHAIN`); the operations and their order are those of a loop over the phalanges."""
    p1, p2, p3, y, z = _TIP_CHAIN[finger]
    angle = 0.0 + mcp
    y += p1 * math.cos(angle)
    z -= p1 * math.sin(angle)
    angle += pip
    y += p2 * math.cos(angle)
    z -= p2 * math.sin(angle)
    angle += _DISTAL_BEND
    y += p3 * math.cos(angle)
    z -= p3 * math.sin(angle)
    return y, z


def finger_tip_y_of(finger: str, pip_per_mcp: float, pip_max: float):
    """The y of :func:`finger_tip` (the same operations) as a function of the MCP angle alone, the PIP at
    ``min(pip_max, pip_per_mcp * mcp)``: one Python call per evaluation for the posture solvers."""
    p1, p2, p3, y0, _ = _TIP_CHAIN[finger]
    cos, bend = math.cos, _DISTAL_BEND

    def tip_y(mcp: float) -> float:
        angle = 0.0 + mcp
        y = y0 + p1 * cos(angle)
        pip = pip_per_mcp * mcp
        angle += pip if pip < pip_max else pip_max  # min(pip_max, pip), without the call
        y += p2 * cos(angle)
        return y + p3 * cos(angle + bend)

    return tip_y


#: Per finger: its three phalanx lengths and the (y, z) of its MCP axis (cm, hand frame).
_TIP_CHAIN = {
    f.name: (*f.lengths_cm, PALM_HALF_CM[1], -PALM_HALF_CM[2] + f.radius_cm) for f in FINGERS
}
_DISTAL_BEND = math.radians(DISTAL_BEND_DEG)


def thumb_tip(flex: float) -> tuple[float, float]:
    """(y, z) in cm, hand frame, of the thumb tip at flexion ``flex`` (radians), thumb rotation zero."""
    q1, q2 = THUMB.lengths_cm
    y, z = THUMB.base_cm[1], THUMB.base_cm[2] - THUMB.metacarpal_cm
    bend = math.radians(THUMB_IP_BEND_DEG)
    y += q1 * math.sin(flex) + q2 * math.sin(flex + bend)
    z -= q1 * math.cos(flex) + q2 * math.cos(flex + bend)
    return y, z
