"""Simulation benchmarks: single trials (physics part) and the validation worker (workers part).

Run: ``python benchmarks/sim_bench.py [--quick] [--only trials|workers|choice|protocols] [--top N] [--repeat N] [--save]``. Prints ratios
against a baseline measured in the same run (no absolute thresholds): trials per second on one and on two
worker processes, the wall time of validating the whole seed catalog's best grasps (planner -> trial ->
knowledge base), and the closed-loop choice (issue 14): objects with a validated grasp, first-choice
success (the rules' and, leave-one-object-out, the experience's: sim/experience.py), how often they differ and trials per CPU second, beside the figures before that issue and at the
start of this session; ``protocols`` runs both validation protocols (sim/protocols.py), today's as the
baseline, with their failures by push direction and cause. ``--save`` (a full-catalog run) saves the choice row for the README (benchmarks/results).
The choice and protocols parts are in benchmarks/sim_validation.py.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from sim_validation import bench_choice, bench_protocols, save_choice, seed_records


def bench_workers(workers: tuple[int, ...] = (1, 2), *, limit: int | None = None) -> dict[str, Any]:
    """Validate the best grasp of every seed catalog object (one seed) into a fresh knowledge base with
    ``n`` local worker processes, for each ``n`` in ``workers``; the first is the baseline."""
    from kb.catalog import KnowledgeBase
    from sim.executors import LocalProcessExecutor
    from sim.worker import validate

    records = seed_records()[:limit] if limit else seed_records()
    out: dict[str, Any] = {"objects": len(records), "runs": []}
    with tempfile.TemporaryDirectory() as tmp:
        csv = Path(tmp) / "catalog.csv"
        from kb.csvio import write_catalog_csv

        write_catalog_csv(records, csv)
        base = None
        for n in workers:
            kb = KnowledgeBase.open(Path(tmp) / f"w{n}.duckdb")
            kb.import_csv(csv)
            start = time.perf_counter()
            with LocalProcessExecutor(n) as pool:
                summary = validate(kb, None, top=1, executor=pool, progress=False, render=None)
            wall = time.perf_counter() - start
            details = [json.loads(r["details"]) for r in summary.results]
            sim_time = sum(float(d.get("sim_time_s") or 0.0) for d in details)
            cpu_time = sum(float(d.get("cpu_time_s") or 0.0) for d in details)
            base = base or wall
            run = {
                "workers": n,
                "trials": summary.ran,
                "wall_s": round(wall, 2),
                "trials_per_s": round(summary.ran / wall, 2),
                "speedup_vs_1": round(base / wall, 2),
                "sim_to_wall": round(sim_time / wall, 2),
                "trial_cpu_s": round(cpu_time, 2),
                "cpu_bound_wall_s": round(cpu_time / n, 2),
                "load_avg_1min": round(os.getloadavg()[0], 2),
                "success": summary.succeeded,
                "failure": summary.failed,
                "error": summary.errors,
            }
            out["runs"].append(run)
            print(
                f"workers={n}: {run['trials']} best-grasp trials in {run['wall_s']} s "
                f"({run['trials_per_s']} trials/s, x{run['speedup_vs_1']} vs 1 worker, "
                f"simulated/wall {run['sim_to_wall']}); {run['success']} success, {run['failure']} failure, "
                f"{run['error']} error; trials used {run['trial_cpu_s']} CPU s "
                f"(= {run['cpu_bound_wall_s']} s on {n} idle core(s)); load average {run['load_avg_1min']}",
                flush=True,
            )
    return out


def best_plans(limit: int | None = None) -> list[tuple[Any, Any]]:
    """(record, best plan) for the seed catalog's objects, in catalog order."""
    from sim.planner import best_grasp

    records = seed_records()[:limit] if limit else seed_records()
    return [(r, best_grasp(r)) for r in records]


def bench_raw_steps(pairs: list[tuple[Any, Any]], steps: int = 1000) -> dict[str, Any]:
    """Baseline: MuJoCo alone stepping the same trial worlds (hand pre-shaped over the object, no control
    or measurement in Python), ``steps`` steps each."""
    import mujoco

    from sim.trial import build_world

    total_steps, wall = 0, 0.0
    for record, plan in pairs:
        world = build_world(record, plan, seed=0)
        start = time.perf_counter()
        mujoco.mj_step(world.model, world.data, nstep=steps)
        wall += time.perf_counter() - start
        total_steps += steps
        dt = world.model.opt.timestep
    return {
        "steps": total_steps,
        "wall_s": round(wall, 3),
        "us_per_step": round(1e6 * wall / total_steps, 1),
        "sim_to_wall": round(total_steps * dt / wall, 1),
    }


def bench_trials(quick: bool = False, *, limit: int | None = None) -> dict[str, Any]:
    """Full trials (pre-shape .. perturbations) of the seed catalog's best grasps, serially on one core:
    trials per second and simulated-to-wall ratio, against the raw-stepping baseline of the same worlds."""
    from sim.trial import run_trial

    pairs = best_plans(limit or (20 if quick else None))
    raw = bench_raw_steps(pairs[: min(len(pairs), 20)])
    start, cpu_start = time.perf_counter(), time.process_time()
    results = [run_trial(record, plan, seed=0) for record, plan in pairs]
    wall = time.perf_counter() - start
    cpu = time.process_time() - cpu_start  # CPU time: robust when other processes share the cores
    sim_time = sum(r.sim_time_s for r in results)
    steps = sim_time / 0.002
    outcomes = {k: sum(r.outcome == k for r in results) for k in ("success", "failure", "error")}
    out = {
        "trials": len(results),
        "wall_s": round(wall, 2),
        "trials_per_s_one_core": round(len(results) / wall, 2),
        "mean_trial_wall_s": round(wall / len(results), 3),
        "max_trial_wall_s": round(max(r.wall_time_s for r in results), 3),
        "sim_to_wall": round(sim_time / wall, 2),
        "cpu_s": round(cpu, 2),
        "trials_per_cpu_s": round(len(results) / cpu, 2),
        "sim_to_cpu": round(sim_time / cpu, 2),
        "us_per_step_in_trials": round(1e6 * wall / steps, 1),
        "baseline_raw": raw,
        "overhead_vs_raw_steps": round((wall / steps) / (raw["wall_s"] / raw["steps"]), 2),
        **outcomes,
    }
    print(
        f"one core: {out['trials']} full trials in {out['wall_s']} s = {out['trials_per_s_one_core']} trials/s "
        f"(mean {out['mean_trial_wall_s']} s, max {out['max_trial_wall_s']} s per trial); simulated/wall "
        f"{out['sim_to_wall']} (CPU time {out['cpu_s']} s: {out['trials_per_cpu_s']} trials per CPU second, "
        f"simulated/CPU {out['sim_to_cpu']}); {out['us_per_step_in_trials']} us per step in trials vs "
        f"{raw['us_per_step']} us raw mj_step (x{out['overhead_vs_raw_steps']}, baseline sim/wall "
        f"{raw['sim_to_wall']}); {outcomes['success']} success, {outcomes['failure']} failure, "
        f"{outcomes['error']} error",
        flush=True,
    )
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="20 objects instead of the whole seed catalog")
    parser.add_argument(
        "--only",
        choices=("trials", "workers", "choice", "protocols"),
        help="run one part (default: trials, workers and choice)",
    )
    parser.add_argument("--top", type=int, default=3, help="candidates per object in the choice part")
    parser.add_argument(
        "--save", action="store_true", help="save the choice part's README row (a full-catalog run only)"
    )
    parser.add_argument(
        "--repeat", type=int, default=1, help="choice: validate N times, add the rate from each trial's least CPU time"
    )
    args = parser.parse_args(argv)
    limit = 20 if args.quick else None
    if args.only in (None, "trials"):
        bench_trials(quick=args.quick)
    if args.only in (None, "workers"):
        bench_workers(limit=limit)
    if args.only == "protocols":
        bench_protocols(args.top, limit=limit)
    if args.only in (None, "choice"):
        choice = bench_choice(args.top, limit=limit, repeat=args.repeat)
        if args.save:
            if args.quick:
                print("not saved: --quick runs 20 objects; the README row is the whole seed catalog")
            else:
                from sim.experience import Experience

                print(f"saved {save_choice(choice)} and {Experience.from_dict(choice['experience']).save()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
