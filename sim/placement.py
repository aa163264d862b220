"""Where the object lies in the trial's world and where the hand grasps it (sim/PHYSICS.md, "Placement").

:func:`layout` gives a plan's :class:`Layout`: each catalog dimension's world axis and sign (the grasped one
along y, the hand's opposition axis), whether a flat object lies overhanging a table edge, a vessel or pan
standing as it is used, a handle or a named part (a cap's brim) held instead of the body, and the grasped
part's centre, extents and width. :mod:`sim.world` builds the model from it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kb.errors import SimulationError
from sim import hand as H
from sim.bodies import HOLD_HANDLE, HOLD_PART
from sim.grasps import GraspPlan, edge_depth_cm, is_flat_grasp
from sim.objects import ObjectModel, free_dim, pose_rotation

__all__ = ["HANDLE_END_MARGIN_CM", "HOLD_HANDLE", "Layout", "layout"]


def _placement(obj: ObjectModel, plan: GraspPlan) -> dict[str, int]:
    """World axis of each catalog dimension: the grasped one along y (the opposition axis); of the other
    two, for a top approach the larger along x and the smaller up (lying on its broad side); for a side
    approach the larger up (standing, like a bottle) and the smaller along x, towards the palm."""
    rest = sorted((d for d in "abc" if d != plan.grasped_dim), key=obj.extent_cm, reverse=True)
    if plan.approach == "top":
        return {plan.grasped_dim: 1, rest[0]: 0, rest[1]: 2}
    return {plan.grasped_dim: 1, rest[0]: 2, rest[1]: 0}


def _upright_placement(obj: ObjectModel, plan: GraspPlan) -> tuple[dict[str, int], dict[str, int]] | None:
    """A vessel or a pan stands as it is used (its ``up`` dimension up) unless the plan grasps across that
    dimension; the grasped one lies along y, the third along x with the handle pointing to -x, away from
    a side approach's palm. None for other bodies. Returns (axes, signs)."""
    body = obj.body
    if body is None or body.up is None or plan.grasped_dim == body.up:
        return None
    other = next(d for d in "abc" if d not in (plan.grasped_dim, body.up))
    signs = {body.handle.dim: -1} if body.handle is not None and body.handle.dim == other else {}
    return {plan.grasped_dim: 1, body.up: 2, other: 0}, signs


def _grasped_body(obj: ObjectModel, axes: dict[str, int], pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where the hand grasps: the centre (cm, world, relative to the stated box's centre; never up or
    down) and the world extents (cm) of the object's main part (a vessel's cylinder, a pan's disk, or the
    whole object), so that a handle or a spout beside it is not taken for the grasped surface."""
    ext = np.zeros(3)
    if obj.body is None or obj.body.form not in ("vessel", "pan"):
        for dim, ax in axes.items():
            ext[ax] = obj.extent_cm(dim)
        return np.zeros(3), ext
    main = obj.body.main
    for dim, ax in axes.items():  # a pan's base disk stands for its body, as deep as its wall
        ext[ax] = obj.extent_cm(dim) if dim == obj.body.up else main.extent_cm(dim)
    centre = pose @ np.asarray(main.pos_cm)
    centre[2] = 0.0
    return centre, ext


def _is_flat(obj: ObjectModel, plan: GraspPlan) -> bool:
    """Does ``plan`` grasp a flat object across its thickness? Such objects lie flat, overhanging a table
    edge, and are grasped from the edge (thumb on top, fingers underneath), as people pick up a plate or
    a book; standing them on edge for a top or side grasp would be neither stable nor realistic."""
    dims = sorted("abc", key=obj.extent_cm)
    thin, middle = dims[0], dims[1]
    return plan.grasped_dim == thin and is_flat_grasp(obj.extent_cm(thin), obj.extent_cm(middle))


def _edge_placement(obj: ObjectModel, plan: GraspPlan) -> dict[str, int]:
    """Flat on the table (grasped thickness up), its longest side along the table edge (world y, where the
    fingers spread) and the other across it (world x, overhanging); the other way round when that side is
    too short to overhang under the pads (sim/grasps.py ``edge_depth_cm``: a key, a ruler)."""
    rest = sorted((d for d in "abc" if d != plan.grasped_dim), key=obj.extent_cm, reverse=True)
    long_cm, middle_cm = obj.extent_cm(rest[0]), obj.extent_cm(rest[1])
    if edge_depth_cm(long_cm, middle_cm) == long_cm and long_cm != middle_cm:
        return {plan.grasped_dim: 2, rest[0]: 0, rest[1]: 1}
    return {plan.grasped_dim: 2, rest[0]: 1, rest[1]: 0}


#: A pan's handle is held this far (cm) from its end to the middle of the palm (half the palm and a margin),
#: unless the plan asks for its middle (``params["handle_grip"] = "middle"``: a heavy pan, held nearer it).
HANDLE_END_MARGIN_CM = H.PALM_HALF_CM[0] + 0.5


@dataclass(frozen=True)
class Layout:
    """Where the object lies and where the hand grasps it (cm, world axes; relative to the stated box's
    centre): the approach as built, the dims' world axes and signs, whether it is a flat object at a table
    edge, the box's extents, the grasped part's centre and extents, and the grasped width."""

    approach: str
    axes: dict[str, int]
    signs: dict[str, int]
    flat: bool
    ext: np.ndarray
    grip_centre: np.ndarray
    grip_ext: np.ndarray
    width: float


def _extents(obj: ObjectModel, axes: dict[str, int]) -> np.ndarray:
    ext = np.zeros(3)
    for dim, ax in axes.items():
        ext[ax] = obj.extent_cm(dim)
    return ext


def layout(obj: ObjectModel, plan: GraspPlan) -> Layout:
    """Where ``obj`` lies on the table for ``plan`` and where the hand grasps it (sim/PHYSICS.md, placement)."""
    if plan.params.get("hold") == HOLD_HANDLE:
        return _handle_layout(obj, plan)
    if plan.params.get("hold") == HOLD_PART:
        return _part_layout(obj, plan)
    flat = _is_flat(obj, plan)
    approach = "edge" if flat else plan.approach
    upright = None if flat else _upright_placement(obj, plan)
    signs: dict[str, int] = {}
    if upright is not None:
        axes, signs = upright
    else:
        axes = _edge_placement(obj, plan) if flat else _placement(obj, plan)
    ext = _extents(obj, axes)
    grip_centre, grip_ext = _grasped_body(obj, axes, pose_rotation(axes, signs, free_dim(obj)))
    return Layout(approach, axes, signs, flat, ext, grip_centre, grip_ext, ext[2] if flat else ext[1])


def _handle_layout(obj: ObjectModel, plan: GraspPlan) -> Layout:
    """The object standing as it is used, its handle pointing to +x, towards the hand: a loop handle's grip
    bar (vertical) wrapped from the side, a pan's handle (along x) wrapped from above near its end. The
    grasped width is the handle's, across world y."""
    body = obj.body
    handle = body.handle if body is not None else None
    if handle is None:
        raise SimulationError(f"{obj.name!r} has no handle to hold (sim/bodies.py builds none for it)")
    wanted = "side" if handle.style == "loop" else "top"
    if plan.approach != wanted:
        raise SimulationError(f"a {handle.style} handle is held from the {wanted}, not the {plan.approach}")
    across = next(d for d in "abc" if d not in (body.up, handle.dim))
    axes, signs = {handle.dim: 0, across: 1, body.up: 2}, {handle.dim: 1}
    pose = pose_rotation(axes, signs, free_dim(obj))
    grip = next(p for p in body.parts if p.name == "handle_grip")
    centre = pose @ np.asarray(grip.pos_cm)
    grip_ext = np.zeros(3)
    for dim, ax in axes.items():
        grip_ext[ax] = grip.extent_cm(dim)
    at_end = plan.params.get("handle_grip", "end") == "end"
    if handle.style == "long" and at_end:  # near the end: the part from the rim out is longer than the palm
        end = centre[0] + grip_ext[0] / 2.0
        centre[0] = max(centre[0], end - HANDLE_END_MARGIN_CM)
    ext = _extents(obj, axes)
    return Layout(plan.approach, axes, signs, False, ext, centre, grip_ext, float(grip_ext[1]))


def _part_layout(obj: ObjectModel, plan: GraspPlan) -> Layout:
    """The object standing as it is used (``c`` up, ``a`` along +x, towards the hand), pinched across the
    thickness of one flat named part (``params["part"]``, sim/bodies.py ``HOLD_PART``: a cap's brim) that
    reaches out over a table edge, like any flat object (thumb on top, fingers under the overhang)."""
    body = obj.body
    name = plan.params.get("part")
    part = next((p for p in body.parts if p.name == name), None) if body is not None else None
    if part is None or body.up != "c":
        raise SimulationError(f"{obj.name!r} has no part {name!r} to hold (sim/bodies.py builds none for it)")
    axes: dict[str, int] = {"a": 0, "b": 1, "c": 2}
    centre = pose_rotation(axes, {}, free_dim(obj)) @ np.asarray(part.pos_cm)
    grip_ext = np.array([part.extent_cm(d) for d in "abc"])
    plate = part.geom == "box" and is_flat_grasp(grip_ext[2], min(grip_ext[0], grip_ext[1]))
    if plan.grasped_dim != "c" or not plate:
        raise SimulationError(f"the {name} of {obj.name!r} is not a flat part pinched across its thickness")
    return Layout("edge", axes, {}, True, _extents(obj, axes), centre, grip_ext, float(grip_ext[2]))
