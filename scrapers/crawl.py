"""The nightly job's crawl: every store discovered and fetched on its own thread, under its own budget.

Each store runs its whole pipeline (discover its URLs, then fetch and extract its pages in order) on a
thread of its own, so a slow or hostile store (a page that drips, a sitemap or robots.txt that hangs) holds
only itself: the other stores' pages go on. Two limits, because waiting and working cost different things:

- **stores crawling at once**, ``max_crawling`` (:data:`MAX_CRAWLING`, 16): threads, each with one
  request in flight at most (its host's rule) or sleeping out its host's delay. A thread waiting on a
  socket costs no CPU, so a store that only waits (a drip, a server that hangs) must not keep another store
  from starting; 16 is Scrapy's default for requests in flight at once (``CONCURRENT_REQUESTS``);
- **stores working at once**, ``max_working`` (:data:`MAX_WORKING`, 4): a :class:`WorkSlots` slot is
  held only to parse what was fetched (a page's extraction, a sitemap's parse): the CPU-bound part, whose
  memory (a parsed tree) is the large one. A store waiting on the network holds no slot.

So four dripping stores listed before a good store hold four of the 16 threads and none of the work
slots: the good store starts at once (it waited for the four before, issue 25's blind tester: 11.5 s for
its first page instead of 0.8 s). And a store whose pages keep timing out gives its thread up: after
:data:`UNRESPONSIVE_AFTER` (2) fetches in a row cut by their deadline (reason ``timeout``: its sitemaps
count, then its pages), its remaining sitemaps are not read (a discovery error) and its remaining pages are
not fetched this run, each a rejected page with the reason ``store_unresponsive`` (a ``page_events``
row). One time-out can be one slow page; two in a row mean the store gave nothing for two
whole deadlines (a minute by default), and the next night reads every such page again in full. A fetch the
store answers (read, or refused for another reason: ``http_503``, ``connection_failed``) resets the count. So a store no longer holds the job for its budget (3600 s by default) by
dripping every page: at most two deadlines after its discovery, however many pages it lists.

The politeness rule is the fetcher's and unchanged: one request at a time per host, with its delay, even
for two stores on one host.

A store's :class:`~scrapers.deadlines.StoreBudget` (``budget_s`` in the sources file) starts with its first
request; every fetch of the store ends by the budget's end, and once it is spent the store's remaining pages
are not fetched: each is a rejected page with the reason ``store_budget_spent`` (a ``page_events`` row).
A page not fetched for either reason keeps its catalog object and stored validators untouched. A URL
listed by two stores is fetched once, by the store that reaches it first.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from scrapers.deadlines import BUDGET_SPENT, DEADLINE_PASSED, StoreBudget
from scrapers.fetcher import Clock, PoliteFetcher
from scrapers.outcomes import PageOutcome
from scrapers.sources import StoreSource

__all__ = [
    "MAX_CRAWLING",
    "MAX_WORKING",
    "STORE_UNRESPONSIVE",
    "UNRESPONSIVE_AFTER",
    "TimeoutStreak",
    "WorkSlots",
    "budget_spent_page",
    "crawl_stores",
    "unresponsive_page",
    "unresponsive_reason",
]

#: Stores crawled at once: threads that mostly wait on a socket or their host's delay.
MAX_CRAWLING = 16
#: Stores parsing a page (or a sitemap) at once: the CPU-bound work, on 2-4 cores.
MAX_WORKING = 4
#: Fetches in a row that timed out after which a store's other sitemaps and pages are not fetched this run.
UNRESPONSIVE_AFTER = 2
#: The reason (``page_events.reason`` prefix) of a page not fetched because its store stopped answering.
STORE_UNRESPONSIVE = "store_unresponsive"

#: discover(fetcher, store, events, until, work, streak) -> the store's page URLs.
Discover = Callable[..., list[str]]
#: process(fetcher, store, url, previous_row, until, work) -> the page's outcome.
Process = Callable[..., PageOutcome]
ProgressFn = Callable[[int, int, str], None]


class WorkSlots:
    """At most ``n`` holders at once (``with slots:``); counts the most that ever held one together."""

    def __init__(self, n: int):
        self._slots = threading.BoundedSemaphore(max(1, n))
        self._lock = threading.Lock()
        self.holding = 0
        self.peak = 0

    def __enter__(self) -> WorkSlots:
        self._slots.acquire()
        with self._lock:
            self.holding += 1
            self.peak = max(self.peak, self.holding)
        return self

    def __exit__(self, *exc: object) -> None:
        with self._lock:
            self.holding -= 1
        self._slots.release()


class TimeoutStreak:
    """Fetches of one store in a row (its sitemaps, then its pages) that timed out; :attr:`gave_up` from
    ``limit`` on."""

    def __init__(self, limit: int = UNRESPONSIVE_AFTER):
        self.limit, self.count = limit, 0

    def record(self, failure: str | None) -> None:
        """Count one fetch: ``failure`` is its failure's kind (``fetch_error_kind``), None if it was read."""
        if failure == DEADLINE_PASSED:
            self.count += 1
        else:
            self.count = 0  # read, not modified, or failed for another reason: the store answers

    def record_page(self, page: PageOutcome) -> None:
        self.record(page.reason if page.outcome == "rejected" and page.stage == "fetch" else None)

    @property
    def gave_up(self) -> bool:
        return self.count >= self.limit


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


def unresponsive_reason(store: StoreSource, streak: int, what: str = "pages") -> str:
    """Why a page (or a sitemap) is not fetched: its store's last ``streak`` fetches all timed out."""
    return (
        f"not fetched: the store's last {streak} fetches in a row each took longer than their deadline "
        f"({store.policy.max_page_s:g} s); its other {what} wait for the next run"
    )


def unresponsive_page(store: StoreSource, url: str, streak: int) -> PageOutcome:
    """The outcome of a page not fetched because its store's last ``streak`` fetches all timed out."""
    return PageOutcome(
        url=url,
        store=store.name,
        outcome="rejected",
        stage="fetch",
        reason=STORE_UNRESPONSIVE,
        detail=unresponsive_reason(store, streak),
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
    max_crawling: int = MAX_CRAWLING,
    max_working: int = MAX_WORKING,
    work: WorkSlots | None = None,
) -> tuple[list[PageOutcome], list[tuple[str, str, str]]]:
    """Crawl every store (see the module docstring); returns the page outcomes (stores in order, each
    store's pages in its order) and the discovery problems as (url, stage, reason). ``discover`` and
    ``process`` get the :class:`WorkSlots` (``work``: made of ``max_working`` unless passed) to hold
    while they parse; ``discover`` gets the store's :class:`TimeoutStreak` to count its sitemaps in."""
    claimed: set[str] = set()
    claim_lock = threading.Lock()
    tracker = _Progress(progress)
    slots = work or WorkSlots(max_working)

    def crawl(store: StoreSource) -> tuple[list[PageOutcome], list[tuple[str, str, str]]]:
        budget = StoreBudget(store.budget_s)
        until = budget.start(clock.monotonic())
        events: list[tuple[str, str, str]] = []
        streak = TimeoutStreak()
        urls = discover(fetcher, store, events, until=until, work=slots, streak=streak)
        with claim_lock:
            mine = [u for u in urls if u not in claimed]
            claimed.update(mine)
        tracker.planned(len(mine))
        outcomes: list[PageOutcome] = []
        for url in mine:
            if budget.spent(clock.monotonic()):
                outcomes.append(budget_spent_page(store, url))
            elif streak.gave_up:
                outcomes.append(unresponsive_page(store, url, streak.count))
            else:
                page = process(fetcher, store, url, previous.get(url), until=until, work=slots)
                streak.record_page(page)
                outcomes.append(page)
            tracker.page(url)
        return outcomes, events

    workers = max(1, min(max_crawling, len(stores)))
    if workers == 1:
        results = [crawl(store) for store in stores]
    else:
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="ingest-store") as pool:
            results = list(pool.map(crawl, stores))  # re-raises a worker's unexpected error
    outcomes = [o for store_outcomes, _ in results for o in store_outcomes]
    events = [e for _, store_events in results for e in store_events]
    return outcomes, events
