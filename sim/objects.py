"""MuJoCo objects built from catalog features (kb.features): shape, size, mass, friction and softness.

Shape from the features and the object's kind (sim/bodies.py; sim/PHYSICS.md, "Objects"): one primitive
(box, cylinder, sphere, ellipsoid) or a composite (a vessel with a handle, a pan), laid out in the
object's frame (axes a, b, c) and posed on the table by a rotation that maps them onto world axes.

Mass is the catalog mass (or the planner's estimate when unknown), spread over the parts by volume; MuJoCo
computes the inertia from the parts with their masses (uniform density). Friction comes from sim/friction.py (the planner's table, so the
planner's grip-force estimate and the physics agree). The object's geoms have contact ``priority`` 1, above
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
from sim.bodies import Body, Part, body_for
from sim.friction import friction_coefficient
from sim.hand import HAND_BIT, OBJECT_BIT, TABLE_BIT

__all__ = [
    "CONTACT_SOFTNESS",
    "ObjectModel",
    "TORSIONAL_PATCH_M",
    "add_object",
    "add_table",
    "free_dim",
    "pose_rotation",
    "object_model",
]

CM = 0.01
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

    ``kind``: box, cylinder, sphere, ellipsoid, vessel (upright, with a handle) or pan; ``axis_dim``: for
    a cylinder, the dimension along its axis; ``body``: its parts (sim/bodies.py). ``friction`` is the
    sliding coefficient; ``assumptions`` names every default used.
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
    body: Body | None = None  # None: built from kind and dims (a record made by hand, in tests)

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
    body = body_for((o.a_cm, o.b_cm, o.c_cm), o.shape, o.mass_g / 1000.0, name=obj.name, aliases=obj.aliases)
    axis = None
    if body.form == "cylinder":
        axis = next(d for d in "abc" if d not in body.round_dims)
    rigidity = o.rigidity if o.rigidity in CONTACT_SOFTNESS else "rigid"
    return ObjectModel(
        name=obj.name,
        kind=body.form,
        dims_cm=(o.a_cm, o.b_cm, o.c_cm),
        mass_kg=o.mass_g / 1000.0,
        friction=friction_coefficient(o.material, o.texture),
        rigidity=rigidity,
        material=o.material,
        axis_dim=axis,
        assumptions=(*o.assumptions, *body.assumptions),
        body=body,
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


def _default_body(model: ObjectModel) -> Body:
    """A body for an ObjectModel made without one: its kind's primitive over its dims."""
    a, b, c = model.dims_cm
    if model.kind == "cylinder":
        axis = model.axis_dim or "a"
        across = [model.extent_cm(d) for d in "abc" if d != axis]
        unit = tuple(1.0 if d == axis else 0.0 for d in "abc")
        return Body("cylinder", (Part("body", "cylinder", (max(across) / 2, model.extent_cm(axis) / 2, 0.0), axis=unit),))
    if model.kind == "sphere":
        return Body("sphere", (Part("body", "sphere", (model.extent_cm("a") / 2, 0.0, 0.0)),))
    geom = "ellipsoid" if model.kind == "ellipsoid" else "box"
    return Body(geom, (Part("body", geom, (a / 2, b / 2, c / 2)),))


def free_dim(model: ObjectModel) -> str:
    """A dimension the body is symmetric across (not its up or handle dimension): the one
    :func:`pose_rotation` may flip to keep a rotation proper."""
    body = model.body
    if body is None:
        return "c"
    taken = {body.up, body.handle.dim if body.handle else None}
    return next(d for d in "cba" if d not in taken)


def pose_rotation(axes: dict[str, int], signs: dict[str, int] | None = None, free: str = "c") -> np.ndarray:
    """The rotation (3 x 3, det +1) that takes the object's frame (a, b, c) onto the world: dimension ``d``
    along world axis ``axes[d]``, pointing ``signs[d]`` (+1 or -1; default +1). If that is a reflection,
    dimension ``free`` (one the body is symmetric across) is flipped."""
    if sorted(axes.values()) != [0, 1, 2] or sorted(axes) != ["a", "b", "c"]:
        raise ValueError(f"axes must map a, b, c onto 0, 1, 2, not {axes}")
    signs = signs or {}
    rot = np.zeros((3, 3))
    for i, dim in enumerate("abc"):
        rot[axes[dim], i] = float(signs.get(dim, 1))
    if np.linalg.det(rot) < 0:
        rot[:, "abc".index(free)] *= -1.0
    return rot


def _part_quat(part: Part, rot: np.ndarray) -> np.ndarray:
    """World orientation of ``part``: its local z onto its axis (cylinders, capsules), turned by its
    ``turn_deg`` about that axis, then posed by ``rot``."""
    axis = np.asarray(part.axis, dtype=float)
    local = np.array([1.0, 0.0, 0.0, 0.0])
    if part.geom in ("cylinder", "capsule"):
        mujoco.mju_quatZ2Vec(local, axis)
    if part.turn_deg:
        turn = np.zeros(4)
        mujoco.mju_axisAngle2Quat(turn, axis, math.radians(part.turn_deg))
        mujoco.mju_mulQuat(local, turn, local.copy())
    pose = np.zeros(4)
    mujoco.mju_mat2Quat(pose, rot.flatten())
    out = np.zeros(4)
    mujoco.mju_mulQuat(out, pose, local)
    return out


_GEOM_TYPES = {
    "box": mujoco.mjtGeom.mjGEOM_BOX,
    "cylinder": mujoco.mjtGeom.mjGEOM_CYLINDER,
    "capsule": mujoco.mjtGeom.mjGEOM_CAPSULE,
    "sphere": mujoco.mjtGeom.mjGEOM_SPHERE,
    "ellipsoid": mujoco.mjtGeom.mjGEOM_ELLIPSOID,
}


def add_object(
    spec: mujoco.MjSpec, model: ObjectModel, axes: dict[str, int], pos_m, signs: dict[str, int] | None = None
) -> np.ndarray:
    """Add ``model`` as a free body named "object" whose frame's origin (the centre of its stated box) is at
    ``pos_m``; ``axes`` maps dims 'a','b','c' to world axes 0, 1, 2 and ``signs`` the direction of each
    (the object's pose on the table: a vessel's handle away from the hand). Its first part is the geom
    "object_geom", the others "object_<part>". Returns the pose rotation (:func:`pose_rotation`)."""
    body_def = model.body or _default_body(model)
    rot = pose_rotation(axes, signs, free_dim(model))
    body = spec.worldbody.add_body(name="object", pos=list(pos_m))
    body.add_freejoint(name="object_free")
    solref, solimp = CONTACT_SOFTNESS[model.rigidity]
    colour = list(MATERIAL_RGBA.get(model.material, MATERIAL_RGBA[None]))
    for k, part in enumerate(body_def.parts):
        common = dict(
            name="object_geom" if k == 0 else f"object_{part.name}",
            type=_GEOM_TYPES[part.geom],
            size=[x * CM for x in part.size_cm],
            pos=list(rot @ np.asarray(part.pos_cm) * CM),
            quat=list(_part_quat(part, rot)),
            rgba=list(part.rgba) if part.rgba else colour,
        )
        if not part.collides:  # a visual part: no mass, no contacts
            body.add_geom(**common, mass=0.0, contype=0, conaffinity=0, group=1)
            continue
        body.add_geom(
            **common,
            mass=part.mass_kg,  # MuJoCo derives the inertia from this shape at this mass
            friction=[model.friction, model.friction * TORSIONAL_PATCH_M, 0.0001],
            condim=4,  # sliding plus torsional friction: a pinch must resist the object twisting out
            priority=1,  # above the hand's 0: this geom's friction, condim and softness govern its contacts
            solref=list(solref),
            solimp=list(solimp),
            contype=OBJECT_BIT,
            conaffinity=HAND_BIT | TABLE_BIT,
        )
    return rot
