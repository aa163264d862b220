"""Lookup benchmark: seconds from a description to an answer when the object is only in a store's search.

Against the demo store on 127.0.0.1 (delay 0, no Crawl-delay), into a copy of the seeded catalog, the
demo's teapot description (only the store's search sells the teapot):

- **cold**: ``recall_with_lookup`` on a fresh catalog copy (search, read the top pages, extract, judge,
  one write transaction, recall again), with the share of its time in fetching, extracting, writing and
  recalling (``LookupResult.seconds``, see :data:`PARTS`);
- **again, forced**: the same lookup once more with ``force=True`` (the pages answer 304, nothing written);
- **baseline**, measured in the same run: a plain recall of the same description from the same catalog
  (``Recaller.from_db(db).recall_text``, the snapshot cached as in a running service), and a bare
  ``requests`` GET of the same search and product URLs (the least any lookup must pay for the network).

Run: ``python benchmarks/lookup_bench.py [--runs N]`` (median of N runs, default 5).
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

#: The parts of a lookup's time (LookupResult.seconds): opening the catalog for writing, fetching, extracting,
#: judging the pages (a recall over each), the write transaction, the recalls before and after, the rest.
PARTS = ("open", "fetch", "extract", "judge", "write", "recall", "other")
DESCRIPTION = "A glazed ceramic teapot about 22 cm wide and 14 cm tall, it weighs around 900 grams."


def _seed(tmp: Path) -> Path:
    from kb.catalog import KnowledgeBase

    template = tmp / "seed.duckdb"
    KnowledgeBase.open(template).import_csv(Path(__file__).resolve().parents[1] / "kb/data/seed_catalog.csv")
    return template


def bench(runs: int = 5) -> dict[str, Any]:
    """Median seconds of each part (see the module docstring); prints a table and returns the numbers."""
    import requests

    from recall.engine import Recaller
    from recall.lookup import recall_with_lookup
    from scrapers.demo_store import DEMO_SOURCES, DemoStore
    from scrapers.sources import load_sources

    tmp = Path(tempfile.mkdtemp(prefix="lookup-bench-"))
    template = _seed(tmp)
    cold: list[dict[str, float]] = []
    again: list[float] = []
    plain: list[float] = []
    bare: list[float] = []
    with DemoStore(crawl_delay=None) as store, requests.Session() as session:
        sources = load_sources(DEMO_SOURCES, base_url=store.base_url, delay_s=0)
        for i in range(runs + 1):  # the first run warms imports and caches up and is not counted
            db = tmp / f"run{i}.duckdb"
            shutil.copy(template, db)
            t0 = time.perf_counter()
            result = recall_with_lookup(db, DESCRIPTION, sources=sources, session=session)
            total = time.perf_counter() - t0
            assert result.found, result.message
            t0 = time.perf_counter()
            recall_with_lookup(db, DESCRIPTION, sources=sources, session=session, force=True)
            forced = time.perf_counter() - t0
            Recaller.from_db(db).recall_text(DESCRIPTION)  # warm the snapshot cache, as a service has it
            t0 = time.perf_counter()
            Recaller.from_db(db).recall_text(DESCRIPTION)
            recall_s = time.perf_counter() - t0
            urls = [p for s in result.stores.stores for p in (*s.search_pages, *s.product_pages)]
            t0 = time.perf_counter()
            for url in urls:
                session.get(url, timeout=5).content  # noqa: B018 - read the body
            bare_s = time.perf_counter() - t0
            if i == 0:
                continue
            cold.append({"total": total, **result.seconds})
            again.append(forced)
            plain.append(recall_s)
            bare.append(bare_s)
    shutil.rmtree(tmp, ignore_errors=True)
    med = {k: statistics.median(r[k] for r in cold) for k in ("total", *PARTS[:-1])}
    med["other"] = max(med["total"] - sum(med[k] for k in PARTS[:-1]), 0.0)
    out = {
        "runs": runs,
        "lookup_s": med,
        "forced_again_s": statistics.median(again),
        "plain_recall_s": statistics.median(plain),
        "bare_fetch_s": statistics.median(bare),
    }
    _print(out)
    return out


def _print(out: dict[str, Any]) -> None:
    med, plain = out["lookup_s"], out["plain_recall_s"]
    print(f"lookup benchmark: demo store on 127.0.0.1, delay 0, median of {out['runs']} runs")
    print(f"  description -> answer with a lookup: {med['total']:.3f} s ({med['total'] / plain:.1f}x a plain recall)")
    for part in PARTS:
        print(f"    {part:<8} {med[part]:.3f} s  {100 * med[part] / med['total']:5.1f} %")
    print(f"  same lookup again, forced (304s, nothing written): {out['forced_again_s']:.3f} s "
          f"({out['forced_again_s'] / plain:.1f}x)")  # fmt: skip
    print(f"  baseline: plain recall {plain:.3f} s; bare GETs of the same URLs {out['bare_fetch_s']:.3f} s "
          f"(fetching is {med['fetch'] / max(out['bare_fetch_s'], 1e-9):.1f}x bare)")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=5, help="measured runs (median), after one warm-up")
    args = parser.parse_args()
    bench(args.runs)


if __name__ == "__main__":
    main()
