"""Extraction speed and accuracy on every labelled page set, and the bound on pathological pages.

Part 1: for each labelled folder (the real pages in ``$OBJRECALL_STOREFRONT_PAGES`` or
``../shared/storefront-pages``, the hold-out pages in ``tests/data/holdout/pages``, the hand-written pages
in ``tests/fixtures/pages/labelled``): pages right (dimensions and mass within 1 %), package values
matched, and extraction ms per page as a ratio against parsing the same pages with lxml alone (the
baseline, measured in the same run).

Part 2: generated spec dumps (20,000 rows of weights and sizes, ~1-4 MB) that took seconds before
extraction was bounded (:data:`scrapers.page.MAX_LINES`, :data:`scrapers.adapters.spec_table.MAX_PAIRS`):
seconds per page, again against an lxml-only parse.

Run: ``python benchmarks/extract_bench.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from kb.errors import ExtractionError

ROOT = Path(__file__).resolve().parents[1]


def _median_s(func, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def _extract_or_none(body: bytes, url: str):
    from scrapers.extract import extract_page

    try:
        return extract_page(body, url, "text/html")
    except ExtractionError:
        return None


def _spec_dump(rows: int, kind: str) -> bytes:
    if kind == "weights":
        body = "".join(f"<tr><td>Gewicht</td><td>{i % 97 + 1},5 kg</td></tr>" for i in range(rows))
    else:
        body = "".join(
            f"<tr><th>Abmessungen Teil {i}</th><td>{i % 90 + 1} x {i % 40 + 1},5 x {i % 7 + 1} cm; {i % 300 + 1} g"
            f"</td></tr><tr><td>Artikel {i} passt zu Modell {i * 7} mit Länge {i % 80} cm</td></tr>"
            for i in range(rows)
        )
    head = "<tr><th>Abmessungen</th><td>30 x 20 x 10 cm</td></tr><tr><th>Gewicht</th><td>4,7 kg</td></tr>"
    return f"<html lang='de'><body><h1>Ersatzteile</h1><table>{head}{body}</table></body></html>".encode()


def main(argv: list[str] | None = None) -> None:
    import lxml.html

    from scrapers.extract import extract_page
    from scrapers.labelled_pages import default_pages_dir, judge, load_labels, package_matches

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)

    folders = {
        "real": default_pages_dir(),
        "holdout": ROOT / "tests" / "data" / "holdout" / "pages",
        "labelled": ROOT / "tests" / "fixtures" / "pages" / "labelled",
    }
    print(f"{'pages':9} {'n':>3} {'right':>6} {'package':>8} {'extract ms':>11} {'lxml ms':>8} {'ratio':>6}")
    for name, folder in folders.items():
        pages = load_labels(folder)
        if not pages:
            print(f"{name:9} (absent: {folder})")
            continue
        right = package = 0
        ms = base = 0.0
        for page in pages:
            body = page.path.read_bytes()
            url = page.url or f"https://example.test/{page.truth['file']}"
            try:
                record = extract_page(body, url, "text/html")
            except ExtractionError:
                record = None  # counts as wrong
            else:
                right += judge(record, page.truth).right
                package += package_matches(record, page.truth)
            ms += _median_s(lambda b=body, u=url: _extract_or_none(b, u), args.repeat) * 1000
            base += _median_s(lambda b=body: lxml.html.document_fromstring(b), args.repeat) * 1000
        n = len(pages)
        print(
            f"{name:9} {n:3} {right:3}/{n:<2} {package:4}/{n:<3} {ms / n:11.1f} {base / n:8.1f} {ms / base:6.2f}"
        )
    print()
    print(f"{'spec dump':24} {'MB':>5} {'extract s':>10} {'lxml s':>7} {'ratio':>6}  dims / mass")
    for kind in ("weights", "sizes"):
        body = _spec_dump(20_000, kind)
        record = extract_page(body, "https://shop.example.de/liste", "text/html")
        s = _median_s(
            lambda b=body: extract_page(b, "https://shop.example.de/liste", "text/html"), args.repeat
        )
        b = _median_s(lambda b=body: lxml.html.document_fromstring(b), args.repeat)
        print(
            f"{'20,000 rows of ' + kind:24} {len(body) / 1e6:5.1f} {s:10.2f} {b:7.2f} {s / b:6.2f}  "
            f"{record.dims_cm} / {record.mass_g}"
        )


if __name__ == "__main__":
    main()
