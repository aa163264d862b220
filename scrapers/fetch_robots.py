"""robots.txt and the per-host state of :class:`scrapers.fetcher.PoliteFetcher`: each host's robots.txt is
fetched once (under its own page deadline) and obeyed, including its ``Crawl-delay``; a robots.txt that
answers 4xx allows everything, one that cannot be read (5xx, network error) disallows the host for the
fetcher's lifetime (RFC 9309 2.3.1.4). A mixin: the fetcher supplies ``_request``, ``policy`` and the host
table."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from urllib.parse import urlsplit

from protego import Protego

from kb.errors import FetchError, RobotsDisallowed
from scrapers.deadlines import PageDeadline
from scrapers.fetch_policy import FetchPolicy
from scrapers.fetch_records import fetch_error_kind, tagged_error

__all__ = ["RobotsRules"]


@dataclass
class _Host:
    lock: threading.Lock = field(default_factory=threading.Lock)
    last_end: float | None = None  # monotonic time the last request to the host ended
    robots: Protego | None = None
    robots_error: str | None = None
    robots_loaded: bool = False


class RobotsRules:
    """The robots.txt half of the polite fetcher (host table, robots.txt loading and checking)."""

    policy: FetchPolicy
    _hosts: dict[str, _Host]
    _hosts_lock: threading.Lock

    def _host(self, url: str) -> tuple[str, _Host]:
        parts = urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.netloc:
            raise tagged_error(FetchError, url, "invalid_url", "not an http(s) URL")
        key = f"{parts.scheme}://{parts.netloc}"
        with self._hosts_lock:
            host = self._hosts.setdefault(key, _Host())
        return key, host

    def robots(
        self, url: str, policy: FetchPolicy | None = None, *, until: float | None = None
    ) -> Protego | None:
        """The parsed robots.txt of ``url``'s host (fetched once), or None when it allows everything."""
        policy = policy or self.policy
        key, host = self._host(url)
        with host.lock:
            self._load_robots(key, host, policy, until)
            return host.robots

    def crawl_delay(self, url: str, policy: FetchPolicy | None = None) -> float | None:
        """The Crawl-delay robots.txt asks of us on ``url``'s host, if any."""
        rp = self.robots(url, policy)
        if rp is None:
            return None
        delay = rp.crawl_delay(policy.user_agent if policy else self.policy.user_agent)
        return float(delay) if delay is not None else None

    def sitemaps(self, url: str, policy: FetchPolicy | None = None, *, until: float | None = None) -> list[str]:
        rp = self.robots(url, policy, until=until)
        return list(rp.sitemaps) if rp is not None else []

    def _load_robots(self, key: str, host: _Host, policy: FetchPolicy, until: float | None = None) -> None:
        """Fetch and parse robots.txt (under its own page deadline); the caller holds ``host.lock``. A
        robots.txt that cannot be read in time disallows the host for this fetcher's life (RFC 9309 2.3.1.4:
        unreachable is disallow-all); one cut only by the store's budget is not remembered, another store on
        the host may still read it."""
        if host.robots_loaded:
            return
        robots_url = key + "/robots.txt"
        deadline = PageDeadline(policy.max_page_s, until)
        try:
            resp = self._request(
                robots_url, host, policy, {}, deadline, delay_s=policy.delay_s, follow_redirects=True
            )
        except FetchError as err:
            if fetch_error_kind(err) == "store_budget_spent":
                raise
            host.robots_error = f"{fetch_error_kind(err)}: {err.reason}"
        else:
            if 200 <= resp.status < 300:
                text = (resp.body or b"").decode("utf-8", errors="replace")
                host.robots = Protego.parse(text)
            elif 400 <= resp.status < 500:
                host.robots = None  # no robots.txt: everything allowed
            else:
                host.robots_error = f"robots.txt answered HTTP {resp.status}"
        host.robots_loaded = True

    def _check_robots(
        self, url: str, key: str, host: _Host, policy: FetchPolicy, until: float | None = None
    ) -> float:
        """Raise RobotsDisallowed if robots.txt forbids ``url``; return the effective delay for the host."""
        if not policy.obey_robots:
            return policy.delay_s
        self._load_robots(key, host, policy, until)
        if host.robots_error is not None:
            raise tagged_error(
                RobotsDisallowed, url, "robots_unavailable", f"robots.txt unavailable: {host.robots_error}"
            )
        if host.robots is None:
            return policy.delay_s
        if not host.robots.can_fetch(url, policy.user_agent):
            raise tagged_error(RobotsDisallowed, url, "robots_disallowed", "disallowed by robots.txt")
        crawl_delay = host.robots.crawl_delay(policy.user_agent)
        return max(policy.delay_s, float(crawl_delay or 0.0))
