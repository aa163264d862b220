"""Why a grasp did not hold (sim/diagnosis.py): each cause on its own, their order, and real trials.

Rows are built as the worker stores them (``details.plan`` holds the plan, sim/task.py) from real plans
of objects written here; two causes come from real MuJoCo trials.
"""

from __future__ import annotations

import json

import pytest

from kb.features import ObjectRecord
from sim.diagnosis import CAUSES, diagnose, failure_cause
from sim.grasps import GRASP_TYPES, GraspPlan, side_force_capacity
from sim.planner import best_grasp, plan_grasps
from sim.programs import program_for

BASKETBALL = dict(a_cm=24.3, b_cm=24.3, c_cm=24.3, mass_g=600, shape="radial", material="rubber", rigidity="squeezable")
PLATE = dict(a_cm=27, b_cm=27, c_cm=2.5, mass_g=550, shape="thin", material="other")
REMOTE = dict(a_cm=16, b_cm=3.5, c_cm=2, mass_g=110, shape="long", material="plastic")

TURNED = "turned 26.3 deg (limit 15) relative to the palm during the lift"
SLIPPED = "slipped 9.6 cm (limit 5) relative to the palm during the -z push"
NOT_LIFTED = "not lifted: the object rose 0.1 cm of 10"
INSIDE = "hand starts inside the object (6.6 mm deep at the grasp pose)"
NO_CONTACT = "no contact after closing: the digits missed the object"


def _row(plan: GraspPlan, reason: str, outcome: str = "failure", grip: float = 0.0) -> dict:
    return {
        "grasp_type": plan.grasp_type, "outcome": outcome, "success": outcome == "success", "reason": reason,
        "grip_force_n": grip, "details": json.dumps({"plan": plan.to_dict()}),
    }  # fmt: skip


def test_a_plan_wider_than_the_hand_is_an_aperture_failure_whatever_the_trial_said():
    plan = best_grasp(BASKETBALL)
    assert plan.params["feasible"] is False
    for reason in (TURNED, SLIPPED, NO_CONTACT, INSIDE):
        cause = diagnose(_row(plan, reason))
        assert cause.kind == "aperture", reason
        assert "24.3 cm" in cause.text and "two hands" in cause.text


def test_starting_inside_is_an_aperture_failure_even_for_an_object_that_fits():
    plan = best_grasp(REMOTE)
    assert plan.params["feasible"] and plan.params["force_within_capacity"]
    assert diagnose(_row(plan, INSIDE)).kind == "aperture"
    assert diagnose(_row(plan, TURNED)).kind != "aperture"  # the reason alone made it one


def test_a_squeeze_beyond_the_grasps_strength_is_a_mass_failure_with_its_numbers():
    plan = best_grasp(PLATE)
    assert plan.params["force_within_capacity"] is False and plan.params["feasible"]
    capacity = side_force_capacity(plan.grasp_type)
    needed = plan.params["needed_force_n"]
    assert needed > capacity == plan.grip_force_n  # the plan is clamped; what it needed is kept
    for reason in (TURNED, SLIPPED, NOT_LIFTED, NO_CONTACT):
        cause = diagnose(_row(plan, reason))
        assert cause.kind == "mass", reason
        assert f"{needed:g} N" in cause.text and f"{capacity:g} N" in cause.text and "550 g" in cause.text


def test_within_strength_the_trials_reason_decides_size_friction_or_moment():
    plan = best_grasp(REMOTE)
    assert diagnose(_row(plan, NO_CONTACT)).kind == "size"
    assert diagnose(_row(plan, NOT_LIFTED)).kind == "friction"
    assert diagnose(_row(plan, SLIPPED)).kind == "friction"
    assert diagnose(_row(plan, TURNED)).kind == "moment"


def test_friction_names_the_measured_squeeze_else_the_planned_one():
    plan = best_grasp(REMOTE)
    measured = diagnose(_row(plan, SLIPPED, grip=2.5))
    assert "squeeze of 2.5 N" in measured.text and f"{2 * plan.params['friction'] * 2.5:.3g} N" in measured.text
    assert f"squeeze of {plan.grip_force_n:.3g} N" in diagnose(_row(plan, SLIPPED)).text


def test_held_and_errored_rows():
    plan = best_grasp(REMOTE)
    assert diagnose(_row(plan, "held: moved 0.1 cm", outcome="success")) is None
    assert failure_cause(_row(plan, "held: moved 0.1 cm", outcome="success")) == "held: moved 0.1 cm"
    err = diagnose(_row(plan, "simulation diverged: non-finite qacc", outcome="error"))
    assert err.kind == "error" and "diverged" in err.text
    assert set(CAUSES) == {"aperture", "mass", "size", "pressed", "friction", "moment"}


def test_a_row_without_its_plan_still_gets_a_cause():
    row = {"grasp_type": "medium_wrap", "outcome": "failure", "reason": TURNED, "details": "not json"}
    assert failure_cause(row).startswith("moment: ")


def _plan(grasp_type: str, aperture: float, force: float) -> GraspPlan:
    params = {"feasible": True, "force_within_capacity": True, "width_cm": 6.5, "friction": 0.32, "assumed_mass_g": 600}
    return GraspPlan(grasp_type, GRASP_TYPES[grasp_type], "c", aperture, program_for(grasp_type).approach, force, 1.0,
                     params=params)  # fmt: skip


BOTTLE = ObjectRecord.create(
    "glass bottle", a_cm=20, b_cm=6.5, c_cm=6.5, mass_g=600, shape="prism", material="glass", texture="smooth"
)


def test_real_trials_a_pinch_opened_too_narrow_and_a_light_wrap():
    from sim.trial import run_trial

    narrow = _plan("thumb_2_finger", 3.0, 14.0)
    r = run_trial(BOTTLE, narrow, seed=0)
    assert diagnose({**r.to_dict(), "details": {"plan": narrow.to_dict()}}).kind == "aperture"


@pytest.mark.slow
def test_real_trial_a_wrap_too_light_to_lift_is_a_friction_failure():
    from sim.trial import run_trial

    light = _plan("heavy_wrap_large_diameter", 8.5, 4.0)
    r = run_trial(BOTTLE, light, seed=0)
    assert r.reason.startswith("not lifted")
    cause = diagnose({**r.to_dict(), "details": {"plan": light.to_dict()}})
    assert cause.kind == "friction" and "5.89 N" in cause.text  # 600 g weighs 5.89 N


def test_every_seed_like_plan_gets_a_known_cause_for_every_reason():
    for features in (BASKETBALL, PLATE, REMOTE):
        for plan in plan_grasps(features):
            for reason in (TURNED, SLIPPED, NOT_LIFTED, INSIDE, NO_CONTACT):
                assert diagnose(_row(plan, reason)).kind in CAUSES


def test_a_plan_the_hand_cannot_open_round_is_a_setup_failure_whatever_the_trial_said():
    from sim.diagnosis import is_setup_failure

    # A teapot 10.8 cm across (data written here): within the span, but a wrap needs a 13.5 cm opening.
    plan = best_grasp(dict(name="ceramic teapot", a_cm=22, b_cm=10.8, c_cm=10.8, mass_g=900, material="ceramic"))
    assert plan.params["feasible"] and not plan.params["fits_aperture"]
    for reason in (TURNED, SLIPPED, NOT_LIFTED, INSIDE):
        cause = diagnose(_row(plan, reason))
        assert cause.kind == "aperture" and "13.5 cm opening" in cause.text, reason
        assert is_setup_failure(_row(plan, reason))
    assert not is_setup_failure(_row(plan, "held", outcome="success"))
    fits = best_grasp(REMOTE)
    assert fits.params["fits_aperture"]
    assert not is_setup_failure(_row(fits, SLIPPED)) and is_setup_failure(_row(fits, INSIDE))


def _rod(diameter: float) -> dict:
    return dict(a_cm=5.05, b_cm=diameter, c_cm=diameter, mass_g=23, shape="long", material="metal")


def test_a_thin_rod_not_lifted_by_a_pinch_from_above_was_pressed_into_the_table_at_its_boundary():
    from sim.diagnosis import PAD_TIP_RADIUS_CM

    assert PAD_TIP_RADIUS_CM == 0.765  # the index's distal pad (0.85 cm x 0.9 taper), thinner than the thumb's
    below, at = 2 * PAD_TIP_RADIUS_CM - 0.01, 2 * PAD_TIP_RADIUS_CM
    plan = best_grasp(_rod(below))
    assert plan.approach == "top" and program_for(plan.grasp_type).control != "wrap"
    assert plan.params["round_across_cm"] == below
    cause = diagnose(_row(plan, NOT_LIFTED))
    assert cause.kind == "pressed" and "above its centre line" in cause.text
    assert diagnose(_row(best_grasp(_rod(at)), NOT_LIFTED)).kind == "friction"  # the pads reach its centre line
    assert diagnose(_row(plan, SLIPPED)).kind == "friction"  # lifted, then slipped: not pressed down
    wrap = next(p for p in plan_grasps(_rod(below)) if program_for(p.grasp_type).control == "wrap")
    assert diagnose(_row(wrap, NOT_LIFTED)).kind != "pressed"
    flat = best_grasp(dict(a_cm=5.05, b_cm=2.0, c_cm=1.0, mass_g=23, shape="long", material="metal"))
    assert "round_across_cm" not in flat.params and diagnose(_row(flat, NOT_LIFTED)).kind == "friction"


TOWEL = dict(a_cm=75, b_cm=40, c_cm=0.5, mass_g=200, shape="thin", material="fabric", rigidity="floppy")


def test_a_draping_sheet_is_no_mass_failure_for_a_rigid_plates_edge_moment():
    plan = best_grasp(TOWEL)
    p = plan.params
    assert p["force_within_capacity"] is False and p["needed_force_n"] > 60  # the rigid plate's edge moment
    assert (p["sheet_held_cm"], p["sheet_grip_in_cm"], p["sheet_hanging_g"]) == (14.0, 6.0, 130.0)  # 40 cm deep
    cause = diagnose(_row(plan, TURNED))
    assert cause.kind == "moment" and "130 g" in cause.text and "8 cm behind the pads" in cause.text
    assert "10.2 N cm" in cause.text  # 0.13 kg x 9.81 m/s^2 x 8 cm
    assert diagnose(_row(plan, SLIPPED)).kind == "friction"  # the friction bound, 3.7 N, is within 60 N
    rigid = best_grasp({**TOWEL, "rigidity": "rigid"})  # the same plate, rigid: no sheet, the edge moment is real
    assert "sheet_held_cm" not in rigid.params and diagnose(_row(rigid, TURNED)).kind == "mass"
    heavy = best_grasp({**TOWEL, "mass_g": 20000})  # its friction bound beyond the grasp: mass, as for a plate
    assert "sheet_held_cm" in heavy.params and diagnose(_row(heavy, TURNED)).kind == "mass"


def test_a_turn_names_a_measured_squeeze_short_of_the_plan_at_its_boundary():
    plan = best_grasp(REMOTE)
    planned = plan.grip_force_n
    short = diagnose(_row(plan, TURNED, grip=round(0.89 * planned, 3))).text
    assert f"of the {planned:g} N planned" in short
    assert "planned" not in diagnose(_row(plan, TURNED, grip=0.9 * planned)).text
    assert "planned" not in diagnose(_row(plan, TURNED)).text  # no measurement: nothing to compare


COIN = dict(a_cm=2.325, b_cm=2.325, c_cm=0.233, mass_g=7.5, shape="thin", material="metal")


def test_a_coin_at_the_table_edge_is_pushed_out_by_pads_nearer_its_rim_than_their_radius():
    """The pads press edge_grip_in_cm in from the rim (sim/grasps.py); under their radius, a pinch that
    closed without holding is said to have pushed it out, with the numbers; from the radius on it is not."""
    from sim.diagnosis import PAD_TIP_RADIUS_CM

    plan = best_grasp(COIN)
    p = plan.params
    assert (p["edge_depth_cm"], p["edge_overhang_cm"], p["edge_grip_in_cm"]) == (2.325, 1.046, 0.3)
    cause = diagnose(_row(plan, NO_CONTACT))
    assert cause.kind == "size"
    assert "overhang only 1.05 cm" in cause.text and "0.3 cm in from its rim" in cause.text
    assert "nails" in cause.text
    below = GraspPlan(**{**plan.to_dict(), "params": {**p, "edge_grip_in_cm": PAD_TIP_RADIUS_CM - 0.001}})
    at = GraspPlan(**{**plan.to_dict(), "params": {**p, "edge_grip_in_cm": PAD_TIP_RADIUS_CM}})
    assert "rim" in diagnose(_row(below, NO_CONTACT)).text
    assert diagnose(_row(at, NO_CONTACT)).text.startswith("the digits closed past it")
    assert "edge_grip_in_cm" not in best_grasp(REMOTE).params  # not flat: no table edge
