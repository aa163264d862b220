"""Smoke and kinematics tests of the AR10-like hand model (sim/hand.py)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from sim import hand as H
from sim.grasps import GRASP_TYPES, GraspPlan
from sim.trial import check_physics


def _plan(grasp_type: str, aperture: float = 7.0, force: float = 10.0) -> GraspPlan:
    approach = "side" if grasp_type == "medium_wrap" else "top"
    return GraspPlan(grasp_type, GRASP_TYPES[grasp_type], "c", aperture, approach, force, 1.0)


@pytest.mark.parametrize("approach", ["top", "side"])
def test_hand_compiles_with_ten_digit_actuators(approach):
    model = H.hand_spec(approach).compile()
    names = [model.actuator(i).name for i in range(model.nu)]
    assert names == [*H.WRIST_ACTUATOR_NAMES, *H.ACTUATOR_NAMES]
    assert len(H.ACTUATOR_NAMES) == 10  # two actuated joints per digit, five digits
    # 3 wrist slides + 10 digit hinges, every digit joint driven by the actuator of the same name
    assert model.njnt == 13
    for name in H.ACTUATOR_NAMES:
        act = model.actuator(name)
        assert model.joint(int(act.trnid[0])).name == name
        assert model.jnt_type[model.joint(name).id] == mujoco.mjtJoint.mjJNT_HINGE
        assert model.actuator_forcelimited[act.id]
    assert {n.split("_")[0] for n in H.ACTUATOR_NAMES} == set(H.DIGITS)


def test_hand_proportions_are_human():
    model = H.hand_spec().compile()
    palm = model.geom("palm_geom")
    width, length = 2 * palm.size[0] * 100, 2 * palm.size[1] * 100
    assert 8.0 <= width <= 9.0 and 8.5 <= length <= 10.0
    middle = sum(H.FINGER_BY_NAME["middle"].lengths_cm)
    assert 8.0 <= middle <= 10.0  # middle finger ~ 9 cm; hand length = palm + middle ~ 18-20 cm
    assert 17.0 <= length + middle <= 21.0
    total_mass = sum(model.body_mass)
    assert 0.3 <= total_mass <= 1.0


def test_smoke_steps_with_control_noise_without_warnings():
    model = H.hand_spec().compile()
    data = mujoco.MjData(model)
    rng = np.random.default_rng(0)
    lo, hi = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    mid = np.where(model.actuator_ctrllimited, 0.5 * (lo + hi), 0.0)
    for _ in range(200):
        data.ctrl[:] = mid + rng.normal(0, 0.05, model.nu)
        mujoco.mj_step(model, data, nstep=5)
        check_physics(model, data)  # raises PhysicsError on NaN or any MuJoCo warning
    assert all(data.warning[i].number == 0 for i in range(int(mujoco.mjtWarning.mjNWARNING)))
    assert data.time == pytest.approx(2.0)


@pytest.mark.parametrize("grasp_type", ["power_sphere", "thumb_2_finger", "medium_wrap", "tripod"])
def test_hand_reaches_the_preshape(grasp_type):
    targets = H.grasp_targets(_plan(grasp_type), width_cm=5.0)
    model = H.hand_spec(_plan(grasp_type).approach).compile()
    data = mujoco.MjData(model)
    digit = [model.actuator(n).id for n in H.ACTUATOR_NAMES]
    qadr = [model.jnt_qposadr[model.joint(n).id] for n in H.JOINT_NAMES]
    data.ctrl[digit] = targets.open
    mujoco.mj_step(model, data, nstep=300)
    check_physics(model, data)
    np.testing.assert_allclose(data.qpos[qadr], targets.open, atol=math.radians(3))


def test_closing_targets_flex_the_used_digits_and_leave_the_others():
    targets = H.grasp_targets(_plan("thumb_index_finger", 4.0), width_cm=3.0)
    idx = {n: i for i, n in enumerate(H.ACTUATOR_NAMES)}
    assert targets.fingers == ("index",)
    assert targets.close[idx["index_mcp"]] > targets.open[idx["index_mcp"]]
    assert targets.close[idx["thumb_flex"]] > targets.open[idx["thumb_flex"]]
    for f in ("middle", "ring", "little"):
        assert targets.close[idx[f"{f}_mcp"]] == targets.open[idx[f"{f}_mcp"]] == 0.0
        assert targets.torque_limits[f"{f}_mcp"] == H.UNUSED_TORQUE_NM


def test_force_limits_follow_the_planned_grip_and_cap_at_the_digits_strength():
    weak = H.grasp_targets(_plan("thumb_index_finger", force=4.0), width_cm=3.0)
    strong = H.grasp_targets(_plan("thumb_index_finger", force=8.0), width_cm=3.0)
    assert strong.torque_limits["index_mcp"] == pytest.approx(2 * weak.torque_limits["index_mcp"])
    huge = H.grasp_targets(_plan("thumb_index_finger", force=500.0), width_cm=3.0)
    assert huge.side_force_n == H.FINGER_MAX_FORCE_N  # one finger opposes the thumb: its strength caps
    power = H.grasp_targets(_plan("power_sphere", force=500.0), width_cm=6.0)
    assert power.side_force_n == H.THUMB_MAX_FORCE_N


def test_pinch_kinematics_are_consistent():
    # the tip solver inverts the planar forward kinematics
    for y in (3.0, 5.0, 7.0):
        q = H.finger_pinch_mcp("index", y)
        assert H.finger_tip("index", q, H.PIP_PER_MCP * q)[0] == pytest.approx(y, abs=1e-6)
        t = H.thumb_flex_for(y - 5.0)
        assert H.thumb_tip(t)[0] == pytest.approx(y - 5.0, abs=1e-6)


def test_the_solvers_tip_y_is_finger_tips_y_to_the_last_bit():
    # finger_tip_y_of writes out finger_tip's chain for the posture solvers: the same floats, with the PIP
    # both below and at its cap (ratio x MCP past pip_max), so a stored posture does not move
    from sim.hand_kinematics import finger_tip_y_of

    pip_max = math.radians(H.RANGE_DEG["pip"][1])
    for finger in (f.name for f in H.FINGERS):
        for ratio in (0.3, 0.8, 1.0, 1.6):
            tip_y = finger_tip_y_of(finger, ratio, pip_max)
            for k in range(41):
                q = k * math.radians(H.RANGE_DEG["mcp"][1]) / 40
                assert tip_y(q) == H.finger_tip(finger, q, min(pip_max, ratio * q))[0]
    assert finger_tip_y_of("index", 1.6, pip_max)(1.5) != finger_tip_y_of("index", 1.6, 1.0)(1.5)  # the cap bites


def test_planar_kinematics_match_the_mujoco_model():
    model = H.hand_spec().compile()
    data = mujoco.MjData(model)
    q = {"index_mcp": 0.7, "index_pip": 0.5, "thumb_flex": 0.6, "thumb_rot": 0.0}
    for name, value in q.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = value
    mujoco.mj_kinematics(model, data)
    palm = model.body("palm").id
    rot = data.xmat[palm].reshape(3, 3)

    def in_palm_cm(site):
        return rot.T @ (data.site_xpos[model.site(site).id] - data.xpos[palm]) * 100

    tip = in_palm_cm("index_tip")
    assert tip[0] == pytest.approx(H.FINGER_BY_NAME["index"].x_cm, abs=1e-6)
    np.testing.assert_allclose(tip[1:], H.finger_tip("index", 0.7, 0.5), atol=1e-6)
    np.testing.assert_allclose(in_palm_cm("thumb_tip")[1:], H.thumb_tip(0.6), atol=1e-6)


def test_unknown_approach_is_refused():
    with pytest.raises(ValueError, match="approach"):
        H.hand_spec("below")


def _touch_heights(targets: H.GraspTargets) -> dict[str, float]:
    q = dict(zip(H.ACTUATOR_NAMES, targets.touch, strict=True))
    out = {f: H.finger_tip(f, q[f"{f}_mcp"], q[f"{f}_pip"])[1] for f in targets.fingers}
    out["thumb"] = H.thumb_tip(q["thumb_flex"])[1]
    return out


@pytest.mark.parametrize("grasp_type", ["thumb_2_finger", "thumb_3_finger", "tripod"])
def test_aligned_pinch_pads_meet_a_thin_rod_at_the_thumbs_height(grasp_type):
    """The index is 1 cm shorter than the middle finger: at one synergy its pad met a 1.45 cm AA battery
    0.4 cm above the middle's, above the rod's centre line, and pressed it into the table. Aligned, every
    used finger's pad touches at the thumb's height; the synergy then differs per finger."""
    plain = _touch_heights(H.grasp_targets(_plan(grasp_type, aperture=3.45), width_cm=1.45))
    aligned_t = H.grasp_targets(_plan(grasp_type, aperture=3.45), width_cm=1.45, align_pads=True)
    aligned = _touch_heights(aligned_t)
    assert plain["index"] - plain["middle"] > 0.5  # the misalignment this fixes
    for f in aligned_t.fingers:
        assert aligned[f] == pytest.approx(aligned["thumb"], abs=0.01)
    q = dict(zip(H.ACTUATOR_NAMES, aligned_t.touch, strict=True))
    assert q["index_pip"] / q["index_mcp"] < q["middle_pip"] / q["middle_mcp"]  # the shorter finger flatter


def test_alignment_keeps_the_programs_synergy_where_it_is_off_and_for_one_finger():
    plan = _plan("thumb_index_finger", aperture=3.45)
    aligned = H.grasp_targets(plan, 1.45, align_pads=True)
    assert np.allclose(H.grasp_targets(plan, 1.45).touch, aligned.touch, atol=1e-3)
    q = dict(zip(H.ACTUATOR_NAMES, H.grasp_targets(_plan("thumb_2_finger", 3.45), 1.45).touch, strict=True))
    assert q["index_pip"] / q["index_mcp"] == pytest.approx(0.8)
    assert q["middle_pip"] / q["middle_mcp"] == pytest.approx(0.8)
