"""Thin rods lying on the table, pinched from above (issue 14, grasp-odd): the fingers' pads aligned at the
thumb's height (sim/hand.py) and a quarter radius below the rod's centre line (sim/world.py). Objects written
here, after the seed catalog's batteries."""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import GRASP_TYPES, GraspPlan
from sim.planner import plan_grasps
from sim.programs import program_for
from sim.trial import run_trial
from sim.world import ROD_BELOW_FRACTION, ROD_PAD_CLEAR_CM, _object_in_hand_cm, build_world


def _battery(name: str, length: float, diameter: float, mass: float) -> ObjectRecord:
    return ObjectRecord.create(name, a_cm=length, b_cm=diameter, c_cm=diameter, mass_g=mass, shape="long",
                               material="metal", texture="smooth", rigidity="rigid")  # fmt: skip


C_BATTERY = _battery("c battery", 5.0, 2.62, 66)
AA_BATTERY = _battery("aa battery", 5.05, 1.45, 23)


@pytest.mark.parametrize(
    ("diameter", "shift"),
    [(2.62, ROD_BELOW_FRACTION * 1.31), (2.0, 1.0 - ROD_PAD_CLEAR_CM), (1.8, 0.0), (1.45, 0.0), (6.0, 0.75),
     (6.2, 0.0)],
)  # fmt: skip
def test_a_lying_rod_is_pinched_below_its_centre_line_as_far_as_the_pads_clear_the_table(diameter, shift):
    """A quarter radius below (the C battery: 0.33 cm), the contact never under 0.9 cm above the table (a
    2 cm rod: 0.1 cm; 1.8 cm and the AA's 1.45 cm: at the centre line); over 6 cm the pads are 3 cm down."""
    program = program_for("thumb_2_finger")
    plan = GraspPlan("thumb_2_finger", "precision", "c", diameter + 2, "top", 2.0, 1.0)
    targets = H.grasp_targets(plan, diameter)
    _, plain = _object_in_hand_cm(program, targets, diameter, False)
    _, rod = _object_in_hand_cm(program, targets, diameter, False, rod=True)
    assert plain == pytest.approx(min(diameter / 2.0, 3.0))
    assert rod - plain == pytest.approx(shift, abs=1e-9)


def test_only_a_rod_lying_under_a_pinch_from_above_is_pinched_low():
    """The C battery's hand is mounted 0.33 cm lower than for a box of its sizes (a block: flat faces)."""
    plan = plan_grasps(C_BATTERY)[0]
    assert plan.grasp_type == "thumb_2_finger" and plan.approach == "top"
    box = ObjectRecord.create("wood block", a_cm=5.0, b_cm=2.62, c_cm=2.62, mass_g=66, shape="long",
                              material="metal", texture="smooth", rigidity="rigid")  # fmt: skip
    rod_world, box_world = build_world(C_BATTERY, plan, seed=0), build_world(box, plan, seed=0)
    assert (rod_world.obj.kind, box_world.obj.kind) == ("cylinder", "box")
    drop = (box_world.model.body("wrist").pos[2] - rod_world.model.body("wrist").pos[2]) / H.CM
    assert drop == pytest.approx(ROD_BELOW_FRACTION * 1.31, abs=1e-6)


@pytest.mark.parametrize("grasp_type", ["thumb_2_finger", "thumb_3_finger"])
def test_the_c_battery_is_lifted_and_held_by_a_pinch(grasp_type):
    """Measured (seed 0): pinched at its centre line both pinches lifted it 3 cm, then it slid down out of
    the pads (a rod slipping down between round pads moves the contacts above its centre line, where the
    squeeze pushes it further down); a quarter radius below, both hold."""
    plan = next(p for p in plan_grasps(C_BATTERY) if p.grasp_type == grasp_type)
    assert GRASP_TYPES[plan.grasp_type] == "precision"
    r = run_trial(C_BATTERY, plan, seed=0)
    assert r.success, r.reason


def test_the_aa_batterys_two_finger_pinch_holds_with_the_pads_aligned():
    plan = next(p for p in plan_grasps(AA_BATTERY) if p.grasp_type == "thumb_2_finger")
    assert run_trial(AA_BATTERY, plan, seed=0).success
