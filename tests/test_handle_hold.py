"""The planner's handle hold (planner version 9): a pan, an object whose kind has a long handle, is planned
first as a small-diameter wrap of its handle from above; nothing else is (sim/PLANNER.md, "Handles")."""

from __future__ import annotations

import mujoco
import pytest

from kb.features import ObjectRecord
from sim.bodies import HOLD_HANDLE, body_for
from sim.planner import HANDLE_GRASP, HANDLE_MIDDLE_MIN_MASS_G, plan_grasps
from sim.world import build_world


def _rec(name, a, b, c, mass_g, shape="thin", material="metal", aliases=()) -> ObjectRecord:
    return ObjectRecord.create(
        name,
        a_cm=a,
        b_cm=b,
        c_cm=c,
        mass_g=mass_g,
        shape=shape,
        material=material,
        texture="smooth",
        aliases=aliases,
    )


PAN = _rec("frying pan", 48, 28, 5, 1200)


def test_a_pan_is_planned_by_its_handle_first():
    plans = plan_grasps(PAN)
    first = plans[0]
    assert (first.grasp_type, first.approach, first.grasped_dim) == (HANDLE_GRASP, "top", "b")
    assert first.params["hold"] == HOLD_HANDLE
    handle = body_for((48, 28, 5), "thin", 1.2, name="frying pan").handle
    assert first.params["width_cm"] == pytest.approx(handle.width_cm)  # the simulated handle's width
    assert first.aperture_cm == pytest.approx(handle.width_cm + 1.5)  # a wrap's margin
    # Squeezed at the wrap's full capacity (the pan's moment beyond the grip), said in the rationale.
    assert first.grip_force_n == 60.0 and first.params["force_within_capacity"]
    assert any(line.startswith("handle:") for line in first.rationale)
    # The body's candidates follow, each hand program once, none of them a handle hold.
    programs = [p.params["program"] for p in plans]
    assert len(programs) == len(set(programs))
    assert all("hold" not in p.params for p in plans[1:])
    assert plans[1].grasp_type == "medium_wrap"  # the flat rule's first choice, as before version 9


def test_a_pan_named_in_another_language_or_by_alias_is_held_by_its_handle():
    alias = _rec("cast iron 26 cm", 45, 26, 5, 2450, aliases=("skillet",))
    assert plan_grasps(alias)[0].params.get("hold") == HOLD_HANDLE
    assert (
        plan_grasps({**alias.features(), "name": "cast iron 26 cm", "aliases": ["skillet"]})[0].params.get(
            "hold"
        )
        == HOLD_HANDLE
    )


@pytest.mark.parametrize(
    "obj",
    [
        _rec("cutting board", 48, 28, 5, 1200, material="wood"),  # a pan's sizes, no handle kind
        _rec("coffee mug", 12, 9.5, 8.2, 330, "prism", "other"),  # a loop handle: its body is wrapped
        _rec("teapot", 22, 15, 14, 900, "prism", "other"),
    ],
)
def test_objects_without_a_long_handle_get_no_handle_hold(obj):
    assert all("hold" not in p.params for p in plan_grasps(obj))


def test_a_round_pot_with_a_long_handle_lists_the_wrap_program_once():
    """A saucepan is not flat: its body would be wrapped by the heavy wrap, the program the handle hold
    uses; the planner lists that program once, on the handle."""
    plans = plan_grasps(_rec("saucepan", 36, 18, 10, 900, "prism"))
    assert plans[0].params["hold"] == HOLD_HANDLE
    assert [p.params["program"] for p in plans].count("heavy_wrap") == 1


@pytest.mark.parametrize(
    ("mass", "where"), [(HANDLE_MIDDLE_MIN_MASS_G - 1, "end"), (HANDLE_MIDDLE_MIN_MASS_G, "middle")]
)
def test_a_heavy_pan_is_held_at_the_middle_of_its_handle(mass, where):
    plan = plan_grasps(_rec("frying pan", 48, 28, 5, mass))[0]
    assert plan.params["handle_grip"] == where


def _palm_to_handle_end_cm(plan) -> float:
    world = build_world(PAN, plan)
    mujoco.mj_forward(world.model, world.data)
    grip = world.model.geom("object_handle_grip").id
    end = world.data.geom_xpos[grip][0] + world.model.geom_size[grip][0]  # the handle points to +x
    return float(end - world.data.xpos[world.palm_body][0]) * 100.0


def test_the_handle_grip_param_moves_the_palm_along_the_handle():
    import dataclasses

    middle = plan_grasps(PAN)[0]
    end = dataclasses.replace(middle, params={**middle.params, "handle_grip": "end"})
    handle = body_for((48, 28, 5), "thin", 1.2, name="frying pan").handle
    assert _palm_to_handle_end_cm(end) == pytest.approx(4.75, abs=0.3)  # half the palm and a margin
    assert _palm_to_handle_end_cm(middle) == pytest.approx(handle.length_cm / 2.0, abs=0.8)


def test_the_planned_handle_hold_lifts_the_pan_by_its_handle_alone():
    from sim.trial import run_trial

    plan = plan_grasps(PAN)[0]
    world = build_world(PAN, plan)
    result = run_trial(PAN, plan, world=world, stop_after="hold")
    assert result.lifted, result.reason
    idx, hand_geoms = world.object_contacts()
    touched = {int(world.data.contact.geom1[k]) for k in idx} | {
        int(world.data.contact.geom2[k]) for k in idx
    }
    assert touched - set(hand_geoms.tolist()) == {world.model.geom("object_handle_grip").id}
