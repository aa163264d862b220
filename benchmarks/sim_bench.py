"""Simulation benchmarks: single trials (physics part) and the validation worker (workers part).

Run: ``python benchmarks/sim_bench.py [--quick]``. Prints ratios against a baseline measured in the same
run (no absolute thresholds): trials per second on one and on two worker processes, and the wall time of
validating the whole seed catalog's best grasps (planner -> trial -> knowledge base), whose goal is under
a minute on two cores.
"""

from __future__ import annotations

import argparse
import importlib.resources
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any


def seed_records() -> list[Any]:
    from kb.csvio import read_catalog_csv

    path = Path(str(importlib.resources.files("kb") / "data" / "seed_catalog.csv"))
    return list(read_catalog_csv(path).records)


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
            sim_time = sum(float(json.loads(r["details"]).get("sim_time_s") or 0.0) for r in summary.results)
            base = base or wall
            run = {
                "workers": n,
                "trials": summary.ran,
                "wall_s": round(wall, 2),
                "trials_per_s": round(summary.ran / wall, 2),
                "speedup_vs_1": round(base / wall, 2),
                "sim_to_wall": round(sim_time / wall, 2),
                "success": summary.succeeded,
                "failure": summary.failed,
                "error": summary.errors,
            }
            out["runs"].append(run)
            print(
                f"workers={n}: {run['trials']} best-grasp trials in {run['wall_s']} s "
                f"({run['trials_per_s']} trials/s, x{run['speedup_vs_1']} vs 1 worker, "
                f"simulated/wall {run['sim_to_wall']}); {run['success']} success, {run['failure']} failure, "
                f"{run['error']} error",
                flush=True,
            )
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="20 objects instead of the whole seed catalog")
    args = parser.parse_args(argv)
    bench_trials = globals().get("bench_trials")  # the single-trial part (physics), when present
    if callable(bench_trials):
        bench_trials(quick=args.quick)
    bench_workers(limit=20 if args.quick else None)
    return 0


if __name__ == "__main__":
    sys.exit(main())
