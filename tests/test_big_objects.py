"""Planner rules for large and heavy objects (planner version 10): a heavy box gets no power sphere, a
circular grasp (Cutkosky 1989); round bodies and light boxes keep it (sim/PLANNER.md, rule 2)."""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from sim.grasp_rules import HEAVY_MASS_G
from sim.planner import plan_grasps


def _rec(name, a, b, c, mass_g, shape="prism", material="other") -> ObjectRecord:
    return ObjectRecord.create(name, a_cm=a, b_cm=b, c_cm=c, mass_g=mass_g, shape=shape, material=material)


def _types(obj) -> list[str]:
    return [p.grasp_type for p in plan_grasps(obj)]


@pytest.mark.parametrize(("mass", "sphere"), [(HEAVY_MASS_G - 1, True), (HEAVY_MASS_G, False)])
def test_a_heavy_box_is_wrapped_not_cupped(mass, sphere):
    brick = _rec("brick", 21.5, 10.25, 7.0, mass)  # a square word: the simulator builds a box
    assert plan_grasps(brick)[0].params["program"] == "heavy_wrap"
    assert ("power_sphere" in _types(brick)) is sphere


def test_a_heavy_round_prism_keeps_the_power_sphere():
    bottle = _rec("water bottle", 21.5, 7.2, 7.2, 1000, material="metal")  # b = c: built as a cylinder
    assert "power_sphere" in _types(bottle)


def test_the_box_test_follows_the_body_not_the_name():
    # The same word, ratios of a round prism (b ~ c) without a square word: a cylinder, the sphere stays.
    assert "power_sphere" in _types(_rec("bleach bottle", 25, 10, 9, 1100))
    assert "power_sphere" not in _types(_rec("bleach bottle", 25, 10, 6.5, 1100))  # b, c apart: a box
