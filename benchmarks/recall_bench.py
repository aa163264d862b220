"""Recall at every size: the engine's exact top-5 against plain scans and SQL, measured in the same run.

For each catalog size (synthetic: log-normal sizes, mass = density x volume x fill, Zipf-like category
frequencies, 3 % unknown values; ``recall.snapshot.synthetic_snapshot``) and each family of feature
masks, one thread, CPU time per query, the fastest of ``--repeat`` runs (``--wall`` for wall clock):

* the engine: ``recall.search.top_k`` for ``jp`` and ``jplog`` (every answer checked against the
  brute force, rows and distances bit for bit);
* the baselines, written as anyone would: a plain vectorised NumPy scan of the stated columns in float32
  and in float64 (terms ``log1p``, summed, ``argpartition`` + sort of the top 5), and DuckDB's
  ``jp_distance`` macro (``recall.sql``) over an in-memory table, one DuckDB thread;
* and prints p50 / p99 / max, the ratio float32 scan / engine (p50 and p99, > 1: the engine is
  faster), build times and memory per object (every array the engine holds).

    nice -n 10 python benchmarks/recall_bench.py --sizes 10000,100000,1000000 [--queries 200]
    nice -n 10 python benchmarks/recall_bench.py --sizes 10000000 --queries 20 --repeat 1 --sql-queries 0
    (``--save``: the largest size's summary becomes the README row, ``benchmarks/results/recall_bench.json``)
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from kb.features import CATEGORICAL_FEATURES, CATEGORIES, NUMERIC_FEATURES  # noqa: E402
from recall import search  # noqa: E402
from recall.metrics import CATEGORY_CODES, MISMATCH_TERM, UNKNOWN_CATEGORY_TERM  # noqa: E402
from recall.search import brute_force_top_k, top_k  # noqa: E402
from recall.snapshot import synthetic_description, synthetic_snapshot  # noqa: E402

K = 5
#: Mask families: (label, how many features, which features (None: any)).
FAMILIES = (
    ("described (2-8 features)", (2, 8), None),
    ("sizes only (a, b, c)", (3, 3), ("a_cm", "b_cm", "c_cm")),
    ("one number", (1, 1), NUMERIC_FEATURES),
    ("categories only (1-5)", (1, 5), CATEGORICAL_FEATURES),
)
_clock = time.process_time
REPEAT = 3


def _queries(snap, rng, family, count):
    _, (lo, hi), pool = family
    out = []
    for _ in range(count):
        if pool is None:
            out.append(synthetic_description(snap, rng, lo, hi)[1])
            continue
        m = int(rng.integers(lo, hi + 1))
        feats = tuple(rng.choice(pool, size=min(m, len(pool)), replace=False))
        q = synthetic_description(snap, rng, features=feats)[1]
        out.append(q if len(q) else synthetic_description(snap, rng, lo, hi)[1])
    return out


def plain_scan(cols, cats, q, dtype):
    """The baseline: JP of every row from plain columns (``dtype``), then the top K."""
    total = np.zeros(len(cols[0]), dtype=dtype)
    for c in q.numeric:
        x = cols[NUMERIC_FEATURES.index(c.feature)]
        d = np.maximum(np.maximum(dtype(c.low) - x, x - dtype(c.high)), dtype(0))
        d[np.isnan(x)] = c.unknown_difference
        total += np.log1p(d)
    for feat, value in q.categorical:
        table = np.full(len(CATEGORIES[feat]) + 1, MISMATCH_TERM, dtype=dtype)
        table[0], table[CATEGORY_CODES[feat][value] + 1] = UNKNOWN_CATEGORY_TERM, 0.0
        total += table[cats[CATEGORICAL_FEATURES.index(feat)].astype(np.intp) + 1]
    top = np.argpartition(total, K)[:K]
    return top[np.argsort(total[top])]


def _duckdb(snap):
    import duckdb
    import pyarrow as pa

    from recall.sql import install_macros

    con = duckdb.connect(config={"threads": 1})
    table = {f: pa.array(c, from_pandas=True) for f, c in zip(NUMERIC_FEATURES, snap.num_cols, strict=True)}
    for feat, codes in zip(CATEGORICAL_FEATURES, snap.cat_cols, strict=True):
        words = pa.array(list(CATEGORIES[feat]))
        table[feat] = pa.DictionaryArray.from_arrays(pa.array(codes, mask=codes < 0), words)
    con.register("arrow_objects", pa.table(table))
    con.execute(
        "CREATE TABLE objects AS SELECT row_number() OVER () - 1 AS name, "
        + ", ".join(f"{f}::DOUBLE AS {f}" for f in NUMERIC_FEATURES)
        + ", "
        + ", ".join(f"{f}::VARCHAR AS {f}" for f in CATEGORICAL_FEATURES)
        + " FROM arrow_objects"
    )
    con.unregister("arrow_objects")
    install_macros(con)
    return con


_PARAM = {"a_cm": "qa", "b_cm": "qb", "c_cm": "qc", "mass_g": "qmass"}


def sql_query(con, q):
    args = [f"{_PARAM[c.feature]} := {c.value!r}" for c in q.numeric]
    args += [f"q{f.replace('_g', '')} := '{v}'" for f, v in q.categorical]
    cols = ", ".join((*NUMERIC_FEATURES, *CATEGORICAL_FEATURES))
    return con.execute(
        f"SELECT name FROM objects ORDER BY jp_distance({cols}, {', '.join(args)}), name LIMIT {K}"
    ).fetchall()


def _timed(fn, samples):
    """Run ``fn`` REPEAT times; keep the fastest (the machine is shared: the others are interference)."""
    best = None
    for _ in range(REPEAT):
        s = _clock()
        out = fn()
        t = _clock() - s
        best = t if best is None else min(best, t)
    samples.append(best)
    return out


def _stats(samples):
    a = np.asarray(samples) * 1e3
    return float(np.percentile(a, 50)), float(np.percentile(a, 99)), float(a.max())


def _index(snap):
    return search.index_for(snap) if hasattr(search, "index_for") else snap.index


def _warm(index) -> None:
    """Build the parts an index builds on first use (so that no query pays for them)."""
    if hasattr(index, "warm"):
        index.warm()
    else:
        _ = index.cells


def _index_bytes(snap) -> int:
    index = _index(snap)
    return int(index.nbytes)


def run_size(n, args, rng, summaries):
    t = _clock()
    snap = synthetic_snapshot(n, rng)
    gen = _clock() - t
    t = _clock()
    _warm(_index(snap))
    build_jp = _clock() - t
    t = _clock()
    _warm(_index(snap.log_scaled))
    build_log = _clock() - t
    cols32 = [np.asarray(c, dtype=np.float32) for c in snap.num_cols]
    cols64 = [np.asarray(c, dtype=np.float64) for c in snap.num_cols]
    cats = snap.cat_cols
    con = _duckdb(snap) if args.sql_queries else None
    print(f"\n== {n:,} objects (generated in {gen:.1f} s; index build: jp {build_jp:.2f} s, jplog {build_log:.2f} s)")
    head = f"{'mask':<26} {'method':<18} {'p50':>8} {'p99':>8} {'max':>8}  {'scan32/engine p50':>17} {'p99':>6}"
    print(head)
    bad, summary = 0, []
    summaries.append((n, summary))
    for family in FAMILIES:
        queries = _queries(snap, rng, family, args.queries)
        times = {m: [] for m in ("engine jp", "engine jplog", "scan float32", "scan float64", "DuckDB macro")}
        for i, q in enumerate(queries):
            rows, dist = _timed(lambda q=q: top_k(snap, q, K, metric="jp"), times["engine jp"])
            lrows, ldist = _timed(lambda q=q: top_k(snap, q, K, metric="jplog"), times["engine jplog"])
            _timed(lambda q=q: plain_scan(cols32, cats, q, np.float32), times["scan float32"])
            _timed(lambda q=q: plain_scan(cols64, cats, q, np.float64), times["scan float64"])
            if con is not None and i < args.sql_queries:
                _timed(lambda q=q: sql_query(con, q), times["DuckDB macro"])
            if i < args.check:
                brows, bdist = brute_force_top_k(snap, q, K)
                bad += not (np.array_equal(rows, brows) and np.array_equal(dist, bdist))
                brows, bdist = brute_force_top_k(snap.log_scaled, q.log_scaled(), K)
                bad += not (np.array_equal(lrows, brows) and np.array_equal(ldist, bdist))
        scan50, scan99, _ = _stats(times["scan float32"])
        jp50, jp99, _ = _stats(times["engine jp"])
        summary.append((family[0], jp50, jp99, scan50 / jp50, scan99 / jp99))
        for method, samples in times.items():
            if not samples:
                continue
            p50, p99, mx = _stats(samples)
            ratio = f"{scan50 / p50:16.2f}x {scan99 / p99:5.2f}x" if method.startswith("engine") else ""
            print(f"{family[0]:<26} {method:<18} {p50:8.3f} {p99:8.3f} {mx:8.2f}  {ratio}")
    cols = snap.nbytes / n
    jp_index = _index_bytes(snap) / n
    log_cols = 4 * len(NUMERIC_FEATURES)
    log_index = _index_bytes(snap.log_scaled) / n
    print(
        f"memory per object: columns {cols:.0f} B (4 float32 + 5 int8); jp index {jp_index:.0f} B; "
        f"jplog: + {log_cols} B log columns + {log_index:.0f} B index -> jplog alone {cols + log_cols + log_index:.0f} B, "
        f"both metrics {cols + jp_index + log_cols + log_index:.0f} B (names and aliases not counted)"
    )
    print(f"answers equal to brute force: {2 * min(args.check, args.queries) * len(FAMILIES) - bad}"
          f"/{2 * min(args.check, args.queries) * len(FAMILIES)}")  # fmt: skip
    if args.recaller and n <= args.recaller:
        from recall.engine import Recaller

        t = time.perf_counter()
        Recaller(snap)
        print(f"Recaller build (name index over {n:,} names): {time.perf_counter() - t:.2f} s wall")
    return bad


def main() -> None:
    global _clock, REPEAT
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000,1000000")
    ap.add_argument("--queries", type=int, default=200, help="descriptions per mask family and size")
    ap.add_argument("--sql-queries", type=int, default=10, help="of those, timed through DuckDB (0: skip)")
    ap.add_argument("--check", type=int, default=50, help="of those, checked against the brute force")
    ap.add_argument("--recaller", type=int, default=1_000_000, help="time Recaller build up to this size")
    ap.add_argument("--wall", action="store_true", help="wall-clock time instead of CPU time")
    ap.add_argument("--repeat", type=int, default=3, help="runs per query, the fastest kept")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--save", action="store_true", help="save the largest size's summary as the README row")
    args = ap.parse_args()
    REPEAT = max(1, args.repeat)
    if args.wall:
        _clock = time.perf_counter
    try:
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    except ImportError:
        pass
    rng = np.random.default_rng(args.seed)
    print(f"exact top-{K}, one thread, {'wall-clock' if args.wall else 'CPU'} time in ms per query")
    summaries = []
    bad = sum(run_size(int(n), args, rng, summaries) for n in args.sizes.split(","))
    if args.save and summaries:
        from saved import save_result

        n, rows = summaries[-1]
        text = "; ".join(f"{fam}: JP p50 {p50:.2f} ms, p99 {p99:.2f} ms ({r50:.0f}x / {r99:.0f}x the float32 scan)"
                         for fam, p50, p99, r50, r99 in rows)  # fmt: skip
        save_result("recall_bench", benchmark=f"recall, exact top-5, one thread, CPU time, {n:,} synthetic objects",
                    result=text, order=10, data={"size": n, "rows": rows})  # fmt: skip
    if bad:
        print(f"{bad} answers differ from the brute force")
        sys.exit(1)


if __name__ == "__main__":
    main()
