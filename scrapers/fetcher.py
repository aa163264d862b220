"""The polite fetcher: how objrecall asks a store for a page.

Polite by default, in the manner of Scrapy's downloader middlewares:

- robots.txt is read once per host (with protego) and obeyed, including its ``Crawl-delay``; a robots.txt
  that answers 4xx allows everything, one that cannot be read (5xx, network error) disallows the host for
  this fetcher's lifetime (the safe side);
- one request at a time per host, and at least ``delay_s`` (or the robots Crawl-delay, whichever is
  larger) between the end of one request and the start of the next to the same host;
- retries with exponential backoff on 408/429/500/502/503/504, timeouts and dropped connections; a
  ``Retry-After`` header (seconds or HTTP date) replaces the backoff when it is longer, up to
  ``max_retry_after_s``;
- conditional requests from stored validators (``If-None-Match`` / ``If-Modified-Since``): a 304 comes
  back as ``not_modified`` with no body, so it costs no parsing;
- connect and read timeouts, a redirect limit (each hop checked against robots.txt), and a size cap
  enforced while streaming: a declared ``Content-Length`` over the cap is refused before any body byte is
  read, and an undeclared body is read in chunks and abandoned as soon as it passes the cap.

The network (a :class:`requests.Session`) and the clock are passed in, so tests run against a local
server with a clock that does not really sleep.
"""

from __future__ import annotations

import email.utils
import threading
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC
from urllib.parse import urljoin, urlsplit

import requests
import urllib3
from protego import Protego

from kb.errors import FetchError, PageTooLarge, RobotsDisallowed
from scrapers.fetch_policy import (
    DEFAULT_POLICY,
    REDIRECT_STATUSES,
    RETRY_STATUSES,
    ROBOT_NAME,
    USER_AGENT,
    Clock,
    FetchPolicy,
    SystemClock,
    with_overrides,
)
from scrapers.fetch_records import FetchResult, Validators, fetch_error_kind, tagged_error

__all__ = [
    "DEFAULT_POLICY",
    "RETRY_STATUSES",
    "ROBOT_NAME",
    "USER_AGENT",
    "Clock",
    "FetchPolicy",
    "FetchResult",
    "PoliteFetcher",
    "SystemClock",
    "Validators",
    "fetch_error_kind",
    "with_overrides",
]


_CHUNK = 64 * 1024


@dataclass
class _Host:
    lock: threading.Lock = field(default_factory=threading.Lock)
    last_end: float | None = None  # monotonic time the last request to the host ended
    robots: Protego | None = None
    robots_error: str | None = None
    robots_loaded: bool = False


class PoliteFetcher:
    """Fetch pages over ``session`` politely (see the module docstring). Safe to share between threads:
    requests to one host are serialised, different hosts proceed in parallel."""

    def __init__(
        self,
        session: requests.Session,
        *,
        clock: Clock | None = None,
        policy: FetchPolicy = DEFAULT_POLICY,
    ):
        self.session = session
        self.clock = clock or SystemClock()
        self.policy = policy
        self._hosts: dict[str, _Host] = {}
        self._hosts_lock = threading.Lock()
        self.requests_made = 0

    # -- hosts and robots.txt -------------------------------------------------------------------------
    def _host(self, url: str) -> tuple[str, _Host]:
        parts = urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.netloc:
            raise tagged_error(FetchError, url, "invalid_url", "not an http(s) URL")
        key = f"{parts.scheme}://{parts.netloc}"
        with self._hosts_lock:
            host = self._hosts.setdefault(key, _Host())
        return key, host

    def robots(self, url: str, policy: FetchPolicy | None = None) -> Protego | None:
        """The parsed robots.txt of ``url``'s host (fetched once), or None when it allows everything."""
        policy = policy or self.policy
        key, host = self._host(url)
        with host.lock:
            self._load_robots(key, host, policy)
            return host.robots

    def crawl_delay(self, url: str, policy: FetchPolicy | None = None) -> float | None:
        """The Crawl-delay robots.txt asks of us on ``url``'s host, if any."""
        rp = self.robots(url, policy)
        if rp is None:
            return None
        delay = rp.crawl_delay(policy.user_agent if policy else self.policy.user_agent)
        return float(delay) if delay is not None else None

    def sitemaps(self, url: str, policy: FetchPolicy | None = None) -> list[str]:
        rp = self.robots(url, policy)
        return list(rp.sitemaps) if rp is not None else []

    def _load_robots(self, key: str, host: _Host, policy: FetchPolicy) -> None:
        """Fetch and parse robots.txt; the caller holds ``host.lock``."""
        if host.robots_loaded:
            return
        robots_url = key + "/robots.txt"
        try:
            resp = self._request(robots_url, host, policy, {}, delay_s=policy.delay_s, follow_redirects=True)
        except FetchError as err:
            host.robots_error = err.reason
        else:
            if 200 <= resp.status < 300:
                text = (resp.body or b"").decode("utf-8", errors="replace")
                host.robots = Protego.parse(text)
            elif 400 <= resp.status < 500:
                host.robots = None  # no robots.txt: everything allowed
            else:
                host.robots_error = f"robots.txt answered HTTP {resp.status}"
        host.robots_loaded = True

    def _check_robots(self, url: str, key: str, host: _Host, policy: FetchPolicy) -> float:
        """Raise RobotsDisallowed if robots.txt forbids ``url``; return the effective delay for the host."""
        if not policy.obey_robots:
            return policy.delay_s
        self._load_robots(key, host, policy)
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

    # -- fetching -------------------------------------------------------------------------------------
    def fetch(
        self,
        url: str,
        *,
        validators: Validators | None = None,
        policy: FetchPolicy | None = None,
        headers: Mapping[str, str] | None = None,
    ) -> FetchResult:
        """Fetch ``url``; returns a 2xx page or a 304 (``not_modified``).

        Raises :class:`RobotsDisallowed`, :class:`PageTooLarge` or :class:`FetchError` (any other status,
        timeouts and connection failures after the retries, too many redirects).
        """
        policy = policy or self.policy
        extra = dict(headers or {})
        if validators is not None:
            extra.update(validators.headers())
        current = url
        redirects = 0
        while True:
            key, host = self._host(current)
            with host.lock:
                delay = self._check_robots(current, key, host, policy)
                result = self._request(current, host, policy, extra, delay_s=delay, follow_redirects=False)
            if result.status in REDIRECT_STATUSES and result.final_url != current:
                redirects += 1
                if redirects > policy.max_redirects:
                    raise tagged_error(
                        FetchError, url, "too_many_redirects", f"more than {policy.max_redirects} redirects"
                    )
                current = result.final_url
                continue
            result.url = url
            result.redirects = redirects
            if result.status == 304 or 200 <= result.status < 300:
                return result
            raise tagged_error(
                FetchError,
                url,
                f"http_{result.status}",
                f"HTTP {result.status} after {result.attempts} attempt(s)",
            )

    def _until_turn(self, host: _Host, delay_s: float) -> float:
        """Seconds until the host may be asked again (0 when it may be now)."""
        if host.last_end is None:
            return 0.0
        return max(0.0, host.last_end + delay_s - self.clock.monotonic())

    def _wait_turn(self, host: _Host, delay_s: float) -> None:
        wait = self._until_turn(host, delay_s)
        if wait > 0:
            self.clock.sleep(wait)

    def _request(
        self,
        url: str,
        host: _Host,
        policy: FetchPolicy,
        headers: Mapping[str, str],
        *,
        delay_s: float,
        follow_redirects: bool,
    ) -> FetchResult:
        """One logical request with retries; the caller holds ``host.lock``.

        A redirect is returned as a result whose ``final_url`` is the Location (unless following).
        """
        attempts = 0
        hops = 0
        while True:
            attempts += 1
            self._wait_turn(host, delay_s)
            retry_after: float | None = None
            try:
                result = self._once(url, policy, headers)
            except FetchError as err:
                host.last_end = self.clock.monotonic()
                if (
                    getattr(err, "kind", "") not in ("timeout", "connection_failed")
                    or attempts > policy.max_retries
                ):
                    if attempts > 1:
                        err.reason = f"{err.reason} after {attempts} attempts"
                        err.args = (f"{err.url}: {err.reason}",)
                    raise
            else:
                host.last_end = self.clock.monotonic()
                result.attempts = attempts
                if result.status in REDIRECT_STATUSES and follow_redirects and result.final_url != url:
                    hops += 1
                    if hops > policy.max_redirects:
                        raise tagged_error(
                            FetchError,
                            url,
                            "too_many_redirects",
                            f"more than {policy.max_redirects} redirects",
                        )
                    url = result.final_url
                    attempts = 0
                    continue
                if result.status not in RETRY_STATUSES or attempts > policy.max_retries:
                    return result
                retry_after = self._retry_after(result, policy)
            backoff = policy.backoff_s * 2 ** (attempts - 1)
            pause = max(backoff, retry_after or 0.0)
            # The host delay is counted from the end of the last request; sleep whatever more the backoff needs.
            extra = pause - self._until_turn(host, delay_s)
            if extra > 0:
                self.clock.sleep(extra)

    def _retry_after(self, result: FetchResult, policy: FetchPolicy) -> float | None:
        value = result.retry_after
        if not value:
            return None
        value = value.strip()
        seconds: float | None
        if value.isascii() and value.isdigit():  # delta-seconds (RFC 9110: 1*DIGIT, ASCII only)
            seconds = float(value)
        else:
            try:
                when = email.utils.parsedate_to_datetime(value)
            except (TypeError, ValueError):
                return None
            if when.tzinfo is None:
                when = when.replace(tzinfo=UTC)
            seconds = (when - self.clock.now()).total_seconds()
        return min(max(seconds, 0.0), policy.max_retry_after_s)

    def _once(self, url: str, policy: FetchPolicy, headers: Mapping[str, str]) -> FetchResult:
        """Exactly one HTTP exchange, body streamed under the size cap."""
        send = {"User-Agent": policy.user_agent, "Accept-Encoding": "gzip, deflate", **headers}
        self.requests_made += 1
        try:
            resp = self.session.get(
                url,
                headers=send,
                timeout=(policy.connect_timeout_s, policy.read_timeout_s),
                stream=True,
                allow_redirects=False,
            )
        except requests.Timeout:
            raise tagged_error(
                FetchError, url, "timeout", f"timed out (read timeout {policy.read_timeout_s:g} s)"
            ) from None
        except (
            requests.exceptions.InvalidURL,
            requests.exceptions.MissingSchema,
            requests.exceptions.InvalidSchema,
        ):
            raise tagged_error(FetchError, url, "invalid_url", "invalid URL") from None
        except requests.ConnectionError as err:
            raise tagged_error(
                FetchError, url, "connection_failed", f"connection failed ({type(err).__name__})"
            ) from None
        except requests.RequestException as err:
            raise tagged_error(
                FetchError, url, "fetch_failed", f"request failed ({type(err).__name__})"
            ) from None
        try:
            fetched_at = self.clock.now()
            status = resp.status_code
            location = resp.headers.get("Location")
            final_url = urljoin(url, location) if status in REDIRECT_STATUSES and location else url
            body: bytes | None = None
            if 200 <= status < 300:
                body = self._read_capped(url, resp, policy)
            result = FetchResult(
                url=url,
                final_url=final_url,
                status=status,
                body=body,
                content_type=resp.headers.get("Content-Type"),
                etag=resp.headers.get("ETag"),
                last_modified=resp.headers.get("Last-Modified"),
                fetched_at=fetched_at,
                retry_after=resp.headers.get("Retry-After"),
            )
            return result
        finally:
            resp.close()

    def _read_capped(self, url: str, resp: requests.Response, policy: FetchPolicy) -> bytes:
        declared = resp.headers.get("Content-Length")
        if declared and declared.strip().isdigit() and int(declared) > policy.max_bytes:
            raise tagged_error(
                PageTooLarge,
                url,
                "too_large",
                f"declared {int(declared)} bytes, over the cap of {policy.max_bytes}",
            )
        chunks: list[bytes] = []
        total = 0
        deadline = self.clock.monotonic() + policy.max_page_s
        try:
            for chunk in _body_chunks(resp):
                if self.clock.monotonic() > deadline:
                    raise tagged_error(
                        FetchError, url, "timeout", f"body took longer than {policy.max_page_s:g} s"
                    )
                total += len(chunk)
                if total > policy.max_bytes:
                    raise tagged_error(
                        PageTooLarge, url, "too_large", f"body passed the cap of {policy.max_bytes} bytes"
                    )
                chunks.append(chunk)
        except (requests.exceptions.ReadTimeout, urllib3.exceptions.ReadTimeoutError):
            raise tagged_error(FetchError, url, "timeout", "timed out while reading the body") from None
        except requests.exceptions.ConnectionError as err:
            if "timed out" in str(err).lower():
                raise tagged_error(FetchError, url, "timeout", "timed out while reading the body") from None
            raise tagged_error(
                FetchError, url, "connection_failed", "connection dropped while reading the body"
            ) from None
        except (requests.exceptions.RequestException, urllib3.exceptions.HTTPError, OSError) as err:
            raise tagged_error(
                FetchError, url, "connection_failed", f"body could not be read ({type(err).__name__})"
            ) from None
        return b"".join(chunks)


def _body_chunks(resp: requests.Response):
    """The decoded body in pieces as they arrive (``read1``: at most one socket read each), so a size cap
    or a time limit is checked while a slow or endless body is still coming."""
    raw = resp.raw
    if hasattr(raw, "read1"):
        while True:
            chunk = raw.read1(_CHUNK, decode_content=True)
            if not chunk:
                return
            yield chunk
    else:  # an adapter without urllib3 underneath
        yield from resp.iter_content(_CHUNK)
