"""Description parser vs quantulum3 on the development set: speed (descriptions per second, one core) and
accuracy of the quantities (dimensions and mass against the true objects), measured in the same run.

    python benchmarks/parse_bench.py [--passes 3] [--tolerance 0.2] [--startup-runs 5] [--startup-only]

Quantities are scored the same way for both: a true dimension (a, b or c) is *found* when an extracted
length is within ``tolerance`` of it; the mass when the first extracted mass is. quantulum3 (a
test/benchmark-only dependency) ships its own unit classifier (``clf.joblib``, pickled with scikit-learn 1.8) and loads it on first use; it
downloads nothing. When that pickle cannot be loaded by the installed scikit-learn (1.9 moved
``sklearn._loss``), the benchmark switches quantulum3 to its no-classifier mode and says so (retraining
would need the ``stemming`` package).
Warm-up (loading, first parse) is timed separately and not counted in the rates.

Start-up is measured by subprocess (fresh interpreters, min of ``--startup-runs``, wall and CPU time of
the child), against a plain ``python -c pass`` measured in the same run: importing NLTK plainly and
through ``recall/toolkit.py``, the unit table built with pint and read from its stored copy, and the
parser's whole start (import, build, first parse) now and as it was (plain NLTK first, pint table).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from kb.features import DIMENSIONS  # noqa: E402
from recall.parse_eval import load_labeled  # noqa: E402

#: quantulum3 unit names -> (kind, factor to cm or g)
Q3_UNITS = {
    "millimetre": ("length", 0.1), "centimetre": ("length", 1.0), "metre": ("length", 100.0),
    "inch": ("length", 2.54), "foot": ("length", 30.48), "yard": ("length", 91.44),
    "milligram": ("mass", 0.001), "gram": ("mass", 1.0), "kilogram": ("mass", 1000.0),
    "ounce": ("mass", 28.349523125), "pound-mass": ("mass", 453.59237), "pound": ("mass", 453.59237),
}  # fmt: skip


def _close(a: float, b: float, tol: float) -> bool:
    return abs(a - b) <= tol * b


def _score(extracted: list[tuple[list[float], list[float]]], records, tol: float) -> dict[str, float]:
    dims_found = dims_total = mass_found = mass_total = 0
    for (lengths, masses), rec in zip(extracted, records, strict=True):
        for d in DIMENSIONS:
            truth = getattr(rec, d)
            if truth is not None:
                dims_total += 1
                dims_found += any(_close(x, truth, tol) for x in lengths)
        if rec.mass_g is not None:
            mass_total += 1
            mass_found += bool(masses) and _close(masses[0], rec.mass_g, tol)
    return {"dims_found": dims_found / dims_total, "mass_found": mass_found / mass_total}


def _ours(texts: list[str]):
    from recall.parser import parse

    out = []
    for text in texts:
        v = parse(text).values()
        out.append(
            ([float(v[d]) for d in DIMENSIONS if d in v], [float(v["mass_g"])] if "mass_g" in v else [])
        )
    return out


def _quantulum_classifier() -> tuple[str | None, str]:
    """(classifier_path for quantulum3.parser.parse, how it was obtained)."""
    from quantulum3 import classifier as clf

    warnings.filterwarnings("ignore")
    try:
        clf.Classifier()
        return None, "its shipped clf.joblib"
    except Exception as err:  # noqa: BLE001 - report whatever the unpickling raised
        # Retraining needs the "stemming" package (not installed); use quantulum3's own fallback for
        # installs without a classifier: heuristic disambiguation (faster than the classifier).
        clf.USE_CLF = False
        return None, (
            f"its shipped clf.joblib does not load with this scikit-learn ({type(err).__name__}: {err}); "
            "using its no-classifier mode (heuristic disambiguation)"
        )


_Q3_PATH: str | None = None


def _quantulum(texts: list[str], unknown: set[str]):
    from quantulum3 import parser as q3

    out = []
    for text in texts:
        lengths: list[float] = []
        masses: list[float] = []
        for q in q3.parse(text, classifier_path=_Q3_PATH):
            kind_factor = Q3_UNITS.get(q.unit.name)
            if kind_factor is None:
                unknown.add(q.unit.name)
                continue
            kind, factor = kind_factor
            (lengths if kind == "length" else masses).append(float(q.value) * factor)
        out.append((lengths, masses))
    return out


def _rates(fns: dict, texts: list[str], passes: int) -> dict[str, float]:
    """Descriptions per CPU second of this process (one core; fairer than wall time on a busy machine),
    median over passes; the parsers take turns within each pass so that both see the same load."""
    rates: dict[str, list[float]] = {name: [] for name in fns}
    for _ in range(passes):
        for name, fn in fns.items():
            t0 = time.process_time()
            fn(texts)
            rates[name].append(len(texts) / (time.process_time() - t0))
    return {name: statistics.median(r) for name, r in rates.items()}


_FIRST = "from recall.parser import parse; parse('a mug about 9.5 cm tall and 8 across, 350 g')"
#: (label, code run by ``python -c``); the first is the baseline.
STARTUP_CASES: tuple[tuple[str, str], ...] = (
    ("python -c pass (baseline)", "pass"),
    ("import nltk (plain)", "import nltk"),
    ("import recall.toolkit (NLTK, no scipy/sklearn)", "import recall.toolkit"),
    ("unit table built with pint", "from kb.measures.units import build_unit_table; build_unit_table()"),
    ("unit table read from units.json", "from kb.measures.units import unit_table; unit_table()"),
    ("parser start, as before (plain NLTK, pint)", "import nltk; from kb.measures.units import build_unit_table; "
     "build_unit_table(); " + _FIRST),
    ("parser start now (import, build, 1st parse)", _FIRST),
)  # fmt: skip


def _run_child(code: str) -> tuple[float, float]:
    """(wall s, CPU s) of one fresh interpreter running ``code``."""
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def startup(runs: int) -> list[tuple[str, float, float]]:
    """(label, min wall s, min CPU s) per :data:`STARTUP_CASES`; the cases take turns in each round."""
    best: dict[str, list[float]] = {label: [float("inf"), float("inf")] for label, _c in STARTUP_CASES}
    for _ in range(runs):
        for label, code in STARTUP_CASES:
            wall, cpu = _run_child(code)
            best[label] = [min(best[label][0], wall), min(best[label][1], cpu)]
    return [(label, *best[label]) for label, _c in STARTUP_CASES]


def _print_startup(rows: list[tuple[str, float, float]], runs: int) -> None:
    _label, base_wall, base_cpu = rows[0]
    print(f"start-up (fresh interpreter, min of {runs}; 'over pass' = minus the baseline, same run)")
    print(f"{'':46s}{'wall s':>8s}{'CPU s':>8s}{'CPU over pass':>15s}{'x pass':>8s}")
    for label, wall, cpu in rows:
        print(f"{label:46s}{wall:8.3f}{cpu:8.3f}{cpu - base_cpu:15.3f}{cpu / base_cpu:8.1f}")
    before, now = rows[-2][2] - base_cpu, rows[-1][2] - base_cpu
    print(f"parser start-up over pass: {before:.3f} s CPU before, {now:.3f} s now ({before / now:.1f}x less)")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--passes", type=int, default=5)
    ap.add_argument("--tolerance", type=float, default=0.2)
    ap.add_argument("--startup-runs", type=int, default=5, help="fresh interpreters per start-up case")
    ap.add_argument("--startup-only", action="store_true", help="only the start-up measurements")
    args = ap.parse_args()
    rows = startup(args.startup_runs) if args.startup_runs > 0 else []
    if rows:
        _print_startup(rows, args.startup_runs)
    if args.startup_only:
        return 0
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})  # one core
    labeled = load_labeled()
    texts = [t for t, _r in labeled]
    records = [r for _t, r in labeled]

    t0 = time.perf_counter()
    ours = _ours(texts[:1])
    ours_warm = time.perf_counter() - t0
    global _Q3_PATH
    _Q3_PATH, how = _quantulum_classifier()
    print(f"quantulum3 classifier: {how}")
    unknown: set[str] = set()
    t0 = time.perf_counter()
    _quantulum(texts[:1], unknown)
    q3_warm = time.perf_counter() - t0

    ours = _ours(texts)
    theirs = _quantulum(texts, unknown)
    rates = _rates({"ours": _ours, "q3": lambda ts: _quantulum(ts, unknown)}, texts, args.passes)
    ours_rate, q3_rate = rates["ours"], rates["q3"]
    s_ours = _score(ours, records, args.tolerance)
    s_q3 = _score(theirs, records, args.tolerance)

    print(f"descriptions: {len(texts)} (recall/data/dev_descriptions.csv), tolerance {args.tolerance:.0%}")
    print(f"{'':14s}{'desc/s':>10s}{'warm-up s':>11s}{'dims found':>12s}{'mass found':>12s}")
    print(
        f"{'objrecall':14s}{ours_rate:10.0f}{ours_warm:11.2f}{s_ours['dims_found']:12.1%}{s_ours['mass_found']:12.1%}"
    )
    print(
        f"{'quantulum3':14s}{q3_rate:10.0f}{q3_warm:11.2f}{s_q3['dims_found']:12.1%}{s_q3['mass_found']:12.1%}"
    )
    print(f"speed ratio objrecall / quantulum3: {ours_rate / q3_rate:.1f}x (goal >= 10x)")
    if unknown:
        print(f"quantulum3 units not scored: {', '.join(sorted(unknown))}")
    if args.passes >= 5 and args.startup_runs >= 5:  # a full run: the README's row
        _save(ours_rate, q3_rate, s_ours, s_q3, rows)
    return 0


def _save(ours_rate: float, q3_rate: float, s_ours: dict, s_q3: dict, rows: list) -> None:
    from benchmarks.saved import save_result

    base = rows[0][2]
    before, now = rows[-2][2] - base, rows[-1][2] - base
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    result = (
        f"{ours_rate / q3_rate:.1f}× the descriptions per second; quantities found: dims "
        f"{s_ours['dims_found']:.0%} vs {s_q3['dims_found']:.0%}, mass {s_ours['mass_found']:.0%} vs "
        f"{s_q3['mass_found']:.0%}; parser start-up {before:.2f} → {now:.2f} s CPU over `python -c pass` "
        f"(load {load:.0f} on 2 cores)"
    ).replace("%", " %")
    data = {
        "desc_per_s": {"objrecall": round(ours_rate), "quantulum3": round(q3_rate)},
        "found": {"objrecall": s_ours, "quantulum3": s_q3},
        "startup_cpu_s": {label: round(cpu, 3) for label, _wall, cpu in rows},
        "load_average": round(load, 1),
    }
    print(f"saved {save_result('parse_bench', benchmark='parser vs quantulum3', result=result, data=data, order=20)}")


if __name__ == "__main__":
    raise SystemExit(main())
