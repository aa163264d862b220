"""The grasp planner's rules: one function per row of sim/PLANNER.md's table (rule 2), each returning the
ordered (grasp type, reason) candidates for the objects it applies to, or ``None``; :func:`candidates`
runs them in the table's order. The thresholds are named constants here (their basis is in PLANNER.md).
"""

from __future__ import annotations

from sim.grasps import edge_depth_cm
from sim.planned_object import PlannedObject

__all__ = ["Candidates", "HEAVY_MASS_G", "LIGHT_MASS_G", "ROD_MAX_THICK_CM", "candidates", "is_tiny_flat"]

#: Feix et al. 2014: 92 % of grasped objects weigh 500 g or less; heavier objects get power grasps.
HEAVY_MASS_G = 500.0
#: Light enough for fingertips (pad opposition) at any width they can span.
LIGHT_MASS_G = 250.0
#: Widths at or below which fingertips pinch comfortably (precision), and above which the hand wraps.
PRECISION_MAX_WIDTH_CM = 5.5
#: A sphere this wide or wider is held in the palm (power sphere): the paper's tennis ball (6.4 cm) and
#: orange (7 cm) both got a power-circular grasp; a golf ball (4.3 cm) is taken on the fingertips. Light
#: balls of 5-6 cm (plum, peach, racquetball) are borderline: the number of fingers used rises with
#: ball size (2.7 golf ball, 3.5 tennis ball, 4.5 softball in a student study, a weak source), so a
#: fingertip grasp is as human; 6 cm was tried in planner version 5's development and dropped: the simulated hand's
#: precision sphere lifts none of those four balls, the power sphere holds all of them (PLANNER.md).
POWER_SPHERE_MIN_CM = 5.0
#: A round object this heavy is cupped in the palm even when smaller than POWER_SPHERE_MIN_CM.
POWER_SPHERE_MIN_MASS_G = 100.0
#: Flat objects at most this thick, this long and this light are held in a lateral pinch (keys, cards).
LATERAL_PINCH_MAX_THICK_CM = 1.0
LATERAL_PINCH_MAX_LENGTH_CM = 10.0
LATERAL_PINCH_MAX_MASS_G = 100.0
#: Flat things no longer than this (coins, paper clips, washers) are picked up between the tips of thumb and
#: index (the tip / palmar pinch of the GRASP taxonomy), not laid against the side of the index.
TIP_PINCH_MAX_LENGTH_CM = 3.5
#: Pen-like objects (long, a round cross-section no thicker than this, light) are held in the writing
#: tripod [Feix 2016], the grasp they are picked up for.
PEN_MAX_THICK_CM = 2.0
PEN_MAX_MASS_G = 50.0

#: A thin rod (long, its section no thicker than this), PEN_MAX_MASS_G to LIGHT_MASS_G: a lateral pinch.
ROD_MAX_THICK_CM = 1.0

#: A light long object at least this long is a utensil or tool held by its handle (spatula, ladle, knife):
#: its bounding box is wider than the handle people actually hold.
TOOL_MIN_LENGTH_CM = 25.0


def _fingers_for_length(length_cm: float, mass_g: float) -> str:
    """Precision prismatic type by how many finger pads fit along the object (a pad is about 2 cm)."""
    if length_cm >= 10.0:
        n = 4
    elif length_cm >= 6.5:
        n = 3
    elif length_cm >= 3.0:
        n = 2
    else:
        n = 1
    if mass_g < 25.0:  # a feather-light object needs no more than two fingers against the thumb
        n = min(n, 2)
    if mass_g >= 150.0:  # a heavier one spreads its weight over more pads
        n = max(n, 3)
    return {4: "thumb_4_finger", 3: "thumb_3_finger", 2: "thumb_2_finger", 1: "thumb_index_finger"}[n]


def _power_wrap(width_cm: float, mass_g: float, long: bool = False) -> str:
    """Power prismatic type by wrap diameter and weight.

    A heavy *long* object is held by a handle thinner than its box (hammer): a tight small-diameter wrap;
    a heavy box 2.5-4.5 cm thick is wrapped as it is (medium wrap; heavy wrap for all of them until
    planner version 5).
    """
    if width_cm >= 4.5:
        return "heavy_wrap_large_diameter"
    if (mass_g >= HEAVY_MASS_G and long) or (width_cm < 2.5 and mass_g >= LIGHT_MASS_G):
        return "heavy_wrap_small_diameter"
    if width_cm >= 2.5:
        return "medium_wrap"
    return "light_tool"


Candidates = list[tuple[str, str]]


def _floppy(o: PlannedObject) -> Candidates | None:
    """Cloth and paper sheets: a fold pinched or gathered in the fist."""
    if o.rigidity != "floppy":
        return None
    if o.mass_g < LATERAL_PINCH_MAX_MASS_G * 2 and o.material == "paper":
        # A sheet of paper does not gather into a fold as cloth does: it is pinched flat at its edge between
        # the thumb and two finger pads (Feix 2016 type 8). Seed catalog (data written here, seed 0): the
        # thumb-2 finger held all four light paper sheets (the a4 sheet, two envelopes, sandpaper), the
        # lateral pinch two; on the five other light floppy objects (cloth, rubber gloves, a bunch of keys)
        # both held (planner version 16).
        return [
            ("thumb_2_finger", "a light paper sheet: pinched flat at its edge between thumb and two finger pads"),
            ("lateral_pinch", "floppy: pinch it between thumb and the side of the index"),
            ("medium_wrap", "floppy: gather it in the fist"),
        ]
    if o.mass_g < LATERAL_PINCH_MAX_MASS_G * 2:
        return [
            ("lateral_pinch", "floppy and light: pinch a fold between thumb and the side of the index"),
            ("thumb_2_finger", "floppy: a fingertip pinch also gathers a fold"),
            ("medium_wrap", "floppy: gather it in the fist"),
        ]
    return [
        ("medium_wrap", "floppy and heavy: gather it in the fist"),
        ("heavy_wrap_small_diameter", "floppy and heavy: a tight fist around a gathered fold"),
        ("lateral_pinch", "floppy: pinch a fold"),
    ]


def _sphere(o: PlannedObject) -> Candidates | None:
    """Cutkosky's circular branch for round objects: power sphere, precision sphere, tripod by size."""
    if not o.is_sphere:
        return None
    d, m = o.c_cm, o.mass_g
    if o.fragility == "fragile" and m < 100.0 and d < 9.0:
        return [
            ("precision_sphere", f"round, fragile and light ({m:.0f} g): gently on the fingertips"),
            ("power_sphere", "round: cupped in the palm"),
            ("tripod", "thumb, index and middle finger pads"),
        ]
    if m >= HEAVY_MASS_G or d >= POWER_SPHERE_MIN_CM or m >= POWER_SPHERE_MIN_MASS_G:
        if m >= HEAVY_MASS_G:
            why = "heavy"
        elif d >= POWER_SPHERE_MIN_CM:
            why = f"{d:g} cm across (>= {POWER_SPHERE_MIN_CM:g} cm)"
        else:
            why = f"{m:.0f} g (>= {POWER_SPHERE_MIN_MASS_G:g} g)"
        return [
            ("power_sphere", f"round and {why}: cupped in the palm (Cutkosky: power, circular)"),
            ("precision_sphere", "round: fingertips around it (precision, circular)"),
            ("heavy_wrap_large_diameter", "wrapped like a thick cylinder"),
        ]
    if d >= 2.5:
        return [
            ("precision_sphere", f"round, light and {d:g} cm across: fingertips around it"),
            ("tripod", "small and round: thumb, index and middle finger pads"),
            ("power_sphere", "round: cupped in the palm"),
        ]
    return [
        ("tripod", f"round and small ({d:g} cm): thumb, index and middle finger pads"),
        ("thumb_index_finger", "tiny: thumb and index tips"),
        ("precision_sphere", "round: fingertips around it"),
    ]


def _disk(o: PlannedObject) -> Candidates | None:
    """Cutkosky's circular branch for disks (lids, coasters): power or precision disk by size and mass."""
    if not o.is_disk or (o.is_flat and o.c_cm <= LATERAL_PINCH_MAX_THICK_CM):
        return None
    diameter, w, m = o.b_cm, o.c_cm, o.mass_g
    if m >= HEAVY_MASS_G or diameter >= 9.0 or m >= 300.0:
        return [
            ("power_disk", f"disk {diameter:g} cm across and {m:.0f} g: palm on the face, fingers round the rim"),
            ("precision_disk", "disk: fingertips round the rim"),
            (_power_wrap(w, m), "held across its thickness"),
        ]
    if diameter >= 3.0:
        return [
            (
                "precision_disk",
                f"disk {diameter:g} cm across and light: fingertips round the rim (Cutkosky: precision, circular)",
            ),
            (_fingers_for_length(diameter, m), "pinched across its thickness"),
            ("power_disk", "disk: palm on the face"),
        ]
    return [
        ("thumb_index_finger", f"small disk ({diameter:g} cm): thumb and index tips on its faces"),
        ("tripod", "small: thumb, index and middle finger pads"),
        ("lateral_pinch", "small and flat: thumb against the side of the index"),
    ]


def _lateral_pinch(o: PlannedObject, why: str) -> Candidates:
    return [
        ("lateral_pinch", f"{why}, thin ({o.c_cm:g} cm) and small: thumb pad against the side of the index (keys, cards)"),
        ("thumb_index_finger", "thin: thumb and index tips"),
        ("thumb_2_finger", "thin: thumb against two finger pads"),
    ]


def _is_small_flat(o: PlannedObject) -> bool:
    """Flat and small enough for a pinch of the thumb against the index (keys, cards, coins)."""
    w = o.c_cm
    return (
        w <= LATERAL_PINCH_MAX_THICK_CM
        and o.a_cm <= LATERAL_PINCH_MAX_LENGTH_CM
        and o.mass_g <= LATERAL_PINCH_MAX_MASS_G
        and w <= 0.6 * o.b_cm
    )


def is_tiny_flat(o: PlannedObject) -> bool:
    """A tiny flat thing (coin, paper clip, washer: at most TIP_PINCH_MAX_LENGTH_CM long), picked up by the tip
    pinch; its own class of experience too (sim/experience.py ``object_class``)."""
    return _is_small_flat(o) and o.a_cm <= TIP_PINCH_MAX_LENGTH_CM


def _small_flat(o: PlannedObject) -> Candidates | None:
    """Tiny flat things (coins, clips: the tip pinch) and small flat-sided ones (keys, cards: lateral)."""
    w, a = o.c_cm, o.a_cm
    small_flat = _is_small_flat(o)
    if small_flat and a <= TIP_PINCH_MAX_LENGTH_CM:
        return [
            (
                "thumb_index_finger",
                f"flat and tiny ({a:g} cm): picked up between the tips of thumb and index (tip pinch)",
            ),
            ("lateral_pinch", "flat: thumb pad against the side of the index"),
            ("thumb_2_finger", "thumb against two finger pads"),
        ]
    if small_flat and (o.is_flat or w < 1.0):
        return _lateral_pinch(o, "flat-sided")
    return None


def _flat(o: PlannedObject) -> Candidates | None:
    """Flat objects (books, plates, phones): lateral pinch when small, a wrap over the edge when heavy,
    else thumb against finger pads along the length."""
    if not o.is_flat:
        return None
    w, a, m = o.c_cm, o.a_cm, o.mass_g
    if w <= LATERAL_PINCH_MAX_THICK_CM and a <= LATERAL_PINCH_MAX_LENGTH_CM and m <= LATERAL_PINCH_MAX_MASS_G:
        return _lateral_pinch(o, "flat")
    if m >= HEAVY_MASS_G:
        return [
            ("medium_wrap", f"flat but heavy ({m:.0f} g >= {HEAVY_MASS_G:g} g): hand wrapped over the edge"),
            ("thumb_4_finger", "flat: thumb on one face, four fingers under the other"),
            ("power_disk", "palm on the face, fingers round the edge"),
        ]
    # The finger pads lie along the table edge: along its length, unless it lies by its length across the
    # edge (too narrow to overhang under the pads, sim/grasps.py edge_depth_cm: a ruler), then its width.
    along, side = (o.b_cm, "width") if edge_depth_cm(a, o.b_cm) == a else (a, "length")
    return [
        (
            _fingers_for_length(along, m),
            f"flat ({w:g} cm thick) and {m:.0f} g: thumb on one face, finger pads on the other, along its "
            f"{along:g} cm {side}",
        ),
        ("lateral_pinch", "flat: thumb against the side of the index"),
        ("medium_wrap", "hand wrapped over the edge"),
    ]


def _utensil(o: PlannedObject) -> Candidates | None:
    """A long light utensil (spatula, ladle) is held by its handle, thinner than its box."""
    a, m = o.a_cm, o.mass_g
    if not (o.shape == "long" and a >= TOOL_MIN_LENGTH_CM and m < LIGHT_MASS_G):
        return None
    return [
        (
            "light_tool",
            f"a long ({a:g} cm), light utensil: held by its handle like a tool (Cutkosky: power, prismatic)",
        ),
        ("medium_wrap", "the handle wrapped by the fingers"),
        (_fingers_for_length(a, m), "finger pads along its length"),
    ]


def _power_prismatic(o: PlannedObject) -> Candidates | None:
    """Heavy, wide or hand-filling prisms (about 5 cm and 150 g or more) are wrapped, not pinched."""
    w, m = o.c_cm, o.mass_g
    heavy = m >= HEAVY_MASS_G
    light_small = m < LIGHT_MASS_G and w <= PRECISION_MAX_WIDTH_CM and not (w >= 4.5 and m >= 150.0)
    if not (heavy or not light_small):
        return None
    if heavy:
        why = f"heavy ({m:.0f} g >= {HEAVY_MASS_G:g} g)"
    elif w <= PRECISION_MAX_WIDTH_CM:
        why = f"{m:.0f} g"
    else:
        why = f"{w:g} cm wide (> {PRECISION_MAX_WIDTH_CM:g} cm)"
    kind = _power_wrap(w, m, long=o.shape == "long")
    out = [
        (kind, f"{why}: fingers and palm wrap it across its {w:g} cm width (Feix 2014: large and heavy -> power)")
    ]
    if kind != "medium_wrap":
        out.append(("medium_wrap", "wrapped with the fingers"))
    if w <= PRECISION_MAX_WIDTH_CM + 1.0 and not heavy:
        out.append(("thumb_4_finger", "thumb against four finger pads"))
    elif w >= POWER_SPHERE_MIN_CM:
        # The power sphere is a circular grasp (Cutkosky): a heavy box's flat faces are wrapped only.
        if not (heavy and _is_box(o)):
            out.append(("power_sphere", "the fingers spread round it"))
    else:
        out.append(("heavy_wrap_small_diameter", "a tight fist round it"))
    return out


def _is_box(o: PlannedObject) -> bool:
    """Is the object, as the simulator builds it, a box (flat faces, square corners: a brick, a carton), not
    a round body? (sim/bodies.py, from its sizes and kind.)"""
    return o.body().form == "box"


def _pen(o: PlannedObject) -> Candidates | None:
    """Pen-like objects are held in the writing tripod (Feix 2016), the grasp they are picked up for."""
    a, w, m = o.a_cm, o.c_cm, o.mass_g
    if not (o.shape == "long" and a >= 10.0 and o.b_cm <= PEN_MAX_THICK_CM and w >= 0.8 * o.b_cm and m < PEN_MAX_MASS_G):
        return None
    return [
        (
            "tripod",
            f"pen-like ({a:g} cm long, {o.b_cm:g} cm thick, {m:.0f} g): held in the writing tripod (Feix 2016)",
        ),
        (_fingers_for_length(a, m), "picked up: finger pads along its length"),
        ("lateral_pinch", "thin: thumb against the side of the index"),
    ]


def _thin_rod(o: PlannedObject) -> Candidates | None:
    """A thin rod too heavy for a pen (a wire, a tube, a small key): the side of the index, Feix 2016's side
    opposition for thin objects; the key pinch is stronger than the tip pinch (sim/PLANNER.md, version 17)."""
    a, b, m = o.a_cm, o.b_cm, o.mass_g
    if not (o.shape == "long" and b <= ROD_MAX_THICK_CM and o.c_cm >= 0.8 * b and PEN_MAX_MASS_G <= m < LIGHT_MASS_G):
        return None
    return [
        (
            "lateral_pinch",
            f"a thin rod ({b:g} cm thick, {m:.0f} g): thumb pad against the side of the index (Feix 2016: side opposition)",
        ),
        (_fingers_for_length(a, m), "picked up: finger pads along its length"),
        ("light_tool", "long and thin: held like a tool handle"),
    ]


def _long_handle(o: PlannedObject) -> Candidates | None:
    """A long object with a thin handle and some weight (kitchen knife, pliers): held like a tool."""
    a, w, m = o.a_cm, o.c_cm, o.mass_g
    if not (o.shape == "long" and w < 3.0 and m >= 150.0):
        return None
    return [
        (
            "light_tool",
            f"long, a thin handle ({w:g} cm) and {m:.0f} g: held like a tool (Cutkosky: power, prismatic)",
        ),
        (_fingers_for_length(a, m), "finger pads along its length"),
        ("heavy_wrap_small_diameter", "a tight fist round the handle"),
    ]


def _long_wrap(o: PlannedObject) -> Candidates | None:
    """A long, handle-thick object (banana, screwdriver handle) is wrapped by the fingers."""
    a, w, m = o.a_cm, o.c_cm, o.mass_g
    if not (o.shape == "long" and a >= 12.0 and w >= 3.0):
        return None
    return [
        ("medium_wrap", f"long ({a:g} cm) and {w:g} cm thick: wrapped by the fingers (Cutkosky: power, prismatic)"),
        (_fingers_for_length(a, m), "light: finger pads along its length"),
        ("adducted_thumb", "long: thumb laid along it"),
    ]


def _small_block(o: PlannedObject) -> Candidates | None:
    """Small blocks (dice): a fingertip pinch; a block is prismatic (Cutkosky)."""
    a = o.a_cm
    if not (o.shape == "compact" and a < 4.0):
        return None
    kind = "thumb_2_finger" if a >= 2.0 else "thumb_index_finger"
    return [
        (kind, f"small ({a:g} cm) and light block: fingertip pinch (Cutkosky: precision, prismatic)"),
        ("tripod", "small: thumb, index and middle finger pads"),
        ("lateral_pinch", "small: thumb against the side of the index"),
    ]


def _precision_prismatic(o: PlannedObject) -> Candidates:
    """Everything else (small light prisms, long light objects: remote, battery): thumb against n pads."""
    a, w, m = o.a_cm, o.c_cm, o.mass_g
    kind = _fingers_for_length(a, m)
    out = [
        (
            kind,
            f"light ({m:.0f} g) and {w:g} cm wide: a precision pinch across the smallest side, finger pads along its {a:g} cm length (Feix 2014; Cutkosky: precision, prismatic)",
        )
    ]
    if o.shape == "long" and w < 3.0:
        out.append(("light_tool", "long and thin: held like a tool handle"))
    else:
        out.append(("medium_wrap", "wrapped by the fingers"))
    out.append(("thumb_3_finger" if kind != "thumb_3_finger" else "thumb_2_finger", "finger pads along its length"))
    return out


#: The rules in the order PLANNER.md's table lists them; the first that applies chooses.
_RULES = (
    _floppy, _sphere, _disk, _small_flat, _flat, _utensil, _power_prismatic, _pen, _thin_rod, _long_handle,
    _long_wrap, _small_block,
)  # fmt: skip


def candidates(o: PlannedObject) -> Candidates:
    """Ordered (grasp type, reason) candidates: the rules' choice first, then sensible alternatives."""
    for rule in _RULES:
        out = rule(o)
        if out is not None:
            return out
    return _precision_prismatic(o)
