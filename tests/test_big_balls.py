"""Balls wider than the hand's span (issue 24; sim/PHYSICS.md "Balls wider than the span", data written here):
where a wrap places a ball, which balls one hand holds over their top, the squeeze that takes, and the mini
soccer ball held in a real trial, not lifted at the friction bound."""

import dataclasses
import math

import pytest

from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import BALL_MAX_ONE_HAND_CM, HAND_MAX_APERTURE_CM
from sim.grip_force import BALL_FINGER_CONTACT_DEG, SAFETY_FACTOR, ball_over_top_force
from sim.planner import best_grasp, plan_grasps
from sim.trial import run_trial

MINI = dict(name="mini soccer ball", a_cm=14, b_cm=14, c_cm=14, mass_g=123, shape="radial", texture="medium",
            fragility="sturdy", material="plastic", rigidity="squeezable")  # fmt: skip


def ball(diameter: float, **kw) -> ObjectRecord:
    return ObjectRecord.create(**{**MINI, "name": "plastic ball", "a_cm": diameter, "b_cm": diameter,
                                  "c_cm": diameter, **kw})  # fmt: skip


def _thumb_lowest_reach_below_equator_cm(diameter: float, gap: float = 0.4) -> float:
    """How far below a ball's equator the thumb's tip gets, outside the ball placed by ball_center_y_cm."""
    radius, centre_y = diameter / 2.0, H.ball_center_y_cm(diameter, gap)
    centre_z = -H.PALM_HALF_CM[2] - gap - radius
    lo, hi = (math.radians(v) for v in H.RANGE_DEG["thumb_flex"])
    zs = []
    for k in range(401):
        y, z = H.thumb_tip(lo + (hi - lo) * k / 400)
        if math.hypot(y - centre_y, z - centre_z) >= radius + H.THUMB.radius_cm * H.TIP_TAPER:
            zs.append(z)
    return centre_z - min(zs)


def test_a_ball_sits_as_near_the_thumb_as_its_curve_clears_the_metacarpal():
    thumb_y, r_t = H.THUMB.base_cm[1], H.THUMB.radius_cm
    for d in (6.4, 9.7, 14.0, 22.0):
        y = H.ball_center_y_cm(d, 0.4)
        # never nearer than a box of that width would be placed, and nearer for any ball that reaches below
        # the metacarpal's end
        assert y < thumb_y + r_t + H.WRAP_THUMB_CLEARANCE_CM + d / 2.0
        centre_z = -H.PALM_HALF_CM[2] - 0.4 - d / 2.0
        end_z = H.THUMB.base_cm[2] - H.THUMB.metacarpal_cm
        gap = math.hypot(y - thumb_y, end_z - centre_z) - d / 2.0 - r_t
        assert gap == pytest.approx(H.WRAP_THUMB_CLEARANCE_CM)
    assert H.ball_center_y_cm(14.0, 0.4) == pytest.approx(3.45, abs=0.01)  # a box 14 cm wide: 5.0


def test_one_hand_holds_a_ball_over_its_top_up_to_where_the_thumb_reaches_its_near_equator():
    assert _thumb_lowest_reach_below_equator_cm(BALL_MAX_ONE_HAND_CM) > 0.0
    assert _thumb_lowest_reach_below_equator_cm(BALL_MAX_ONE_HAND_CM + 1.0) < 0.0
    assert HAND_MAX_APERTURE_CM < BALL_MAX_ONE_HAND_CM


def test_the_over_the_top_squeeze_balances_both_contacts_at_their_friction_limits():
    a, mu = math.radians(BALL_FINGER_CONTACT_DEG), 0.45
    weight = 0.123 * 9.81
    expected = SAFETY_FACTOR["sturdy"] * weight * (math.cos(a) + mu * math.sin(a))
    expected /= 2 * mu * math.cos(a) + (mu * mu - 1) * math.sin(a)
    assert ball_over_top_force(123, mu, "sturdy") == pytest.approx(expected, abs=0.01)
    assert ball_over_top_force(123, mu, "sturdy") == pytest.approx(18.72, abs=0.01)
    # no squeeze lifts it below mu = tan(a / 2): the fingers' press down outgrows what friction carries
    limit = math.tan(a / 2.0)
    assert ball_over_top_force(123, limit - 0.001) is None
    assert ball_over_top_force(123, limit + 0.01) is not None
    assert ball_over_top_force(123, 0.6, "sturdy") < ball_over_top_force(123, 0.45, "sturdy")


def test_the_planner_holds_a_ball_up_to_15_cm_over_its_top_and_flags_wider_ones_for_two_hands():
    mini = best_grasp(ObjectRecord.create(**MINI))
    assert mini.grasp_type == "power_sphere" and mini.params["feasible"] and not mini.params["two_hands"]
    assert mini.grip_force_n == ball_over_top_force(123, mini.params["friction"], "sturdy")
    assert any(line.startswith("over its top:") for line in mini.rationale)
    at_limit = best_grasp(ball(BALL_MAX_ONE_HAND_CM))
    wider = best_grasp(ball(BALL_MAX_ONE_HAND_CM + 0.1))
    assert at_limit.params["feasible"] and not wider.params["feasible"] and wider.params["two_hands"]
    assert not any(line.startswith("over its top:") for line in wider.rationale)
    within = best_grasp(ball(HAND_MAX_APERTURE_CM))  # fits the span: the friction bound as before
    assert not any(line.startswith("over its top:") for line in within.rationale)
    # a side wrap of the same ball is not held over its top
    side = next(p for p in plan_grasps(ObjectRecord.create(**MINI), top=5) if p.approach == "side")
    assert not any(line.startswith("over its top:") for line in side.rationale)


def test_the_mini_soccer_ball_is_held_over_its_top_and_not_lifted_at_the_friction_bound():
    mini = ObjectRecord.create(**MINI)
    plan = best_grasp(mini)
    held = run_trial(mini, plan, seed=0)
    assert held.success and held.slip_cm < 2.0 and held.rotation_deg < 5.0
    light = run_trial(mini, dataclasses.replace(plan, grip_force_n=plan.params["required_force_n"]), seed=0)
    assert light.reason.startswith("not lifted")
