"""Hand programs: what the simulated AR10-like hand does for each grasp type of the GRASP taxonomy.

A grasp type names a human posture (Feix et al. 2016, "The GRASP taxonomy of human grasp types", IEEE
THMS 46(1), which pictures each one); a :class:`HandProgram` says how this hand reproduces it: approach,
the fingers that oppose the thumb, the pre-shape and closing synergy (how PIP follows MCP), where the object
sits (against the palm or on the pads) and where the thumb aims. ``sim/hand.py`` turns a program into
joint targets, ``sim/trial.py`` places the object by it.

The hand has ten actuated joints and **no finger abduction**: its fingers flex in parallel planes. Two
taxonomy types that differ only in what this hand lacks are one program here, named for both, and the
planner lists such a program once (``sim/planner.py``; the plan's rationale and the report say so):

* ``heavy_wrap`` = heavy wrap large diameter + heavy wrap small diameter. Feix tells them apart by the
  object's diameter; the hand's action is the same full wrap, the object sets the diameter.
* ``adducted_thumb_wrap`` = adducted thumb + light tool: the fingers wrap, the thumb lies adducted along
  the object instead of over the fingers; Feix separates them by the object (a tool handle is thinner and
  lighter), not by a posture this hand can make differently.
* ``precision_circular`` = precision disk + precision sphere: four fingertips round the object's rim; a
  human spreads the fingers round a sphere and keeps them in a row for a disk's rim, which needs the
  abduction this hand has not got.

Every other type is its own program. Bump :data:`PROGRAMS_VERSION` when a program changes (it is part of
the hand version stored with each result).
"""

from __future__ import annotations

from dataclasses import dataclass

from sim.grasps import GRASP_TYPES

__all__ = ["PROGRAMS", "PROGRAMS_VERSION", "HandProgram", "merged_types", "program_for"]

# 10: the slide's thumb hook hangs at most a third of a low rim's height above the table (sim/slide.py);
# 9: a ball wrapped as near the thumb as its curved side clears the metacarpal (sim/hand.py ball_center_y_cm);
# 8: a flat object thinner than a pad radius and too shallow to pinch where it lies (coins, a paper clip) is
# slid out over the table edge by a thumb hook first (sim/slide.py);
# 7: a stuffed fabric bag laid flat (a pillow) drapes as a sheet (sim/sheet.py, sim/grasps.py drapes);
# 6: a rod lying under a pinch from above is pinched a quarter radius below its centre line (sim/world.py);
# 5: an edge lever hold's fingers lead the thumb, extended (sim/hand.py); 4: a floppy object's lateral pinch
# closes 2 cm past it (sim/world.py); 3: pinch pads aligned at the thumb's height off the table edge;
# 2: precision circular on three fingers
PROGRAMS_VERSION = "10"

ALL4 = ("index", "middle", "ring", "little")


@dataclass(frozen=True)
class HandProgram:
    """How the simulated hand executes one or more grasp types (merged ones share a program).

    ``control``: ``wrap`` (the object seated against the palm or the fingers, every used joint driven
    beyond contact) or ``pinch`` (pads placed at the plan's aperture round a pinch centre, closing to
    1 cm past the surface). ``pip_per_mcp``: the closing synergy of a pinch (0.8 flat pads facing the
    thumb, prismatic; 1.0 curled fingertips, circular). ``mcp_close_deg`` / ``pip_close_deg``: a wrap's
    closing targets (beyond the joint range = press to the limit). ``palm_gap_cm``: a wrap's gap between
    palm and object at the grasp pose (0.4 pressed to the palm; more: held in the fingers). ``thumb_aim``:
    the hand-frame x (cm) the thumb's rotation aims at (``None``: the mean of the used fingers).
    ``lever``: where along the digit it presses (fraction beyond the joint), for its torque limits.
    """

    name: str
    grasp_types: tuple[str, ...]
    approach: str
    fingers: tuple[str, ...]
    control: str
    preshape: str
    synergy: str
    contacts: str
    basis: str
    pip_per_mcp: float = 0.8
    mcp_close_deg: float = 120.0
    pip_close_deg: float = 130.0
    palm_gap_cm: float = 0.4
    thumb_aim: float | None = None
    lever: float = 0.85

    @property
    def merged(self) -> bool:
        return len(self.grasp_types) > 1


_WRAP_SHAPE = "fingers straight (PIP 10 deg), thumb swung back 5 mm off the object's near side"

PROGRAMS: tuple[HandProgram, ...] = (
    HandProgram(
        "heavy_wrap",
        ("heavy_wrap_large_diameter", "heavy_wrap_small_diameter"),
        "side",
        ALL4,
        "wrap",
        _WRAP_SHAPE,
        "MCP and PIP of all four fingers flex together to full flexion; the thumb flexes over them",
        "palm, all three phalanges of four fingers, thumb pad on the far side",
        "Feix 2016 types 1-2 (heavy wrap): object pressed into the palm, fingers fully flexed round it",
        lever=0.6,
    ),
    HandProgram(
        "medium_wrap",
        ("medium_wrap",),
        "side",
        ALL4,
        "wrap",
        _WRAP_SHAPE,
        "fingers wrap fully round an object seated 1 cm off the palm; the thumb flexes over them",
        "finger phalanges (less palm contact), thumb pad on the far side",
        "Feix 2016 type 3 (medium wrap): the fingers hold, the palm barely touches (a thumb aimed at the "
        "index side was tried: 6 instead of 9 of 17 seed objects held)",
        palm_gap_cm=1.0,
        lever=0.6,
    ),
    HandProgram(
        "adducted_thumb_wrap",
        ("adducted_thumb", "light_tool"),
        "side",
        ALL4,
        "wrap",
        _WRAP_SHAPE,
        "fingers wrap with the MCP stopping at 100 deg; the thumb turned to the index side (adducted) and "
        "flexed against the object there",
        "palm and fingers; thumb along the object next to the index",
        "Feix 2016 types 4-5 (light tool, adducted thumb): thumb adducted, the fingers hold",
        mcp_close_deg=100.0,
        thumb_aim=3.15,
        lever=0.6,
    ),
    HandProgram(
        "power_disk",
        ("power_disk",),
        "top",
        ALL4,
        "wrap",
        "palm flat over the face, fingers straight",
        "MCP flexes fully while the PIP stays at 30 deg: long fingers hook round the rim",
        "palm on the face, finger middle phalanges and tips on the rim, thumb on the opposite rim",
        "Feix 2016 type 10 (power disk): palm on the disk's face, fingers and thumb round its rim",
        pip_close_deg=30.0,
        lever=0.6,
    ),
    HandProgram(
        "power_sphere",
        ("power_sphere",),
        "top",
        ALL4,
        "wrap",
        "palm over the top, fingers slightly curled",
        "PIP leads the curl: the MCP is driven only 15 deg past its range (a wrap's 30), so the knuckles "
        "press more gently and the fingers curl down round the ball",
        "palm on the top, all finger phalanges round the sides, thumb opposite",
        "Feix 2016 type 11 (power sphere): the ball cupped in the palm, every finger round it (with a "
        "wrap's synergy it gave bit-identical results to the heavy wrap on flat objects at a table edge; "
        "a thumb aimed at the index side held 7 instead of 14 of 18)",
        mcp_close_deg=105.0,
        lever=0.6,
    ),
    HandProgram(
        "lateral_pinch",
        ("lateral_pinch",),
        "side",
        ("index", "middle"),
        "pinch",
        "thumb and the index/middle fingers opened to the aperture, fingers nearly straight",
        "straight-finger synergy (PIP 0.5 of MCP): the fingers press with their middle and distal "
        "phalanges, not the tips; pressing 0.8 of the way along the digits; approached from the side",
        "thumb pad against the index and middle fingers' flat inner faces side by side (for the side of "
        "the index's middle phalanx)",
        "Feix 2016 type 16 (lateral pinch): thumb pad on the radial side of the index; this hand's fingers "
        "flex in one plane, so two straight fingers side by side stand for that contact (with the pad "
        "synergy, 0.8, it gave bit-identical results to thumb-2 finger on flat objects at a table edge and "
        "held 7 instead of 6 of 12; a thumb aimed at the index held 2)",
        pip_per_mcp=0.5,
        lever=0.8,
    ),
    HandProgram(
        "thumb_index_finger",
        ("thumb_index_finger",),
        "top",
        ("index",),
        "pinch",
        "thumb and index tips opened to the aperture, others straight above",
        "flat pad synergy (PIP 0.8 of MCP)",
        "thumb pad against the index pad",
        "Feix 2016 type 9 (palmar pinch / thumb-index)",
    ),
    HandProgram(
        "thumb_2_finger",
        ("thumb_2_finger",),
        "top",
        ("index", "middle"),
        "pinch",
        "thumb, index and middle pads opened to the aperture",
        "flat pad synergy (PIP 0.8 of MCP)",
        "thumb pad against the index and middle pads",
        "Feix 2016 type 8 (prismatic 2 finger)",
    ),
    HandProgram(
        "thumb_3_finger",
        ("thumb_3_finger",),
        "top",
        ("index", "middle", "ring"),
        "pinch",
        "thumb and three finger pads opened to the aperture",
        "flat pad synergy (PIP 0.8 of MCP)",
        "thumb pad against index, middle and ring pads",
        "Feix 2016 type 7 (prismatic 3 finger)",
    ),
    HandProgram(
        "thumb_4_finger",
        ("thumb_4_finger",),
        "top",
        ALL4,
        "pinch",
        "thumb and four finger pads opened to the aperture",
        "flat pad synergy (PIP 0.8 of MCP)",
        "thumb pad against four finger pads in a row",
        "Feix 2016 type 6 (prismatic 4 finger)",
    ),
    HandProgram(
        "tripod",
        ("tripod",),
        "top",
        ("index", "middle"),
        "pinch",
        "thumb, index and middle tips curled towards one point",
        "curled fingertip synergy (PIP = MCP, pads 0.8): the tips, not the pads, meet the object",
        "thumb, index and middle fingertips",
        "Feix 2016 type 14 (tripod): three fingertips, a circular precision grasp (Cutkosky 1989)",
        pip_per_mcp=1.0,
    ),
    HandProgram(
        "precision_circular",
        ("precision_disk", "precision_sphere"),
        "top",
        ("index", "middle", "ring"),
        "pinch",
        "thumb and three fingertips curled, opened to the aperture",
        "fingertip synergy (PIP 0.9 of MCP, pads 0.8): fingertips round the rim",
        "thumb tip against the index, middle and ring fingertips",
        "Feix 2016 types 12-13 (precision disk, precision sphere): fingertips round a circular object. "
        "A person spreads the fingers round it; this hand's fingers stay in a row 6.3 cm long, so on a "
        "ball under 8 cm the little finger, at the row's end, reaches past the ball's side and presses on "
        "nothing while the thumb pushes against all four: the ball is pushed off the pads. Three fingers "
        "(version 2) held 16 of 32 precision-circular candidates on the seed catalog, 11 of 13 first "
        "choices, against 7 and 7 with four (PIP = MCP, as the tripod, held 1 of 8 light balls; 0.9 holds 3)",
        pip_per_mcp=0.9,
    ),
)

_BY_TYPE = {t: p for p in PROGRAMS for t in p.grasp_types}
assert set(_BY_TYPE) == set(GRASP_TYPES), "every grasp type needs exactly one hand program"


def program_for(grasp_type: str) -> HandProgram:
    """The hand program that executes ``grasp_type``. Raises ValueError for an unknown type."""
    try:
        return _BY_TYPE[grasp_type]
    except KeyError:
        raise ValueError(f"unknown grasp type {grasp_type!r}") from None


def merged_types(grasp_type: str) -> tuple[str, ...]:
    """The other grasp types simulated by the same program as ``grasp_type``."""
    return tuple(t for t in program_for(grasp_type).grasp_types if t != grasp_type)
