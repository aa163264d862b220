"""Hand programs (sim/programs.py): one per grasp type or honestly merged; distinct ones act differently."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import GRASP_TYPES, GraspPlan, active_fingers
from sim.planner import plan_grasps
from sim.programs import PROGRAMS, merged_types, program_for
from sim.trial import run_trial


def _plan(program, aperture: float = 7.5, force: float = 6.0) -> GraspPlan:
    t = program.grasp_types[0]
    return GraspPlan(t, GRASP_TYPES[t], "c", aperture, program.approach, force, 1.0)


def test_every_grasp_type_has_one_program_and_merges_are_named():
    names = [p.name for p in PROGRAMS]
    assert len(names) == len(set(names))
    assert sorted(t for p in PROGRAMS for t in p.grasp_types) == sorted(GRASP_TYPES)
    for t in GRASP_TYPES:
        p = program_for(t)
        assert p.fingers == active_fingers(t)  # the planner's capacity counts the same fingers
        assert p.basis and p.preshape and p.synergy and p.contacts
        assert t not in merged_types(t)
    assert set(merged_types("heavy_wrap_large_diameter")) == {"heavy_wrap_small_diameter"}
    assert set(merged_types("precision_sphere")) == {"precision_disk"}
    assert set(merged_types("light_tool")) == {"adducted_thumb"}
    assert merged_types("tripod") == () and merged_types("thumb_2_finger") == ()
    with pytest.raises(ValueError, match="unknown grasp type"):
        program_for("fist_bump")


def test_distinct_programs_have_distinct_joint_targets_for_the_same_object():
    """Pure kinematics: pre-shape or closing targets or torque limits differ for every pair."""
    sigs = {}
    for p in PROGRAMS:
        tg = H.grasp_targets(_plan(p), 5.5)
        sigs[p.name] = (p.approach, p.palm_gap_cm, tuple(np.round(tg.open, 4)), tuple(np.round(tg.close, 4)),
                        tuple(np.round(tg.touch, 4)), tuple(sorted(tg.torque_limits.items())))
    for a, b in itertools.combinations(sigs, 2):
        assert sigs[a] != sigs[b], f"{a} and {b} would move the hand identically"


def test_planner_lists_a_merged_program_once_and_says_so():
    # a heavy bottle: heavy wrap large diameter first; heavy wrap small diameter (same program) not repeated
    bottle = {"a_cm": 25, "b_cm": 7, "c_cm": 7, "mass_g": 900, "shape": "prism", "material": "glass"}
    plans = plan_grasps(bottle)
    programs = [p.params["program"] for p in plans]
    assert len(programs) == len(set(programs))
    first = plans[0]
    assert first.grasp_type == "heavy_wrap_large_diameter"
    assert any("shared with heavy wrap small diameter" in r for r in first.rationale)
    for p in plans:
        assert p.approach == program_for(p.grasp_type).approach


@pytest.mark.slow
def test_distinct_programs_give_distinct_trajectories_on_the_same_object():
    """Every program on one 5.5 cm, 200 g box: the closed postures and the measured results all differ."""
    box = ObjectRecord(name="test box", a_cm=9.0, b_cm=6.5, c_cm=5.5, mass_g=200.0, shape="prism",
                       material="plastic")
    results = {p.name: run_trial(box, _plan(p), seed=0) for p in PROGRAMS}
    for name, r in results.items():
        assert r.program == name and r.outcome != "error", r.reason
    for a, b in itertools.combinations(results, 2):
        ra, rb = results[a], results[b]
        assert ra.closed_posture != rb.closed_posture, f"{a} and {b} closed identically"
        assert (ra.slip_cm, ra.rotation_deg, ra.grip_force_n) != (rb.slip_cm, rb.rotation_deg, rb.grip_force_n)


@pytest.mark.slow
def test_no_two_programs_give_identical_results_on_any_seed_object(seeded_db):
    """The seed catalog (data written here), each object's top 3 candidates (distinct programs by the
    planner's construction): no two give the same numbers and closed posture (two that never touch the
    object differ in where the fingers closed). Runs ~500 trials on 2 workers: a few minutes."""
    from kb.catalog import KnowledgeBase
    from sim.report import row_details as _details
    from sim.worker import validate

    summary = validate(KnowledgeBase.open(seeded_db), None, top=3, workers=2, progress=False, render=None)
    assert summary.errors == 0
    by_object: dict[str, list[dict]] = {}
    for r in summary.results:
        by_object.setdefault(r["object_name"], []).append(r)
    assert len(by_object) == summary.objects >= 150
    for name, rows in by_object.items():
        programs = [program_for(r["grasp_type"]).name for r in rows]
        assert len(programs) == len(set(programs)), name
        keys = [
            (r["outcome"], r["reason"], r["slip_cm"], r["rotation_deg"], r["grip_force_n"],
             tuple(_details(r).get("closed_posture") or ()))
            for r in rows
        ]  # fmt: skip
        for a, b in itertools.combinations(range(len(rows)), 2):
            assert keys[a] != keys[b], f"{name}: {rows[a]['grasp_type']} and {rows[b]['grasp_type']} identical"
    s = summary.choice_summary
    assert s.objects == summary.objects and s.first_holds <= s.validated <= s.objects
    assert s.differs >= s.validated - s.first_holds
