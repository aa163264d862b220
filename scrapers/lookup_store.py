"""One store's side of an on-demand lookup: its search, within the budgets all stores share.

:func:`search_one` asks one store for the search words in order, until one's pages hold one that fits,
and reads each one's product pages ``search_results`` at a time (a ``rel="next"`` results page only when its products are
wanted, :mod:`scrapers.store_search`), while none settles the search (:data:`SETTLED_ERROR`), up to
:data:`MAX_RESULT_BATCHES` batches; every request takes from the shared :class:`Budget` (time left and
pages left) and has its timeouts clamped to the time left, without retries. :mod:`scrapers.lookup` runs
one per store at the same time, judges the pages and writes what fits.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from typing import Any
from urllib.parse import urlsplit

from kb.errors import ExtractionError, FetchError
from kb.features import ObjectRecord
from scrapers.fetcher import Clock, PoliteFetcher, fetch_error_kind
from scrapers.ingest import PageOutcome, process_page
from scrapers.sources import StoreSource
from scrapers.store_search import parse_search_page

__all__ = [
    "MAX_RESULT_BATCHES", "SETTLED_ERROR", "Budget", "FitFn", "StoreAnswer", "any_fits", "search_one", "settled",
]  # fmt: skip

#: A store's results are read ``search_results`` at a time; while none of them settles the search
#: (:data:`SETTLED_ERROR`), the next ones, up to this many batches in all (within the page and time
#: budgets): a vague description ("a computer monitor") in a store that sells many of the kind lists the
#: described one further down, below siblings that fit loosely (a 27-inch monitor for a 32-inch one).
MAX_RESULT_BATCHES = 5
#: A page that fits with a score (the mean relative error over the features it states) at most this
#: settles its store's search: a description whose every value is the product's rounded to two figures
#: ("71 by 51 cm, 6.8 kg") is within 5 % of each. A page that fits less closely may be a sibling of the
#: described product (the same kind, another size): the next batch is read, and the closest fit wins.
SETTLED_ERROR = 0.05
#: fits(record) -> (fits?, why) or (fits?, why, score): whether a product page is the described object; the
#: score (lower is closer) says which of several pages that fit fits best.
FitFn = Callable[[ObjectRecord], "tuple[bool, str] | tuple[bool, str, float]"]


@dataclass
class StoreAnswer:
    """What one store did: ``status`` is ``answered`` (listed products), ``no_results`` or ``skipped``
    (with the ``reason``); the search pages and product pages it was asked for."""

    store: str
    status: str = "no_results"
    reason: str | None = None
    queries: list[str] = field(default_factory=list)
    search_pages: list[str] = field(default_factory=list)
    product_pages: list[str] = field(default_factory=list)


class Budget:
    """The time left before a deadline and the requests left, shared by the store threads."""

    def __init__(self, clock: Clock, deadline: float, max_pages: int):
        self.clock, self.deadline, self.pages_left = clock, deadline, max_pages
        self._lock = threading.Lock()
        self.extract_s = 0.0

    def remaining(self) -> float:
        return self.deadline - self.clock.monotonic()

    def take_page(self) -> bool:
        with self._lock:
            if self.pages_left <= 0:
                return False
            self.pages_left -= 1
            return True

    def policy_for(self, store: StoreSource) -> StoreSource:
        """The store with timeouts clamped to the time left and no retries (a lookup is interactive)."""
        left = max(self.remaining(), 0.05)
        p = store.policy
        policy = replace(
            p,
            connect_timeout_s=min(p.connect_timeout_s, left),
            read_timeout_s=min(p.read_timeout_s, left),
            max_page_s=min(p.max_page_s, left),
            max_retries=0,
        )
        return replace(store, policy=policy)


class _Stop(Exception):
    """A store's search ends here, with the reason."""


def _checked(fetcher: PoliteFetcher, budget: Budget, store: StoreSource) -> StoreSource:
    """The store to fetch with now; raises _Stop when the time or page budget is used up or the host's
    delay would not leave time for the request."""
    if budget.remaining() <= 0:
        raise _Stop("time budget used up")
    bounded = budget.policy_for(store)
    delay = fetcher.crawl_delay(store.base_url + "/", bounded.policy) or 0.0
    if max(delay, bounded.policy.delay_s) >= budget.remaining():
        raise _Stop(f"the store's delay between requests ({max(delay, bounded.policy.delay_s):g} s) "
                    "is longer than the time left")  # fmt: skip
    if not budget.take_page():
        raise _Stop("page budget used up")
    return bounded


def _result_urls(
    fetcher: PoliteFetcher, budget: Budget, store: StoreSource, query: str, answer
) -> Iterator[str]:
    """The product URLs the search lists for ``query``, in order: a ``rel=next`` page is fetched only
    when the URLs before it are used up and another is wanted."""
    url: str | None = store.search_url(query)
    found: set[str] = set()
    seen: set[str] = set()
    while url and url not in seen:
        seen.add(url)
        bounded = _checked(fetcher, budget, store)
        answer.search_pages.append(url)
        try:
            result = fetcher.fetch(url, policy=bounded.policy)
            page = parse_search_page(result.body or b"", result.final_url, result.content_type, store)
        except FetchError as err:
            raise _Stop(f"search failed: {fetch_error_kind(err)}: {err.reason} ({err.url})") from None
        except ExtractionError as err:
            raise _Stop(f"search answer unreadable: {err}") from None
        for u in page.product_urls:
            if u not in found:
                found.add(u)
                yield u
        nxt = page.next_url
        url = nxt if nxt and urlsplit(nxt).netloc == urlsplit(store.base_url).netloc else None


def _timed_extractor(budget: Budget):
    from scrapers.extract import extract_page

    def extract(body, url, content_type):
        t0 = time.perf_counter()
        try:
            return extract_page(body, url, content_type)
        finally:
            with budget._lock:
                budget.extract_s += time.perf_counter() - t0

    return extract


def search_one(
    fetcher: PoliteFetcher,
    budget: Budget,
    store: StoreSource,
    queries: Sequence[str],
    previous: dict[str, dict[str, Any]],
    fits: FitFn | None = None,
) -> tuple[StoreAnswer, list[PageOutcome]]:
    """One store: the queries in order, each one's top product pages read a batch of ``search_results`` at
    a time while none settles the search (:func:`settled`, up to :data:`MAX_RESULT_BATCHES`), until a
    query's pages hold one that fits (:func:`any_fits`); the next query reads only pages not read yet.
    A store's search lists a product when one query word is in its title, brand or description text, so
    the most specific words ("smart bird feeder") can list only other products ("smart" plugs) while
    fewer words ("bird feeder") list the one described. Without ``fits``: the first query that lists
    products, one batch."""
    answer = StoreAnswer(store.name)
    outcomes: list[PageOutcome] = []
    extract = _timed_extractor(budget)
    batch = store.search_results
    read: set[str] = set()
    try:
        for query in queries:
            answer.queries.append(query)
            listed = (u for u in _result_urls(fetcher, budget, store, query, answer) if u not in read)
            mine: list[PageOutcome] = []
            for i in range(batch * (MAX_RESULT_BATCHES if fits is not None else 1)):
                if i and i % batch == 0 and settled(mine, fits):
                    break
                url = next(listed, None)
                if url is None:
                    break
                bounded = _checked(fetcher, budget, store)
                answer.product_pages.append(url)
                read.add(url)
                mine.append(process_page(fetcher, bounded, url, previous.get(url), extract))
            outcomes += mine
            if mine:
                answer.status = "answered"
            if (mine and fits is None) or any_fits(mine, fits):
                break
    except _Stop as stop:
        if not outcomes:
            answer.status = "skipped"
        answer.reason = str(stop)
    return answer, outcomes


def any_fits(outcomes: list[PageOutcome], fits: FitFn | None) -> bool:
    """Whether one of the pages read is known from an earlier lookup or fits (no further query is asked)."""
    if fits is None:
        return False
    return any(p.outcome == "not_modified" or (p.outcome == "extracted" and fits(p.clean)[0]) for p in outcomes)


def settled(outcomes: list[PageOutcome], fits: FitFn | None) -> bool:
    """Whether the pages read settle the search (no further results are read): one is known from an
    earlier lookup, or fits with a score at most :data:`SETTLED_ERROR` (a ``fits`` that gives no score
    settles it with any fit); without ``fits``, always."""
    if fits is None:
        return True
    for page in outcomes:
        if page.outcome == "not_modified":
            return True
        if page.outcome == "extracted":
            ok, _why, *score = fits(page.clean)
            if ok and (score[0] if score else 0.0) <= SETTLED_ERROR:
                return True
    return False
