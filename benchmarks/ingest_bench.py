"""Ingestion benchmark.

Part 1, :func:`bench_extraction`: extraction milliseconds per page on the real storefront pages
(``$OBJRECALL_STOREFRONT_PAGES`` or ``../shared/storefront-pages``), each page extracted ``--repeat``
times (median reported), as a ratio against the baseline measured in the same run: parsing the same
page with lxml alone (the least any HTML extractor must pay). Also prints how many pages are right
(dimensions and mass within 1 %).

Part 2, :func:`bench_end_to_end`: pages per second end to end (discover -> fetch -> extract -> validate ->
one write transaction) against the demo store on 127.0.0.1 with the delay set to zero, into a seeded
catalog, cold (every page new) and warm (a second run: 304s). Baseline measured in the same run: the same
URLs fetched by a bare ``requests.Session`` (no robots.txt, no extraction, no database). The slow, flaky
and huge demo pages are left out of this part (they measure timeouts, not throughput).

Run: ``python benchmarks/ingest_bench.py [--repeat N] [--runs N] [--skip-extraction] [--skip-end-to-end] [--save]``
(``--save``: the end-to-end figures become the README row, ``benchmarks/results/ingest_bench.json``).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path
from typing import Any


def _median_ms(func, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append((time.perf_counter() - start) * 1000.0)
    return statistics.median(times)


def bench_extraction(pages_dir: Path | None = None, repeat: int = 5) -> dict[str, Any]:
    """Extraction ms per real page vs an lxml-only parse of the same page; prints a table, returns the
    numbers (``pages``: per page dicts; ``total_ms``, ``baseline_ms``, ``ratio``, ``right``)."""
    import lxml.html

    from scrapers.extract import extract_page
    from scrapers.labelled_pages import judge, load_labels

    pages = load_labels(pages_dir)
    if not pages:
        print("extraction: no labelled pages found (set OBJRECALL_STOREFRONT_PAGES); skipped")
        return {"pages": [], "total_ms": 0.0, "baseline_ms": 0.0, "ratio": None, "right": 0}
    rows = []
    for page in pages:
        body = page.path.read_bytes()
        record = extract_page(body, page.url, "text/html")  # warm-up, and the verdict
        ms = _median_ms(lambda b=body, u=page.url: extract_page(b, u, "text/html"), repeat)
        base = _median_ms(lambda b=body: lxml.html.document_fromstring(b.decode("utf-8", "replace")), repeat)
        verdict = judge(record, page.truth)
        rows.append(
            {
                "file": page.truth["file"],
                "kb": len(body) / 1024,
                "ms": ms,
                "baseline_ms": base,
                "right": verdict.right,
            }
        )
    total = sum(r["ms"] for r in rows)
    base_total = sum(r["baseline_ms"] for r in rows)
    print(f"{'page':24} {'KiB':>7} {'extract ms':>11} {'lxml ms':>8} {'ratio':>6}  right")
    for r in rows:
        print(
            f"{r['file']:24} {r['kb']:7.0f} {r['ms']:11.1f} {r['baseline_ms']:8.1f} "
            f"{r['ms'] / r['baseline_ms']:6.2f}  {'yes' if r['right'] else 'NO'}"
        )
    right = sum(r["right"] for r in rows)
    print(
        f"extraction: {total / len(rows):.1f} ms/page mean, {statistics.median(r['ms'] for r in rows):.1f} ms median, "
        f"{total / base_total:.2f}x an lxml-only parse (baseline {base_total / len(rows):.1f} ms/page); "
        f"{right}/{len(rows)} pages right"
    )
    return {
        "pages": rows,
        "total_ms": total,
        "baseline_ms": base_total,
        "ratio": total / base_total,
        "right": right,
    }


_BENCH_SOURCES = """
[defaults]
delay_s = 0
read_timeout_s = 5
max_retries = 0

[[stores]]
name = "demo"
base_url = "http://127.0.0.1:1"
sitemaps = ["{base_url}/sitemap.xml"]
exclude = ["slow", "flaky", "huge"]

[[stores]]
name = "demo-shopify-json"
base_url = "http://127.0.0.1:1"
sitemaps = ["{base_url}/sitemap.xml"]
include = ["^/products/"]
adapter = "shopify"
"""


def bench_end_to_end(runs: int = 3) -> dict[str, Any]:
    """Pages/s of the whole ingestion job vs bare fetching of the same URLs (see the module docstring);
    prints a summary, returns the medians over ``runs`` runs."""
    import shutil
    import tempfile

    import requests

    from kb.catalog import KnowledgeBase
    from scrapers.demo_store import DemoStore
    from scrapers.discovery import discover_urls
    from scrapers.fetcher import FetchPolicy, PoliteFetcher
    from scrapers.ingest import run_ingestion
    from scrapers.sources import parse_sources

    seed = Path(__file__).resolve().parents[1] / "kb" / "data" / "seed_catalog.csv"
    tmp = Path(tempfile.mkdtemp(prefix="ingest-bench-"))
    template = tmp / "seeded.duckdb"
    KnowledgeBase.open(template).import_csv(seed)
    cold, warm, bare, write_ms = [], [], [], []
    counts: dict[str, Any] = {}
    try:
        with DemoStore(crawl_delay=None) as store, requests.Session() as session:
            sources = parse_sources(_BENCH_SOURCES, origin="bench", base_url=store.base_url)
            fetcher = PoliteFetcher(session, policy=FetchPolicy(delay_s=0))
            urls = [u for st in sources.stores for u in discover_urls(fetcher, st, [])]
            for i in range(runs):
                start = time.perf_counter()
                for url in urls:
                    _ = session.get(url, timeout=10).content
                bare.append(len(urls) / (time.perf_counter() - start))
                db = tmp / f"run{i}.duckdb"
                shutil.copy(template, db)
                kb = KnowledgeBase.open(db)
                start = time.perf_counter()
                report = run_ingestion(kb, sources, session=session)
                cold.append(report.pages / (time.perf_counter() - start))
                write_ms.append(report.write_s * 1000)
                counts = {k: getattr(report, k) for k in ("pages", "fetched", "new", "updated", "rejected")}
                counts["rejected_reasons"] = report.rejected_reasons
                start = time.perf_counter()
                again = run_ingestion(kb, sources, session=session)
                warm.append(again.pages / (time.perf_counter() - start))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    med = statistics.median
    result = {
        "pages": counts.get("pages", 0),
        "cold_pages_per_s": med(cold),
        "warm_pages_per_s": med(warm),
        "bare_fetch_pages_per_s": med(bare),
        "cold_ratio": med(cold) / med(bare),
        "warm_ratio": med(warm) / med(bare),
        "write_ms": med(write_ms),
        "counts": counts,
    }
    print(
        f"end to end ({result['pages']} pages, delay 0, median of {runs}): "
        f"cold {result['cold_pages_per_s']:.1f} pages/s = {result['cold_ratio']:.2f}x bare fetching "
        f"({result['bare_fetch_pages_per_s']:.1f} pages/s); warm (304s) {result['warm_pages_per_s']:.1f} pages/s "
        f"= {result['warm_ratio']:.2f}x; write transaction {result['write_ms']:.0f} ms; counts {counts}"
    )
    return result


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per page (median reported)")
    parser.add_argument("--pages", type=Path, default=None, help="folder with labels.jsonl and the pages")
    parser.add_argument("--runs", type=int, default=3, help="end-to-end runs (median reported)")
    parser.add_argument("--skip-extraction", action="store_true", help="only the end-to-end part")
    parser.add_argument("--skip-end-to-end", action="store_true", help="only the extraction part")
    parser.add_argument("--save", action="store_true", help="save the end-to-end figures as the README row")
    args = parser.parse_args(argv)
    if not args.skip_extraction:
        bench_extraction(args.pages, args.repeat)
    if not args.skip_end_to_end:
        result = bench_end_to_end(args.runs)
        if args.save:
            _save(result, args.runs)


def _save(result: dict[str, Any], runs: int) -> None:
    """The README row: pages/s cold and warm against bare fetching, and the write transaction."""
    from saved import save_result

    load = os.getloadavg()[0]
    text = (
        f"demo store (data written here), {result['pages']} pages, median of {runs} runs: "
        f"{result['cold_pages_per_s']:.0f} pages/s first run ({result['cold_ratio']:.2f}× bare fetching at "
        f"{result['bare_fetch_pages_per_s']:.0f} pages/s), {result['warm_pages_per_s']:.0f} pages/s all-304 rerun "
        f"({result['warm_ratio']:.2f}×); write transaction {result['write_ms'] / 1000:.2f} s; "
        f"2 shared cores, load {load:.0f}"
    )
    data = {k: (round(v, 3) if isinstance(v, float) else v) for k, v in result.items()}
    data.update(runs=runs, load_average=round(load, 1))
    path = save_result("ingest_bench", benchmark="ingestion, demo store, delay 0", result=text, data=data, order=40)
    print(f"saved {path}")


if __name__ == "__main__":
    main()
