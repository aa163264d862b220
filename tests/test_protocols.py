"""The two validation protocols (sim/protocols.py), each success condition pinned at its boundary, on real
MuJoCo trials of objects written here (tests/test_success_rule.py's bottle and book)."""

from __future__ import annotations

import json

import pytest
from test_success_rule import BOOK, BOTTLE, _plan
from typer.testing import CliRunner

import sim.trial as trial_mod
from kb.catalog import KnowledgeBase
from kb.errors import SimulationError
from kb.service.cli import app
from sim.hand import HAND_VERSION
from sim.protocols import DEFAULT_PROTOCOL, LIFT_PUSH, PROTOCOLS, SIX_DIRECTION, protocol_named
from sim.trial import PERTURBATION_DIRECTIONS, run_six_direction_trial, run_trial
from sim.worker import validate

WRAP = "heavy_wrap_large_diameter"


def test_thresholds_at_their_boundaries_each_alone():
    assert DEFAULT_PROTOCOL == "lift_push" and set(PROTOCOLS) == {"lift_push", "six_direction"}
    assert (LIFT_PUSH.max_translation_cm, LIFT_PUSH.max_rotation_deg) == (5.0, 15.0)
    assert (SIX_DIRECTION.max_translation_cm, SIX_DIRECTION.max_rotation_deg) == (10.0, 180.0)  # DexGraspBench's
    for p in PROTOCOLS.values():
        t, r = p.max_translation_cm, p.max_rotation_deg
        assert not p.beyond(0.0, 0.0)
        assert p.beyond(t, 0.0) and not p.beyond(t - 1e-9, 0.0)
        assert p.beyond(0.0, r) and not p.beyond(0.0, r - 1e-9)
        assert not p.beyond(t - 1e-9, r - 1e-9)  # neither alone: holds
    assert SIX_DIRECTION.independent and not LIFT_PUSH.independent
    assert SIX_DIRECTION.raise_m == 0.10 and LIFT_PUSH.raise_m == 0.0
    assert LIFT_PUSH.version_tag == "" and SIX_DIRECTION.version_tag


def test_an_unknown_protocol_is_refused_with_the_known_ones():
    with pytest.raises(SimulationError, match="lift_push, six_direction"):
        protocol_named("shake")
    with pytest.raises(SimulationError, match="unknown validation protocol 'shake'"):
        run_trial(BOTTLE, _plan(WRAP, 8.5, 10.0), protocol="shake")
    result = CliRunner().invoke(app, ["grasp", "validate", "--all", "--protocol", "shake", "--db", "/nonexistent"])
    assert result.exit_code == 1 and "unknown validation protocol" in result.output
    assert "Traceback" not in result.output


@pytest.mark.slow
def test_a_slip_past_10_cm_fails_six_direction_in_that_direction_alone():
    """8 N round the 600 g glass bottle: every push holds but -z (its weight on top of gravity), where it
    slides out of the wrap; translation alone fails it (rotation under both protocols' limits)."""
    r = run_trial(BOTTLE, _plan(WRAP, 8.5, 8.0), seed=0, protocol="six_direction")
    assert r.protocol == "six_direction" and r.hand_version == HAND_VERSION + SIX_DIRECTION.version_tag
    assert r.lifted and r.outcome == "failure" and "during the -z push" in r.reason, r.reason
    assert r.failed_directions == ["-z"]
    assert list(r.perturbation) == list(PERTURBATION_DIRECTIONS)
    assert r.slip_cm >= SIX_DIRECTION.max_translation_cm and r.rotation_deg < LIFT_PUSH.max_rotation_deg


@pytest.mark.slow
def test_a_slip_between_5_and_10_cm_fails_lift_push_and_passes_six_direction():
    today = run_trial(BOTTLE, _plan(WRAP, 8.5, 10.0), seed=0)
    assert today.protocol == "lift_push" and today.hand_version == HAND_VERSION
    assert today.outcome == "failure" and today.reason.startswith("slipped"), today.reason
    six = run_trial(BOTTLE, _plan(WRAP, 8.5, 10.0), seed=0, protocol="six_direction")
    assert six.success, six.reason
    assert LIFT_PUSH.max_translation_cm <= six.slip_cm < SIX_DIRECTION.max_translation_cm
    assert six.failed_directions == []


@pytest.mark.slow
def test_a_turn_past_15_deg_fails_lift_push_and_passes_six_direction():
    """The 600 g book pinched with 12 N at the table edge turns past 15 degrees under the -z push, hardly
    moving: rotation is not judged under DexGraspBench's 180 degree threshold."""
    today = run_trial(BOOK, _plan("thumb_4_finger", 4.0, 12.0), seed=0)
    assert today.outcome == "failure" and today.reason.startswith("turned"), today.reason
    six = run_six_direction_trial(BOOK, _plan("thumb_4_finger", 4.0, 12.0), seed=0)
    assert six.success and six.protocol == "six_direction", six.reason
    assert six.rotation_deg >= LIFT_PUSH.max_rotation_deg and six.slip_cm < LIFT_PUSH.max_translation_cm


@pytest.mark.slow
def test_not_lifted_fails_six_direction_too():
    r = run_trial(BOTTLE, _plan(WRAP, 8.5, 5.0), seed=0, protocol="six_direction")
    assert not r.lifted and r.outcome == "failure" and r.reason.startswith("not lifted"), r.reason
    assert r.perturbation == {}


@pytest.mark.slow
def test_six_direction_pushes_each_direction_from_the_same_held_state(monkeypatch):
    """The order of the directions changes nothing under six_direction (each starts again from the exact
    held state); under lift_push, where the pushes follow one another, it does."""
    plan = _plan(WRAP, 8.5, 10.0)
    six = run_trial(BOTTLE, plan, seed=0, protocol="six_direction").perturbation
    today = run_trial(BOTTLE, plan, seed=0).perturbation
    reversed_order = dict(reversed(list(PERTURBATION_DIRECTIONS.items())))
    monkeypatch.setattr(trial_mod, "PERTURBATION_DIRECTIONS", reversed_order)
    six_rev = run_trial(BOTTLE, plan, seed=0, protocol="six_direction").perturbation
    today_rev = run_trial(BOTTLE, plan, seed=0).perturbation
    assert list(six_rev) == list(reversed_order)
    assert {d: six_rev[d] for d in six} == six
    assert any(today_rev.get(d) != v for d, v in today.items())


@pytest.mark.slow
def test_validate_stores_each_protocol_apart(tmp_path):
    csv = tmp_path / "objects.csv"
    csv.write_text("name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\n"
                   "small cube,5,5,5,100,compact,medium,sturdy,wood,rigid\n")  # fmt: skip
    kb = KnowledgeBase.open(tmp_path / "kb.duckdb")
    kb.import_csv(csv)
    today = validate(kb, None, top=1, executor="serial", progress=False, render=None)
    six = validate(kb, None, top=1, executor="serial", progress=False, render=None, protocol="six_direction")
    assert today.ran == 1 and six.ran == 1 and six.skipped == 0  # not mistaken for today's stored result
    assert six.hand_version == HAND_VERSION + SIX_DIRECTION.version_tag and today.hand_version == HAND_VERSION
    details = json.loads(six.results[0]["details"])
    assert details["protocol"] == "six_direction" and "failed_directions" in details
    again = validate(kb, None, top=1, executor="serial", progress=False, render=None, protocol="six_direction")
    assert again.ran == 0 and again.skipped == 1
    with pytest.raises(SimulationError):
        validate(kb, None, top=1, executor="serial", progress=False, render=None, protocol="shake")
    stored = {r["hand_version"] for r in KnowledgeBase.open(tmp_path / "kb.duckdb", read_only=True).grasp_results()}
    assert stored == {HAND_VERSION, HAND_VERSION + SIX_DIRECTION.version_tag}
