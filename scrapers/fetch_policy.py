"""How the fetcher behaves and who it says it is: the fetch policy, the robot's identity, the clock.

:class:`FetchPolicy` holds every politeness and patience knob with a safe default; :class:`Clock` is the
time the fetcher sees (passed in, so tests use a clock that does not really sleep).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from datetime import UTC, datetime
from typing import Protocol

__all__ = [
    "DEFAULT_PAGE_DEADLINE_S",
    "DEFAULT_POLICY",
    "REDIRECT_STATUSES",
    "RETRY_STATUSES",
    "ROBOT_NAME",
    "USER_AGENT",
    "Clock",
    "FetchPolicy",
    "SystemClock",
    "with_overrides",
]


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("objrecall")
    except Exception:  # not installed: running from a source tree
        return "0.1.0"


#: The product token robots.txt groups are matched against.
ROBOT_NAME = "objrecall"
PROJECT_URL = "https://github.com/objrecall/objrecall"
USER_AGENT = f"{ROBOT_NAME}/{_version()} (+{PROJECT_URL}; contact: {PROJECT_URL}/issues)"

#: Statuses worth another try (Scrapy's RETRY_HTTP_CODES).
RETRY_STATUSES: frozenset[int] = frozenset({408, 429, 500, 502, 503, 504})
REDIRECT_STATUSES: frozenset[int] = frozenset({301, 302, 303, 307, 308})


#: The default total deadline of one page (issue 25: at most 30 s).
DEFAULT_PAGE_DEADLINE_S = 30.0


class Clock(Protocol):
    """Time as the fetcher sees it: a monotonic clock for delays, a sleep, and wall time for records."""

    def monotonic(self) -> float: ...

    def sleep(self, seconds: float) -> None: ...

    def now(self) -> datetime: ...


class SystemClock:
    """The real clock."""

    def monotonic(self) -> float:
        return time.monotonic()

    def sleep(self, seconds: float) -> None:
        if seconds > 0:
            time.sleep(seconds)

    def now(self) -> datetime:
        return datetime.now(UTC)


@dataclass(frozen=True)
class FetchPolicy:
    """How politely and patiently to fetch; every field has a safe default.

    ``delay_s`` is the minimum gap between two requests to one host (robots.txt Crawl-delay can raise it,
    never lower it). ``read_timeout_s`` bounds each wait for bytes; ``max_page_s`` is the page's total
    deadline (connect, headers and body, across retries and redirects; default 30 s), so a server that drips
    a byte at a time cannot hold the crawl (:mod:`scrapers.deadlines`). ``max_retries`` counts extra
    attempts after the first. Backoff before retry *n* (1-based) is ``backoff_s * 2 ** (n - 1)``.
    """

    delay_s: float = 1.0
    connect_timeout_s: float = 10.0
    read_timeout_s: float = 30.0
    max_bytes: int = 10 * 1024 * 1024
    max_redirects: int = 5
    max_retries: int = 3
    backoff_s: float = 1.0
    max_retry_after_s: float = 120.0
    max_page_s: float = DEFAULT_PAGE_DEADLINE_S
    obey_robots: bool = True
    user_agent: str = USER_AGENT

    def __post_init__(self) -> None:
        for name in ("delay_s", "backoff_s", "max_retry_after_s"):
            if getattr(self, name) < 0:
                raise ValueError(f"{name} must be >= 0")
        for name in ("connect_timeout_s", "read_timeout_s", "max_page_s"):
            if getattr(self, name) <= 0:
                raise ValueError(f"{name} must be > 0")
        if self.max_bytes <= 0:
            raise ValueError("max_bytes must be > 0")
        if self.max_redirects < 0 or self.max_retries < 0:
            raise ValueError("max_redirects and max_retries must be >= 0")


DEFAULT_POLICY = FetchPolicy()


def with_overrides(policy: FetchPolicy, **changes: object) -> FetchPolicy:
    """A copy of ``policy`` with the given fields replaced (None values ignored)."""
    return replace(policy, **{k: v for k, v in changes.items() if v is not None})
