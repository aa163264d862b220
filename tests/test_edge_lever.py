"""The edge lever hold of a heavy flat object (sim/PLANNER.md rule 3, sim/PHYSICS.md): the finger pads
under it lead the thumb on top by the lead whose couple carries the moment of its weight."""

from __future__ import annotations

from dataclasses import replace

import pytest

from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import (
    EDGE_LEVER_MAX_LEAD_CM,
    EDGE_LEVER_MIN_LEAD_CM,
    FINGER_LEAD_PARAM,
    edge_grip_in_cm,
    edge_lever_lead_cm,
)
from sim.planner import plan_grasps
from sim.trial import run_trial


def _plate(mass_g: float = 550, **features) -> ObjectRecord:
    """The seed catalog's dinner plate (features written here): 27 cm, 2.5 cm thick, ceramic."""
    base = dict(a_cm=27, b_cm=27, c_cm=2.5, shape="thin", texture="smooth", material="other")
    base.update(features)
    return ObjectRecord.create("dinner plate", mass_g=mass_g, fragility="fragile", rigidity="rigid", **base)


def _pinch(obj: ObjectRecord):
    return next(p for p in plan_grasps(obj) if p.grasp_type == "thumb_4_finger")


def _level(plan):
    """The same plan with the pads at one depth (no lead)."""
    return replace(plan, params={k: v for k, v in plan.params.items() if k != FINGER_LEAD_PARAM})


def test_the_lead_carries_the_weights_moment_about_the_pads_within_its_bounds():
    lever_cm = 27 / 2 - edge_grip_in_cm(27)  # 7.5 cm beyond the pads
    assert edge_lever_lead_cm(550, 27, 60) == pytest.approx(0.55 * 9.81 * lever_cm / 60, abs=1e-3)
    assert edge_lever_lead_cm(50, 27, 60) == EDGE_LEVER_MIN_LEAD_CM == 0.5
    assert edge_lever_lead_cm(5000, 27, 60) == EDGE_LEVER_MAX_LEAD_CM == 2.4


def test_only_a_rigid_flat_pinch_over_its_capacity_gets_a_lead():
    heavy = _pinch(_plate())
    assert heavy.params["force_within_capacity"] is False
    assert heavy.params[FINGER_LEAD_PARAM] == pytest.approx(0.674, abs=1e-3)
    assert any(line.startswith("lever: the finger pads 0.674 cm deeper") for line in heavy.rationale)
    light = _pinch(_plate(mass_g=150))  # a plastic plate's weight: the pads at one depth carry it
    assert light.params["force_within_capacity"] is True and FINGER_LEAD_PARAM not in light.params
    assert not any(line.startswith("lever:") for line in light.rationale)
    wraps = [p for p in plan_grasps(_plate()) if p.grasp_type in ("medium_wrap", "power_disk")]
    assert wraps and all(FINGER_LEAD_PARAM not in p.params for p in wraps)
    towel = ObjectRecord.create(
        "towel",
        a_cm=75,
        b_cm=40,
        c_cm=0.5,
        mass_g=2000,
        shape="thin",
        texture="rough",
        fragility="sturdy",
        material="fabric",
        rigidity="floppy",
    )
    assert all(FINGER_LEAD_PARAM not in p.params for p in plan_grasps(towel))  # a sheet drapes instead


def test_the_lead_puts_the_finger_pads_deeper_than_the_thumb_with_the_fingers_extended():
    plan = _pinch(_plate())
    level = _level(plan)
    lever, flat = H.grasp_targets(plan, 2.5), H.grasp_targets(level, 2.5)
    k = H.ACTUATOR_NAMES.index("middle_mcp")

    def thumb_z(t):
        return H.thumb_tip(t.touch[H.ACTUATOR_NAMES.index("thumb_flex")])[1]

    def middle_z(t):
        return H.finger_tip("middle", t.touch[k], t.touch[k + 1])[1]

    assert thumb_z(lever) - middle_z(lever) > thumb_z(flat) - middle_z(flat) + 0.4
    assert lever.touch[k + 1] / lever.touch[k] == pytest.approx(H.EDGE_LEVER_PIP_PER_MCP, abs=0.02)


def test_the_dinner_plate_holds_with_the_lever_and_turns_out_of_the_level_pinch():
    """Seed 0: with its 0.67 cm lead the thumb-4 finger pinch holds the 550 g plate (turned 9 deg); the
    same pinch with the pads at one depth turns past 15 deg (the failure before planner version 11)."""
    obj = _plate()
    plan = _pinch(obj)
    level = _level(plan)
    held, turned = run_trial(obj, plan), run_trial(obj, level)
    assert held.success, held.reason
    assert not turned.success and "turned" in turned.reason
