"""Extraction on the real-page corpus (``scrapers.corpus.load_corpus``), scored by the rule of
``scrapers/verdicts.py``: dimensions right when every stated extent is found and every extracted extent is
stated (within 2 %; a page stating none gives none), mass the same; invented values counted.

Prints, for the development stores (and, with ``--held-out``, the held-out stores in aggregate only: no
page of a held-out store is ever named): pages right by language and by layout class, the shared batches
apart, the invented-value count over the whole corpus, the values one store's pages report for
different products (a size guide or a banner read as the product's), a leave-one-store-out table
of the chooser's weights fitted without the store (``--loso``), and the CPU time of extraction against a bare lxml parse of
the same page (median of the per-page ratios), with the load average.

Run: ``python benchmarks/corpus_bench.py [--held-out] [--loso] [--failures] [--stages] [--repeat N] [--save]``.
``--failures`` lists the development pages that fail (never a held-out one). ``--save`` (needs
``--held-out``) writes ``benchmarks/results/corpus_bench.json``, from which ``scripts/readme_figures.py``
renders the README's extraction table.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections import defaultdict
from functools import partial
from pathlib import Path

from timing import median_cpu_s

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from kb.errors import ExtractionError  # noqa: E402

#: Layout classes of the shared batches, whose labels have a free-text ``format`` instead of ``layout``.
_FORMAT_WORDS = (
    ("json-ld", "json-ld"), ("microdata", "microdata"), ("state", "embedded-json"), ("json", "embedded-json"),
    ("table", "table"), ("dl", "dl"), ("bullet", "list"), ("list", "list"), ("description", "free-text"),
    ("prose", "free-text"), ("title", "title"), ("variant", "variant-list"), ("select", "variant-list"),
)  # fmt: skip


def layouts(page) -> list[str]:
    """The layout classes of a page's label (``layout``; for the shared batches read from ``format``)."""
    truth = page.truth or {}
    found = truth.get("layout")
    if isinstance(found, str):
        found = [found]
    if found:
        return list(found)
    text = (truth.get("format") or "").lower()
    classes = [cls for word, cls in _FORMAT_WORDS if word in text]
    return list(dict.fromkeys(classes)) or ["unlabelled"]


def part_of(page) -> str:
    batch = (page.source or {}).get("batch")
    return batch if batch else "corpus"


def extract(page):
    from scrapers.extract import extract_page

    try:
        return extract_page(page.path.read_bytes(), page.url or f"https://example.test/{page.id}", "text/html")
    except ExtractionError:
        return None


def score_page(page, repeat: int) -> dict:
    import lxml.html

    from scrapers.verdicts import invented, judge, page_numbers

    body = page.path.read_bytes()
    record = extract(page)
    verdict = judge(record, page.truth)
    text = body.decode("utf-8", errors="replace")
    out = {"dims": verdict.dims_right, "mass": verdict.mass_right, "problems": verdict.problems,
           "invented": invented(record, page.truth, page_numbers(text)),
           "samples": choice_samples(record, page.truth), "reported": reported(record)}  # fmt: skip
    if repeat:
        cpu = median_cpu_s(lambda: extract(page), repeat)
        base = median_cpu_s(lambda: lxml.html.document_fromstring(body), repeat)
        out["cpu"], out["lxml"] = cpu, base
    return out


def stages(pages, repeat: int) -> list[str]:
    """CPU per page of each stage of extraction (decoding, the tree, the visible lines, each adapter run
    on every page, fallbacks too, the category trail, the chooser) beside a bare lxml parse: where the
    time goes. Medians over pages of the per-page median of ``repeat`` runs."""
    import lxml.html

    per: dict[str, list[float]] = defaultdict(list)
    for page in pages:
        body, url = page.path.read_bytes(), page.url or f"https://example.test/{page.id}"
        per["lxml parse (baseline)"].append(median_cpu_s(partial(lxml.html.document_fromstring, body), repeat))
        runs: dict[str, list[float]] = defaultdict(list)
        for _ in range(max(repeat, 1)):
            for name, seconds in _stage_times(body, url):
                runs[name].append(seconds)
        for name, times in runs.items():
            per[name].append(statistics.median(times))
    lines = [f"CPU per page by stage ({len(pages)} pages; every adapter on every page), median ms:"]
    lines += [f"  {name:28} {statistics.median(v) * 1000:6.2f}" for name, v in per.items()]
    return lines


def _stage_times(body: bytes, url: str) -> list[tuple[str, float]]:
    """One extraction of ``body`` run stage by stage: (stage, CPU seconds)."""
    from scrapers.extract import ADAPTERS, fuse
    from scrapers.page import Page
    from scrapers.trail import category_trail

    out = []
    clock = time.process_time
    t = clock()
    pg = Page(body, url, "text/html")
    out.append(("decode", clock() - t))
    for name, attr in (("tree", "tree"), ("lines", "lines"), ("language and decimal mark", "decimal_comma")):
        t = clock()
        getattr(pg, attr)
        out.append((name, clock() - t))
    obs = []
    for a in ADAPTERS:
        t = clock()
        found = a.func(pg)
        out.append((f"adapter {a.name}", clock() - t))
        for o in found:
            o.source = a.name
        obs.extend(found)
    t = clock()
    category_trail(pg)
    out.append(("trail", clock() - t))
    t = clock()
    try:
        fuse(obs, url)
    except ExtractionError:
        pass
    out.append(("chooser", clock() - t))
    return out


def reported(record) -> list[tuple]:
    """The product values a record reports, as comparable keys: ("dims", extents) and ("mass", g)."""
    if record is None:
        return []
    out = []
    if record.dims:
        out.append(("dims", tuple(sorted(round(e["cm"], 1) for e in record.dims))))
    if record.mass_g is not None:
        out.append(("mass", round(record.mass_g, 1)))
    return out


def shared_values(rows: list[tuple]) -> tuple[int, int]:
    """Values one store's pages report for different products (a size guide or a banner read as the
    product's): (how many such values, on how many pages). A value counts when two or more pages of one
    store report it and it is wrong on at least one of them."""
    by_store: dict[str, dict[tuple, list[dict]]] = defaultdict(lambda: defaultdict(list))
    for page, s in rows:
        for key in s["reported"]:
            by_store[page.store][key].append(s)
    values, pages = 0, 0
    for seen in by_store.values():
        for (feature, _), group in seen.items():
            if len(group) > 1 and not all(s[feature] for s in group):
                values, pages = values + 1, pages + len(group)
    return values, pages


def _cell(rows: list[dict], key: str) -> str:
    return f"{sum(r[key] for r in rows)}/{len(rows)}" if rows else "-"


def table(rows: list[tuple], title: str) -> list[str]:
    """Rows (page, score) grouped by language and by layout class: dims and mass right."""
    lines = [f"{title}: {len(rows)} pages, {len({p.store for p, _ in rows})} stores",
             f"  {'group':24} {'pages':>5} {'dims':>8} {'mass':>8} {'both':>8}"]
    groups: dict[str, list[dict]] = defaultdict(list)
    for page, s in rows:
        s = {**s, "both": s["dims"] and s["mass"]}
        groups["all"].append(s)
        groups[f"lang {page.language or '?'}"].append(s)
        for cls in layouts(page):
            groups[f"layout {cls}"].append(s)
        groups[f"part {part_of(page)}"].append(s)
    order = sorted(groups, key=lambda k: (k != "all", k.split()[0], -len(groups[k]), k))
    for key in order:
        g = groups[key]
        lines.append(f"  {key:24} {len(g):5} {_cell(g, 'dims'):>8} {_cell(g, 'mass'):>8} {_cell(g, 'both'):>8}")
    return lines


def choice_samples(record, truth) -> dict[str, list[tuple[dict, bool]]]:
    """Per feature, the clusters the chooser weighed on one page as ``(features, right)``: what
    ``scrapers.choice.fit_weights`` fits on (``right``: the cluster's value is the label's, within 2 %)."""
    from scrapers.records import ProductRecord
    from scrapers.verdicts import dims_right, truth_of, within

    if record is None:
        return {}
    want_dims, want_mass = truth_of(truth)
    found: dict[str, dict[int, tuple[dict, bool]]] = defaultdict(dict)
    for c in record.candidates:
        if not c.get("representative"):
            continue
        if c["feature"] == "dims":
            right = dims_right(ProductRecord(name=None, url="", dims=c["extents"]), want_dims)
        else:
            right = want_mass is not None and within(c["value"], want_mass)
        found[c["feature"]][c["cluster"]] = (c["features"], right)
    return {f: [v for _, v in sorted(d.items())] for f, d in found.items()}


def loso_table(rows: list[tuple]) -> dict:
    """Leave-one-store-out over the development stores: the chooser's weights fitted
    (``scrapers.choice.fit_weights``) on every development store but one, then that store scored with
    them; beside it the store's score with the weights in use (``scrapers.choice.WEIGHTS``)."""
    from scrapers.choice import WEIGHTS, fit_weights, pick

    by_store: dict[str, list[dict]] = defaultdict(list)
    for page, s in rows:
        by_store[page.store].append(s)

    def right(s: dict, feature: str, weights: dict) -> bool:
        sample = s["samples"].get(feature)
        return pick(sample, weights) if sample and weights is not WEIGHTS else s[feature]

    table_rows = []
    for store, scored in sorted(by_store.items()):
        others = [x for k, v in by_store.items() if k != store for s in v for x in s["samples"].values()]
        w = fit_weights(others)
        changed = {k: v for k, v in w.items() if v != WEIGHTS[k]}
        row = {"store": store, "pages": len(scored), "weights": changed}
        for f in ("dims", "mass"):
            row[f] = f"{sum(right(s, f, w) for s in scored)}/{len(scored)}"
            row[f"{f}_in_use"] = f"{sum(s[f] for s in scored)}/{len(scored)}"
        table_rows.append(row)
    lines = [f"leave-one-store-out (development stores): {len(by_store)} stores; fitted on the others "
             "(in use: scrapers.choice.WEIGHTS)",
             f"  {'store':20} {'pages':>5} {'dims':>7} {'in use':>7} {'mass':>7} {'in use':>7}  weights fitted"]
    for r in table_rows:
        lines.append(f"  {r['store']:20} {r['pages']:5} {r['dims']:>7} {r['dims_in_use']:>7} {r['mass']:>7} "
                     f"{r['mass_in_use']:>7}  {r['weights'] or 'same'}")
    return {"rows": table_rows, "lines": lines}  # fmt: skip


def summary(rows: list[tuple]) -> dict:
    """The saved figures of a part: counts overall, by language, by layout class and by batch."""
    def counts(sel):
        return {"pages": len(sel), "dims": sum(s["dims"] for s in sel), "mass": sum(s["mass"] for s in sel)}

    by: dict[str, dict[str, list]] = {"language": defaultdict(list), "layout": defaultdict(list),
                                      "part": defaultdict(list)}  # fmt: skip
    for page, s in rows:
        by["language"][page.language or "?"].append(s)
        for cls in layouts(page):
            by["layout"][cls].append(s)
        by["part"][part_of(page)].append(s)
    return {"all": counts([s for _, s in rows]), "stores": len({p.store for p, _ in rows}),
            **{k: {g: counts(v) for g, v in sorted(d.items())} for k, d in by.items()}}  # fmt: skip


def speed(rows: list[tuple]) -> dict:
    ratios = [s["cpu"] / s["lxml"] for _, s in rows if s.get("lxml")]
    if not ratios:
        return {}
    return {
        "median_ratio": round(statistics.median(ratios), 2),
        "cpu_ms_median": round(statistics.median(s["cpu"] for _, s in rows) * 1000, 1),
        "lxml_ms_median": round(statistics.median(s["lxml"] for _, s in rows) * 1000, 1),
        "pages": len(ratios), "load_average": round(os.getloadavg()[0], 1),
    }  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    from scrapers.corpus import load_corpus

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--held-out", action="store_true", help="also score the held-out stores (aggregate only)")
    ap.add_argument("--failures", action="store_true", help="list the failing development pages")
    ap.add_argument("--loso", action="store_true", help="leave-one-store-out table of the fitted chooser")
    ap.add_argument("--repeat", type=int, default=3, help="timing repeats per page (0: no timing)")
    ap.add_argument("--stages", action="store_true", help="CPU per page of each stage of extraction")
    ap.add_argument("--save", action="store_true")
    args = ap.parse_args(argv)

    pages = load_corpus()
    if not pages:
        print("no corpus pages (the cache and the shared batches are absent)")
        return 0
    dev = [p for p in pages if not p.held_out]
    held = [p for p in pages if p.held_out] if args.held_out else []
    dev_rows = [(p, score_page(p, args.repeat)) for p in dev]
    held_rows = [(p, score_page(p, args.repeat)) for p in held]
    print("\n".join(table(dev_rows, "development stores")))
    if args.failures:
        for page, s in dev_rows:
            if not (s["dims"] and s["mass"]) or s["invented"]:
                print(f"    FAIL {page.id} [{page.store}, {page.language}, {'/'.join(layouts(page))}]: "
                      f"{'; '.join(s['problems'] + s['invented'])}")
    if held_rows:
        print("\n".join(table(held_rows, "held-out stores (aggregate only)")))
    else:
        print(f"held-out stores: {len(pages) - len(dev)} pages, not scored (--held-out)")
    inv = [(p, s) for p, s in dev_rows + held_rows if s["invented"]]
    n_inv = sum(len(s["invented"]) for _, s in inv)
    print(f"invented values: {n_inv} on {len(inv)} pages of {len(dev_rows) + len(held_rows)} scored")
    n_shared, on_pages = shared_values(dev_rows + held_rows)
    print(f"values one store reports for different products, wrong on one at least: {n_shared} ({on_pages} pages)")
    loso = loso_table(dev_rows) if args.loso else None
    if loso:
        print("\n".join(loso["lines"]))
    sp = speed(dev_rows + held_rows)
    if sp:
        print(f"speed: extraction {sp['cpu_ms_median']} ms CPU median, lxml parse {sp['lxml_ms_median']} ms; "
              f"median per-page ratio {sp['median_ratio']}x over {sp['pages']} pages; load {sp['load_average']}")
    if args.stages:
        print("\n".join(stages(dev + held, args.repeat)))
    if args.save:
        if not held_rows:
            print("not saved: --save needs --held-out")
            return 1
        save(dev_rows, held_rows, n_inv, sp, loso)
    return 0


def save(dev_rows, held_rows, n_inv: int, sp: dict, loso: dict | None) -> None:
    from saved import save_result

    d, h = summary(dev_rows), summary(held_rows)
    def pct(c, k):
        return f"{c[k]}/{c['pages']}"

    result = (
        f"real pages ({d['all']['pages'] + h['all']['pages']} pages, {d['stores'] + h['stores']} stores): held-out "
        f"stores dims {pct(h['all'], 'dims')}, mass {pct(h['all'], 'mass')}; development dims {pct(d['all'], 'dims')}, "
        f"mass {pct(d['all'], 'mass')} (every stated extent found and every extracted one stated, within 2 %); "
        f"invented values {n_inv}; extraction {sp.get('median_ratio')}x a bare lxml parse (median per page, "
        f"CPU, load {sp.get('load_average')})"
    )
    data = {"development": d, "held_out": h, "invented": n_inv, "speed": sp,
            "shared_across_products": shared_values(dev_rows + held_rows)[0],
            "loso": loso["rows"] if loso else None}  # fmt: skip
    path = save_result("corpus_bench", benchmark="extraction, real-page corpus", result=result, data=data, order=29)
    print(f"saved {path}")


if __name__ == "__main__":
    raise SystemExit(main())
