"""Object geometry from features and kind (sim/bodies.py, sim/objects.py): which primitives each class of
object gets, that the parts fill the stated a x b x c box, carry the catalog's mass, and that handles go
only to objects that have one."""

from __future__ import annotations

from collections import Counter

import mujoco
import numpy as np
import pytest

from kb.features import ObjectRecord
from sim import hand as H
from sim.bodies import HANDLE_NOUNS, body_for, handle_style
from sim.grasps import GraspPlan
from sim.objects import add_object, add_table, object_model
from sim.world import build_world


def _rec(name, a, b, c, mass_g, shape=None, material="plastic", aliases=()) -> ObjectRecord:
    return ObjectRecord.create(
        name, a_cm=a, b_cm=b, c_cm=c, mass_g=mass_g, shape=shape, material=material, aliases=aliases
    )


MUG = _rec("coffee mug", 12, 9.5, 8.2, 330, "prism", "other")
TEAPOT = _rec("glazed ceramic teapot 1.2 l", 22, 15, 14, 900, None, "other")
MOKA = _rec("caffettiera moka in alluminio 3 tazze", 20, 13, 9, 450, "prism", "metal")
PAN = _rec("frying pan", 48, 28, 5, 1200, "thin", "metal")
PITCHER = _rec("pitcher", 23.5, 10.8, 10.8, 178, "prism")


def _compiled(obj: ObjectRecord):
    model_obj = object_model(obj)
    spec = mujoco.MjSpec()
    H.configure_options(spec)
    add_table(spec)
    add_object(spec, model_obj, {"a": 0, "b": 1, "c": 2}, [0, 0, 0.3])
    m = spec.compile()
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return model_obj, m, d


def _geoms(m) -> list[int]:
    body = m.body("object").id
    return [g for g in range(m.ngeom) if m.geom_bodyid[g] == body]


def _world_half_extents(m, d, g) -> np.ndarray:
    """Half-extents (m) along world x, y, z of geom ``g`` (exact for MuJoCo's primitives)."""
    rot = d.geom_xmat[g].reshape(3, 3)
    size = m.geom_size[g]
    kind = m.geom_type[g]
    if kind == mujoco.mjtGeom.mjGEOM_BOX:
        return np.abs(rot) @ size
    if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
        return np.full(3, size[0])
    if kind == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
        return np.sqrt((rot * size) ** 2 @ np.ones(3))
    u = rot[:, 2]
    if kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
        return np.abs(u) * size[1] + size[0]
    return np.abs(u) * size[1] + size[0] * np.sqrt(np.clip(1 - u**2, 0, 1))  # cylinder


def _bounds_cm(m, d, collides_only=True) -> np.ndarray:
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for g in _geoms(m):
        if collides_only and m.geom_contype[g] == 0:
            continue
        half = _world_half_extents(m, d, g)
        lo, hi = np.minimum(lo, d.geom_xpos[g] - half), np.maximum(hi, d.geom_xpos[g] + half)
    return (hi - lo) * 100


def _types(m) -> Counter:
    return Counter(mujoco.mjtGeom(int(m.geom_type[g])).name.removeprefix("mjGEOM_").lower() for g in _geoms(m))


@pytest.mark.parametrize(
    ("record", "form", "types"),
    [
        (MUG, "vessel", {"cylinder": 2, "box": 3}),  # body + visual opening; handle: grip bar and two struts
        (TEAPOT, "vessel", {"cylinder": 1, "box": 3, "capsule": 1}),  # a lid (no opening) and a spout
        (MOKA, "vessel", {"cylinder": 1, "box": 3}),  # an Italian store title: caffettiera -> moka pot
        (PAN, "pan", {"cylinder": 1, "box": 17}),  # base disk, 16 wall segments, the handle
        (_rec("water bottle", 21.5, 7.2, 7.2, 660, "prism", "metal"), "cylinder", {"cylinder": 1}),
        (_rec("tuna can", 8.5, 8.5, 3.3, 171, "compact", "metal"), "cylinder", {"cylinder": 1}),
        (_rec("dinner plate", 27, 27, 2.5, 600, "thin", "other"), "cylinder", {"cylinder": 1}),
        (_rec("one euro coin", 2.325, 2.325, 0.233, 7.5, "thin", "metal"), "cylinder", {"cylinder": 1}),
        (_rec("ballpoint pen", 14.9, 1.0, 1.0, 5, "long"), "cylinder", {"cylinder": 1}),
        (_rec("tennis ball", 6.4, 6.4, 6.4, 57, "radial", "rubber"), "sphere", {"sphere": 1}),
        (_rec("egg", 5.7, 4.4, 4.4, 50, "radial", "other"), "ellipsoid", {"ellipsoid": 1}),
        (_rec("milk carton", 23, 7, 7, 1000, "prism", "paper"), "box", {"box": 1}),  # a carton is square
        (_rec("wood block", 20, 8.5, 8.5, 600, "prism", "wood"), "box", {"box": 1}),
        (_rec("gelatin box", 8.5, 7.3, 2.8, 97, "prism", "paper"), "box", {"box": 1}),  # a ~ b, yet a box
        (_rec("potted meat can", 9.7, 8.2, 5, 370, "prism", "metal"), "box", {"box": 1}),  # a square tin
        (_rec("hardcover book", 24, 16, 3, 700, "thin", "paper"), "box", {"box": 1}),
        (_rec("calculator", 15.4, 7.9, 1.5, 116, "thin"), "box", {"box": 1}),
    ],
    ids=lambda v: v.name if isinstance(v, ObjectRecord) else None,
)
def test_each_class_of_object_gets_its_primitives(record, form, types):
    model_obj, m, _ = _compiled(record)
    assert model_obj.kind == form
    assert _types(m) == Counter(types)


@pytest.mark.parametrize("record", [MUG, TEAPOT, MOKA, PAN, _rec("tuna can", 8.5, 8.5, 3.3, 171, "compact")])
def test_the_bodys_extents_are_the_stated_sizes_and_its_mass_the_catalogs(record):
    model_obj, m, d = _compiled(record)
    np.testing.assert_allclose(_bounds_cm(m, d), [record.a_cm, record.b_cm, record.c_cm], atol=0.02)
    assert m.body("object").mass[0] == pytest.approx(record.mass_g / 1000.0, rel=1e-9)
    assert all(m.body("object").inertia > 0)  # MuJoCo's, from the parts and their shares


def test_visual_parts_have_no_mass_and_no_contacts():
    _, m, _ = _compiled(MUG)
    g = m.geom("object_opening").id
    assert m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0
    others = [k for k in _geoms(m) if k != g]
    assert sum(float(m.geom_size[k][0]) > 0 for k in others) == len(others)
    assert m.body("object").mass[0] == pytest.approx(0.33)


def test_the_pans_mass_is_spread_towards_its_handle():
    _, m, d = _compiled(PAN)
    disk_x = d.geom_xpos[m.geom("object_geom").id][0]
    handle_x = d.geom_xpos[m.geom("object_handle_grip").id][0]
    com_x = d.xipos[m.body("object").id][0]
    assert disk_x < com_x < handle_x


def test_a_handle_without_room_in_the_stated_sizes_goes_outside_them_and_says_so():
    model_obj, m, d = _compiled(PITCHER)
    bounds = _bounds_cm(m, d)
    assert bounds[0] == pytest.approx(23.5, abs=0.02) and bounds[2] == pytest.approx(10.8, abs=0.02)
    assert bounds[1] > 10.8 + 3.0  # the loop reaches out beyond the stated 10.8 cm
    assert any("outside the stated sizes" in note for note in model_obj.assumptions)
    assert m.body("object").mass[0] == pytest.approx(0.178)


@pytest.mark.parametrize(
    ("name", "aliases", "style"),
    [
        ("coffee mug", (), "loop"),
        ("plastic mug", ("plastic cup with handle",), "loop"),
        ("teacup", (), "loop"),
        ("pitcher", (), "loop"),
        ("glazed ceramic teapot", (), "spout"),
        ("electric kettle", (), "spout"),
        ("caffettiera moka in alluminio", (), "loop"),
        ("frying pan", (), "long"),
        ("cast iron skillet 26 cm", (), "long"),
        ("paper cup", ("paper coffee cup",), None),
        ("plastic cup", ("solo cup",), None),
        ("drinking glass", (), None),
        ("wine glass", (), None),
        ("water bottle", (), None),
        ("tomato soup can", (), None),
        ("glass jar", (), None),
        ("ceramic bowl", (), None),
        ("dinner plate", (), None),
        ("hammer", (), None),
    ],
)
def test_handles_only_for_kinds_that_have_one(name, aliases, style):
    found = handle_style(name, aliases)
    assert (found[0] if found else None) == style
    body = body_for((12.0, 9.5, 8.2), "prism", 0.3, name=name, aliases=aliases)
    assert (body.handle is not None) == (style is not None)
    assert any("handle" in p.name for p in body.parts) == (style is not None)


def test_every_handle_noun_is_a_lexicon_noun():
    from kb.kinds import nouns

    english = {n.english for n in nouns().values()} | {n.text for n in nouns().values()}
    assert set(HANDLE_NOUNS) <= english


def test_partial_sizes_use_the_planners_defaults_and_say_so():
    mug = object_model(ObjectRecord.create("coffee mug", a_cm=12, mass_g=330, shape="prism"))
    assert mug.kind == "vessel" and mug.body.handle is not None
    assert any("only one size known" in note for note in mug.assumptions)
    total = sum(p.mass_kg for p in mug.body.parts)
    assert total == pytest.approx(0.33)


def _side_wrap(dim="c", width=8.2) -> GraspPlan:
    return GraspPlan("heavy_wrap_large_diameter", "power", dim, width + 2, "side", 10.0, 1.0)


def test_a_vessel_stands_upright_with_its_handle_away_from_the_palm():
    world = build_world(MUG, _side_wrap())
    m, d = world.model, world.data
    mujoco.mj_forward(m, d)
    body = d.geom_xpos[m.geom("object_geom").id]
    handle = d.geom_xpos[m.geom("object_handle_grip").id]
    palm = d.xpos[world.palm_body]
    axis = d.geom_xmat[m.geom("object_geom").id].reshape(3, 3)[:, 2]
    assert abs(axis[2]) == pytest.approx(1.0)  # the cylinder's axis is vertical
    assert handle[0] < body[0] < palm[0]  # palm at +x, handle at -x
    assert world.is_object.sum() == len(_geoms(m))
    # The hand meets the cylinder as it meets a plain cup of the same size: the handle's box is not grasped.
    cup = build_world(_rec("plastic cup", 9.5, 8.2, 8.2, 330, "prism", "other"), _side_wrap())
    mujoco.mj_forward(cup.model, cup.data)
    cup_body = cup.data.geom_xpos[cup.model.geom("object_geom").id]
    np.testing.assert_allclose(palm - body, cup.data.xpos[cup.palm_body] - cup_body, atol=1e-3)


def test_the_hand_feels_every_part_of_a_composite_object():
    """An edge pinch of the pan touches its wall or base, not its first geom only: the grip force loop and
    the contact count see those contacts."""
    from sim.trial import run_trial

    plan = GraspPlan("thumb_4_finger", "precision", "c", 7.0, "top", 20.0, 1.0)
    world = build_world(PAN, plan)
    run_trial(PAN, plan, stop_after="hold", world=world)
    idx, hand_geoms = world.object_contacts()
    assert idx.size > 0
    parts = {int(world.data.contact.geom1[k]) for k in idx} | {int(world.data.contact.geom2[k]) for k in idx}
    assert parts - {world.object_geom} - set(hand_geoms.tolist())  # parts other than the base disk
    assert sum(world.digit_forces().values()) > 0


def _by_handle(grasp_type="heavy_wrap_small_diameter", approach="top") -> GraspPlan:
    from sim.world import HOLD_HANDLE

    return GraspPlan(grasp_type, "power", "b", 4.0, approach, 60.0, 1.0, params={"hold": HOLD_HANDLE})


def test_a_pan_held_by_its_handle_is_lifted_by_the_handle_alone():
    from sim.trial import run_trial

    world = build_world(PAN, _by_handle())
    result = run_trial(PAN, _by_handle(), world=world, stop_after="hold")
    assert result.lifted, result.reason
    idx, hand_geoms = world.object_contacts()
    touched = {int(world.data.contact.geom1[k]) for k in idx} | {int(world.data.contact.geom2[k]) for k in idx}
    assert touched - set(hand_geoms.tolist()) == {world.model.geom("object_handle_grip").id}
    handle_x = world.data.geom_xpos[world.model.geom("object_handle_grip").id][0]
    disk_x = world.data.geom_xpos[world.object_geom][0]
    assert handle_x > disk_x  # the handle points at the hand (+x), the pan hangs beyond it


def test_holding_a_handle_needs_one_and_its_approach():
    from kb.errors import SimulationError

    bottle = _rec("water bottle", 21.5, 7.2, 7.2, 660, "prism", "metal")
    with pytest.raises(SimulationError, match="has no handle"):
        build_world(bottle, _by_handle())
    with pytest.raises(SimulationError, match="held from the top, not the side"):
        build_world(PAN, _by_handle(approach="side"))
    with pytest.raises(SimulationError, match="held from the side, not the top"):
        build_world(MUG, _by_handle(approach="top"))
