"""Validation worker: objects x grasps x seeds through an executor, stored in a real DuckDB, resumable.

Most tests inject a trivial trial function through the worker's ``trial`` parameter (dependency
injection: the worker's own contract), so they exercise scheduling, storage and resume quickly; the
end-to-end test at the bottom runs the real MuJoCo trial.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from kb.catalog import KnowledgeBase
from kb.errors import ObjectNotFound, PhysicsError
from sim.executors import LocalProcessExecutor, SerialExecutor, make_executor
from sim.worker import validate

CSV = """name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity
tv remote,16,3.5,2,110,long,medium,medium,plastic,rigid
tennis ball,6.4,6.4,6.4,56,radial,rough,medium,fabric,squeezable
water bottle,21.5,7.2,7.2,660,prism,smooth,sturdy,metal,rigid
"""
HAND = "test-hand-1"
LOG_ENV = "OBJRECALL_TEST_TRIAL_LOG"


def fake_trial(obj, plan, *, seed=0):
    """A trivial trial: power grasps succeed, others fail; logs each call to count the work done."""
    log = os.environ.get(LOG_ENV)
    if log:
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(f"{obj.name}|{plan.grasp_type}|{seed}\n")
    ok = plan.family == "power"
    return {
        "object_name": obj.name,
        "grasp_type": plan.grasp_type,
        "outcome": "success" if ok else "failure",
        "success": ok,
        "reason": None if ok else "slipped",
        "slip_cm": 0.5 + seed,
        "rotation_deg": 2.0,
        "grip_force_n": plan.grip_force_n,
        "max_contact_force_n": 3 * plan.grip_force_n,
        "lifted": True,
        "perturbation": {"+z": 0.1},
        "sim_time_s": 3.0,
        "simulator": "fake",
    }


def diverging_trial(obj, plan, *, seed=0):
    raise PhysicsError("simulation diverged (NaN in qacc)")


def buggy_trial(obj, plan, *, seed=0):
    raise ZeroDivisionError("division by zero")


@pytest.fixture
def kb(tmp_path):
    csv = tmp_path / "objects.csv"
    csv.write_text(CSV)
    kb = KnowledgeBase.open(tmp_path / "kb.duckdb")
    kb.import_csv(csv)
    return kb


@pytest.fixture
def trial_log(tmp_path, monkeypatch):
    log = tmp_path / "calls.log"
    monkeypatch.setenv(LOG_ENV, str(log))
    return log


def calls(log: Path) -> list[str]:
    return log.read_text().splitlines() if log.exists() else []


def run(kb, names=None, **kw):
    kw.setdefault("executor", SerialExecutor())
    kw.setdefault("trial", fake_trial)
    kw.setdefault("render", None)
    kw.setdefault("progress", False)
    kw.setdefault("hand_version", HAND)
    return validate(kb, names, **kw)


def test_validates_objects_times_top_grasps_and_stores_every_result(kb, trial_log):
    summary = run(kb, ["tv remote", "tennis ball"], top=3, seeds=[0, 1])
    assert summary.objects == 2
    assert summary.trials == summary.ran == 2 * 3 * 2
    assert summary.succeeded + summary.failed == summary.ran and summary.errors == 0
    stored = kb.grasp_results()
    assert len(stored) == 12
    row = next(r for r in stored if r["object_name"] == "tennis ball" and r["rank"] == 0 and r["seed"] == 1)
    assert row["grasp_type"] == "power_sphere" and row["family"] == "power"
    assert row["success"] is True and row["outcome"] == "success"
    assert row["slip_cm"] == 1.5 and row["simulator"] == "fake" and row["hand_version"] == HAND
    assert row["planner_version"] and row["features_hash"] and row["object_id"] is not None
    details = json.loads(row["details"])
    assert details["plan"]["grasp_type"] == "power_sphere" and details["perturbation"] == {"+z": 0.1}
    assert {r["shape"] for r in summary.results} == {"long", "radial"}


def test_all_objects_and_aliases(kb, trial_log):
    summary = run(kb, "all", top=1)
    assert summary.objects == 3 and summary.ran == 3
    with pytest.raises(ObjectNotFound):
        run(kb, ["no such thing"])


def test_interrupted_run_resumes_without_repeating_work(kb, trial_log):
    first = run(kb, None, top=2, limit=4)
    assert first.ran == 4 and len(kb.grasp_results()) == 4
    second = run(kb, None, top=2)
    assert second.skipped == 4 and second.ran == 2
    third = run(kb, None, top=2)
    assert third.ran == 0 and third.skipped == 6
    done = calls(trial_log)
    assert len(done) == 6 and len(set(done)) == 6, "no trial ran twice"
    assert len(third.results) == 6 and len(kb.grasp_results()) == 6


def test_changed_features_or_hand_rerun_the_trials(kb, trial_log, tmp_path):
    run(kb, ["tv remote"], top=1)
    csv = tmp_path / "changed.csv"
    csv.write_text(CSV.splitlines()[0] + "\ntv remote,16,3.5,2,150,long,medium,medium,plastic,rigid\n")
    kb.import_csv(csv)
    assert run(kb, ["tv remote"], top=1).ran == 1  # new features hash
    assert run(kb, ["tv remote"], top=1, hand_version="test-hand-2").ran == 1
    assert run(kb, ["tv remote"], top=1).ran == 0
    assert len(calls(trial_log)) == 3


def test_diverged_simulation_is_stored_as_an_error_never_a_success(kb):
    summary = run(kb, ["water bottle"], top=1, trial=diverging_trial)
    assert summary.errors == 1 and summary.succeeded == 0
    (row,) = kb.grasp_results("water bottle")
    assert row["outcome"] == "error" and row["success"] is False and "diverged" in row["reason"]


def test_unexpected_exception_is_reported_not_stored(kb):
    summary = run(kb, ["water bottle"], top=1, trial=buggy_trial)
    assert summary.errors == 1 and summary.not_stored == 1
    assert kb.grasp_results() == []
    assert "ZeroDivisionError" in summary.results[0]["reason"] if summary.results else True


def test_results_are_flushed_in_batches_while_running(kb, trial_log):
    seen: list[int] = []

    class Spy(SerialExecutor):
        def map(self, fn, items):
            for result in super().map(fn, items):
                seen.append(len(kb.grasp_results()))
                yield result

    run(kb, None, top=3, executor=Spy(), flush_every=2, flush_seconds=1e9)
    assert seen[0] == 0 and max(seen) >= 6, "earlier results were stored before the run ended"
    assert len(kb.grasp_results()) == 9


def test_process_pool_matches_serial_run(kb, trial_log, tmp_path):
    serial = {(r["object_name"], r["grasp_type"]): r["outcome"] for r in run(kb, None, top=3).results}
    other = KnowledgeBase.open(tmp_path / "other.duckdb")
    other.import_csv(tmp_path / "objects.csv")
    with LocalProcessExecutor(2) as pool:
        parallel = run(other, None, top=3, executor=pool)
    assert parallel.workers == 2
    assert {(r["object_name"], r["grasp_type"]): r["outcome"] for r in parallel.results} == serial


def test_make_executor_names():
    assert isinstance(make_executor("local", workers=1), SerialExecutor)
    pool = make_executor("local", workers=2)
    assert isinstance(pool, LocalProcessExecutor) and pool.workers == 2
    pool.close()
    with pytest.raises(Exception, match="unknown executor"):
        make_executor("carrier-pigeon")


@pytest.mark.slow  # starting Ray takes 10-30 s
def test_ray_executor_on_a_local_ray(kb, trial_log):
    ray = pytest.importorskip("ray", reason="Ray is an optional extra (pip install 'objrecall[ray]')")
    from sim.executors import RayExecutor

    tests_dir = str(Path(__file__).parent)
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        runtime_env={
            "env_vars": {"PYTHONPATH": os.pathsep.join([tests_dir, os.environ.get("PYTHONPATH", "")])}
        },
    )
    try:
        with RayExecutor() as ex:
            assert ex.workers == 2
            summary = run(kb, None, top=2, executor=ex)
        assert summary.ran == 6 and len(kb.grasp_results()) == 6
        assert len(set(calls(trial_log))) == 6
    finally:
        ray.shutdown()


def test_real_trials_are_deterministic_per_seed(kb, tmp_path):
    """The real MuJoCo trial through the worker: the same seed gives the same stored numbers."""
    other = KnowledgeBase.open(tmp_path / "again.duckdb")
    other.import_csv(tmp_path / "objects.csv")
    fields = ("grasp_type", "outcome", "slip_cm", "rotation_deg", "max_contact_force_n", "simulator")
    runs = []
    for target in (kb, other):
        summary = validate(
            target, ["tennis ball"], top=1, executor=SerialExecutor(), render=None, progress=False
        )
        assert summary.ran == 1 and summary.not_stored == 0
        runs.append([tuple(r[f] for f in fields) for r in target.grasp_results()])
    assert runs[0] == runs[1]
    assert runs[0][0][5].startswith("mujoco")
