"""The pictures show the grasp (sim/render.py): with the pictures' camera, both the hand and the object fill
a visible part of the frame for each kind of approach and body (a segmentation render counts the pixels)."""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from sim.planner import plan_grasps
from sim.render import visible_fractions
from sim.trial import run_trial
from sim.world import build_world

#: Each of hand and object covers at least this fraction of the frame (1.5 % of 480 x 360 is 2,600 pixels).
MIN_VISIBLE = 0.015

OBJECTS = [
    ObjectRecord.create("coffee mug", a_cm=12, b_cm=9.5, c_cm=8.2, mass_g=330, shape="prism", material="other"),
    ObjectRecord.create("frying pan", a_cm=48, b_cm=28, c_cm=5, mass_g=1200, shape="thin", material="metal"),
    ObjectRecord.create("hardcover book", a_cm=24, b_cm=16, c_cm=3, mass_g=700, shape="thin", material="paper"),
    ObjectRecord.create("tennis ball", a_cm=6.4, b_cm=6.4, c_cm=6.4, mass_g=57, shape="radial", material="rubber"),
    ObjectRecord.create("glazed ceramic teapot", a_cm=22, b_cm=15, c_cm=14, mass_g=900, material="other"),
]


@pytest.mark.parametrize("obj", OBJECTS, ids=lambda o: o.name)
def test_the_hand_and_the_object_are_both_in_the_picture(obj):
    plan = plan_grasps(obj, top=1)[0]
    world = build_world(obj, plan)
    run_trial(obj, plan, stop_after="hold", world=world)
    seen = visible_fractions(world)
    assert seen["hand"] >= MIN_VISIBLE, (plan.grasp_type, world.approach, seen)
    assert seen["object"] >= MIN_VISIBLE, (plan.grasp_type, world.approach, seen)
