"""The object as the grasp planner sees it: its features, validated, with documented defaults for the
unknown ones and the assumptions made (sim/PLANNER.md, "Unknown features").

:func:`resolve_features` is shared with the simulator (sim/objects.py), so planner and trial see the same
object.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from kb.features import FEATURES, ObjectRecord, validate_features
from sim.friction import friction_coefficient
from sim.grasps import HAND_MAX_APERTURE_CM

__all__ = ["DEFAULTS", "EFFECTIVE_DENSITY", "SHAPE_FILL", "PlannedObject", "resolve_features"]

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
    aliases: tuple[str, ...] = field(default=())  # with the name, they give its kind (sim/bodies.py)

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

    def body(self) -> Any:
        """The body the simulator builds for this object (sim/bodies.py ``Body``: its form, handle), from
        its sizes, shape, mass and kind (name and aliases)."""
        from sim.bodies import body_for

        sizes = (self.a_cm, self.b_cm, self.c_cm)
        return body_for(sizes, self.shape, self.mass_g / 1000.0, name=self.name, aliases=self.aliases)


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
        aliases = tuple(obj.aliases)
        values = obj.features()
    else:
        name = obj.get("name")
        aliases = tuple(obj.get("aliases") or ())
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
        aliases=aliases,
    )
