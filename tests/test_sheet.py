"""Floppy sheets as hinged strips that droop (sim/sheet.py), built by the trial's world (sim/world.py)."""

from __future__ import annotations

import numpy as np
import pytest

from kb.features import ObjectRecord
from sim.objects import object_model
from sim.planner import plan_grasps
from sim.sheet import SEGMENT_CM, is_sheet, sheet_strips
from sim.trial import build_world, run_trial


def _sheet(rigidity: str = "floppy", **features) -> ObjectRecord:
    base = dict(a_cm=29.7, b_cm=21, c_cm=0.01, mass_g=5, shape="thin", texture="smooth", material="paper")
    base.update(features)
    return ObjectRecord.create("sheet", rigidity=rigidity, fragility="medium", **base)


def _plan(obj: ObjectRecord, grasp_type: str):
    return next(p for p in plan_grasps(obj) if p.grasp_type == grasp_type)


def test_held_strip_reaches_twice_the_overhang_and_the_rest_drapes_in_strips():
    held, strips = sheet_strips(21.0, 7.0)
    assert held == 14.0
    assert len(strips) == 2 and sum(strips) == pytest.approx(7.0)
    # At the boundary: exactly twice the overhang deep is one rigid strip; a little deeper adds one.
    assert sheet_strips(14.0, 7.0) == (14.0, [])
    held, strips = sheet_strips(14.5, 7.0)
    assert held == 14.0 and strips == [pytest.approx(0.5)]
    # No strip wider than SEGMENT_CM; a shallow sheet is all held.
    held, strips = sheet_strips(69.0, 7.0)
    assert max(strips) <= SEGMENT_CM and sum(strips) == pytest.approx(55.0)
    assert sheet_strips(8.0, 3.6) == (7.2, [pytest.approx(0.8)])
    assert sheet_strips(6.0, 3.6) == (6.0, [])


def test_only_floppy_objects_laid_flat_are_sheets():
    assert is_sheet(object_model(_sheet()), flat=True)
    assert not is_sheet(object_model(_sheet()), flat=False)
    assert not is_sheet(object_model(_sheet("rigid")), flat=True)


def test_sheet_world_has_hinged_strips_of_the_catalog_mass_that_are_not_hand():
    obj = _sheet()
    world = build_world(obj, _plan(obj, "thumb_2_finger"))
    m = world.model
    strips = [b for b in range(m.nbody) if m.body(b).name.startswith("sheet_")]
    assert len(strips) == 2
    assert all(m.jnt_type[m.body_jntadr[b]] == 3 for b in strips)  # mjJNT_HINGE
    assert all(m.jnt_stiffness[m.body_jntadr[b]] > 0 for b in strips)
    total = m.body_mass[world.object_body] + sum(m.body_mass[b] for b in strips)
    assert total == pytest.approx(0.005)
    strip_geoms = np.isin(m.geom_bodyid, strips)
    assert not world.is_hand[strip_geoms].any() and not world.is_object[strip_geoms].any()
    rigid = _sheet("rigid")
    plain = build_world(rigid, _plan(rigid, "thumb_2_finger")).model
    assert not [b for b in range(plain.nbody) if plain.body(b).name.startswith("sheet_")]


def _droop_after_hold(obj: ObjectRecord) -> float:
    """The sheet's bend (rad, summed over its hinges; negative: the far part hangs down) after the hold."""
    world = build_world(obj, _plan(obj, "thumb_2_finger"))
    flat_z = world.data.xpos[world.object_body][2]
    result = run_trial(obj, world.plan, world=world, stop_after="hold")
    assert result.lifted
    assert world.data.xpos[world.object_body][2] - flat_z > 0.05  # the held strip rose with the hand
    m = world.model
    hinges = [m.jnt_qposadr[m.joint(f"sheet_hinge_{k}").id] for k in range(2)]
    return float(sum(world.data.qpos[hinges]))


def test_lifted_sheet_droops_behind_the_held_strip_and_cloth_more_than_paper():
    paper = _droop_after_hold(_sheet())
    cloth = _droop_after_hold(_sheet(material="fabric", texture="medium"))
    assert paper < -0.1  # held by one strip, the rest bends down under its weight
    assert cloth < paper - 0.2  # six times less stiff: it hangs further


def test_a4_sheet_held_as_a_sheet_turns_out_as_one_floppy_plate(monkeypatch):
    """The same pinch on the same features: the draping sheet holds; built as one soft plate (the model
    before sim/sheet.py) it turns out of the pads during the lift, the class of failure the sheet removes."""
    import sim.world

    obj = _sheet()
    plan = _plan(obj, "thumb_2_finger")
    as_sheet = run_trial(obj, plan)
    monkeypatch.setattr(sim.world, "is_sheet", lambda model, flat: False)
    as_plate = run_trial(obj, plan)
    assert as_sheet.success, as_sheet.reason
    assert not as_plate.success and "turned" in as_plate.reason


def _towel() -> ObjectRecord:
    """The seed catalog's hand towel (features written here): 75 x 40 x 0.5 cm, 200 g, cotton."""
    return ObjectRecord.create(
        "towel",
        a_cm=75,
        b_cm=40,
        c_cm=0.5,
        mass_g=200,
        shape="thin",
        texture="rough",
        fragility="sturdy",
        material="fabric",
        rigidity="floppy",
    )


def test_a_lateral_pinch_closes_further_past_a_floppy_surface_only():
    """The gather overshoot applies to the lateral pinch on a floppy object, nowhere else (its boundaries:
    another pinch on the same cloth, the same pinch on a rigid plate)."""
    import sim.world
    from sim import hand as H
    from sim.programs import program_for

    cloth, board = object_model(_towel()), object_model(_sheet("rigid"))
    lateral, pads = program_for("lateral_pinch"), program_for("thumb_2_finger")
    assert sim.world._overshoot_cm(lateral, cloth) == sim.world.LATERAL_GATHER_OVERSHOOT_CM == 2.0
    assert sim.world._overshoot_cm(lateral, board) == H.PRECISION_OVERSHOOT_CM == 1.0
    assert sim.world._overshoot_cm(pads, cloth) == H.PRECISION_OVERSHOOT_CM
    plan = _plan(_towel(), "lateral_pinch")
    near, far = H.grasp_targets(plan, 0.5), H.grasp_targets(plan, 0.5, overshoot_cm=2.0)
    assert (far.open == near.open).all() and (far.touch == near.touch).all()
    thumb, index = H.ACTUATOR_NAMES.index("thumb_flex"), H.ACTUATOR_NAMES.index("index_mcp")
    assert far.close[thumb] > near.close[thumb] and far.close[index] > near.close[index]


def test_a_towel_pinched_laterally_holds_when_the_pinch_gathers_its_edge(monkeypatch):
    """The hand towel's lateral pinch: closing 1 cm past the cloth, the held strip turns out under the
    hanging cloth (21.9 deg, seed 0); closing 2 cm past (the gather), it holds (sim/PHYSICS.md)."""
    import sim.world

    obj = _towel()
    plan = _plan(obj, "lateral_pinch")
    gathered = run_trial(obj, plan)
    monkeypatch.setattr(sim.world, "LATERAL_GATHER_OVERSHOOT_CM", 1.0)
    pressed = run_trial(obj, plan)
    assert gathered.success, gathered.reason
    assert not pressed.success and "turned" in pressed.reason


def _pillow(material: str = "fabric") -> ObjectRecord:
    """The seed catalog's pillow (features written here): 65 x 45 x 12 cm, 600 g, a stuffed fabric bag."""
    return ObjectRecord.create(
        "pillow",
        a_cm=65,
        b_cm=45,
        c_cm=12,
        mass_g=600,
        shape="thin",
        texture="smooth",
        fragility="sturdy",
        material=material,
        rigidity="squeezable",
    )


def test_floppy_things_and_stuffed_fabric_drape_other_squeezables_do_not():
    from sim.grasps import drapes

    assert drapes("floppy", None) and drapes("floppy", "paper") and drapes("squeezable", "fabric")
    assert not drapes("squeezable", "other") and not drapes("squeezable", None)
    assert not drapes("rigid", "fabric")
    assert is_sheet(object_model(_pillow()), flat=True)
    assert not is_sheet(object_model(_pillow("other")), flat=True)  # a foam block keeps its shape


def test_a_pillow_wrapped_at_its_edge_holds_as_a_draping_bag_and_slips_as_a_rigid_slab(monkeypatch):
    """Seed 0: the pillow's medium wrap (its first choice) holds once the rest of it bends down behind the
    held strip; as one rigid 65 x 45 x 12 cm box it slips past 5 cm in the sideways push (the failure
    before programs version 7). Its hinges are the stuffed bag's stiffness, not a cloth's."""
    import sim.world
    from sim.sheet import STUFFED_BENDING_STIFFNESS_NM

    obj = _pillow()
    plan = _plan(obj, "medium_wrap")
    world = build_world(obj, plan)
    m = world.model
    hinge = m.joint("sheet_hinge_0").id
    strip_cm = 2 * (m.geom_size[m.geom("sheet_0_geom").id][0] * 100)
    assert m.jnt_stiffness[hinge] == pytest.approx(STUFFED_BENDING_STIFFNESS_NM * 0.65 / (strip_cm / 100))
    draped = run_trial(obj, plan)
    monkeypatch.setattr(sim.world, "is_sheet", lambda model, flat: False)
    rigid = run_trial(obj, plan)
    assert draped.success, draped.reason
    assert not rigid.success and "slipped" in rigid.reason
