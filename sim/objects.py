"""MuJoCo objects built from catalog features (kb.features): shape, size, mass, friction and softness.

Shape from the features (see sim/PHYSICS.md, "Objects"):

* ``radial`` with all three sides within 20 % -> sphere (diameter the mean side); with the two larger
  sides within 20 % and a thinner third -> a disk (cylinder along ``c``); otherwise an ellipsoid.
* ``prism`` or ``long`` with ``b`` and ``c`` within 20 % -> cylinder along ``a`` (bottles, cans, pens: the
  vocabulary maps "cylindrical" to prism); otherwise a box.
* ``thin``, ``compact`` and unknown shapes -> box.

Mass is the catalog mass (or the planner's estimate when unknown); MuJoCo computes the inertia from the
geom with that mass (uniform density). Friction comes from sim/friction.py (the planner's table, so the
planner's grip-force estimate and the physics agree). The object's geom has contact ``priority`` 1, above
the hand's 0, so its friction, ``condim`` and solver parameters decide every hand contact. Squeezable and
floppy objects get softer contacts (``solref``/``solimp``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np

from kb.errors import InvalidFeature, SimulationError
from kb.features import ObjectRecord, validate_features
from sim.friction import friction_coefficient
from sim.hand import HAND_BIT, OBJECT_BIT, TABLE_BIT

__all__ = [
    "CONTACT_SOFTNESS",
    "ObjectModel",
    "TORSIONAL_PATCH_M",
    "add_object",
    "add_table",
    "object_model",
]

CM = 0.01
#: Sides within this ratio count as equal (sphere, disk, round cross-section).
ROUND_RATIO = 0.8
#: Torsional friction (condim 4) is mu times the contact patch radius: a fingertip pad presses a patch
#: about 5 mm across (Serina et al. 1997, fingertip contact area at 1-5 N), so mu * 5 mm of twist resistance.
TORSIONAL_PATCH_M = 0.005
#: Contact softness per rigidity: (solref (time constant s, damping ratio), solimp (dmin, dmax, width m,
#: midpoint, power); the last two are MuJoCo's defaults).
#: Rigid: a stiff contact (10 ms, 5 steps of 2 ms: the fastest that stays stable) that reaches full
#: impedance within 1 mm. Squeezable (sponges, tennis balls, bread): twice as slow with a 5 mm wide
#: impedance ramp, so fingers sink in a few millimetres as into foam. Floppy (cloth, bags): softer still.
CONTACT_SOFTNESS: dict[str, tuple[tuple[float, float], tuple[float, ...]]] = {
    "rigid": ((0.01, 1.0), (0.95, 0.99, 0.001, 0.5, 2.0)),
    "squeezable": ((0.02, 1.0), (0.7, 0.95, 0.005, 0.5, 2.0)),
    "floppy": ((0.03, 1.0), (0.5, 0.9, 0.01, 0.5, 2.0)),
}
#: Display colour per material (only for pictures).
MATERIAL_RGBA: dict[str | None, tuple[float, float, float, float]] = {
    "fabric": (0.55, 0.35, 0.6, 1.0),
    "glass": (0.6, 0.8, 0.85, 0.7),
    "metal": (0.65, 0.67, 0.7, 1.0),
    "paper": (0.8, 0.7, 0.5, 1.0),
    "plastic": (0.2, 0.5, 0.85, 1.0),
    "rubber": (0.3, 0.3, 0.3, 1.0),
    "wood": (0.6, 0.42, 0.25, 1.0),
    "other": (0.75, 0.75, 0.7, 1.0),
    None: (0.9, 0.55, 0.2, 1.0),
}
TABLE_FRICTION = 0.5  # laminate table top; the object's priority makes its own friction count anyway


@dataclass(frozen=True)
class ObjectModel:
    """What the simulator builds for one object (sizes in cm as in the catalog, mass in kg).

    ``kind``: box, cylinder, sphere or ellipsoid; ``axis_dim``: for a cylinder, the dimension along its
    axis. ``friction`` is the sliding coefficient; ``assumptions`` names every default used.
    """

    name: str
    kind: str
    dims_cm: tuple[float, float, float]
    mass_kg: float
    friction: float
    rigidity: str
    material: str | None
    axis_dim: str | None = None
    assumptions: tuple[str, ...] = field(default=())

    def extent_cm(self, dim: str) -> float:
        """Extent of the built shape along catalog dimension ``dim`` ('a', 'b' or 'c')."""
        a, b, c = self.dims_cm
        ext = {"a": a, "b": b, "c": c}
        if self.kind == "sphere":
            return (a + b + c) / 3.0
        if self.kind == "cylinder":
            round_dims = [d for d in "abc" if d != self.axis_dim]
            if dim in round_dims:
                return sum(ext[d] for d in round_dims) / 2.0
        return ext[dim]

    @property
    def weight_n(self) -> float:
        return self.mass_kg * 9.81


def object_model(obj: ObjectRecord) -> ObjectModel:
    """The simulated object for catalog record ``obj`` (unknown features get the planner's defaults)."""
    from sim.planner import resolve_features

    try:
        validate_features(obj.features())  # records built without create() are checked here
        o = resolve_features(obj)
    except InvalidFeature as exc:
        raise SimulationError(f"cannot build {obj.name!r} for simulation: {exc}") from exc
    a, b, c = o.a_cm, o.b_cm, o.c_cm
    kind, axis = "box", None
    if o.shape == "radial":
        if c >= ROUND_RATIO * a:
            kind = "sphere"
        elif b >= ROUND_RATIO * a:
            kind, axis = "cylinder", "c"
        else:
            kind = "ellipsoid"
    elif o.shape in ("prism", "long") and c >= ROUND_RATIO * b:
        kind, axis = "cylinder", "a"
    rigidity = o.rigidity if o.rigidity in CONTACT_SOFTNESS else "rigid"
    return ObjectModel(
        name=obj.name,
        kind=kind,
        dims_cm=(a, b, c),
        mass_kg=o.mass_g / 1000.0,
        friction=friction_coefficient(o.material, o.texture),
        rigidity=rigidity,
        material=o.material,
        axis_dim=axis,
        assumptions=tuple(o.assumptions),
    )


def add_table(spec: mujoco.MjSpec, edge_x_m: float | None = None) -> None:
    """A 80 x 80 cm table whose top is the plane z = 0; it touches only the object. With ``edge_x_m`` the
    table ends there (its +x edge), so that an object can overhang it."""
    center_x = 0.0 if edge_x_m is None else edge_x_m - 0.4
    spec.worldbody.add_geom(
        name="table",
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[0.4, 0.4, 0.02],
        pos=[center_x, 0, -0.02],
        friction=[TABLE_FRICTION, 0.005, 0.0001],
        contype=TABLE_BIT,
        conaffinity=OBJECT_BIT,
        rgba=[0.55, 0.5, 0.45, 1.0],
    )


_AXIS_QUAT = {  # rotate a cylinder's local z axis onto world x, y or z
    0: (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0),
    1: (math.cos(math.pi / 4), -math.sin(math.pi / 4), 0.0, 0.0),
    2: (1.0, 0.0, 0.0, 0.0),
}


def add_object(spec: mujoco.MjSpec, model: ObjectModel, axes: dict[str, int], pos_m) -> None:
    """Add ``model`` as a free body named "object" at ``pos_m``; ``axes`` maps dims 'a','b','c' to world
    axes 0, 1, 2 (the object's pose on the table)."""
    if sorted(axes.values()) != [0, 1, 2] or sorted(axes) != ["a", "b", "c"]:
        raise ValueError(f"axes must map a, b, c onto 0, 1, 2, not {axes}")
    half = np.zeros(3)
    for dim, ax in axes.items():
        half[ax] = model.extent_cm(dim) * CM / 2.0
    body = spec.worldbody.add_body(name="object", pos=list(pos_m))
    body.add_freejoint(name="object_free")
    quat = (1.0, 0.0, 0.0, 0.0)
    if model.kind == "box":
        gtype, size = mujoco.mjtGeom.mjGEOM_BOX, list(half)
    elif model.kind == "ellipsoid":
        gtype, size = mujoco.mjtGeom.mjGEOM_ELLIPSOID, list(half)
    elif model.kind == "sphere":
        gtype, size = mujoco.mjtGeom.mjGEOM_SPHERE, [half[0], 0, 0]
    else:
        ax = axes[model.axis_dim or "a"]
        radius = max(h for i, h in enumerate(half) if i != ax)
        gtype, size, quat = mujoco.mjtGeom.mjGEOM_CYLINDER, [radius, half[ax], 0], _AXIS_QUAT[ax]
    solref, solimp = CONTACT_SOFTNESS[model.rigidity]
    body.add_geom(
        name="object_geom",
        type=gtype,
        size=size,
        quat=list(quat),
        mass=model.mass_kg,  # MuJoCo derives the inertia from this shape at this mass
        friction=[model.friction, model.friction * TORSIONAL_PATCH_M, 0.0001],
        condim=4,  # sliding plus torsional friction: a pinch must resist the object twisting out
        priority=1,  # above the hand's 0: this geom's friction, condim and softness govern its contacts
        solref=list(solref),
        solimp=list(solimp),
        contype=OBJECT_BIT,
        conaffinity=HAND_BIT | TABLE_BIT,
        rgba=list(MATERIAL_RGBA.get(model.material, MATERIAL_RGBA[None])),
    )
