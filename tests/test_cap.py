"""A peaked cap (issue 14, grasp-odd): a crown on a brim (sim/bodies.py), picked up by its brim at a table
edge (sim/planner.py ``_brim_plan``, sim/world.py ``_part_layout``). Objects written here."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from kb.errors import SimulationError
from kb.features import ObjectRecord
from sim import hand as H
from sim.bodies import HOLD_PART, body_for, peaked
from sim.diagnosis import diagnose
from sim.planner import best_grasp, plan_grasps
from sim.trial import run_trial
from sim.world import build_world

CAP = ObjectRecord.create("baseball cap", a_cm=27, b_cm=19, c_cm=12, mass_g=90, shape="prism", material="fabric",
                          texture="medium", fragility="medium", rigidity="squeezable", aliases=("ball cap",))  # fmt: skip


@pytest.mark.parametrize(
    ("name", "aliases", "is_peaked"),
    [("baseball cap", (), True), ("peaked cap", (), True), ("ball cap", (), True), ("bottle cap", (), False),
     ("plastic cap", (), False), ("swim cap", (), False), ("sun hat", (), False), ("cappellino", ("ball cap",), True)],
)  # fmt: skip
def test_a_peaked_cap_is_known_by_its_kind_noun(name, aliases, is_peaked):
    assert peaked(name, aliases) is is_peaked


def test_the_cap_is_a_stepped_crown_on_a_thin_brim_within_its_stated_sizes():
    body = body_for((27, 19, 12), "prism", 0.09, name="baseball cap")
    assert body.form == "cap" and body.up == "c"
    names = [p.name for p in body.parts]
    assert names == ["crown_0", "crown_1", "crown_top", "brim"]
    radii = [p.size_cm[0] for p in body.parts[:3]]
    assert (
        radii == sorted(radii, reverse=True) and radii[0] == 9.5
    )  # the crown narrows to the top, 19 cm across
    brim = body.parts[3]
    assert brim.extent_cm("a") == pytest.approx(8.0) and brim.extent_cm("c") == pytest.approx(0.38)
    lo = min(p.pos_cm[0] - p.extent_cm("a") / 2 for p in body.parts)
    hi = max(p.pos_cm[0] + p.extent_cm("a") / 2 for p in body.parts)
    top = max(p.pos_cm[2] + p.extent_cm("c") / 2 for p in body.parts)
    assert (lo, hi, top) == pytest.approx((-13.5, 13.5, 6.0))
    assert sum(p.mass_kg for p in body.parts) == pytest.approx(0.09)
    assert body_for((3.4, 3.4, 1.3), "compact", 0.005, name="plastic cap").form == "cylinder"  # a lid's cap


def test_the_cap_is_planned_by_its_brim_with_the_crowns_moment():
    plans = plan_grasps(CAP)
    first = plans[0]
    assert first.grasp_type == "thumb_4_finger" and first.params["hold"] == HOLD_PART
    assert first.params["part"] == "brim" and first.grasped_dim == "c" and first.params["width_cm"] == 0.38
    lever = first.params["brim_lever_cm"]
    assert (
        14.0 < lever < 15.0
    )  # the brim's pads 2.7 cm in from its tip, the crown's centre of mass near its axis
    assert first.grip_force_n == pytest.approx(2.4 * 0.09 * 9.81 * lever / (2 * 0.3), abs=0.02)
    assert first.params["force_within_capacity"] and any("crown's weight" in r for r in first.rationale)
    assert not any("grasped width 12 cm" in r for r in first.rationale)  # the brim, not the crown's height
    assert [p.params.get("hold") for p in plans[1:]] == [None] * (len(plans) - 1)  # its body's grasps follow
    box = ObjectRecord.create(
        "shoe box", a_cm=27, b_cm=19, c_cm=12, mass_g=90, shape="prism", material="paper"
    )
    assert "hold" not in best_grasp(box).params


def test_the_brim_overhangs_a_table_edge_and_the_hand_pinches_it_there():
    plan = best_grasp(CAP)
    world = build_world(CAP, plan, seed=0)
    assert world.approach == "edge"
    m = world.model
    table = m.geom("table")
    edge_x = (m.geom_pos[table.id][0] + m.geom_size[table.id][0]) / H.CM
    assert edge_x == pytest.approx(9.5 + 4.0 - 3.6, abs=0.01)  # brim centre + half its length - the overhang
    with pytest.raises(SimulationError, match="no part"):
        build_world(CAP, dataclasses.replace(plan, params={**plan.params, "part": "visor"}), seed=0)
    with pytest.raises(SimulationError, match="not a flat part"):
        build_world(CAP, dataclasses.replace(plan, params={**plan.params, "part": "crown_top"}), seed=0)


def test_the_brim_pinch_runs_and_its_failure_is_the_crowns_moment():
    """Measured (seed 0): the crown swings down about the pinch during the lift; reported as the moment
    that turned it, not as friction (the squeeze carries 70 times its weight)."""
    plan = best_grasp(CAP)
    r = run_trial(CAP, plan, seed=0)
    assert r.outcome == "failure" and r.lifted and r.rotation_deg > 15.0
    row = {**r.to_dict(), "details": json.dumps({"plan": plan.to_dict()})}
    cause = diagnose(row)
    assert (
        cause.kind == "moment"
        and "crown" in cause.text
        and f"{plan.params['brim_lever_cm']:g} cm" in cause.text
    )
    assert np.isfinite(r.slip_cm)
