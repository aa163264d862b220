"""How long a page, and a store, may take: the total deadline of one fetch and a store's budget per run.

A :class:`PageDeadline` bounds one fetch from its first request to its last byte: connect, headers and body,
across retries (their backoff and ``Retry-After`` pauses) and redirects. The read time-out alone bounds
each wait for bytes, not the page: a store that drips its bytes, each within the read time-out, held the
job for 487 s on one page (issue 25). The deadline starts when the page's first request may go (after the
host's politeness delay, which is the store's own pace, not the page's); every later wait counts.

A :class:`StoreBudget` bounds one store's share of a run: once spent, its remaining pages are not fetched
(each recorded with the reason ``store_budget_spent``), and a page in flight is cut at the budget's end.

Both work on monotonic times of the clock passed in, and each rule is one comparison pinned by the tests
(``tests/test_hostile_deadlines.py``): a wait that would end at or after the end is not taken; a request is
sent only with time left (> 0), with its connect and read time-outs clamped to that time.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.errors import FetchError
from scrapers.fetch_records import tagged_error

__all__ = ["BUDGET_SPENT", "DEADLINE_PASSED", "PageDeadline", "StoreBudget"]

#: The reasons (``page_events.reason`` prefixes) of a page cut by its deadline or its store's budget.
DEADLINE_PASSED = "timeout"
BUDGET_SPENT = "store_budget_spent"


@dataclass
class PageDeadline:
    """The end of one fetch: ``limit_s`` after it started, or the outer ``until`` (the store's budget end,
    monotonic) when that comes first. Not started until :meth:`start`."""

    limit_s: float
    until: float | None = None
    started: float | None = None

    def start(self, now: float) -> None:
        if self.started is None:
            self.started = now

    def end(self, now: float) -> float:
        """The monotonic time the fetch must be over by (counted from ``now`` if not started yet)."""
        own = (self.started if self.started is not None else now) + self.limit_s
        return own if self.until is None else min(own, self.until)

    def passed(self, now: float) -> bool:
        return self.end(now) <= now

    def _cut_by_budget(self, now: float) -> bool:
        return self.until is not None and self.until <= self.end(now)

    def error(self, url: str, now: float, why: str | None = None) -> FetchError:
        more = f"; {why}" if why else ""
        if self._cut_by_budget(now):
            return tagged_error(FetchError, url, BUDGET_SPENT, f"the store's time budget for this run is spent{more}")
        return tagged_error(
            FetchError, url, DEADLINE_PASSED, f"page took longer than {self.limit_s:g} s (its deadline){more}"
        )

    def left(self, url: str, now: float) -> float:
        """Seconds left for the fetch; raises the deadline's error when none are."""
        left = self.end(now) - now
        if left <= 0:
            raise self.error(url, now)
        return left

    def may_wait(self, url: str, now: float, wait_s: float, why: str | None = None) -> None:
        """Raise the deadline's error if a pause of ``wait_s`` would end at or after the end: better to
        give the page up now than to sleep and then give it up. ``why`` names the pause in the reason
        (``the server's Retry-After of 100 s``), so the page's reason says what would have run over."""
        at = now + wait_s if self.started is None else now  # when the page's own clock would start
        if wait_s > 0 and now + wait_s >= self.end(at):
            raise self.error(url, at, f"{why} ({wait_s:.3g} s) would end past it" if why else None)


@dataclass
class StoreBudget:
    """A store's time for one run: ``budget_s`` from its first request (``start``)."""

    budget_s: float
    started: float | None = None

    def start(self, now: float) -> float:
        """Start the budget (once) and return its end."""
        if self.started is None:
            self.started = now
        return self.started + self.budget_s

    def spent(self, now: float) -> bool:
        return self.started is not None and now >= self.started + self.budget_s
