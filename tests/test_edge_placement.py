"""Which side of a flat object lies across the table edge (sim/grasps.py ``edge_depth_cm``), shared by the
trial's world (sim/world.py) and the planner's edge moment (sim/planner.py)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from kb.features import ObjectRecord
from sim.grasps import EDGE_MIN_GRIP_IN_CM, EDGE_PAD_CLEAR_CM, edge_depth_cm, edge_overhang_cm
from sim.grip_force import edge_grip_force
from sim.planner import plan_grasps
from sim.trial import build_world


def _flat(name: str, a: float, b: float, c: float, mass: float) -> ObjectRecord:
    return ObjectRecord.create(
        name, a_cm=a, b_cm=b, c_cm=c, mass_g=mass, shape="thin", texture="smooth", material="metal",
        rigidity="rigid", fragility="sturdy",
    )  # fmt: skip


def test_a_side_too_short_to_overhang_under_the_pads_puts_the_length_across_the_edge():
    # 0.45 b - 0.9 cm of pad clearance must leave the pads 0.3 cm: b >= 2.67 cm.
    boundary = (EDGE_PAD_CLEAR_CM + EDGE_MIN_GRIP_IN_CM) / 0.45
    assert edge_overhang_cm(boundary) - EDGE_PAD_CLEAR_CM == pytest.approx(EDGE_MIN_GRIP_IN_CM)
    assert edge_depth_cm(10.0, 2.6) == 10.0  # a key, a ruler: slid out by their length
    assert edge_depth_cm(10.0, 2.7) == 2.7
    assert edge_depth_cm(8.56, 5.4) == 5.4  # a card: its length along the edge, the fingers spread along it


def _object_x_extent_cm(obj: ObjectRecord) -> float:
    plan = plan_grasps(obj)[0]
    world = build_world(obj, plan)
    assert world.approach == "edge"
    mujoco.mj_forward(world.model, world.data)
    geom = world.model.geom("object_geom").id
    rot = world.data.geom_xmat[geom].reshape(3, 3)
    return 2 * float(np.abs(rot[0]) @ world.model.geom_size[geom]) * 100  # along world x, across the edge


def test_world_lays_a_key_by_its_length_across_the_edge_and_a_card_by_its_width():
    key = _flat("key", 5.5, 2.3, 0.2, 7)
    card = _flat("card", 8.56, 5.4, 0.08, 5)
    assert _object_x_extent_cm(key) == pytest.approx(5.5)
    assert _object_x_extent_cm(card) == pytest.approx(5.4)


def test_planner_edge_moment_uses_the_side_across_the_edge():
    ruler = _flat("ruler", 30, 2.5, 0.1, 40)
    plan = plan_grasps(ruler)[0]
    across = edge_grip_force(40, 30, "sturdy")
    assert across > edge_grip_force(40, 2.5, "sturdy")
    assert plan.grip_force_n == pytest.approx(across, rel=0.05)
    assert any("flat: picked up at its edge" in line and "15 cm in" in line for line in plan.rationale)
