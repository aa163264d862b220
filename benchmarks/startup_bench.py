"""Start-up: ``objrecall --help``, a one-shot ``objrecall recall``, and building a Recaller at 100k / 1M.

Every figure is a fresh subprocess (the min of ``--runs``, wall and CPU = user + system of the child),
printed beside baselines measured in the same run: ``python -c pass`` and ``python -c "import numpy,
duckdb"`` for the commands; for the build, a plain DuckDB read of the same catalog's columns into NumPy
(``SELECT ... FROM objects``, ``fetchnumpy``). The commands run with bytecode caching on (into a
temporary ``PYTHONPYCACHEPREFIX``, after one warm-up run), as an installed package runs.

The one-shot recall reads a fresh ``objrecall init --seed`` catalog (169 objects). The build catalogs are
synthetic (data written here): DuckDB files of N objects with names "adjective noun number" over 20
nouns, every 10th with an alias; "cold" builds the index (and stores it), "stored" reloads it. Memory
per object: what the built recaller holds (tracemalloc, in a separate run), broken down by part (the
arrays' sizes), then what the first recall adds (the default metric's query structures, by the module
that builds them), and the stored file's size.

    python benchmarks/startup_bench.py [--sizes 100000,1000000] [--runs 5] [--save]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DESCRIPTION = "a red mug, 9 cm tall"
ADJECTIVES = ["red", "blue", "small", "large", "steel", "wooden", "plastic", "glass", "soft", "round", "kids",
              "travel"]  # fmt: skip
NOUNS = ["mug", "cup", "bowl", "plate", "teapot", "ball", "box", "bottle", "jar", "spoon", "knife", "fork", "pan",
         "lid", "toy bear", "remote control", "tennis ball", "book", "phone case", "candle"]  # fmt: skip

BUILD = """
import json, sys, time
t, w = time.process_time(), time.perf_counter()
from recall.engine import Recaller
r = Recaller.from_db(sys.argv[1])
cpu, wall = time.process_time() - t, time.perf_counter() - w
print("RESULT", json.dumps({"cpu": cpu, "wall": wall}))
"""
MEMORY = """
import json, sys, tracemalloc
import numpy, duckdb, recall.engine, recall.parser, pyarrow, pyarrow.compute
sys.path.insert(0, sys.argv[2])
from startup_bench import DESCRIPTION, held_parts, query_parts
r = recall.engine.Recaller.from_db(sys.argv[1])  # once untraced: the lexicons and caches of any first call
r.recall_text(DESCRIPTION)
del r
tracemalloc.start()
r = recall.engine.Recaller.from_db(sys.argv[1])
held = tracemalloc.get_traced_memory()[0]
before = tracemalloc.take_snapshot()
r.recall_text(DESCRIPTION)  # the default metric's query structures, built on first use
queried = tracemalloc.get_traced_memory()[0]
print("RESULT", json.dumps({"bytes": held, "queried": queried, **held_parts(r),
                            **query_parts(tracemalloc.take_snapshot().compare_to(before, "filename"))}))
"""
#: What the first recall builds, by the module that builds it (the default metric's query structures).
QUERY_MODULES = {"snapshot.py": "log-scaled columns (jplog)", "columns.py": "sorted columns",
                 "cells.py": "cells (columns permuted, bounds)", "search.py": "row records (columns packed)",
                 "combinations.py": "category combinations"}  # fmt: skip


def held_parts(recaller) -> dict[str, int]:
    """Bytes held by a recaller just built, by part (``part:`` keys; the arrays' own sizes, the Python
    objects' ``sys.getsizeof``)."""
    snap, names = recaller.snapshot, recaller.names
    if hasattr(snap.aliases, "nbytes"):  # read back from the index: arrays
        aliases = snap.aliases.nbytes
    else:
        aliases = sys.getsizeof(snap.aliases) + sum(sys.getsizeof(a) + sum(sys.getsizeof(x) for x in a)
                                                     for a in snap.aliases if a)  # fmt: skip
    if hasattr(snap.names, "nbytes"):
        name_bytes = snap.names.nbytes
    else:
        name_bytes = sys.getsizeof(snap.names) + sum(sys.getsizeof(x) for x in snap.names)
    heads = names.heads
    head_bytes = heads.starts.nbytes + heads.rows.nbytes + names.head_materials.masks.nbytes
    vocabulary = getattr(names.vocabulary, "table", None)
    return {
        "part:feature columns (4 float32, 5 int8)": snap.nbytes,
        "part:names (UTF-8 text, int32 starts)": name_bytes,
        "part:aliases (UTF-8 text, int32 starts per alias and per row)": aliases,
        "part:name index phrases (string table, CSR rows)": getattr(names.phrases, "nbytes", 0),
        "part:name index vocabulary (string table)": vocabulary.nbytes if vocabulary is not None else 0,
        "part:name index head nouns (CSR rows, uint8 material masks)": head_bytes,
        "part:submaterial flags (bool)": recaller._submaterials._is_other.nbytes,
    }


def query_parts(diff) -> dict[str, int]:
    """Bytes the first recall added, by the module that allocated them (``query:`` keys)."""
    out: dict[str, int] = {}
    for stat in diff:
        name = Path(stat.traceback[0].filename).name
        label = QUERY_MODULES.get(name, "other (lexicons, caches, the answer)")
        out[f"query:{label}"] = out.get(f"query:{label}", 0) + stat.size_diff
    return out


PLAIN_READ = """
import json, sys, time
t, w = time.process_time(), time.perf_counter()
import duckdb, numpy
con = duckdb.connect(sys.argv[1], read_only=True)
con.execute("SET enable_progress_bar = false")
cols = con.execute("SELECT name, a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity "
                   "FROM objects ORDER BY name").fetchnumpy()
aliases = con.execute("SELECT alias, object_id FROM object_aliases").fetchall()
names = cols["name"].tolist()
print("RESULT", json.dumps({"cpu": time.process_time() - t, "wall": time.perf_counter() - w}))
"""


def _env(cache: Path, root: Path) -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    # run in the cache's folder: `python -c` and `-m` put the working directory first on sys.path
    env.update(PYTHONPATH=str(root), PYTHONPYCACHEPREFIX=str(cache), NLTK_DATA=str(cache / "no-nltk-data"),
               BENCH_CWD=str(cache))  # fmt: skip
    return env


def timed(cmd: list[str], env: dict[str, str], runs: int) -> tuple[float, float]:
    """The fastest of ``runs`` runs of ``cmd``: (wall s, CPU s of the child)."""
    best_wall = best_cpu = float("inf")
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL, cwd=env["BENCH_CWD"])
        wall = time.perf_counter() - t
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        best_wall, best_cpu = min(best_wall, wall), min(best_cpu, cpu)
    return best_wall, best_cpu


def reported(code: str, db: Path, env: dict[str, str], runs: int, before=None, args=()) -> dict[str, float]:
    """The fastest of ``runs`` runs of ``code`` (which prints its own JSON), ``before()`` before each."""
    best: dict[str, float] = {}
    for _ in range(runs):
        if before is not None:
            before()
        done = subprocess.run([sys.executable, "-c", code, str(db), *args], env=env, check=True, capture_output=True,
                              text=True, cwd=db.parent)  # fmt: skip
        line = [x for x in done.stdout.splitlines() if "RESULT " in x][-1]  # after any progress bar
        for key, value in json.loads(line.rpartition("RESULT ")[2]).items():
            best[key] = min(best.get(key, float("inf")), value)
    return best


def synthetic_catalog(db: Path, n: int) -> None:
    """A catalog of ``n`` synthetic objects (varied names and features, an alias for every 10th)."""
    sys.path.insert(0, str(ROOT))
    from kb.catalog import KnowledgeBase

    adjectives = ", ".join(repr(a) for a in ADJECTIVES)
    nouns = ", ".join(repr(a) for a in NOUNS)
    with KnowledgeBase.open(db).connect(write=True) as con:
        con.execute(
            "INSERT INTO objects (name, a_cm, b_cm, c_cm, mass_g, shape, texture, material, created_at, updated_at) "
            f"SELECT list_element([{adjectives}], (hash(i) % {len(ADJECTIVES)})::INT + 1) || ' ' || "
            f"list_element([{nouns}], (hash(i + 7) % {len(NOUNS)})::INT + 1) || ' ' || i, "
            "round(2 + random() * 40, 1), round(1 + random() * 20, 1), round(0.5 + random() * 10, 1), "
            "round(5 + random() * 2000), list_element(['compact', 'prism', 'thin', NULL], (i % 4)::INT + 1), "
            "list_element(['smooth', 'rough', NULL], (i % 3)::INT + 1), "
            "list_element(['metal', 'wood', 'glass', 'plastic', 'fabric'], (i % 5)::INT + 1), now(), now() "
            f"FROM range({n}) t(i)"
        )
        con.execute("INSERT INTO object_aliases (alias, object_id) SELECT 'model ' || id, id FROM objects "
                    "WHERE id % 10 = 0")  # fmt: skip


def commands(env: dict[str, str], work: Path, runs: int) -> dict[str, tuple[float, float]]:
    exe = Path(sys.executable)
    objrecall = [str(exe), "-m", "kb.service.cli"]
    db = work / "seed.duckdb"
    subprocess.run([*objrecall, "init", "--seed", "--db", str(db)], env=env, check=True, stdout=subprocess.DEVNULL,
                   cwd=work)  # fmt: skip
    cases = {
        "python -c pass": [str(exe), "-c", "pass"],
        "import numpy, duckdb": [str(exe), "-c", "import numpy, duckdb"],
        "objrecall --help": [*objrecall, "--help"],
        "objrecall recall (seed catalog)": [*objrecall, "recall", DESCRIPTION, "--db", str(db)],
    }
    out = {}
    for label, cmd in cases.items():
        timed(cmd, env, 1)  # warm-up: bytecode caches written
        out[label] = timed(cmd, env, runs)
    base = out["python -c pass"][1]
    lib = out["import numpy, duckdb"][1]
    print(f"{'command':<34} {'wall s':>7} {'CPU s':>7} {'CPU / python':>13} {'CPU / numpy+duckdb':>19}")
    for label, (wall, cpu) in out.items():
        print(f"{label:<34} {wall:7.3f} {cpu:7.3f} {cpu / base:12.1f}x {cpu / lib:18.2f}x")
    return out


def builds(env: dict[str, str], work: Path, sizes: list[int], runs: int) -> dict[int, dict]:
    from recall.stored_index import index_path

    out = {}
    print(f"\n{'Recaller.from_db':<22} {'plain read s':>13} {'cold s':>8} {'stored s':>9} {'cold/plain':>11} "
          f"{'stored/plain':>13} {'memory B/obj':>13} {'file B/obj':>11}")  # fmt: skip
    for n in sizes:
        db = work / f"synthetic-{n}.duckdb"
        synthetic_catalog(db, n)
        file = index_path(db)
        plain = reported(PLAIN_READ, db, env, runs)
        cold = reported(BUILD, db, env, max(1, min(runs, 2)), before=lambda f=file: f.unlink(missing_ok=True))
        stored = reported(BUILD, db, env, runs)
        size = file.stat().st_size if file.exists() else 0
        parts = reported(MEMORY, db, env, 1, args=[str(ROOT / "benchmarks")])
        memory = parts["bytes"]
        out[n] = {"plain_cpu": plain["cpu"], "cold_cpu": cold["cpu"], "stored_cpu": stored["cpu"],
                  "cold_wall": cold["wall"], "stored_wall": stored["wall"], "memory_per_object": memory / n,
                  "queried_per_object": parts["queried"] / n, "file_per_object": size / n,
                  "parts_per_object": {k: v / n for k, v in parts.items() if ":" in k}}  # fmt: skip
        print(f"{n:>10,} objects, CPU {plain['cpu']:13.2f} {cold['cpu']:8.2f} {stored['cpu']:9.2f} "
              f"{cold['cpu'] / plain['cpu']:10.1f}x {stored['cpu'] / plain['cpu']:12.1f}x {memory / n:13.0f} "
              f"{size / n:11.0f}")  # fmt: skip
        print(f"{'':>10}          wall {plain['wall']:13.2f} {cold['wall']:8.2f} {stored['wall']:9.2f}")
        print_parts(out[n])
        db.unlink()
        file.unlink(missing_ok=True)
    return out


def print_parts(built: dict) -> None:
    """The memory per object by part: held once built, then added by the first recall."""
    parts = built["parts_per_object"]
    held = sum(v for k, v in parts.items() if k.startswith("part:"))
    print(f"{'':>10}  B/object held once built: {built['memory_per_object']:.1f} (tracemalloc), of which")
    for key, value in parts.items():
        if key.startswith("part:"):
            print(f"{'':>14}{value:8.1f}  {key[5:]}")
    print(f"{'':>14}{built['memory_per_object'] - held:8.1f}  the rest (Python containers, fixed costs / N)")
    print(f"{'':>10}  B/object after the first recall (default metric): {built['queried_per_object']:.1f}, added:")
    for key, value in parts.items():
        if key.startswith("query:"):
            print(f"{'':>14}{value:8.1f}  {key[6:]}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="100000,1000000", help="catalog sizes for the Recaller build ('' to skip)")
    ap.add_argument("--runs", type=int, default=5, help="runs per figure, the fastest kept")
    ap.add_argument("--save", action="store_true", help="save the README row (benchmarks/results/startup_bench.json)")
    ap.add_argument("--root", type=Path, default=ROOT, help="the checkout whose code runs (default: this one)")
    args = ap.parse_args()
    sys.path.insert(0, str(ROOT))
    load = os.getloadavg()[0]
    work = Path(tempfile.mkdtemp(prefix="startup-bench-"))
    try:
        env = _env(work / "pycache", args.root.resolve())
        (work / "pycache" / "no-nltk-data").mkdir(parents=True)
        print(f"code of {args.root.resolve()}; load average {load:.1f} on {os.cpu_count()} cores; "
              f"min of {args.runs} runs")
        cmds = commands(env, work, args.runs)
        sizes = [int(s) for s in args.sizes.split(",") if s]
        built = builds(env, work, sizes, args.runs) if sizes else {}
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if args.save:
        _save(cmds, built, load, args.runs)


def _save(cmds: dict, built: dict, load: float, runs: int) -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from saved import save_result

    help_wall, help_cpu = cmds["objrecall --help"]
    rec_wall, rec_cpu = cmds["objrecall recall (seed catalog)"]
    base = cmds["python -c pass"][1]
    parts = [f"`objrecall --help` {help_wall:.2f} s wall / {help_cpu:.2f} s CPU ({help_cpu / base:.0f}x `python -c pass`); "
             f"one-shot `objrecall recall` {rec_wall:.2f} s wall / {rec_cpu:.2f} s CPU "
             f"({rec_cpu / cmds['import numpy, duckdb'][1]:.1f}x `import numpy, duckdb`)"]  # fmt: skip
    for n, b in built.items():
        p = b["parts_per_object"]
        names = sum(v for k, v in p.items() if k.startswith("part:name") or k.startswith("part:aliases"))
        columns = p["part:feature columns (4 float32, 5 int8)"] + sum(v for k, v in p.items()
                                                                       if k.startswith("query:") and "other" not in k)  # fmt: skip
        parts.append(f"Recaller at {n:,} (synthetic): cold {b['cold_cpu']:.1f} s, from the stored index "
                     f"{b['stored_cpu']:.2f} s CPU ({b['stored_cpu'] / b['plain_cpu']:.1f}x a plain DuckDB read), "
                     f"{b['memory_per_object']:.0f} B/object held once built (names, aliases and name index "
                     f"{names:.0f}), {b['queried_per_object']:.0f} after the first recall (the default metric's "
                     f"columns and their index {columns:.0f})")  # fmt: skip
    data = {"commands": {k: list(v) for k, v in cmds.items()}, "builds": {str(k): v for k, v in built.items()},
            "load_average": load, "runs": runs}  # fmt: skip
    save_result("startup_bench", benchmark="start-up: CLI and Recaller build, fresh subprocesses, min of "
                f"{runs}", result="; ".join(parts), data=data, order=15,
                source=f"benchmarks/startup_bench.py, load average {load:.1f} on 2 shared cores")  # fmt: skip


if __name__ == "__main__":
    main()
