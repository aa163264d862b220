"""Grasp planner: ranked candidate grasps for an object, from its features, with the rules that chose them.

The rules, and the published findings they rest on, are written down in ``sim/PLANNER.md``. In short:

1. **Grasped dimension.** Grasp across the smallest dimension ``c`` (Feix et al. 2014: the smallest major
   dimension is grasped in 94 % of grasps), unless it is wider than the hand can open.
2. **Family first** (power, intermediate, precision), from mass and grasped width, the strongest object
   predictors of grasp type (Feix et al. 2014, 2014b): heavy or wide objects get power grasps, small light
   ones precision grasps; thin small flat objects (keys, cards) the lateral pinch.
3. **Type within the family** from shape (Cutkosky 1989: prismatic versus circular; disk versus sphere)
   and size (wrap diameter; how many fingers fit along the object).
4. **Force**: the normal force a two-sided grip needs to hold the weight against friction,
   ``F >= m g SF / (2 mu)``, with friction from material and texture (sim/friction.py) and a safety factor
   lowered for fragile objects (Johansson & Westling 1984).
5. **Feasibility**: the aperture is capped by the hand's span; a plan the hand cannot open for, or whose
   force exceeds what its fingers can give, is kept but flagged and ranked down.

Unknown features get documented defaults (:data:`DEFAULTS`) and every assumption is named in the plan's
rationale, so that ``plan_grasps`` always answers for any valid feature set.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from kb.features import FEATURES, ObjectRecord, validate_features
from sim.friction import friction_coefficient
from sim.grasps import GRASP_TYPES, GraspPlan, edge_grip_in_cm, is_flat_grasp, side_force_capacity
from sim.programs import program_for

__all__ = [
    "DEFAULTS",
    "GRAVITY",
    "HAND_MAX_APERTURE_CM",
    "HEAVY_MASS_G",
    "PLANNER_VERSION",
    "PlannedObject",
    "best_grasp",
    "plan_grasps",
    "edge_grip_force",
    "required_grip_force",
    "resolve_features",
]

#: Stored with every validation result; bump when the rules change what they choose.
PLANNER_VERSION = "6"  # 6: candidates listed once per hand program (sim/programs.py)

GRAVITY = 9.81  # m/s^2

#: Widest opening of a human-sized hand (AR10-like): thumb tip to finger tips about 12 cm, the span that
#: holds a 12 cm ball in a power sphere grasp. Wider extents cannot be held in one hand.
HAND_MAX_APERTURE_CM = 12.0
#: Feix et al. 2014: 96 % of grasp locations are 7 cm wide or less; beyond this the hand wraps or spans.
TYPICAL_MAX_WIDTH_CM = 7.0
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

#: A light long object at least this long is a utensil or tool held by its handle (spatula, ladle, knife):
#: its bounding box is wider than the handle people actually hold.
TOOL_MIN_LENGTH_CM = 25.0
# The squeeze each grasp type can give is the hand's (sim/grasps.py side_force_capacity, from the
# FINGER_MAX_FORCE_N / THUMB_MAX_FORCE_N constants the simulated hand uses too): thumb-index 15 N,
# thumb-2 finger 30 N, thumb-3 finger 45 N, thumb-4 finger and power grasps 60 N per side.
#: How far (cm) a pressed pad can shift its centre of pressure to resist a flat object tilting about the
#: grip (see edge_grip_force): a fingertip pad's contact is about 1 cm across at a few newtons (Serina et
#: al. 1997), so at most 5 mm; 3 mm, calibrated on the trial (books, phones, frames held at the edge).
EDGE_PAD_LEVER_CM = 0.3
#: Fingertip grasps open at least this much wider than the object (cm): people's maximum grip aperture
#: during the reach exceeds the object by a few centimetres (Jeannerod 1984, "The timing of natural
#: prehension movements"). 1 cm left the pads' capsules brushing round objects and boxes on the way down
#: (pinched higher, they squeezed them out); 2 cm: 127 instead of 124 of the seed catalog's best plans held.
PRECISION_APERTURE_MARGIN_CM = 2.0
#: Never plan less than this: the fingers must at least hold contact.
MIN_GRIP_FORCE_N = 1.5
#: Safety factor on the weight: 2 covers the weight plus the trial's perturbation (a force equal to the
#: weight), the rest is the grip-force safety margin people keep above slip (Johansson & Westling 1984).
SAFETY_FACTOR = {"sturdy": 2.6, "medium": 2.4, "fragile": 2.1}

#: Defaults for unknown features (see PLANNER.md, "Unknown features").
DEFAULTS: dict[str, Any] = {
    "dims_cm": (12.0, 6.0, 4.0),  # a typical hand-held object: grasp location within 7 cm (Feix 2014)
    "material": None,  # friction then uses sim.friction.DEFAULT_FRICTION (hard plastic)
    "texture": "medium",
    "fragility": "medium",
    "rigidity": "rigid",
}
#: Effective density (mass over bounding-box volume, g/cm^3) used to guess an unknown mass; household
#: objects are mostly hollow or shaped, far below their materials' solid density.
EFFECTIVE_DENSITY = {
    "fabric": 0.15,
    "paper": 0.3,
    "plastic": 0.35,
    "wood": 0.55,
    "rubber": 0.6,
    "glass": 0.6,
    "metal": 0.8,
    "other": 0.5,
    None: 0.4,
}
#: Fraction of the bounding box a shape fills (sphere pi/6, cylinder pi/4, others about a box).
SHAPE_FILL = {"radial": 0.52, "prism": 0.79, "long": 0.8, "compact": 0.9, "thin": 0.9, None: 0.8}



#: Feature keys accepted in a features mapping besides the canonical ones (the paper says "stiffness").
_KEY_ALIASES = {"a": "a_cm", "b": "b_cm", "c": "c_cm", "mass": "mass_g", "stiffness": "rigidity"}


@dataclass(frozen=True)
class PlannedObject:
    """The features the planner worked with: known values plus defaults, and the assumptions it made."""

    name: str | None
    a_cm: float
    b_cm: float
    c_cm: float
    mass_g: float
    shape: str
    texture: str | None
    fragility: str
    material: str | None
    rigidity: str
    friction: float
    assumptions: tuple[str, ...] = field(default=())

    @property
    def is_disk(self) -> bool:
        """Round and flat: the two larger sides about equal, clearly thicker than a sheet, within the span."""
        return (
            self.shape in ("radial", "compact", "thin")
            and self.b_cm >= 0.8 * self.a_cm
            and 1.0 <= self.c_cm <= 0.6 * self.b_cm
            and self.b_cm <= HAND_MAX_APERTURE_CM
        )

    @property
    def is_sphere(self) -> bool:
        return self.shape == "radial" and self.c_cm >= 0.6 * self.b_cm

    @property
    def is_flat(self) -> bool:
        return self.shape == "thin"


def _infer_shape(a: float, b: float, c: float) -> str:
    """Shape class from the dimension ratios alone (round objects cannot be told from boxes: compact)."""
    if c <= 0.35 * b:
        return "thin"
    if b <= 0.35 * a:
        return "long"
    if a <= 1.4 * c:
        return "compact"
    return "prism"


def resolve_features(obj: ObjectRecord | Mapping[str, Any]) -> PlannedObject:
    """Validate ``obj``'s features and fill unknown ones with the planner's documented defaults.

    Raises :class:`kb.errors.InvalidFeature` for invalid values (through ``validate_features``).
    """
    if isinstance(obj, ObjectRecord):
        name: str | None = obj.name
        values = obj.features()
    else:
        name = obj.get("name")
        raw = {_KEY_ALIASES.get(str(k).lower(), str(k).lower()): v for k, v in obj.items()}
        values = validate_features({k: v for k, v in raw.items() if k in FEATURES})
    notes: list[str] = []
    a, b, c = values["a_cm"], values["b_cm"], values["c_cm"]
    shape = values["shape"]
    if a is None:
        a, b, c = DEFAULTS["dims_cm"]
        notes.append(f"size unknown: assumed {a:g} x {b:g} x {c:g} cm, a typical hand-held object")
    elif b is None:
        ratio = {"radial": (1.0, 1.0), "compact": (0.8, 0.8), "long": (0.2, 0.15), "thin": (0.7, 0.1)}
        rb, rc = ratio.get(shape or "", (0.5, 0.35))
        b, c = a * rb, a * rc
        notes.append(
            f"only one size known: assumed {a:g} x {b:.3g} x {c:.3g} cm from shape {shape or 'unknown'}"
        )
    elif c is None:
        rc = {"radial": 1.0, "thin": 0.15, "compact": 0.9}.get(shape or "", 0.7)
        c = b * rc
        notes.append(f"third size unknown: assumed {c:.3g} cm from shape {shape or 'unknown'}")
    if shape is None:
        shape = _infer_shape(a, b, c)
        notes.append(f"shape unknown: {shape} from the dimension ratios")
    material = values["material"]
    mass = values["mass_g"]
    if mass is None:
        density = EFFECTIVE_DENSITY[material] * SHAPE_FILL.get(shape, 0.8)
        mass = max(1.0, a * b * c * density)
        notes.append(f"mass unknown: about {mass:.0f} g from its size and {material or 'unknown'} material")
    texture = values["texture"]
    fragility = values["fragility"] or DEFAULTS["fragility"]
    if values["fragility"] is None:
        notes.append("fragility unknown: treated as medium")
    rigidity = values["rigidity"] or DEFAULTS["rigidity"]
    if values["rigidity"] is None:
        notes.append("rigidity unknown: treated as rigid")
    mu = friction_coefficient(material, texture)
    if material is None or texture is None:
        notes.append(f"material or texture unknown: friction {mu:g} assumed")
    return PlannedObject(
        name=name,
        a_cm=float(a),
        b_cm=float(b),
        c_cm=float(c),
        mass_g=float(mass),
        shape=shape,
        texture=texture,
        fragility=fragility,
        material=material,
        rigidity=rigidity,
        friction=mu,
        assumptions=tuple(notes),
    )


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


def _small_flat(o: PlannedObject) -> Candidates | None:
    """Tiny flat things (coins, clips: the tip pinch) and small flat-sided ones (keys, cards: lateral)."""
    w, a = o.c_cm, o.a_cm
    small_flat = (
        w <= LATERAL_PINCH_MAX_THICK_CM
        and a <= LATERAL_PINCH_MAX_LENGTH_CM
        and o.mass_g <= LATERAL_PINCH_MAX_MASS_G
        and w <= 0.6 * o.b_cm
    )
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
    return [
        (
            _fingers_for_length(a, m),
            f"flat ({w:g} cm thick) and {m:.0f} g: thumb on one face, finger pads on the other, along its {a:g} cm length",
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
        out.append(("power_sphere", "the fingers spread round it"))
    else:
        out.append(("heavy_wrap_small_diameter", "a tight fist round it"))
    return out


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
    _floppy, _sphere, _disk, _small_flat, _flat, _utensil, _power_prismatic, _pen, _long_handle, _long_wrap,
    _small_block,
)  # fmt: skip


def _candidates(o: PlannedObject) -> Candidates:
    """Ordered (grasp type, reason) candidates: the rules' choice first, then sensible alternatives."""
    for rule in _RULES:
        out = rule(o)
        if out is not None:
            return out
    return _precision_prismatic(o)


def _aperture(grasp_type: str, width_cm: float) -> float:
    """Opening before closing: the grasped width plus a margin (more for wraps, which close around)."""
    margin = (
        max(1.5, 0.25 * width_cm)
        if GRASP_TYPES[grasp_type] == "power"
        else max(PRECISION_APERTURE_MARGIN_CM, 0.2 * width_cm)
    )
    return round(min(HAND_MAX_APERTURE_CM, width_cm + margin), 2)


def plan_grasps(obj: ObjectRecord | Mapping[str, Any], *, top: int | None = None) -> list[GraspPlan]:
    """Ranked candidate grasps for ``obj`` (an ObjectRecord or a features mapping), best first.

    Every plan carries its rationale (the rules that chose it and the assumptions made for unknown
    features). ``top`` keeps only the first ``top`` plans. Raises InvalidFeature for invalid features.
    """
    o = resolve_features(obj)
    width = o.c_cm
    dim = "c"
    notes = list(o.assumptions)
    feasible = True
    two_hands = False
    if width > HAND_MAX_APERTURE_CM:
        feasible = False
        two_hands = True
        notes.append(
            f"every side is wider than the hand's {HAND_MAX_APERTURE_CM:g} cm span (smallest {width:g} cm): "
            "needs two hands; the best one-hand option is listed but flagged infeasible"
        )
    elif width > TYPICAL_MAX_WIDTH_CM:
        notes.append(
            f"grasped width {width:g} cm is over 7 cm, wider than 96 % of human grasp locations (Feix 2014)"
        )

    base_force = required_grip_force(o.mass_g, o.friction, o.fragility)
    edge_force = edge_grip_force(o.mass_g, o.b_cm, o.fragility) if is_flat_grasp(o.c_cm, o.b_cm) else 0.0
    plans: list[GraspPlan] = []
    seen: set[str] = set()  # hand programs already listed: a merged type is simulated once
    for rank, (grasp_type, reason) in enumerate(_candidates(o)):
        program = program_for(grasp_type)
        if program.name in seen:
            continue
        seen.add(program.name)
        family = GRASP_TYPES[grasp_type]
        rationale = [reason]
        if program.merged:
            others = ", ".join(t.replace("_", " ") for t in program.grasp_types if t != grasp_type)
            rationale.append(
                f"simulated by the {program.name.replace('_', ' ')} hand program, shared with {others}: "
                "this hand (no finger abduction) cannot make them differently (sim/programs.py)"
            )
        if rank == 0:
            rationale.append(f"grasped across its smallest side c = {width:g} cm (Feix 2014: 94 % of grasps)")
        score = 1.0 - 0.2 * rank
        capacity = side_force_capacity(grasp_type)
        force = base_force
        if o.rigidity == "squeezable":
            force = round(max(MIN_GRIP_FORCE_N, force * 0.8), 2)
            rationale.append("squeezable: a softer grip (it deforms to the fingers, more contact area)")
        if edge_force > force:
            force = edge_force
            rationale.append(
                f"flat: picked up at its edge, the pads {edge_grip_in_cm(o.b_cm):.3g} cm in and its centre of mass "
                f"{o.b_cm / 2:.3g} cm in; the squeeze must hold the moment of its weight: {edge_force:g} N"
            )
        rationale.append(
            f"grip {force:g} N = m g SF / (2 mu) with m = {o.mass_g:.0f} g, mu = {o.friction:g} ({o.material or 'unknown'}, "
            f"{o.texture or 'unknown'} texture), SF = {SAFETY_FACTOR.get(o.fragility, 2.4):g} ({o.fragility})"
        )
        force_ok = force <= capacity
        if not force_ok:
            score *= 0.4
            rationale.append(f"needs {force:g} N, more than a {grasp_type} grasp's {capacity:g} N: risky")
            force = capacity
        if not feasible:
            score *= 0.2
        plans.append(
            GraspPlan(
                grasp_type=grasp_type,
                family=family,
                grasped_dim=dim,
                aperture_cm=_aperture(grasp_type, width),
                approach=program.approach,  # type: ignore[arg-type]
                grip_force_n=force,
                score=round(score, 3),
                rationale=tuple(rationale + notes),
                params={
                    "width_cm": round(width, 3),
                    "friction": o.friction,
                    "safety_factor": SAFETY_FACTOR.get(o.fragility, 2.4),
                    "required_force_n": required_grip_force(o.mass_g, o.friction, o.fragility),
                    "force_within_capacity": force_ok,
                    "feasible": feasible,
                    "two_hands": two_hands,
                    "assumed_mass_g": round(o.mass_g, 1),
                    "planner_version": PLANNER_VERSION,
                    "program": program.name,
                },
            )
        )
    plans.sort(key=lambda p: -p.score)  # stable: rule order breaks ties
    return plans[:top] if top else plans


def best_grasp(obj: ObjectRecord | Mapping[str, Any]) -> GraspPlan:
    """The planner's first choice for ``obj``."""
    return plan_grasps(obj, top=1)[0]
