"""Planner version 17: a thin rod too heavy for a pen (50-250 g, at most 1 cm thick, a round or square
section) is held in the lateral pinch, intermediate (sim/PLANNER.md, "The mapping, the intermediate family
and ties"). Each boundary is pinned on both sides."""

from __future__ import annotations

import pytest

from sim.planner import plan_grasps


def _first(**kw) -> str:
    f = {"a_cm": 15.0, "b_cm": 1.0, "c_cm": 1.0, "mass_g": 130.0, "shape": "long"} | kw
    return plan_grasps(f, top=1)[0].grasp_type


def test_a_thin_rod_takes_the_side_of_the_index():
    plans = plan_grasps({"a_cm": 15.0, "b_cm": 1.0, "c_cm": 1.0, "mass_g": 130.0, "shape": "long"})
    assert (plans[0].grasp_type, plans[0].family) == ("lateral_pinch", "intermediate")
    assert "thin rod" in " ".join(plans[0].rationale)
    assert [p.family for p in plans[1:]] == ["precision", "power"]  # both other families are tried


@pytest.mark.parametrize(
    ("kw", "expected"),
    [
        ({"b_cm": 1.0, "c_cm": 1.0}, "lateral_pinch"),  # exactly 1 cm thick
        ({"b_cm": 1.05, "c_cm": 1.05}, "thumb_4_finger"),
        ({"mass_g": 50.0}, "lateral_pinch"),  # the pen rule's 50 g: no longer a pen
        ({"mass_g": 49.9}, "tripod"),  # a pen
        ({"mass_g": 249.9}, "lateral_pinch"),
        ({"mass_g": 250.0}, "heavy_wrap_small_diameter"),  # the power boundary
        ({"c_cm": 0.8}, "lateral_pinch"),  # section at 0.8 of its width: round or square
        ({"c_cm": 0.79}, "thumb_4_finger"),  # a strip, not a rod
        ({"shape": "prism"}, "thumb_4_finger"),
    ],
)
def test_rod_boundaries(kw, expected):
    assert _first(**kw) == expected
