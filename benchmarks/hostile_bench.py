"""Hostile-store benchmark (issue 25): what a slow or hostile store costs the nightly job.

Part 1, :func:`bench_drip_beside_demo`: the nightly job (``run_ingestion`` with ``scrapers/demo_sources.toml``,
its delays and robots Crawl-delay as they are) over the demo store alone, then with one dripping store
beside it (a page that sends a byte every 50 ms, each well within the read time-out, for 60 s). Reported:
when the demo store's last page is done in each case and their ratio (the goal: 1 ± 0.2), and when the
dripping page was rejected (the goal: within its deadline, default 30 s) with its reason, counted from its
request's arrival at the store (what the deadline counts; its robots.txt and the host's delay come before)
and from the run's start. Baseline, measured in the same run: the demo store alone.

Part 2, :func:`bench_each_store`: every hostile store of ``tests/hostile_stores.py`` (written here), one
at a time, each ingested by a fresh child process (so its peak RSS is its own): wall seconds, peak RSS
(``VmHWM`` of the child, MB) and the reason recorded, against the same child reading one good page (the
baseline, same run). Default policy (page deadline 30 s, max_bytes 10 MiB); the robots.txt hangs 40 s.

Part 3, :func:`bench_drips_before_good`: four dripping stores (each page a byte every 50 ms; 4 pages each)
listed *before* a good store (5 pages, 0.2 s host delay), page deadline 5 s (a blind tester's case: the
crawl's 4 threads were all held by the drips). Reported: when the good store's first and last page were
done, alone and beside the drips, and their ratio against the good store alone (same run, median of
``--runs``); and the same run with the old limit of 4 stores crawling at once (``max_crawling=4``), to
show what the store giving up after 2 time-outs in a row bounds when more stores wait than threads.

Run: ``python benchmarks/hostile_bench.py [--runs N] [--skip-drip] [--skip-stores] [--skip-queue] [--save]``.
All figures come from stores written here (loopback), not from real stores.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO), str(REPO / "tests")]  # the hostile stores are the tests' own


# ---------------------------------------------------------------------------------------------- part 1
def _nightly(base_url: str, extra: str, db: Path) -> tuple[float, float | None, dict[str, str], float, float]:
    """One nightly run: (demo store's last page done s, drip page rejected s, drip reasons, total s, the
    run's start: ``time.monotonic()``), times in seconds from the run's start."""
    import requests

    from kb.catalog import KnowledgeBase
    from scrapers.ingest import run_ingestion
    from scrapers.sources import parse_sources

    text = (REPO / "scrapers" / "demo_sources.toml").read_text(encoding="utf-8") + extra
    sources = parse_sources(text, origin="demo_sources.toml")
    sources = type(sources)(
        tuple(s if s.name == "drip" else _rebased(s, base_url) for s in sources.stores), sources.origin
    )
    done: dict[str, float] = {}
    start = time.monotonic()  # the clock the stores' handlers record requests with

    def progress(_done: int, _total: int, url: str) -> None:
        if url:
            done["drip" if "/p/drip" in url else "demo"] = time.monotonic() - start

    kb = KnowledgeBase.open(db)
    with requests.Session() as session:
        run_ingestion(kb, sources, session=session, progress=progress)
    total = time.monotonic() - start
    with kb.connect() as con:
        reasons = {u: r for u, r in con.execute("SELECT url, reason FROM page_events").fetchall() if "/p/drip" in u}
    return done["demo"], done.get("drip"), reasons, total, start


def _rebased(store, base_url: str):
    from dataclasses import replace

    old = store.base_url
    return replace(
        store,
        base_url=base_url,
        sitemaps=tuple(u.replace(old, base_url) for u in store.sitemaps),
        urls=tuple(u.replace(old, base_url) for u in store.urls),
        search=store.search.replace(old, base_url) if store.search else None,
    )


def bench_drip_beside_demo(runs: int = 3) -> dict[str, Any]:
    from hostile_stores import PageStore

    from scrapers.demo_store import DemoStore

    tmp = Path(tempfile.mkdtemp(prefix="hostile-bench-"))
    alone, beside, rejected, after_request, totals = [], [], [], [], []
    reasons: dict[str, str] = {}
    with DemoStore() as demo, PageStore(drip_s=60.0) as drip:
        drip.mode = "hostile"
        extra = (
            f'\n[[stores]]\nname = "drip"\nbase_url = "{drip.base_url}"\nurls = ["{drip.base_url}/p/drip"]\n'
        )
        for i in range(runs):
            alone.append(_nightly(demo.base_url, "", tmp / f"alone{i}.duckdb")[0])
            drip.seen.clear()
            demo_s, drip_s, reasons, total, start = _nightly(demo.base_url, extra, tmp / f"beside{i}.duckdb")
            beside.append(demo_s)
            rejected.append(drip_s)
            after_request.append(start + drip_s - drip.seen["/p/drip"])  # what the page's deadline counts
            totals.append(total)
    med = statistics.median
    result = {
        "demo_alone_s": med(alone),
        "demo_beside_drip_s": med(beside),
        "ratio": med(beside) / med(alone),
        "drip_rejected_s": max(after_request),
        "drip_rejected_from_run_start_s": max(rejected),
        "run_total_s": med(totals),
        "drip_reason": next(iter(reasons.values()), None),
        "runs": runs,
    }
    print(
        f"nightly job, demo store ({runs} runs, median): its last page done after {result['demo_alone_s']:.1f} s alone, "
        f"{result['demo_beside_drip_s']:.1f} s beside a dripping store = {result['ratio']:.2f}x; the dripping "
        f"page rejected at most {result['drip_rejected_s']:.3f} s after its request reached the store "
        f"({result['drip_rejected_from_run_start_s']:.2f} s after the run started: its robots.txt and host "
        f"delay first) ({result['drip_reason']}); "
        f"whole run {result['run_total_s']:.1f} s"
    )
    return result


# ---------------------------------------------------------------------------------------------- part 2
def _child(spec: str) -> None:
    """In a child process: ingest one store described by ``spec`` (JSON), print wall s, peak RSS, reason."""
    import requests

    from kb.catalog import KnowledgeBase
    from scrapers.ingest import run_ingestion
    from scrapers.sources import parse_sources

    args = json.loads(spec)
    kb = KnowledgeBase.open(Path(args["db"]))
    sources = parse_sources(args["sources"])
    start = time.perf_counter()
    with requests.Session() as session:
        report = run_ingestion(kb, sources, session=session)
    wall = time.perf_counter() - start
    with kb.connect() as con:
        events = [r for (r,) in con.execute("SELECT reason FROM page_events").fetchall()]
    reason = events[0].split(":")[0] if events else ("read" if report.extracted else "none")
    rss_mb = _peak_rss_mb()
    print(json.dumps({"wall_s": wall, "rss_mb": rss_mb, "reason": reason, "events": events[:2]}))


def _peak_rss_mb() -> float:
    """This process's own peak RSS: ``VmHWM`` (Linux; reset by exec), else ``getrusage`` (which on Linux
    keeps the parent's peak across fork and exec, so a child would report at least its parent's)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux


def _store_sources(name: str, base: str, paths: list[str] | None, sitemap: bool = False) -> str:
    text = f'[[stores]]\nname = "{name}"\nbase_url = "{base}"\ndelay_s = 0\n'
    if sitemap:
        return text + 'sitemaps = ["{base_url}/sitemap.xml"]\nmax_pages = 3\nmax_bytes = 67108864\n'
    return text + "urls = [" + ", ".join(f'"{base}{p}"' for p in paths or []) + "]\n"


def bench_each_store() -> list[dict[str, Any]]:
    from hostile_stores import PAGE_KINDS, PageStore

    tmp = Path(tempfile.mkdtemp(prefix="hostile-bench-"))
    rows: list[dict[str, Any]] = []
    with (
        PageStore() as good,
        PageStore() as pages,
        PageStore(robots_hang_s=40.0) as robots,
        PageStore(sitemap_urls=1_000_000) as sitemap,
    ):
        for store in (pages, robots, sitemap):
            store.mode = "hostile"
        cases = [("baseline: one good page", _store_sources("good", good.base_url, ["/p/error-page"]))]
        cases += [(kind, _store_sources(kind, pages.base_url, [f"/p/{kind}"])) for kind in PAGE_KINDS]
        cases.append(("robots.txt hangs", _store_sources("robots", robots.base_url, ["/p/behind-robots"])))
        cases.append(("sitemap of 1M URLs", _store_sources("sitemap", sitemap.base_url, None, sitemap=True)))
        for i, (label, text) in enumerate(cases):
            spec = json.dumps({"db": str(tmp / f"s{i}.duckdb"), "sources": text})
            env = {**os.environ, "NLTK_DATA": os.environ.get("NLTK_DATA", tempfile.mkdtemp())}
            proc = subprocess.run(
                [sys.executable, __file__, "--child", spec], capture_output=True, text=True, env=env, timeout=300
            )
            if proc.returncode != 0:
                rows.append({"store": label, "wall_s": None, "rss_mb": None, "reason": f"CRASH {proc.stderr[-300:]}"})
                continue
            rows.append({"store": label, **json.loads(proc.stdout.strip().splitlines()[-1])})
    base = rows[0]
    print(f"{'store':28} {'wall s':>7} {'peak RSS MB':>12} {'vs baseline':>12}  reason")
    for row in rows:
        if row["wall_s"] is None:
            print(f"{row['store']:28} {'-':>7} {'-':>12} {'-':>12}  {row['reason']}")
            continue
        row["rss_ratio"] = row["rss_mb"] / base["rss_mb"]
        print(f"{row['store']:28} {row['wall_s']:7.2f} {row['rss_mb']:12.0f} {row['rss_ratio']:11.2f}x  {row['reason']}")
    return rows


# ---------------------------------------------------------------------------------------------- part 3
QUEUE_DEADLINE_S = 5.0
DRIP_KINDS = ("drip", "drip-status", "drip-headers", "drip-chunked")
GOOD_KINDS = ("nested", "error-page", "jsonld-10000", "wrong-charset", "missing-charset")  # good in good mode


def _queue_sources(drips: list[Any], good: Any):
    from scrapers.sources import parse_sources

    text = f"[defaults]\nread_timeout_s = 30.0\nmax_retries = 1\nbackoff_s = 0\nmax_page_s = {QUEUE_DEADLINE_S}\n"
    listed = [(f"drip-{i}", d, DRIP_KINDS, 0.0) for i, d in enumerate(drips)] + [("good", good, GOOD_KINDS, 0.2)]
    for name, store, kinds, delay in listed:
        urls = ", ".join(f'"{store.base_url}/p/{k}?n={name}"' for k in kinds)
        text += f'[[stores]]\nname = "{name}"\nbase_url = "{store.base_url}"\ndelay_s = {delay}\nurls = [{urls}]\n'
    return parse_sources(text)


def _queue_run(db: Path, sources, good_base: str, **limits: int) -> dict[str, float]:
    """One run: the good store's first and last page done, the run's total (s from its start)."""
    import requests

    from kb.catalog import KnowledgeBase
    from scrapers.ingest import run_ingestion

    good: list[float] = []
    start = time.monotonic()

    def progress(_done: int, _total: int, url: str) -> None:
        if url.startswith(good_base):
            good.append(time.monotonic() - start)

    with requests.Session() as session:
        report = run_ingestion(KnowledgeBase.open(db), sources, session=session, progress=progress, **limits)
    return {"first": min(good), "last": max(good), "total": time.monotonic() - start,
            "reasons": report.rejected_reasons}  # fmt: skip


def bench_drips_before_good(runs: int = 3) -> dict[str, Any]:
    from dataclasses import replace

    from hostile_stores import PageStore

    tmp = Path(tempfile.mkdtemp(prefix="hostile-bench-"))
    rows: dict[str, list[dict[str, float]]] = {"alone": [], "beside": [], "beside, 4 crawling": []}
    with PageStore() as good, PageStore(drip_s=60.0) as d0, PageStore(drip_s=60.0) as d1, \
            PageStore(drip_s=60.0) as d2, PageStore(drip_s=60.0) as d3:  # fmt: skip
        drips = [d0, d1, d2, d3]
        for d in drips:
            d.mode = "hostile"
        both = _queue_sources(drips, good)
        alone = replace(both, stores=tuple(s for s in both.stores if s.name == "good"))
        for i in range(runs):  # a fresh catalog each: every good page read and extracted
            rows["alone"].append(_queue_run(tmp / f"a{i}.duckdb", alone, good.base_url))
            rows["beside"].append(_queue_run(tmp / f"b{i}.duckdb", both, good.base_url))
            rows["beside, 4 crawling"].append(_queue_run(tmp / f"c{i}.duckdb", both, good.base_url, max_crawling=4))
    med = statistics.median
    result: dict[str, Any] = {"runs": runs, "deadline_s": QUEUE_DEADLINE_S}
    base_last = med(r["last"] for r in rows["alone"])
    for label, rs in rows.items():
        first, last, total = (med(r[k] for r in rs) for k in ("first", "last", "total"))
        result[label] = {"good_first_s": first, "good_last_s": last, "ratio": last / base_last, "total_s": total,
                         "reasons": rs[-1]["reasons"]}  # fmt: skip
        print(f"four dripping stores before a good one ({label:18}): good store's first page {first:6.2f} s, "
              f"last {last:6.2f} s = {last / base_last:5.2f}x alone; run {total:5.1f} s; {rs[-1]['reasons']}")  # fmt: skip
    return result


# ---------------------------------------------------------------------------------------------- main
def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="nightly runs with and without the drip (median)")
    parser.add_argument("--skip-drip", action="store_true")
    parser.add_argument("--skip-stores", action="store_true")
    parser.add_argument("--skip-queue", action="store_true", help="skip part 3 (drips listed before a good store)")
    parser.add_argument("--save", action="store_true", help="save the figures as the README row")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        _child(args.child)
        return
    drip = None if args.skip_drip else bench_drip_beside_demo(args.runs)
    rows = None if args.skip_stores else bench_each_store()
    queue = None if args.skip_queue else bench_drips_before_good(args.runs)
    if args.save and drip and rows:
        _save(drip, rows, queue)


def _save(drip: dict[str, Any], rows: list[dict[str, Any]], queue: dict[str, Any] | None = None) -> None:
    from saved import save_result

    measured = [r for r in rows[1:] if r["wall_s"] is not None]
    worst_wall = max(measured, key=lambda r: r["wall_s"])
    worst_rss = max(measured, key=lambda r: r["rss_mb"])
    crashes = sum(1 for r in rows if r["wall_s"] is None)
    load = os.getloadavg()[0]
    text = (
        f"loopback stores written here: the demo store's pages done in {drip['demo_beside_drip_s']:.1f} s beside a "
        f"dripping store vs {drip['demo_alone_s']:.1f} s alone ({drip['ratio']:.2f}×, median of {drip['runs']}), the "
        f"drip rejected {drip['drip_rejected_s']:.2f} s after its request (`timeout`, deadline 30 s; "
        f"{drip['drip_rejected_from_run_start_s']:.1f} s after the run began, robots.txt and host delay first); "
        f"{len(measured)} hostile stores one at a time: longest {worst_wall['wall_s']:.1f} s ({worst_wall['store']}), peak RSS at most "
        f"{worst_rss['rss_mb']:.0f} MB ({worst_rss['rss_ratio']:.2f}× one good page, {worst_rss['store']}), "
        f"{crashes} crashes; 2 shared cores, load {load:.0f}"
    )
    data = {"drip": drip, "stores": rows, "queue": queue, "load_average": round(load, 1)}
    path = save_result("hostile_bench", benchmark="hostile stores, nightly job", result=text, data=data, order=45)
    print(f"saved {path}")


if __name__ == "__main__":
    main()
