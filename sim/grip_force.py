"""Grip force: the squeeze a grasp needs to hold an object's weight against friction, and, for a flat object
picked up at a table edge, against the moment of its weight (sim/PLANNER.md rule 3)."""

from __future__ import annotations

import math

from sim.grasps import edge_grip_in_cm

__all__ = [
    "BALL_FINGER_CONTACT_DEG",
    "ball_over_top_force",
    "EDGE_PAD_LEVER_CM",
    "GRAVITY",
    "MIN_GRIP_FORCE_N",
    "SQUEEZABLE_WRAP_LEVER_FRACTION",
    "SAFETY_FACTOR",
    "WRAP_FRICTION_LEVER_CM",
    "WRAP_REACH_CM",
    "edge_grip_force",
    "required_grip_force",
    "wrap_moment_force",
]

GRAVITY = 9.81  # m/s^2
# The squeeze each grasp type can give is the hand's (sim/grasps.py side_force_capacity, from the
# FINGER_MAX_FORCE_N / THUMB_MAX_FORCE_N constants the simulated hand uses too): thumb-index 15 N,
# thumb-2 finger 30 N, thumb-3 finger 45 N, thumb-4 finger and power grasps 60 N per side.

#: How far (cm) a pressed pad can shift its centre of pressure to resist a flat object tilting about the
#: grip (see edge_grip_force): a fingertip pad's contact is about 1 cm across at a few newtons (Serina et
#: al. 1997), so at most 5 mm; 3 mm, calibrated on the trial (books, phones, frames held at the edge).
EDGE_PAD_LEVER_CM = 0.3
#: A wrap from the side holds the object from the palm out to about this far (cm): the fingers' reach round
#: it. An object deeper than that along the approach (a tissue box, a bowl, a cracker box held by its
#: thickness) has its centre of mass beyond the grip, and its weight turns it about the opposition axis.
WRAP_REACH_CM = 6.0
#: The lever (cm) of the friction couple with which a side wrap resists that turn: the fingers press the far
#: face at heights spread along their row (6.3 cm), the thumb the near face at one, and friction along the
#: approach at those heights makes the couple ``2 mu F r``. Calibrated on the trial (the seed catalog's deep
#: boxes and bowls: at the friction bound alone five of them turned out of both wraps; they held at 2-4 x).
WRAP_FRICTION_LEVER_CM = 1.6
#: ... half that for a squeezable object (planner version 14): its soft contacts (twice the time constant and
#: a 5 mm impedance ramp, sim/objects.py) let it turn further under the same moment before the couple
#: builds. Calibrated on the seed catalog's squeezable deep objects (data written here, seed 0): at the rigid
#: lever the toilet paper and paper towel rolls' medium wraps turned 26-35 deg and the baseball cap's two
#: wraps 16-22 deg; at half it they held (1.2-14 deg), the bread loaf and the sneaker at both.
SQUEEZABLE_WRAP_LEVER_FRACTION = 0.5
#: How far above a ball's far equator (degrees) the fingers press when a wrap from above holds a ball wider
#: than the hand's span (sim/grasps.py BALL_MAX_ONE_HAND_CM): measured on the mini soccer ball (14 cm),
#: the distal phalanges at 25-37 deg, the middle ones at 44 (force-weighted 31); 40, calibrated on the
#: trial: a squeeze of 15 N slipped out in the -z push and 20-30 N held (seeds 0-3), where the balance
#: below gives 14.5 N for twice the weight at 40 deg (the palm's push on the ball's top is left out).
BALL_FINGER_CONTACT_DEG = 40.0
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


def wrap_moment_force(
    mass_g: float, depth_cm: float, friction: float, fragility: str = "medium", *, squeezable: bool = False
) -> float:
    """Squeeze (N) a side wrap needs to hold an object ``depth_cm`` deep along the approach against the
    moment of its weight about the grip: ``F = SF m g d / (2 mu r)``, or 0 when it fits in the wrap.

    The wrap holds the object from the palm out to :data:`WRAP_REACH_CM`; its centre of mass lies
    ``depth / 2`` from the palm, so the weight acts ``d = depth / 2 - WRAP_REACH_CM / 2`` beyond the grip's
    centre; the trial's downward push doubles that moment and ``SF`` covers both, as in the friction bound.
    The grip resists by a friction couple of lever ``r`` (:data:`WRAP_FRICTION_LEVER_CM`) on both faces;
    a ``squeezable`` object's is :data:`SQUEEZABLE_WRAP_LEVER_FRACTION` of it.
    """
    d = depth_cm / 2.0 - WRAP_REACH_CM / 2.0
    if d <= 0.0:
        return 0.0
    sf = SAFETY_FACTOR.get(fragility, SAFETY_FACTOR["medium"])
    lever = WRAP_FRICTION_LEVER_CM * (SQUEEZABLE_WRAP_LEVER_FRACTION if squeezable else 1.0)
    force = sf * (mass_g / 1000.0) * GRAVITY * d / (2.0 * friction * lever)
    return round(max(MIN_GRIP_FORCE_N, force), 2)


def ball_over_top_force(mass_g: float, friction: float, fragility: str = "medium") -> float | None:
    """Squeeze (N) of a wrap from above that holds a ball wider than the hand's span over its top: the thumb
    at its near equator, the fingers :data:`BALL_FINGER_CONTACT_DEG` (``a``) above its far one, where their
    press pushes the ball down. Force balance with both contacts at their friction limit ``mu``: per unit of
    finger force the thumb presses ``cos a + mu sin a`` and the ball is carried by
    ``2 mu cos a + (mu^2 - 1) sin a``, so ``F = SF m g (cos a + mu sin a) / (2 mu cos a + (mu^2 - 1) sin a)``;
    ``None`` when that carrying term is not positive (too slippery: no squeeze lifts it)."""
    a = math.radians(BALL_FINGER_CONTACT_DEG)
    carried = 2.0 * friction * math.cos(a) + (friction * friction - 1.0) * math.sin(a)
    if carried <= 0.0:
        return None
    sf = SAFETY_FACTOR.get(fragility, SAFETY_FACTOR["medium"])
    force = sf * (mass_g / 1000.0) * GRAVITY * (math.cos(a) + friction * math.sin(a)) / carried
    return round(max(MIN_GRIP_FORCE_N, force), 2)
