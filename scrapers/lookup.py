"""The store side of an on-demand lookup: search the stores, read the top results, keep what fits, write it.

:func:`search_stores` asks every store of a sources file that declares a ``search`` (see
:mod:`scrapers.sources`) for the given words, fetches its first ``search_results`` product pages (and
while none settles the search, :data:`SETTLED_ERROR`, the next, up to :data:`MAX_RESULT_BATCHES`
batches; a ``rel="next"`` results page is read only when its products are wanted,
:mod:`scrapers.store_search`; one store's search: :mod:`scrapers.lookup_store`) and extracts and validates them exactly as the nightly job does
(:func:`scrapers.ingest.process_page`), keeps the pages that ``fits`` accepts, and writes them as one
small ingestion run through the nightly job's own short write transaction (:func:`scrapers.ingest.write_run`):
observations with adapter ``lookup:<extractor>`` (provisional under the fusion rule, :mod:`scrapers.fusion`)
and an ``ingestion_runs`` row whose ``sources`` is ``lookup {"query": ..., "description": ..., ...}``.

Bounded: stores are searched at the same time (one thread each; each host still gets one request at a
time and its delay); every request's connect and read timeouts are clamped to the time left before
``deadline`` and there are no retries, so a slow store costs at most the time budget; ``max_pages`` counts
every request (search pages and product pages) over all stores. A store that fails (HTTP error, timeout,
robots.txt disallowing its search, a robots Crawl-delay longer than the time left) is skipped with its
reason. Nothing is written when no page fits, so the same lookup again adds nothing (its pages answer
304 and the objects are already there).

Knows nothing of recall: what "fits" means is the caller's (:mod:`recall.lookup` passes a recall of the
description over each candidate alone).
"""

from __future__ import annotations

import functools
import json
import re
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor, wait
from dataclasses import asdict, dataclass, field, replace
from typing import Any

import requests

from kb.features import ObjectRecord
from scrapers.fetcher import Clock, PoliteFetcher, SystemClock
from scrapers.fusion import LOOKUP_ADAPTER_PREFIX
from scrapers.ingest import IngestionReport, PageOutcome, previous_pages, write_run
from scrapers.lookup_store import (
    MAX_RESULT_BATCHES,
    SETTLED_ERROR,
    Budget,
    FitFn,
    StoreAnswer,
    search_one,
)
from scrapers.sources import Sources

__all__ = [
    "DEFAULT_MAX_PAGES", "MAX_RESULT_BATCHES", "MIN_MODEL_DIGITS", "SETTLED_ERROR", "Candidate", "StoreAnswer",
    "StoresLookup", "model_numbers", "search_stores",
]  # fmt: skip

#: Requests (search pages + product pages, all stores together) one lookup may make: a store's first
#: :data:`MAX_RESULT_BATCHES` batches of its default ``search_results`` (3) over two results pages, and
#: robots.txt (the time budget bounds a store with a delay between requests well before this).
DEFAULT_MAX_PAGES = 20
#: Stores searched at the same time.
MAX_PARALLEL_STORES = 4
#: Digits a model number holds at least ("E274F", "GB2470HSU-W5", "MP273APDE"; not a series letter and
#: number, "S9", "K2", "X27", that several products of a brand share).
MIN_MODEL_DIGITS = 3
_TOKEN = re.compile(r"[^\W_]+(?:[-/][^\W_]+)*")
#: A number and its unit ("128GB", "1080p", "20000mAh", "165Hz"): a quantity many products share.
_QUANTITY = re.compile(r"\d+(?:[.,]\d+)?[^\W\d_]{1,4}")


def model_numbers(name: str | None) -> set[str]:
    """The model numbers a product's name holds, lower case: words of letters and at least
    :data:`MIN_MODEL_DIGITS` digits that are no number with its unit ("NEC MultiSync E274F - LED-Monitor
    - 69 cm (27\") - 1920 x 1080" -> {"e274f"}; "Apple iPhone 13 (128GB)" -> none). Two stores' pages
    that fit and name one model number are one product (:func:`_judge`)."""
    found = set()
    for token in _TOKEN.findall(name or ""):
        letters = any(ch.isalpha() for ch in token)
        if letters and sum(ch.isdigit() for ch in token) >= MIN_MODEL_DIGITS and not _QUANTITY.fullmatch(token):
            found.add(token.lower())
    return found


@dataclass
class Candidate:
    """A product page read: its name and values, whether it fits, why, and what became of it."""

    url: str
    store: str
    name: str | None
    outcome: str  # added | known (not modified) | does_not_fit | rejected
    reason: str | None = None
    features: dict[str, Any] = field(default_factory=dict)


@dataclass
class StoresLookup:
    """The store side of one lookup: per-store answers, the candidates, what the write did, and times."""

    query: tuple[str, ...]
    stores: list[StoreAnswer] = field(default_factory=list)
    candidates: list[Candidate] = field(default_factory=list)
    run_id: int | None = None
    new_objects: list[str] = field(default_factory=list)
    updated_objects: list[str] = field(default_factory=list)
    observations_added: int = 0
    requests: int = 0
    fetch_s: float = 0.0
    extract_s: float = 0.0
    judge_s: float = 0.0
    write_s: float = 0.0
    message: str = ""

    @property
    def answered(self) -> list[str]:
        return [s.store for s in self.stores if s.status in ("answered", "no_results")]

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["answered"] = self.answered
        return d


def _judge(outcomes: list[PageOutcome], fits: FitFn, names: Sequence[str] = (), as_judged=None) -> list[Candidate]:
    """Mark each page: extracted pages that do not fit become rejections (recorded, never added); a page that
    fits is written as ``fits`` judged it (``as_judged``, when given: the record without what the fit read
    as no evidence, so that the recall after the lookup compares what the fit compared), named as a person
    reads it (:func:`scrapers.product_names.person_name`) and ``names`` (what the search asked for) become
    the aliases of the one that fits best (an alias names one object). Pages that fit and hold a model
    number of a better fit (:func:`model_numbers`) are that product sold by another store: they take its
    name (their own as an alias), so the write makes them one object whose values both pages observe,
    not two that compete for the recall (two stores' "iiyama G-Master GB2470HSU-W5" monitors)."""
    from scrapers.product_names import person_name

    out = []
    scored: list[tuple[float, int, PageOutcome, Candidate]] = []
    for page in outcomes:
        name = page.clean.name if page.clean is not None else None
        cand = Candidate(page.url, page.store, name, "rejected", page.reason and f"{page.reason}: {page.detail}")
        if page.outcome == "not_modified":
            cand.outcome, cand.reason = "known", "not modified since it was last read"
        elif page.outcome == "extracted":
            cand.features = page.clean.known_features()
            ok, why, *score = fits(page.clean)
            cand.outcome, cand.reason = ("added", why) if ok else ("does_not_fit", why)
            if ok:
                page.record.adapter = LOOKUP_ADAPTER_PREFIX + (page.record.adapter or "unknown")
                page.clean = as_judged(page.clean) if as_judged is not None else page.clean
                scored.append((score[0] if score else 0.0, len(scored), page, cand))
            else:
                page.outcome, page.stage, page.reason, page.detail = "rejected", "lookup", "does_not_fit", why
        out.append(cand)
    models: dict[str, str] = {}  # model number -> the name of the best fit that holds it
    for rank, (_, _, page, cand) in enumerate(sorted(scored, key=lambda s: s[:2])):
        own = person_name(page.clean.name)
        held = model_numbers(page.clean.name)
        twin = next((models[m] for m in sorted(held) if m in models), None)
        if twin is not None:  # another store's page of the same product: one object, its title an alias
            page.clean = _named(page.clean, twin, (own,))
        else:
            page.clean = _named(page.clean, own, names if rank == 0 else ())
            models.update({m: page.clean.name for m in held if m not in models})
        cand.name = page.clean.name
    return out


def _named(clean: ObjectRecord, name: str, names: Sequence[str]) -> ObjectRecord:
    """``clean`` under ``name`` with ``names`` as aliases (normalised as a record's; the name itself and
    names no record may hold are left out)."""
    from kb.errors import InvalidFeature
    from kb.features import check_name, normalize_name

    name = normalize_name(name) or clean.name
    aliases = []
    for alias in (*clean.aliases, *names):
        alias = normalize_name(alias)
        try:
            check_name("aliases", alias)
        except InvalidFeature:
            continue
        if alias and alias != name and alias not in aliases:
            aliases.append(alias)
    return replace(clean, name=name, aliases=tuple(aliases))


def search_stores(
    kb,
    sources: Sources,
    queries: Sequence[str],
    *,
    description: str,
    fits: FitFn,
    session: requests.Session,
    deadline: float,
    clock: Clock | None = None,
    max_pages: int = DEFAULT_MAX_PAGES,
    names: Sequence[str] = (),
    as_judged: Callable[[ObjectRecord], ObjectRecord] | None = None,
) -> StoresLookup:
    """Search the stores for ``queries`` (tried in order per store until one lists products), read the top
    results, and add those ``fits`` accepts to ``kb`` (see the module docstring), with ``names`` (what the
    description calls the object) as their aliases, each as ``as_judged`` makes it (:func:`_judge`).
    ``deadline`` is a ``clock.monotonic()`` time."""
    clock = clock or SystemClock()
    fits = functools.lru_cache(maxsize=None)(fits)  # judged once a record: by the stop rule, then by _judge
    report = StoresLookup(tuple(queries))
    stores = [s for s in sources.stores if s.search]
    if not stores:
        report.message = f"no store in {sources.origin} has a search (add search = \"...{{query}}\")"
        return report
    budget = Budget(clock, deadline, max_pages)
    fetcher = PoliteFetcher(session, clock=clock)
    previous = previous_pages(kb)
    t0 = time.perf_counter()
    pool = ThreadPoolExecutor(max_workers=min(MAX_PARALLEL_STORES, len(stores)), thread_name_prefix="lookup")
    futures = [pool.submit(search_one, fetcher, budget, s, queries, previous, fits) for s in stores]
    done, _ = wait(futures, timeout=max(budget.remaining(), 0.0) + 0.25)
    pool.shutdown(wait=False, cancel_futures=True)
    outcomes: list[PageOutcome] = []
    for store, fut in zip(stores, futures, strict=True):
        if fut in done:
            answer, pages = fut.result()
        else:
            answer, pages = StoreAnswer(store.name, "skipped", "still answering when the time ran out"), []
        report.stores.append(answer)
        outcomes += [p for p in pages if p.url not in {o.url for o in outcomes}]
    report.requests = fetcher.requests_made
    report.extract_s = budget.extract_s
    report.fetch_s = max(time.perf_counter() - t0 - budget.extract_s, 0.0)
    t0 = time.perf_counter()
    report.candidates = _judge(outcomes, fits, names, as_judged)
    report.judge_s = time.perf_counter() - t0
    _name_known(kb, report.candidates, previous)
    _write(kb, report, outcomes, description, clock)
    report.message = _message(report)
    return report


def _name_known(kb, candidates: list[Candidate], previous: dict[str, dict[str, Any]]) -> None:
    """The catalog names of pages not modified since a lookup or crawl read them (one short read)."""
    ids = {c.url: previous[c.url]["object_id"] for c in candidates if c.outcome == "known" and c.url in previous}
    if not ids:
        return
    with kb.connect() as con:
        sql = "SELECT id, name FROM objects WHERE list_contains(?, id)"
        names = dict(con.execute(sql, [list(ids.values())]).fetchall())
    for c in candidates:
        if c.url in ids:
            c.name = names.get(ids[c.url])


def _write(kb, report: StoresLookup, outcomes: list[PageOutcome], description: str, clock: Clock) -> None:
    """One ingestion run of the lookup's pages, only when a page fits (otherwise nothing changes)."""
    if not any(c.outcome == "added" for c in report.candidates):
        return
    meta = {"query": list(report.query), "description": description,
            "stores": [s.store for s in report.stores]}  # fmt: skip
    run = IngestionReport(run_id=None, status="ok", sources="lookup " + json.dumps(meta), started_at=clock.now())
    run.pages = run.fetched = len(outcomes)
    run.extracted = sum(1 for p in outcomes if p.record is not None)
    run.not_modified = sum(1 for p in outcomes if p.outcome == "not_modified")
    run.rejected = sum(1 for p in outcomes if p.outcome == "rejected")
    events = [(s.search_pages[-1] if s.search_pages else s.store, "lookup", s.reason)
              for s in report.stores if s.status == "skipped"]  # fmt: skip
    if events:
        run.status = "ok_with_errors"
        run.errors = [{"url": u, "stage": st, "reason": r} for u, st, r in events]
    write_run(kb, outcomes, run, events, clock)
    report.run_id, report.write_s = run.run_id, run.write_s
    report.new_objects, report.updated_objects = run.new_objects, run.updated_objects
    report.observations_added = run.observations_added


def _message(report: StoresLookup) -> str:
    asked = len(report.stores)
    skipped = [f"{s.store} ({s.reason})" for s in report.stores if s.status == "skipped"]
    if not report.answered:
        return f"no store answered: {'; '.join(skipped)}"
    added = report.new_objects + report.updated_objects
    if added:
        return f"added from {len(report.answered)} of {asked} store(s): {', '.join(added)}"
    known = [c.name for c in report.candidates if c.outcome == "known"]
    if known:
        return f"already in the catalog from an earlier lookup: {', '.join(n or '?' for n in known)}"
    if not report.candidates:
        return f"no store lists anything for {' / '.join(report.query)!r}"
    return f"{len(report.candidates)} product page(s) read, none fits the description"
