"""Knowledge-service benchmark: recall requests per second and latency percentiles over HTTP on loopback,
with and without a concurrent ingestion.

Run: ``python benchmarks/service_bench.py [--requests 300] [--clients 4] [--quick] [--save]`` (``--save``: the
figures become the README row, ``benchmarks/results/service_bench.json``). It seeds a temporary
catalog, serves it with a real ``objrecall serve`` on a free 127.0.0.1 port, and sends recall requests
(descriptions from the development set) from ``--clients`` threads:

1. **baseline**: the same recalls in-process (``Recaller.recall_text``), one thread: what HTTP adds;
2. **idle**: HTTP recall while nothing else touches the database;
3. **ingesting**: HTTP recall while ``objrecall ingest`` reads the demo storefront (served on 127.0.0.1 by
   this process) and writes the catalog, restarted until the phase ends (bounded: at most 5 runs).

Results are printed as a table and as ratios against the baseline and against the idle phase (no absolute
thresholds). Everything stays on loopback.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]


def descriptions(n: int) -> list[str]:
    with (REPO / "recall" / "data" / "dev_descriptions.csv").open(newline="", encoding="utf-8") as fh:
        texts = [row["description"] for row in csv.DictReader(fh)]
    return [texts[i % len(texts)] for i in range(n)]


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    if not ordered:
        return float("nan")
    k = min(len(ordered) - 1, max(0, round(q / 100 * (len(ordered) - 1))))
    return ordered[k]


def summarize(name: str, latencies: list[float], wall: float, errors: int) -> dict[str, Any]:
    return {
        "phase": name,
        "requests": len(latencies),
        "errors": errors,
        "rps": len(latencies) / wall if wall > 0 else float("nan"),
        "p50_ms": percentile(latencies, 50) * 1000,
        "p99_ms": percentile(latencies, 99) * 1000,
        "max_ms": max(latencies) * 1000 if latencies else float("nan"),
    }


def bench_in_process(db: Path, texts: list[str]) -> dict[str, Any]:
    from recall.engine import Recaller

    recaller = Recaller.from_db(db)
    recaller.recall_text(texts[0])
    latencies = []
    start = time.perf_counter()
    for text in texts:
        t = time.perf_counter()
        recaller.recall_text(text, top=5)
        latencies.append(time.perf_counter() - t)
    return summarize("baseline (in-process)", latencies, time.perf_counter() - start, 0)


def bench_http(base: str, texts: list[str], clients: int, name: str) -> dict[str, Any]:
    import httpx

    latencies: list[float] = []
    errors = [0]
    lock = threading.Lock()
    chunks = [texts[i::clients] for i in range(clients)]

    def worker(chunk: list[str]) -> None:
        with httpx.Client(base_url=base, timeout=120) as c:
            for text in chunk:
                t = time.perf_counter()
                try:
                    r = c.post("/recall", json={"text": text[:5000], "top": 5})
                    ok = r.status_code == 200
                except httpx.HTTPError:
                    ok = False
                dt = time.perf_counter() - t
                with lock:
                    latencies.append(dt)
                    errors[0] += not ok

    threads = [threading.Thread(target=worker, args=(chunk,)) for chunk in chunks]
    start = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return summarize(name, latencies, time.perf_counter() - start, errors[0])


class IngestLoop:
    """``objrecall ingest`` of the demo store, restarted until stopped (at most ``max_runs`` runs)."""

    def __init__(self, db: Path, sources: Path, env: dict[str, str], max_runs: int = 5):
        self.command = [sys.executable, "-m", "kb.service.cli", "ingest", "--sources", str(sources), "--db", str(db)]
        self.env = env
        self.max_runs = max_runs
        self.runs = 0
        self.failed = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, daemon=True)

    def _loop(self) -> None:
        while not self._stop.is_set() and self.runs < self.max_runs:
            r = subprocess.run(self.command, env=self.env, capture_output=True, text=True)
            self.runs += 1
            self.failed += r.returncode != 0

    def __enter__(self) -> IngestLoop:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=300, help="recall requests per phase")
    parser.add_argument("--clients", type=int, default=4, help="concurrent HTTP clients")
    parser.add_argument("--quick", action="store_true", help="60 requests per phase")
    parser.add_argument("--json", action="store_true", help="print the results as JSON")
    parser.add_argument("--save", action="store_true", help="save the figures as the README row")
    args = parser.parse_args(argv)
    n = 60 if args.quick else max(10, args.requests)
    texts = descriptions(n)

    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path
    from kb.service.http import serve_subprocess
    from scrapers.demo_store import DemoStore

    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env.setdefault("NLTK_DATA", tempfile.mkdtemp(prefix="empty-nltk-"))
    with (
        tempfile.TemporaryDirectory(prefix="objrecall-service-bench-") as tmp,
        DemoStore(crawl_delay=None, slow_s=0.5) as store,
    ):
        db = Path(tmp) / "catalog.duckdb"
        KnowledgeBase.open(db).import_csv(seed_catalog_path())
        sources = Path(tmp) / "sources.toml"
        sources.write_text(
            "[defaults]\ndelay_s = 0\nread_timeout_s = 1\nmax_retries = 0\n\n"
            f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\nsitemaps = ["{{base_url}}/sitemap.xml"]\n'
        )
        results = [bench_in_process(db, texts)]
        with serve_subprocess(db, env=env, extra_args=["--log-level", "warning"]) as base:
            bench_http(base, texts[: min(20, n)], args.clients, "warm-up")
            results.append(bench_http(base, texts, args.clients, "idle (HTTP)"))
            with IngestLoop(db, sources, env) as ingest:
                time.sleep(1.0)  # let the first ingestion start fetching
                results.append(bench_http(base, texts, args.clients, "during ingestion (HTTP)"))
            results[-1]["ingestion_runs"] = ingest.runs
            results[-1]["ingestion_failures"] = ingest.failed
    baseline, idle, busy = results
    ratios = {
        "idle_rps_vs_in_process": idle["rps"] / baseline["rps"],
        "idle_p99_vs_in_process": idle["p99_ms"] / baseline["p99_ms"],
        "ingesting_rps_vs_idle": busy["rps"] / idle["rps"],
        "ingesting_p99_vs_idle": busy["p99_ms"] / idle["p99_ms"],
    }
    if args.save:
        _save(results, ratios, n, args.clients)
    if args.json:
        print(json.dumps({"clients": args.clients, "results": results, "ratios": ratios}))
        return 0
    print(f"recall over HTTP on 127.0.0.1, {n} requests per phase, {args.clients} clients")
    print(f"{'phase':28} {'req':>5} {'err':>4} {'req/s':>8} {'p50 ms':>8} {'p99 ms':>8} {'max ms':>8}")
    for r in results:
        print(
            f"{r['phase']:28} {r['requests']:5d} {r['errors']:4d} {r['rps']:8.1f} {r['p50_ms']:8.1f} "
            f"{r['p99_ms']:8.1f} {r['max_ms']:8.1f}"
        )
    print(
        f"ingestion runs during the last phase: {busy['ingestion_runs']} ({busy['ingestion_failures']} failed)"
    )
    for key, value in ratios.items():
        print(f"{key:28} {value:8.2f}x")
    return 1 if idle["errors"] or busy["errors"] else 0


def _save(results: list[dict[str, Any]], ratios: dict[str, float], n: int, clients: int) -> None:
    """The README row: HTTP recall req/s and p99, idle and during an ingestion, against in-process recall."""
    from saved import save_result

    baseline, idle, busy = results
    load = os.getloadavg()[0]
    text = (
        f"seed catalog, demo store ingestion (data written here), {n} requests per phase, {clients} clients: "
        f"HTTP recall {idle['rps']:.0f} req/s idle (p99 {idle['p99_ms']:.0f} ms; {ratios['idle_rps_vs_in_process']:.2f}× "
        f"in-process recall at {baseline['rps']:.0f}/s), {busy['rps']:.0f} req/s during an ingestion "
        f"(p99 {busy['p99_ms']:.0f} ms, {busy['ingestion_runs']} ingestion run{'s' * (busy['ingestion_runs'] != 1)}, "
        f"{busy['ingestion_failures']} failed); "
        f"{idle['errors'] + busy['errors']} errors; 2 shared cores, load {load:.0f}"
    )
    data = {"requests_per_phase": n, "clients": clients, "results": results, "ratios": ratios,
            "load_average": round(load, 1)}  # fmt: skip
    print(f"saved {save_result('service_bench', benchmark='service', result=text, data=data, order=70)}")


if __name__ == "__main__":
    sys.exit(main())
