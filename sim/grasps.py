"""Grasp taxonomy (Cutkosky 1989; Feix et al. 2016) and the plan record shared by planner and simulator.

The planner (sim/planner.py) produces :class:`GraspPlan` records; the trial runner (sim/trial.py) executes
one in MuJoCo. Grasp type names are stable identifiers stored in the knowledge base.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any, Literal

__all__ = [
    "ACTIVE_FINGERS",
    "BALL_MAX_ONE_HAND_CM",
    "drapes",
    "sheet_held_cm",
    "FAMILIES",
    "FINGER_LEAD_PARAM",
    "FINGER_MAX_FORCE_N",
    "GRASP_TYPES",
    "THUMB_MAX_FORCE_N",
    "Family",
    "GraspPlan",
    "active_fingers",
    "side_force_capacity",
    "EDGE_MAX_GRIP_IN_CM",
    "FLAT_RATIO",
    "edge_depth_cm",
    "edge_grip_in_cm",
    "edge_lever_lead_cm",
    "edge_overhang_cm",
    "is_flat_grasp",
]

Family = Literal["power", "intermediate", "precision"]

#: grasp type -> family, after Cutkosky (1989) and the Feix et al. (2016) GRASP taxonomy.
GRASP_TYPES: dict[str, Family] = {
    "heavy_wrap_large_diameter": "power",
    "heavy_wrap_small_diameter": "power",
    "medium_wrap": "power",
    "adducted_thumb": "power",
    "light_tool": "power",
    "power_disk": "power",
    "power_sphere": "power",
    "lateral_pinch": "intermediate",
    "thumb_4_finger": "precision",
    "thumb_3_finger": "precision",
    "thumb_2_finger": "precision",
    "thumb_index_finger": "precision",
    "precision_disk": "precision",
    "precision_sphere": "precision",
    "tripod": "precision",
}
FAMILIES: tuple[str, ...] = ("power", "intermediate", "precision")

# ---------------------------------------------------------------------------------------------------------
# The hand's strength: ONE set of constants for the planner (sim/planner.py: which plans are within the
# hand's capacity) and the simulated hand (sim/hand.py: actuator force limits), so they cannot disagree.
# ---------------------------------------------------------------------------------------------------------
#: Strongest normal force one finger presses with (N). People: a tip pinch (thumb against the index) is
#: about 50-70 N, a key (lateral) pinch 70-100 N and a whole-hand power grip 300-400 N (Mathiowetz et al.
#: 1985, "Grip and pinch strength: normative data for adults", Arch Phys Med Rehabil 66). The AR10 drives
#: each digit through a small linear servo and a linkage: far weaker than a person. We take a quarter of a
#: human tip pinch per finger (15 N) and a thumb that can oppose all four fingers (60 N): a power grasp then
#: squeezes with up to 60 N per side (120 N in all, a third of a person's power grip), a thumb-index pinch
#: with 15 N, so a heavy slippery object still slides out of a fingertip pinch, as it does for a person
#: pinching with a quarter of their strength. (Was 10 N / 30 N, which held neither a 1 kg bottle in a
#: wrap nor matched the planner's 60 N power capacity.)
FINGER_MAX_FORCE_N = 15.0
THUMB_MAX_FORCE_N = 60.0
#: Widest opening of a human-sized hand (AR10-like): thumb tip to finger tips about 12 cm, the span that
#: holds a 12 cm ball in a power sphere grasp. Wider extents cannot be held in one hand.
HAND_MAX_APERTURE_CM = 12.0
#: A ball is the exception: a wrap from above holds one wider than the span over its top, its near side
#: against the thumb and the fingers curled over its far side (sim/hand.py ``ball_center_y_cm`` places it as
#: near the thumb as its curve clears the metacarpal). That needs the thumb's pad to reach down to the
#: ball's near equator, and this hand's thumb (a 2.5 cm metacarpal, phalanges 3.2 and 2.6 cm) reaches it up
#: to a 15.4 cm ball (tests/test_big_balls.py computes it from the hand): 15 cm. Wider balls need two hands.
BALL_MAX_ONE_HAND_CM = 15.0

#: Fingers each grasp type uses (the thumb always opposes them); types not listed use all four. The
#: lateral pinch presses the object on the radial side of the index's middle phalanx, a ~2.5 cm long
#: contact; fingers here flex in one plane, so the index and middle pads side by side stand for it.
ACTIVE_FINGERS: dict[str, tuple[str, ...]] = {
    "thumb_index_finger": ("index",),
    "lateral_pinch": ("index", "middle"),
    "thumb_2_finger": ("index", "middle"),
    "tripod": ("index", "middle"),
    "thumb_3_finger": ("index", "middle", "ring"),
    # fingertips round a ball or a rim: the little finger, at the end of a row no abduction spreads, misses
    # balls under 8 cm (sim/programs.py, precision_circular)
    "precision_disk": ("index", "middle", "ring"),
    "precision_sphere": ("index", "middle", "ring"),
}
ALL_FINGERS: tuple[str, ...] = ("index", "middle", "ring", "little")


def active_fingers(grasp_type: str) -> tuple[str, ...]:
    """The fingers that oppose the thumb in ``grasp_type``."""
    return ACTIVE_FINGERS.get(grasp_type, ALL_FINGERS)


def side_force_capacity(grasp_type: str) -> float:
    """Strongest squeeze (N, normal force per side) the hand gives in ``grasp_type``: the weaker of the
    thumb and the sum of the fingers opposing it."""
    return min(THUMB_MAX_FORCE_N, FINGER_MAX_FORCE_N * len(active_fingers(grasp_type)))


# ---------------------------------------------------------------------------------------------------------
# Flat objects are picked up at a table edge: one geometry for the trial (where the object lies and where
# the pads press) and the planner (the squeeze the moment of the weight needs about that grip).
# ---------------------------------------------------------------------------------------------------------
#: A grasp across a side at most this fraction of the next larger side grasps a flat object (a book, a
#: plate, a phone, a board) across its thickness: it lies flat, overhanging a table edge, and is picked
#: from that edge, thumb on top and fingers underneath, as people pick up a plate or a book.
FLAT_RATIO = 0.35
#: The object overhangs the edge by at most this fraction of its depth (its centre of mass stays on the
#: table) ...
EDGE_OVERHANG_FRACTION = 0.45
#: ... and the pads press at most this far in from its edge: the reach of a pinch whose thumb and finger
#: pads meet at one depth (the fingers' middle and distal phalanges under the object).
EDGE_MAX_GRIP_IN_CM = 6.0
#: The finger pads stay this far short of the table edge under the overhang (a pad radius plus a gap).
EDGE_PAD_CLEAR_CM = 0.9
#: The pads press at least this far in from the edge (a pad's contact patch is about 5 mm across).
EDGE_MIN_GRIP_IN_CM = 0.3


def is_flat_grasp(grasped_cm: float, next_larger_cm: float) -> bool:
    """Does a grasp across ``grasped_cm`` hold a flat object (see :data:`FLAT_RATIO`)?"""
    return grasped_cm <= FLAT_RATIO * next_larger_cm


def edge_overhang_cm(depth_cm: float) -> float:
    """How far a flat object ``depth_cm`` deep (across the edge) overhangs the table edge."""
    return min(EDGE_OVERHANG_FRACTION * depth_cm, EDGE_MAX_GRIP_IN_CM + 1.0)


def edge_grip_in_cm(depth_cm: float) -> float:
    """How far in from a flat object's edge the pads press: as near its centre of mass as the overhang
    and the pinch's reach allow (the nearer, the smaller the moment of its weight about the grip)."""
    overhang = edge_overhang_cm(depth_cm)
    return max(EDGE_MIN_GRIP_IN_CM, min(depth_cm / 2.0, EDGE_MAX_GRIP_IN_CM, overhang - EDGE_PAD_CLEAR_CM))


#: ``GraspPlan.params`` key of an edge lever hold (sim/planner.py): how much deeper (cm, along the approach)
#: the finger pads meet a flat object's underside than the thumb meets its top (absent: at one depth).
FINGER_LEAD_PARAM = "finger_lead_cm"
#: An edge lever hold (sim/PLANNER.md rule 3): the finger pads meet a heavy flat object's underside this
#: much deeper (cm) than the thumb meets its top, at least ...
EDGE_LEVER_MIN_LEAD_CM = 0.5
#: ... and at most: the thumb, hanging from the palm's wrist end, reaches a top nearer the palm only at its
#: flexion stop (sim/PHYSICS.md), so about 2.4 cm is the largest lead with which it still presses.
EDGE_LEVER_MAX_LEAD_CM = 2.4


def edge_lever_lead_cm(mass_g: float, depth_cm: float, squeeze_n: float) -> float:
    """The finger lead (cm) of an edge lever hold: the thumb pressing the top with ``squeeze_n`` that much
    nearer the edge than the finger pads (at ``edge_grip_in_cm``) carries the moment of the weight, whose
    centre of mass lies ``depth_cm / 2`` in, about the pads' line (F L = m g d), within the bounds above."""
    lever_cm = max(0.0, depth_cm / 2.0 - edge_grip_in_cm(depth_cm))
    lead = mass_g / 1000.0 * 9.81 * lever_cm / max(squeeze_n, 1e-9)
    return round(min(EDGE_LEVER_MAX_LEAD_CM, max(EDGE_LEVER_MIN_LEAD_CM, lead)), 3)


def drapes(rigidity: str | None, material: str | None) -> bool:
    """Does a flat object of this rigidity and material bend under its own weight when lifted by one edge,
    so that the trial builds it as a draping sheet (sim/sheet.py)? Floppy things (paper, cloth, gloves), and
    a fabric bag of stuffing (a pillow, a cushion: squeezable fabric), which folds over the hand as cloth
    does, only far stiffer."""
    return rigidity == "floppy" or (rigidity == "squeezable" and material == "fabric")


def sheet_held_cm(depth_cm: float, overhang_cm: float) -> float:
    """How deep (cm, from its overhanging edge in) the strip of a draping sheet is that the hand holds: to
    twice the overhang, so its own centre of mass sits over the table edge, or the whole sheet when that is
    shallower (sim/sheet.py builds it so; sim/diagnosis.py reads it from the plan)."""
    return min(depth_cm, 2.0 * overhang_cm)


def edge_depth_cm(long_cm: float, middle_cm: float) -> float:
    """The side of a flat object that lies across the table edge (the rest along it): its middle side, so
    that the fingers spread along its length, unless laid so it would overhang too little for the pads to
    reach in under it (the overhang short of the pads' clearance plus :data:`EDGE_MIN_GRIP_IN_CM`); then its
    length, as a person slides a key or a ruler out over the edge by its length and pinches the end."""
    if edge_overhang_cm(middle_cm) - EDGE_PAD_CLEAR_CM < EDGE_MIN_GRIP_IN_CM:
        return long_cm
    return middle_cm


@dataclass(frozen=True)
class GraspPlan:
    """One candidate grasp for an object.

    grasp_type: a key of :data:`GRASP_TYPES`; family: its family.
    grasped_dim: which object dimension lies between thumb and fingers ("a", "b" or "c").
    aperture_cm: hand opening before closing (the grasped extent plus a margin).
    approach: direction the palm approaches from, in the object frame ("top" = from +z, "side" = from +x).
    grip_force_n: the squeeze: normal force on each side of the grip, F = m g SF / (2 mu) (from mass,
    friction and fragility); the trial measures half the total hand-object normal force to compare.
    score: planner preference, higher is better (plans are ranked by it).
    rationale: the rules that chose it, in words.
    """

    grasp_type: str
    family: Family
    grasped_dim: Literal["a", "b", "c"]
    aperture_cm: float
    approach: Literal["top", "side"]
    grip_force_n: float
    score: float
    rationale: tuple[str, ...] = ()
    params: dict[str, Any] = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.grasp_type not in GRASP_TYPES:
            raise ValueError(f"unknown grasp type {self.grasp_type!r}")
        if GRASP_TYPES[self.grasp_type] != self.family:
            raise ValueError(
                f"{self.grasp_type} is a {GRASP_TYPES[self.grasp_type]} grasp, not {self.family}"
            )

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["rationale"] = list(self.rationale)
        return d
