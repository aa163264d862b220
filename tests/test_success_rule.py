"""The trial's success rule pinned down, each condition on its own (sim/trial.py).

Each trial below fails (or holds) for exactly one reason and asserts that reason, so that turning the
rule's ``or`` into ``and``, raising the slip limit (5 -> 50 cm), making ``failed()`` always false or
removing the lift check each fails a test here (checked by hand: sim/PHYSICS.md, "Success rule"). The
objects are written here; the physics is real MuJoCo (deterministic for a seed).
"""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from sim.grasps import GRASP_TYPES, GraspPlan
from sim.programs import program_for
from sim.trial import MAX_ROTATION_DEG, MAX_SLIP_CM, PERTURBATION_DIRECTIONS, beyond_limits, run_trial

#: A smooth 600 g glass bottle, 6.5 cm across: in a heavy wrap, 4 N does not lift it, 9 N holds it through
#: every push but the last (-z, its weight again on top of gravity), 14 N holds it to the end.
BOTTLE = ObjectRecord.create(
    "glass bottle", a_cm=20, b_cm=6.5, c_cm=6.5, mass_g=600, shape="prism", material="glass", texture="smooth"
)
#: A 600 g book, picked at the table edge: a 12 N pinch turns it in the -z push alone, hardly moving it.
BOOK = ObjectRecord.create("heavy book", a_cm=18, b_cm=11, c_cm=2, mass_g=600, shape="thin", material="paper")


def _plan(grasp_type: str, aperture: float, force: float) -> GraspPlan:
    gt = grasp_type
    return GraspPlan(gt, GRASP_TYPES[gt], "c", aperture, program_for(gt).approach, force, 1.0)


def test_motion_limits_at_their_boundaries():
    assert not beyond_limits(0.0, 0.0)
    assert beyond_limits(MAX_SLIP_CM, 0.0) and not beyond_limits(MAX_SLIP_CM - 1e-9, 0.0)
    assert beyond_limits(0.0, MAX_ROTATION_DEG) and not beyond_limits(0.0, MAX_ROTATION_DEG - 1e-9)
    assert beyond_limits(MAX_SLIP_CM, 0.0) and beyond_limits(0.0, MAX_ROTATION_DEG)  # either alone fails
    assert (MAX_SLIP_CM, MAX_ROTATION_DEG) == (5.0, 15.0)


@pytest.fixture(scope="module")
def bottle_slips():
    return run_trial(BOTTLE, _plan("heavy_wrap_large_diameter", 8.5, 9.0), seed=0)


@pytest.mark.slow
def test_lifted_then_slipped_past_5_cm_fails_for_the_slip_alone(bottle_slips):
    r = bottle_slips
    assert r.lifted, r.reason
    assert r.outcome == "failure" and not r.success
    assert r.reason.startswith("slipped") and "during the -z push" in r.reason, r.reason
    assert MAX_SLIP_CM <= r.slip_cm < 50.0
    assert r.rotation_deg < MAX_ROTATION_DEG  # the slip alone failed it


@pytest.mark.slow
def test_held_until_the_last_push_then_failed_in_it(bottle_slips):
    r = bottle_slips
    pushes = list(PERTURBATION_DIRECTIONS)
    assert list(r.perturbation) == pushes  # every push was applied, the trial stopped only in the last
    assert all(r.perturbation[d] < 1.0 for d in pushes[:-1]), r.perturbation
    assert r.perturbation[pushes[-1]] >= MAX_SLIP_CM - 1.0


@pytest.mark.slow
def test_turned_past_15_degrees_under_one_push_fails_for_the_turn_alone():
    r = run_trial(BOOK, _plan("thumb_4_finger", 4.0, 12.0), seed=0)
    assert r.lifted and r.outcome == "failure"
    assert r.reason.startswith("turned") and "during the -z push" in r.reason, r.reason
    assert r.rotation_deg >= MAX_ROTATION_DEG
    assert r.slip_cm < MAX_SLIP_CM / 2  # hardly moved: the turn alone failed it
    assert list(r.perturbation) == list(PERTURBATION_DIRECTIONS)  # the pushes before it did not


@pytest.mark.slow
def test_not_lifted_fails_as_not_lifted():
    r = run_trial(BOTTLE, _plan("heavy_wrap_large_diameter", 8.5, 4.0), seed=0)
    assert not r.lifted and r.outcome == "failure"
    assert r.reason.startswith("not lifted"), r.reason
    assert r.perturbation == {}


@pytest.mark.slow
def test_the_same_bottle_held_firmly_holds_until_the_end():
    r = run_trial(BOTTLE, _plan("heavy_wrap_large_diameter", 8.5, 14.0), seed=0)
    assert r.outcome == "success" and r.success and r.lifted, r.reason
    assert list(r.perturbation) == list(PERTURBATION_DIRECTIONS)
    assert r.slip_cm < MAX_SLIP_CM and r.rotation_deg < MAX_ROTATION_DEG


def test_starting_inside_the_object_fails_before_any_motion():
    # a pinch opened to 3 cm round a 6.5 cm bottle (a wrap's thumb always clears the near side)
    r = run_trial(BOTTLE, _plan("thumb_2_finger", 3.0, 14.0), seed=0)
    assert r.outcome == "failure" and not r.lifted
    assert r.reason.startswith("hand starts inside the object"), r.reason
    assert r.sim_time_s == 0.0 and r.perturbation == {}
