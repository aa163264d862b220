"""Lookup on real store pages: a person's description of a product the catalog lacks, recalled with a lookup.

A store on 127.0.0.1 (:class:`scrapers.corpus_store.CorpusStore`, written here) sells the real-page corpus's
product pages (real pages, :mod:`scrapers.corpus`) behind a word-overlap search over what a store's search
indexes (title, brand, category trail, description text, in the page's language; rarer words and name words
count more).
Each description (data written here, ``tests/data/lookup_real/``) is recalled with
``recall_with_lookup`` (default time budget) into its own copy of the seeded catalog:

- **right**: the recall's match after the lookup is the object written from the page the description is of;
- **values right**: and that object's sizes and mass are the page's labelled ones (within 2 %, the
  corpus's tolerance, ``scrapers.verdicts.TOLERANCE``);
- **over budget**: the lookup's own clock past its time budget;
- **catalog**: descriptions of seed-catalog objects, which must be recalled without searching.

Figures per split of the corpus by store (:func:`scrapers.corpus.held_out`): the development stores were
looked at while fixing, the held-out ones only measured.

Run: ``python benchmarks/lookup_real_bench.py [--failures] [--only ID] [--save]``. ``--failures`` lists the
development descriptions that miss (never a held-out one).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def run(only: str | None = None, budget_s: float | None = None):
    import requests

    from kb.catalog import KnowledgeBase
    from recall.lookup import DEFAULT_BUDGET_S
    from recall.lookup_eval import load_descriptions, run_trial
    from scrapers.corpus import load_corpus
    from scrapers.corpus_store import CorpusStore
    from scrapers.sources import parse_sources

    budget_s = budget_s or DEFAULT_BUDGET_S
    corpus = load_corpus()
    pages = {p.id: p for p in corpus}
    rows = load_descriptions()
    catalog_rows = load_descriptions("catalog_descriptions.jsonl")
    if only:
        rows = [r for r in rows if only in r["page"]]
        catalog_rows = [r for r in catalog_rows if only in r["object"]]
    tmp = Path(tempfile.mkdtemp(prefix="lookup-real-"))
    template = tmp / "seed.duckdb"
    KnowledgeBase.open(template).import_csv(Path(__file__).resolve().parents[1] / "kb/data/seed_catalog.csv")
    with CorpusStore(corpus) as store, requests.Session() as session:
        sources = parse_sources(store.sources_toml())
        trials = [run_trial(template, tmp, r, store, sources, session, pages, budget_s) for r in rows]
        catalog = [run_trial(template, tmp, r, store, sources, session, pages, budget_s) for r in catalog_rows]
        sold = len(store.items)
    return trials, catalog, budget_s, sold


def report(trials, catalog, budget_s: float, sold: int, failures: bool) -> dict:
    from recall.lookup_eval import summary

    dev = [t for t in trials if not t.held_out]
    held = [t for t in trials if t.held_out]
    new = [t for t in dev if t.written_by]  # the later development rows (README: written before any run)
    out = {"all": summary(trials), "development": summary(dev), "new_development": summary(new),
           "held_out": summary(held),
           "catalog": summary(catalog), "budget_s": budget_s, "pages": sold}  # fmt: skip
    print(f"lookup on real store pages ({sold} pages real, descriptions written here), time budget "
          f"{budget_s:g} s per lookup")  # fmt: skip
    for part in ("all", "development", "new_development", "held_out"):
        s = out[part]
        if not s["descriptions"]:
            continue
        print(f"  {part:<15} right {s['right']}/{s['descriptions']} ({s['right_share']}), values right "
              f"{s['values_right']}/{s['descriptions']} ({s['values_share']}), over budget {s['over_budget']}, "
              f"slowest {s['max_s']} s")  # fmt: skip
    c = out["catalog"]
    print(f"  catalog objects: searched {c['looked_up']}/{c['descriptions']}, recalled right {c['right']}")
    if failures:
        # Development descriptions and catalog objects only: a held-out store's miss is never listed, so
        # no rule is chosen for it (its count is in the summary above).
        for t in [*dev, *catalog]:
            if not t.values_right:
                cand = t.candidate or {}
                print(f"- {t.expected} {'H' if t.held_out else 'D'} {t.text!r}: match {t.match!r}; why {t.why}; "
                      f"page {cand.get('outcome')} {cand.get('name')!r} ({cand.get('reason')}); "
                      f"{'; '.join(t.problems)}; {t.seconds:.1f} s")  # fmt: skip
    return out


def save(out: dict, trials) -> None:
    from saved import save_result

    d, h, c, n = out["development"], out["held_out"], out["catalog"], out["new_development"]
    load = round(os.getloadavg()[0], 1)
    result = (
        f"{d['descriptions'] + h['descriptions']} descriptions of products the seed catalog lacks (written here) "
        f"against {out['pages']} real corpus pages behind a word-overlap search over title, brand, trail and description (the store written here): "
        f"right product {d['right']}/{d['descriptions']} development stores, "
        f"{h['right']}/{h['descriptions']} held-out (of the development ones, {n['right']}/{n['descriptions']} "
        f"written later, before any run: unseen when written); values right {d['values_right']}/{d['descriptions']} and "
        f"{h['values_right']}/{h['descriptions']}; over the {out['budget_s']:g} s budget {out['all']['over_budget']}, "
        f"slowest {out['all']['max_s']} s; catalog objects searched {c['looked_up']}/{c['descriptions']} "
        f"(load {load} on 2 cores)"
    )
    data = {**out, "trials": [t.to_dict() for t in trials]}
    path = save_result("lookup_real_bench", benchmark="lookup, real store pages", result=result, data=data,
                       order=85)  # fmt: skip
    print(f"saved {path}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--failures", action="store_true", help="list the development descriptions not right (never a held-out one)")
    ap.add_argument("--only", help="only the descriptions whose page id (or catalog object) holds this")
    ap.add_argument("--save", action="store_true", help="save the README row (benchmarks/results)")
    args = ap.parse_args()
    trials, catalog, budget_s, sold = run(args.only)
    out = report(trials, catalog, budget_s, sold, args.failures)
    if args.save and not args.only:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        save(out, trials)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
