"""Extraction speed and accuracy on every labelled page set, and the bound on pathological pages.

Part 1: each shared real batch (dev and, with ``--blind``, blind split) and the pages written here in the
held-back classes (``tests/fixtures/pages/unseen``): dims within 2 % by how many axes the page states, mass,
ms per page, beside the figures before issue 11 and before this session (:data:`BEFORE`). Then for each
other labelled folder (the real pages in ``$OBJRECALL_STOREFRONT_PAGES`` or
``../shared/storefront-pages``, the hold-out pages in ``tests/data/holdout/pages``, the hand-written pages
in ``tests/fixtures/pages/labelled``): pages right (dimensions and mass within 1 %), package values
matched, and extraction ms per page as a ratio against parsing the same pages with lxml alone (the
baseline, measured in the same run).

Part 2: generated spec dumps (20,000 rows of weights and sizes, ~1-4 MB) that took seconds before
extraction was bounded (:data:`scrapers.page_lines.MAX_LINES`, :data:`scrapers.adapters.spec_table.MAX_PAIRS`):
seconds per page, again against an lxml-only parse.

Run: ``python benchmarks/extract_bench.py [--repeat N] [--save]`` (``--save``: the real dev pages' figures and the
spec dumps' become the README row, ``benchmarks/results/extract_bench.json``).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from timing import median_cpu_s

from kb.errors import ExtractionError

ROOT = Path(__file__).resolve().parents[1]


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


#: 2 %: the issue's goal ("dims and mass within 2 %").
SCORE_TOLERANCE = 0.02


def _score(pages, repeat: int) -> dict:
    """Per page set: dims right by stated axes (3/2/1, and 'none' = nothing reported where the label has
    no dims), mass right (and 'none'), ms per page of extraction and of an lxml-only parse."""
    import lxml.html

    from scrapers.labelled_pages import dims_within, within

    out = {"n": len(pages), "dims": {}, "mass": [0, 0], "mass_none": [0, 0], "ms": 0.0, "lxml": 0.0}
    for page in pages:
        body = page.path.read_bytes()
        url = page.url or f"https://example.test/{page.truth['file']}"
        record = _extract_or_none(body, url)
        dims = record.dims_cm if record else None
        mass = record.mass_g if record else None
        want_dims, want_mass = page.truth.get("dims_cm"), page.truth.get("mass_g")
        key = str(len(want_dims)) if want_dims else "none"
        ok = dims_within(dims, want_dims, SCORE_TOLERANCE) if want_dims else dims is None
        cell = out["dims"].setdefault(key, [0, 0])
        cell[0] += ok
        cell[1] += 1
        if want_mass is not None:
            out["mass"][0] += mass is not None and within(mass, want_mass, SCORE_TOLERANCE)
            out["mass"][1] += 1
        else:
            out["mass_none"][0] += mass is None
            out["mass_none"][1] += 1
        out["ms"] += median_cpu_s(lambda b=body, u=url: _extract_or_none(b, u), repeat) * 1000
        out["lxml"] += median_cpu_s(lambda b=body: lxml.html.document_fromstring(b), repeat) * 1000
    return out


def _fmt_cell(cell) -> str:
    return f"{cell[0]}/{cell[1]}" if cell and cell[1] else "-"


def _print_scores(name: str, s: dict, before: list[tuple[str, str]] | None) -> None:
    stated = [s["dims"].get(k) for k in ("3", "2", "1")]
    right = sum(c[0] for c in stated if c)
    total = sum(c[1] for c in stated if c)
    n = max(s["n"], 1)
    row = (
        f"{name:16} {s['n']:3} {_fmt_cell([right, total]):>7} {_fmt_cell(stated[0]):>6} "
        f"{_fmt_cell(stated[1]):>6} {_fmt_cell(stated[2]):>6} {_fmt_cell(s['dims'].get('none')):>6} "
        f"{_fmt_cell(s['mass']):>7} {_fmt_cell(s['mass_none']):>7} {s['ms'] / n:8.1f} {s['lxml'] / n:7.1f}"
        f" {s['ms'] / max(s['lxml'], 1e-9):5.1f}x"
    )
    print(row)
    widths = (7, 6, 6, 6, 6, 7, 7, 8, 7, 6)
    for label, figures in before or []:
        print(f"{'  ' + label:16} {'':3} " + " ".join(f"{v:>{w}}" for v, w in zip(figures.split(), widths, strict=True)))


#: Figures of the extractor before issue 11 (main at b01e090, measured with this script, --repeat 1) and at the
#: start of its third session (main at 6539669, the same day, before this session's work): dims, 3/2/1 axes,
#: none, mass, mass none, ms per page, ratio to lxml. The blind split was scored once at the end of the
#: first session (so it is no longer blind) and again at the end of this one; the machine was loaded each
#: time: compare ratios, not ms. The pages written here in the held-back classes (``unseen``) were written at
#: the start of the third session and scored on 6539669 before any change (ms not measured then).
BEFORE = {
    "batch1 dev": [("before", "9/9 9/9 - - - 7/7 2/2 46.4 9.6 4.8x"),
                   ("session", "9/9 9/9 - - - 7/7 2/2 49.3 9.0 5.5x")],
    "batch1 blind": [("before", "2/2 2/2 - - 1/1 2/2 1/1 244.9 41.9 5.8x"),
                     ("session", "2/2 2/2 - - 1/1 2/2 1/1 55.3 11.5 4.8x")],
    "batch2 dev": [("before", "15/17 14/15 0/1 1/1 2/2 11/13 5/6 46.9 9.8 4.8x"),
                   ("session", "15/17 14/15 0/1 1/1 2/2 12/13 5/6 61.7 12.4 5.0x")],
    "batch2 blind": [("before", "5/6 4/5 - 1/1 1/1 3/3 4/4 207.4 50.7 4.1x"),
                     ("session", "6/6 5/5 - 1/1 1/1 3/3 4/4 78.7 17.5 4.5x")],
    "written unseen": [("session", "13/18 11/12 2/5 0/1 - 12/14 3/4 - - -")],
}  # fmt: skip
#: The pages written here in the held-back classes (data written here: not evidence of generality).
UNSEEN = ROOT / "tests" / "fixtures" / "pages" / "unseen"


def main(argv: list[str] | None = None) -> None:
    from scrapers.extract import extract_page
    from scrapers.labelled_pages import blind_split, default_pages_dir, judge, load_labels, package_matches

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument(
        "--blind", action="store_true", help="also score the blind split (done once, at the end)"
    )
    parser.add_argument("--save", action="store_true", help="save the real dev pages' figures as the README row")
    args = parser.parse_args(argv)

    shared = default_pages_dir()
    print(f"shared real pages (within {SCORE_TOLERANCE:.0%}); dims by axes the page states; "
          "'none' = no value reported where the page states none")
    print(f"{'pages':16} {'n':>3} {'dims':>7} {'3 ax':>6} {'2 ax':>6} {'1 ax':>6} {'none':>6} "
          f"{'mass':>7} {'m none':>7} {'cpu ms':>8} {'lxml':>7} {'ratio':>6}")
    scores: dict[str, dict] = {}
    for batch, folder in (("batch1", shared), ("batch2", shared / "batch2")):
        pages = load_labels(folder)
        if not pages:
            print(f"{batch:16} (absent: {folder})")
            continue
        dev, blind = blind_split(pages)
        for split, subset in (("dev", dev), ("blind", blind)):
            if split == "blind" and not args.blind:
                print(f"{batch + ' blind':16} {len(subset):3} (run with --blind: no longer blind, scored at the end of sessions 2 and 3)")
                continue
            scores[f"{batch} {split}"] = _score(subset, args.repeat)
            _print_scores(f"{batch} {split}", scores[f"{batch} {split}"], BEFORE.get(f"{batch} {split}"))
    unseen = load_labels(UNSEEN)
    if unseen:
        scores["written unseen"] = _score(unseen, args.repeat)
        _print_scores("written unseen", scores["written unseen"], BEFORE.get("written unseen"))
    print("(before: main at b01e090, before issue 11; session: main at 6539669, before this session's work; their ms are wall time)")
    print()
    _print_other_folders(extract_page, judge, load_labels, package_matches, args.repeat)
    print()
    dumps = _print_spec_dumps(extract_page, args.repeat)
    if args.save:
        _save({k: v for k, v in scores.items() if k.endswith(" dev")}, dumps, scores)


def _save(dev: dict[str, dict], dumps: dict[str, float], scores: dict[str, dict] | None = None) -> None:
    """The README row: extraction ms per real dev page against lxml alone, dims/mass right, spec dumps."""
    from saved import save_result

    if not dev:
        print("not saved: the real pages are absent (set OBJRECALL_STOREFRONT_PAGES)")
        return
    n = sum(s["n"] for s in dev.values())
    ms, lxml_ms = sum(s["ms"] for s in dev.values()), sum(s["lxml"] for s in dev.values())
    stated = [c for s in dev.values() for k, c in s["dims"].items() if k != "none"]
    dims = [sum(c[0] for c in stated), sum(c[1] for c in stated)]
    mass = [sum(s["mass"][0] for s in dev.values()), sum(s["mass"][1] for s in dev.values())]
    load = os.getloadavg()[0]
    result = (
        f"real pages (dev split, {n} pages of both batches): {ms / n:.0f} ms CPU per page, {ms / lxml_ms:.1f}× an lxml "
        f"parse alone; dims right {dims[0]}/{dims[1]}, mass {mass[0]}/{mass[1]} (within 2 %); a 20 000-row "
        f"generated spec dump {min(dumps.values()):.1f}–{max(dumps.values()):.1f} s; 2 shared cores, load {load:.0f}"
    )
    data = {
        "pages": n, "ms_per_page": round(ms / n, 1), "lxml_ms_per_page": round(lxml_ms / n, 1),
        "ratio_to_lxml": round(ms / lxml_ms, 2), "dims_right": dims, "mass_right": mass,
        "by_split": {k: {"n": s["n"], "ms_per_page": round(s["ms"] / max(s["n"], 1), 1), "dims": s["dims"],
                         "mass": s["mass"], "mass_none": s["mass_none"]} for k, s in (scores or dev).items()},
        "spec_dump_s": {k: round(v, 2) for k, v in dumps.items()}, "load_average": round(load, 1),
    }  # fmt: skip
    path = save_result("extract_bench", benchmark="extraction, real pages", result=result, data=data, order=30)
    print(f"saved {path}")


def _print_other_folders(extract_page, judge, load_labels, package_matches, repeat: int) -> None:
    """The hand-written and hold-out folders: pages right within 1 % (the old rule) and packages."""
    import lxml.html

    folders = {
        "holdout": ROOT / "tests" / "data" / "holdout" / "pages",
        "labelled": ROOT / "tests" / "fixtures" / "pages" / "labelled",
    }
    print("pages written here (right = dims and mass within 1 %)")
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
            record = _extract_or_none(body, url)
            if record is not None:
                right += judge(record, page.truth).right
                package += package_matches(record, page.truth)
            ms += median_cpu_s(lambda b=body, u=url: _extract_or_none(b, u), repeat) * 1000
            base += median_cpu_s(lambda b=body: lxml.html.document_fromstring(b), repeat) * 1000
        n = len(pages)
        print(
            f"{name:9} {n:3} {right:3}/{n:<2} {package:4}/{n:<3} {ms / n:11.1f} {base / n:8.1f} {ms / base:6.2f}"
        )


def _print_spec_dumps(extract_page, repeat: int) -> dict[str, float]:
    """Seconds to extract each 20,000-row spec dump (printed against an lxml-only parse); returned by kind."""
    import lxml.html

    seconds = {}

    print(f"{'spec dump':24} {'MB':>5} {'extract s':>10} {'lxml s':>7} {'ratio':>6}  dims / mass")
    for kind in ("weights", "sizes"):
        body = _spec_dump(20_000, kind)
        record = extract_page(body, "https://shop.example.de/liste", "text/html")
        s = median_cpu_s(lambda b=body: extract_page(b, "https://shop.example.de/liste", "text/html"), repeat)
        b = median_cpu_s(lambda b=body: lxml.html.document_fromstring(b), repeat)
        seconds[kind] = s
        print(
            f"{'20,000 rows of ' + kind:24} {len(body) / 1e6:5.1f} {s:10.2f} {b:7.2f} {s / b:6.2f}  "
            f"{record.dims_cm} / {record.mass_g}"
        )
    return seconds


if __name__ == "__main__":
    main()
