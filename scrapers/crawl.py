"""The nightly job's crawl: every store discovered and fetched on its own thread, under its own budget.

Each store runs its whole pipeline (discover its URLs, then fetch and extract its pages in order) on a
thread of its own, up to ``max_stores`` at a time, so a slow or hostile store (a page that drips, a sitemap
or robots.txt that hangs) holds only itself: the other stores' pages go on. The politeness rule is the
fetcher's and unchanged: one request at a time per host, with its delay, even for two stores on one host.

A store's :class:`~scrapers.deadlines.StoreBudget` (``budget_s`` in the sources file) starts with its first
request; every fetch of the store ends by the budget's end, and once it is spent the store's remaining pages
are not fetched: each is a rejected page with the reason ``store_budget_spent`` (a ``page_events`` row), its
catalog object and stored validators untouched. A URL listed by two stores is fetched once, by the store
that reaches it first.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from scrapers.deadlines import BUDGET_SPENT, StoreBudget
from scrapers.fetcher import Clock, PoliteFetcher
from scrapers.outcomes import PageOutcome
from scrapers.sources import StoreSource

__all__ = ["budget_spent_page", "crawl_stores"]

#: discover(fetcher, store, events, until) -> the store's page URLs.
Discover = Callable[..., list[str]]
#: process(fetcher, store, url, previous_row, until) -> the page's outcome.
Process = Callable[..., PageOutcome]
ProgressFn = Callable[[int, int, str], None]


def budget_spent_page(store: StoreSource, url: str) -> PageOutcome:
    """The outcome of a page not fetched because its store's budget for the run was spent."""
    return PageOutcome(
        url=url,
        store=store.name,
        outcome="rejected",
        stage="fetch",
        reason=BUDGET_SPENT,
        detail=f"the store's time budget ({store.budget_s:g} s) for this run was spent before this page",
    )


class _Progress:
    """Pages done over pages known so far (the total grows as stores finish discovering)."""

    def __init__(self, fn: ProgressFn | None):
        self.fn, self.done, self.total = fn, 0, 0
        self.lock = threading.Lock()

    def planned(self, n: int) -> None:
        with self.lock:
            self.total += n
            if self.fn:
                self.fn(self.done, self.total, "")

    def page(self, url: str) -> None:
        with self.lock:
            self.done += 1
            if self.fn:
                self.fn(self.done, self.total, url)


def crawl_stores(
    fetcher: PoliteFetcher,
    stores: tuple[StoreSource, ...] | list[StoreSource],
    previous: dict[str, dict[str, Any]],
    *,
    discover: Discover,
    process: Process,
    clock: Clock,
    progress: ProgressFn | None = None,
    max_stores: int = 4,
) -> tuple[list[PageOutcome], list[tuple[str, str, str]]]:
    """Crawl every store (see the module docstring); returns the page outcomes (stores in order, each
    store's pages in its order) and the discovery problems as (url, stage, reason)."""
    claimed: set[str] = set()
    claim_lock = threading.Lock()
    tracker = _Progress(progress)

    def crawl(store: StoreSource) -> tuple[list[PageOutcome], list[tuple[str, str, str]]]:
        budget = StoreBudget(store.budget_s)
        until = budget.start(clock.monotonic())
        events: list[tuple[str, str, str]] = []
        urls = discover(fetcher, store, events, until=until)
        with claim_lock:
            mine = [u for u in urls if u not in claimed]
            claimed.update(mine)
        tracker.planned(len(mine))
        outcomes: list[PageOutcome] = []
        for url in mine:
            if budget.spent(clock.monotonic()):
                outcomes.append(budget_spent_page(store, url))
            else:
                outcomes.append(process(fetcher, store, url, previous.get(url), until=until))
            tracker.page(url)
        return outcomes, events

    workers = max(1, min(max_stores, len(stores)))
    if workers == 1:
        results = [crawl(store) for store in stores]
    else:
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="ingest-store") as pool:
            results = list(pool.map(crawl, stores))  # re-raises a worker's unexpected error
    outcomes = [o for store_outcomes, _ in results for o in store_outcomes]
    events = [e for _, store_events in results for e in store_events]
    return outcomes, events
