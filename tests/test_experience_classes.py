"""Experience classes (sim/experience.py ``object_class``): a tiny flat thing (the planner's tip-pinch row,
sim.grasp_rules ``is_tiny_flat``) is its own class, so coins' trials do not reorder a key's grasps."""

from __future__ import annotations

import pytest

from sim.experience import TINY_SUFFIX, Experience, Outcome, object_class
from sim.grasp_rules import TIP_PINCH_MAX_LENGTH_CM
from sim.planned_object import resolve_features
from sim.planner import plan_grasps

COIN = dict(name="one euro coin", a_cm=2.325, b_cm=2.325, c_cm=0.233, mass_g=7.5, shape="thin", material="metal")
KEY = dict(name="house key", a_cm=5.5, b_cm=2.3, c_cm=0.2, mass_g=7, shape="thin", material="metal",
           texture="smooth", fragility="sturdy")  # fmt: skip


def _klass(**kw) -> str:
    return object_class(resolve_features(kw))


def test_a_coin_is_tiny_metal_and_a_key_plain_thin_metal():
    assert _klass(**COIN) == "thin/metal" + TINY_SUFFIX
    assert _klass(**KEY) == "thin/metal"


@pytest.mark.parametrize(("a_cm", "tiny"), [(TIP_PINCH_MAX_LENGTH_CM, True), (TIP_PINCH_MAX_LENGTH_CM + 0.1, False)])
def test_the_tiny_class_ends_at_the_tip_pinch_length(a_cm, tiny):
    assert _klass(**{**COIN, "a_cm": a_cm, "b_cm": 2.3}).endswith(TINY_SUFFIX) is tiny


@pytest.mark.parametrize(("c_cm", "mass_g", "tiny"), [(1.0, 7.5, True), (1.1, 7.5, False), (0.2, 100.0, True),
                                                       (0.2, 100.1, False)])  # fmt: skip
def test_the_tiny_class_needs_the_tip_pinch_rows_thickness_and_mass(c_cm, mass_g, tiny):
    assert _klass(**{**COIN, "b_cm": 3.0, "c_cm": c_cm, "mass_g": mass_g}).endswith(TINY_SUFFIX) is tiny


def test_coins_held_by_the_tip_pinch_do_not_promote_it_over_a_keys_lateral_pinch():
    """The seed catalog's outcomes (data written here): both coins and the paper clip held in the thumb-index
    pinch and not in the lateral pinch; the steel ruler (thin metal, 30 cm) in both."""
    tiny, thin = "thin/metal" + TINY_SUFFIX, "thin/metal"
    seen = [Outcome(n, p, tiny, r, ok) for n in ("coin", "quarter", "clip")
            for p, r, ok in (("thumb_index_finger", 0, True), ("lateral_pinch", 1, False))]  # fmt: skip
    seen += [Outcome("ruler", "lateral_pinch", thin, 0, True), Outcome("ruler", "thumb_index_finger", thin, 2, True)]
    rules = [p.grasp_type for p in plan_grasps(KEY)]
    assert rules[:2] == ["lateral_pinch", "thumb_index_finger"]
    assert [p.grasp_type for p in plan_grasps(KEY, experience=Experience.learn(seen))] == rules
    # lumped in one class (before), the same trials promoted the tip pinch
    lumped = Experience.learn(Outcome(o.object_name, o.program, thin, o.rank, o.holds) for o in seen)
    assert plan_grasps(KEY, experience=lumped)[0].grasp_type == "thumb_index_finger"
