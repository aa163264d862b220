"""Floppy sheets (paper, envelopes, cloth) as a chain of hinged strips that droops, instead of a rigid plate.

A floppy flat object picked up at a table edge (sim/world.py) is built here: the strip the hand takes, from
the overhanging edge back until its own centre of mass sits over the table edge (so it neither tips nor
droops before the hand arrives), is the free body "object" the trial measures; the rest of the sheet lies
on the table as strips of at most :data:`SEGMENT_CM` hinged one to the next about the table edge's
direction (world y). Each hinge is a spring of the sheet's bending stiffness, so once lifted the rest
hangs from the held strip as a real sheet does, and its weight acts near the grip instead of as the
moment of a rigid plate 20-70 cm long (sim/PHYSICS.md, "Floppy sheets"). The catalog's mass is spread
over the strips by area; the pushes of the trial (its weight, on the held strip) are unchanged.

A rigid model cannot represent such an object: held 6 cm in from one edge, a rigid A4 sheet turns 35 deg
out of any pinch during the lift (the planner's edge moment), where a real sheet bends right behind the
fingers.
"""

from __future__ import annotations

import mujoco
import numpy as np

from sim.grasps import drapes, sheet_held_cm
from sim.hand import HAND_BIT, OBJECT_BIT, TABLE_BIT
from sim.objects import CM, CONTACT_SOFTNESS, MATERIAL_RGBA, TORSIONAL_PATCH_M, ObjectModel

__all__ = [
    "BENDING_STIFFNESS_NM",
    "SEGMENT_CM",
    "STUFFED_BENDING_STIFFNESS_NM",
    "add_sheet",
    "is_sheet",
    "sheet_strips",
]

#: Strips of the draping part at most this wide (cm) across the table edge: a sheet bends on a scale of a
#: few centimetres under its own weight; finer chains cost solver time and change nothing measured here.
SEGMENT_CM = 4.0
#: Bending stiffness per unit width (N m, i.e. N m^2 per m of sheet) by material. Paper: 80 g/m^2 copy
#: paper, E about 4 GPa at 0.1 mm, E t^3 / 12 = 3e-4 N m. Fabric: woven cotton about 0.1-1 gf cm^2/cm
#: (Kawabata KES-FB2 bending rigidity; 1 gf cm^2/cm = 1e-4 N m): 5e-5 N m. Rubber and others (a glove, a
#: hot water bottle's bag): 1e-4 N m. Ours, within those published ranges; the trial's verdict barely
#: depends on them (the weight, not the stiffness, dominates once the rest hangs).
BENDING_STIFFNESS_NM: dict[str | None, float] = {"paper": 3e-4, "fabric": 5e-5, None: 1e-4}
#: A stuffed fabric bag (a pillow, a cushion; squeezable fabric): far stiffer than its cover. Ours, from the
#: droop of a bed pillow held by one edge, which bends through most of a right angle over its 45 cm: a
#: cantilever of 13 N/m over 0.45 m deflecting about its length has EI of about q L^4 / (8 L) = 0.15 N m^2,
#: 0.2 N m per metre of its 0.65 m width. The trial's verdict on the seed pillow is the same from 0.01 to
#: 2 N m (sim/PHYSICS.md, floppy sheets).
STUFFED_BENDING_STIFFNESS_NM = 0.2
#: Hinge damping per unit of stiffness (s): a 10 ms time constant, the contacts' own, so a strip settles
#: within a few control ticks instead of swinging.
HINGE_DAMPING_S = 0.01
#: Reflected inertia of each hinge (kg m^2): a thin 1 g strip 4 cm wide has 1.3e-7 about its edge; this
#: keeps the stiffest hinge's period (about 25 ms) above ten time steps.
HINGE_ARMATURE = 2e-7


def is_sheet(model: ObjectModel, flat: bool) -> bool:
    """Is ``model`` built as a draping sheet? Objects that drape (sim/grasps.py ``drapes``: floppy, or a
    stuffed fabric bag) laid flat at a table edge, of a plain box body (a composite keeps its rigid parts)."""
    body = model.body
    plain = body is None or (len(body.parts) == 1 and body.parts[0].geom == "box")
    return flat and drapes(model.rigidity, model.material) and plain


def sheet_strips(depth_cm: float, overhang_cm: float) -> tuple[float, list[float]]:
    """Widths (cm, across the table edge) of the held strip and of the draping strips behind it, from the
    overhanging edge inwards. The held strip reaches twice the overhang in (its centre of mass over the
    table edge), or the whole sheet when that is shallower."""
    held = sheet_held_cm(depth_cm, overhang_cm)
    rest = depth_cm - held
    n = int(np.ceil(rest / SEGMENT_CM - 1e-9)) if rest > 1e-6 else 0
    return held, [rest / n] * n if n else []


def add_sheet(spec: mujoco.MjSpec, model: ObjectModel, ext_cm: np.ndarray, pos_m, overhang_cm: float) -> None:
    """Add ``model`` as a draping sheet: ``ext_cm`` its world extents (x across the table edge, y along it,
    z its thickness), ``pos_m`` the centre of its flat box, its +x edge overhanging by ``overhang_cm``.
    The held strip is the free body "object" (geom "object_geom"); the others are "sheet_<k>"."""
    depth, width, thick = (float(v) for v in ext_cm)
    held, strips = sheet_strips(depth, overhang_cm)
    density = model.mass_kg / (depth * width * thick)  # per cm^3: the catalog mass spread by area
    per_width = (
        STUFFED_BENDING_STIFFNESS_NM
        if model.rigidity == "squeezable"
        else BENDING_STIFFNESS_NM.get(model.material, BENDING_STIFFNESS_NM[None])
    )
    stiffness = per_width * width * CM
    solref, solimp = CONTACT_SOFTNESS[model.rigidity]
    # A finger cannot sink into a sheet deeper than the sheet is thick: the soft ramp ends within it.
    solimp = (*solimp[:2], min(solimp[2], thick * CM), *solimp[3:])
    colour = list(MATERIAL_RGBA.get(model.material, MATERIAL_RGBA[None]))
    geom = dict(
        type=mujoco.mjtGeom.mjGEOM_BOX,
        friction=[model.friction, model.friction * TORSIONAL_PATCH_M, 0.0001],
        condim=4,
        priority=1,
        solref=list(solref),
        solimp=list(solimp),
        contype=OBJECT_BIT,
        conaffinity=HAND_BIT | TABLE_BIT,
        rgba=colour,
    )
    centre_x = pos_m[0] + (depth / 2.0 - held / 2.0) * CM
    body = spec.worldbody.add_body(name="object", pos=[centre_x, pos_m[1], pos_m[2]])
    body.add_freejoint(name="object_free")
    body.add_geom(
        name="object_geom",
        size=[held / 2.0 * CM, width / 2.0 * CM, thick / 2.0 * CM],
        mass=density * held * width * thick,
        **geom,
    )
    parent_half = held / 2.0
    for k, w in enumerate(strips):
        # The child's frame at its centre, w / 2 beyond the hinge on the parent's inner (-x) edge.
        child = body.add_body(name=f"sheet_{k}", pos=[-(parent_half + w / 2.0) * CM, 0.0, 0.0])
        child.add_joint(
            name=f"sheet_hinge_{k}",
            type=mujoco.mjtJoint.mjJNT_HINGE,
            axis=[0.0, 1.0, 0.0],
            pos=[w / 2.0 * CM, 0.0, 0.0],
            stiffness=stiffness / (w * CM),
            damping=stiffness / (w * CM) * HINGE_DAMPING_S,
            armature=HINGE_ARMATURE,
        )
        child.add_geom(
            name=f"sheet_{k}_geom",
            size=[w / 2.0 * CM, width / 2.0 * CM, thick / 2.0 * CM],
            mass=density * w * width * thick,
            **geom,
        )
        body, parent_half = child, w / 2.0
