"""The slide-to-the-edge experiment (sim/slide.py, sim/PHYSICS.md "Sliding a coin to the edge"): the class
rule at its boundary, the rim-push geometry, and the two slide phases on a euro coin (data written here)."""

import math

import pytest

from kb.features import ObjectRecord
from sim import slide as S
from sim.grasps import EDGE_PAD_CLEAR_CM, edge_grip_in_cm
from sim.planner import best_grasp
from sim.world import build_world

COIN = dict(name="one euro coin", a_cm=2.325, b_cm=2.325, c_cm=0.233, mass_g=7.5, shape="thin",
            material="metal", texture="medium", rigidity="rigid")  # fmt: skip
CLIP = dict(name="paper clip", a_cm=3.3, b_cm=0.8, c_cm=0.1, mass_g=0.5, shape="thin",
            material="metal", texture="smooth", rigidity="rigid")  # fmt: skip


def test_needs_slide_where_the_pads_would_press_nearer_the_rim_than_their_radius_plus_the_margin():
    need = S.pad_radius_cm() + S.SLIDE_MARGIN_CM  # 1.065 cm
    # edge_grip_in_cm = 0.45 d - 0.9 in this range: the boundary depth d = (need + 0.9) / 0.45
    boundary = (need + EDGE_PAD_CLEAR_CM) / 0.45
    assert edge_grip_in_cm(boundary) == pytest.approx(need)
    assert S.needs_slide(boundary - 0.01, 0.2) and not S.needs_slide(boundary + 0.01, 0.2)
    assert S.needs_slide(2.325, 0.233) and S.needs_slide(3.3, 0.1)  # the euro coin; the paper clip
    assert not S.needs_slide(10.0, 0.2)  # a phone


def test_needs_slide_only_for_things_thinner_than_a_pad_radius():
    r = S.pad_radius_cm()
    assert S.needs_slide(3.0, r - 0.001) and not S.needs_slide(3.0, r)
    assert not S.needs_slide(3.0, 1.0)  # the teaspoon: held by the plain edge pinch


def test_overhang_needed_puts_a_coins_centre_of_mass_off_the_table():
    assert S.overhang_needed_cm() == pytest.approx(EDGE_PAD_CLEAR_CM + S.pad_radius_cm() + S.SLIDE_MARGIN_CM)
    assert S.overhang_needed_cm() > 2.325 / 2.0


def test_rim_push_ratio_at_its_limits():
    assert S.rim_push_ratio(0.233, 0.9) == pytest.approx(math.sqrt(0.81 - 0.717**2) / 0.717)
    assert S.rim_push_ratio(1.0, 0.9) == math.inf  # a rim above the tip's centre: a horizontal push
    assert S.rim_push_ratio(0.04, 0.9) == 0.0  # a rim lower than the gap: the tip passes over it
    assert S.rim_push_ratio(0.1, 0.9) < S.rim_push_ratio(0.233, 0.9)  # the paper clip's is lower


def test_the_hook_hangs_at_most_a_quarter_of_a_low_rims_height():
    boundary = S.HOOK_CLEARANCE_CM / S.HOOK_RIM_FRACTION  # a 2 mm rim
    assert S.hook_clearance_cm(boundary) == pytest.approx(S.HOOK_CLEARANCE_CM)
    assert S.hook_clearance_cm(boundary + 0.01) == S.HOOK_CLEARANCE_CM  # the euro coin's 2.33 mm: 0.5 mm
    assert S.hook_clearance_cm(boundary - 0.01) < S.HOOK_CLEARANCE_CM
    assert S.hook_clearance_cm(0.1) == pytest.approx(0.025)  # the paper clip's 1 mm wire
    # lower, the tip meets the wire's side: it pushes it along more than down (0.35 at 0.5 mm)
    r = S.pad_radius_cm()
    assert S.rim_push_ratio(0.1, r, S.hook_clearance_cm(0.1)) > 1.4 * 0.32 > S.rim_push_ratio(0.1, r, 0.05)


def test_a_paper_clip_is_slid_out_and_held_but_not_with_the_hook_at_half_its_height(monkeypatch):
    import sim.trial as T

    clip = ObjectRecord.create(**CLIP)
    plan = best_grasp(clip)
    held = T.run_trial(clip, plan, seed=0)
    monkeypatch.setattr(S, "HOOK_RIM_FRACTION", 0.5)  # 0.5 mm above the table: half the wire's height
    high = T.run_trial(clip, plan, seed=0)
    assert plan.grasp_type == "thumb_index_finger" and S.slides(build_world(clip, plan))
    assert held.success and held.rotation_deg < 10.0 and len(held.perturbation) == 6
    assert high.reason == "no contact after closing: the digits pushed the object out of the grasp and off the table"


def test_a_hook_behind_the_inner_rim_slides_a_coin_out_and_holds_it_on_the_table():
    coin = ObjectRecord.create(**COIN)
    slide = S.hook_pull(build_world(coin, best_grasp(coin), seed=0), 2.325, 1.5)
    assert slide.slid_cm > 0.8 and not slide.fell and slide.tilt_deg < 5.0
    assert slide.thumb_n > 0.05  # the thumb pushes it


def test_a_light_press_does_not_drag_a_coin_the_object_friction_governs_both_contacts():
    coin = ObjectRecord.create(**COIN)
    slide = S.press_drag(build_world(coin, best_grasp(coin), seed=0), 1.5, press_cm=0.05)
    assert slide.thumb_n > 0.05  # pressed ...
    assert abs(slide.slid_cm) < 0.05 and not slide.fell  # ... and the pad slid over it


def test_the_trial_slides_a_coin_out_and_then_holds_it_through_the_same_checks(monkeypatch):
    import sim.trial as T

    coin = ObjectRecord.create(**COIN)
    plan = best_grasp(coin)
    slid = T.run_trial(coin, plan, seed=0)
    monkeypatch.setattr(T, "slides", lambda world: False)
    unslid = T.run_trial(coin, plan, seed=0)
    assert plan.grasp_type == "thumb_index_finger" and S.slides(build_world(coin, plan))
    assert slid.success and slid.lifted and len(slid.perturbation) == 6  # lifted, held, every push survived
    assert slid.slip_cm < 1.0 and slid.rotation_deg < 10.0 and slid.grip_force_n > 1.0
    # the plain edge pinch of the same plan: pushed out of the pinch and off the table, and a distinct trajectory
    assert (
        unslid.reason
        == "no contact after closing: the digits pushed the object out of the grasp and off the table"
    )
    assert slid.closed_posture != unslid.closed_posture


def test_objects_that_do_not_need_a_slide_are_not_slid():
    spoon = ObjectRecord.create(name="teaspoon", a_cm=14, b_cm=3, c_cm=1, mass_g=20, shape="long",
                                material="metal", texture="smooth", rigidity="rigid")  # fmt: skip
    from sim.planner import plan_grasps

    assert not any(S.slides(build_world(spoon, p)) for p in plan_grasps(spoon, top=3))
