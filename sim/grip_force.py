"""Grip force: the squeeze a grasp needs to hold an object's weight against friction, and, for a flat object
picked up at a table edge, against the moment of its weight (sim/PLANNER.md rule 3)."""

from __future__ import annotations

from sim.grasps import edge_grip_in_cm

__all__ = ["EDGE_PAD_LEVER_CM", "GRAVITY", "MIN_GRIP_FORCE_N", "SAFETY_FACTOR", "edge_grip_force", "required_grip_force"]

GRAVITY = 9.81  # m/s^2
# The squeeze each grasp type can give is the hand's (sim/grasps.py side_force_capacity, from the
# FINGER_MAX_FORCE_N / THUMB_MAX_FORCE_N constants the simulated hand uses too): thumb-index 15 N,
# thumb-2 finger 30 N, thumb-3 finger 45 N, thumb-4 finger and power grasps 60 N per side.

#: How far (cm) a pressed pad can shift its centre of pressure to resist a flat object tilting about the
#: grip (see edge_grip_force): a fingertip pad's contact is about 1 cm across at a few newtons (Serina et
#: al. 1997), so at most 5 mm; 3 mm, calibrated on the trial (books, phones, frames held at the edge).
EDGE_PAD_LEVER_CM = 0.3
#: Never plan less than this: the fingers must at least hold contact.
MIN_GRIP_FORCE_N = 1.5
#: Safety factor on the weight: 2 covers the weight plus the trial's perturbation (a force equal to the
#: weight), the rest is the grip-force safety margin people keep above slip (Johansson & Westling 1984).
SAFETY_FACTOR = {"sturdy": 2.6, "medium": 2.4, "fragile": 2.1}


def required_grip_force(mass_g: float, friction: float, fragility: str = "medium") -> float:
    """Total normal force (N) a two-sided grip needs: ``m g SF / (2 mu)``, at least MIN_GRIP_FORCE_N.

    Two contact faces each give at most ``mu N`` of friction, so holding weight ``m g`` times the safety
    factor ``SF`` takes ``N >= m g SF / (2 mu)``. Fragile objects get a smaller SF.
    """
    sf = SAFETY_FACTOR.get(fragility, SAFETY_FACTOR["medium"])
    force = (mass_g / 1000.0) * GRAVITY * sf / (2.0 * friction)
    # Fragile objects get the smaller safety factor only. (A fixed 12 N cap used to apply too: it only ever
    # bound for heavy fragile objects -- a 1.25 kg wine bottle, a glass vase -- and guaranteed they slipped;
    # light fragile objects, eggs and ornaments, need far less than 12 N anyway.)
    force = max(MIN_GRIP_FORCE_N, force)
    return round(force, 2)


def edge_grip_force(mass_g: float, depth_cm: float, fragility: str = "medium") -> float:
    """Squeeze (N) that holds a flat object ``depth_cm`` deep, picked up at its edge, against the moment
    of its weight: ``F = SF m g d / (2 r)``.

    The pads press ``edge_grip_in_cm(depth)`` in from the edge (sim/grasps.py, as the trial places them),
    so the weight acts ``d = depth / 2 - grip_in`` beyond them; the trial's downward push of the same
    force doubles that moment, and ``SF`` (2.1-2.6) covers both with a margin, as in the friction bound.
    Two opposed pads resist tilting by shifting their centres of pressure, each by up to ``r``
    (:data:`EDGE_PAD_LEVER_CM`), so their couple is at most ``2 F r``.
    """
    d = max(0.0, depth_cm / 2.0 - edge_grip_in_cm(depth_cm))
    sf = SAFETY_FACTOR.get(fragility, SAFETY_FACTOR["medium"])
    force = sf * (mass_g / 1000.0) * GRAVITY * d / (2.0 * EDGE_PAD_LEVER_CM)
    return round(max(MIN_GRIP_FORCE_N, force), 2)
