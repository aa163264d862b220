"""First choice from experience (sim/experience.py): counts per (program, object class), a prior that keeps
the rules' order for an unseen class, a switch only at the margin, leave-one-object-out measurement."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.errors import SimulationError
from sim.experience import (
    SWITCH_MARGIN,
    WINDOW,
    Experience,
    Outcome,
    leave_one_object_out,
    object_class,
    outcomes,
)
from sim.planned_object import resolve_features
from sim.planner import plan_grasps

K = "thin/paper"


def _exp(**counts):
    return Experience({(p, K): hc for p, hc in counts.items()})


def test_an_unseen_class_keeps_the_rules_order():
    assert Experience().pick(["a", "b", "c"], K) == 0
    assert _exp(b=(9, 9)).pick(["a", "b"], "radial/glass") == 0
    assert Experience().estimate("a", K) == 0.5


def test_a_later_candidate_goes_first_only_at_the_margin():
    # a: 0 of 1 -> 1/3; b: 10 of 13 -> 11/15, exactly 0.4 above: switch; 9 of 12 -> 10/14: not enough
    assert SWITCH_MARGIN == 0.4
    assert _exp(a=(0, 1), b=(10, 13)).pick(["a", "b"], K) == 1
    assert _exp(a=(0, 1), b=(9, 12)).pick(["a", "b"], K) == 0
    # and the other way round never switches (a later one estimated lower)
    assert _exp(a=(10, 13), b=(0, 1)).pick(["a", "b"], K) == 0


def test_the_pick_is_compared_with_the_current_pick_not_only_the_first():
    # b beats a by the margin; c beats a but not b by it: b stays
    e = _exp(a=(0, 4), b=(4, 4), c=(5, 6))
    assert e.pick(["a", "b", "c"], K) == 1
    # c beats b by the margin too: c
    assert _exp(a=(0, 4), b=(2, 4), c=(20, 20)).pick(["a", "b", "c"], K) == 2


def test_only_the_validated_window_is_reordered():
    assert WINDOW == 3
    e = _exp(a=(0, 9), b=(0, 9), c=(0, 9), d=(9, 9))
    assert e.pick(["a", "b", "c", "d"], K) == 0
    assert e.pick(["a", "b", "d"], K) == 2


def _rows(obj, *cands, seeds=(0,)):
    return [{"object_name": obj, "grasp_type": gt, "rank": r, "seed": s, "success": ok,
             "outcome": "success" if ok else "failure"}
            for r, (gt, ok) in enumerate(cands) for s in seeds]  # fmt: skip


def test_outcomes_merge_seeds_and_programs_and_name_a_missing_class():
    rows = _rows("box", ("thumb_2_finger", True), ("heavy_wrap_small_diameter", True), seeds=(0, 1))
    rows[1]["success"] = False  # thumb_2_finger failed in seed 1
    rows.append({**rows[2], "outcome": "error"})  # an error never holds
    got = outcomes(rows, {"box": K})
    assert [(o.program, o.rank, o.holds) for o in got] == [("thumb_2_finger", 0, False), ("heavy_wrap", 1, False)]
    with pytest.raises(SimulationError, match="'box'"):
        outcomes(rows, {})


def test_leave_one_object_out_never_uses_the_objects_own_trials():
    a, b = "lateral_pinch", "thumb_2_finger"
    one = outcomes(_rows("x", (a, False), (b, True)), {"x": K})
    m = leave_one_object_out(one)  # its own trials alone would switch it: they are left out
    assert (m.with_hold, m.rules_first_holds, m.first_holds, m.changed) == (1, 0, 0, ())
    rows = _rows("x", (a, False), (b, True)) + _rows("y", (a, False), (b, True)) + _rows("z", (a, False), (b, True))
    m = leave_one_object_out(outcomes(rows, dict.fromkeys("xyz", K)))
    # for each: others' a 0 of 2 (0.25), b 2 of 2 (0.75): switched, and b holds
    assert (m.objects, m.with_hold, m.rules_first_holds, m.first_holds) == (3, 3, 0, 3)
    assert m.changed[0] == ("x", a, b, True)
    assert m.to_dict()["share_of_with_hold"] == 1.0
    # objects with no holding candidate count in objects but not in with_hold
    rows += _rows("w", (a, False), (b, False))
    m = leave_one_object_out(outcomes(rows, dict.fromkeys("xyzw", K)))
    assert (m.objects, m.with_hold, m.first_holds) == (4, 3, 3)


def test_save_load_and_bad_files(tmp_path):
    e = _exp(a=(1, 3), b=(0, 2))
    path = e.save(tmp_path / "exp.json")
    assert Experience.load(path) == e
    assert Experience.load(tmp_path / "missing.json") == Experience()
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(SimulationError, match="bad.json"):
        Experience.load(tmp_path / "bad.json")
    for row in ({"program": "a", "object_class": K, "held": 3, "tried": 2},
                {"program": "a", "object_class": K, "held": -1, "tried": 2},
                {"program": "a", "object_class": K, "held": "x", "tried": 2}, {"held": 1, "tried": 2}):  # fmt: skip
        with pytest.raises(SimulationError, match="experience count"):
            Experience.from_dict({"counts": [row]})
    assert Experience.from_dict({"counts": [{"program": "a", "object_class": K, "held": 2, "tried": 2}]}).counts


def test_the_planner_puts_the_experience_pick_first_and_says_why():
    remote = {"name": "tv remote", "a_cm": 16, "b_cm": 3.5, "c_cm": 2, "mass_g": 110, "shape": "long",
              "material": "plastic"}  # fmt: skip
    rules = plan_grasps(remote)
    klass = object_class(resolve_features(remote))
    from sim.programs import program_for

    p0, p1 = (program_for(p.grasp_type).name for p in rules[:2])
    e = Experience({(p0, klass): (0, 5), (p1, klass): (5, 5)})
    got = plan_grasps(remote, experience=e)
    assert [p.grasp_type for p in got] == [rules[1].grasp_type, rules[0].grasp_type] + [p.grasp_type for p in rules[2:]]
    assert "experience:" in got[0].rationale[-1] and "held 5 of 5" in got[0].rationale[-1]
    assert plan_grasps(remote, experience=Experience()) == rules
    assert plan_grasps(remote, top=1, experience=e)[0].grasp_type == rules[1].grasp_type


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=1, max_size=5))
def test_pick_is_in_the_window_and_beats_the_first_by_the_margin(spec):
    counts = {(f"p{i}", K): (min(h, t), t) for i, (h, t) in enumerate(spec)}
    e = Experience(counts)
    programs = [f"p{i}" for i in range(len(spec))]
    j = e.pick(programs, K)
    assert 0 <= j < min(WINDOW, len(programs))
    if j:
        assert e.estimate(programs[j], K) >= e.estimate(programs[0], K) + SWITCH_MARGIN - 1e-9
    else:
        assert all(e.estimate(p, K) < e.estimate(programs[0], K) + SWITCH_MARGIN - 1e-9 for p in programs[1:WINDOW])
    # the object's own outcomes removed again give the counts before
    own = [Outcome("o", p, K, i, True) for i, p in enumerate(programs)]
    assert Experience.learn(own).without(own).counts == dict.fromkeys(Experience.learn(own).counts, (0, 0))
    json.dumps(e.to_dict())
