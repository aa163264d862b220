"""Ingestion benchmark.

Part 1, :func:`bench_extraction`: extraction milliseconds per page on the real storefront pages
(``$OBJRECALL_STOREFRONT_PAGES`` or ``../shared/storefront-pages``), each page extracted ``--repeat``
times (median reported), as a ratio against the baseline measured in the same run: parsing the same
page with lxml alone (the least any HTML extractor must pay). Also prints how many pages are right
(dimensions and mass within 1 %).

Run: ``python benchmarks/ingest_bench.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
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


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per page (median reported)")
    parser.add_argument("--pages", type=Path, default=None, help="folder with labels.jsonl and the pages")
    args = parser.parse_args(argv)
    bench_extraction(args.pages, args.repeat)


if __name__ == "__main__":
    main()
