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
  read, and an undeclared body is read in chunks and abandoned as soon as it passes the cap;
- a total deadline per page (``max_page_s``, default 30 s: connect, headers and body, across retries and
  redirects; :class:`~scrapers.deadlines.PageDeadline`), and an optional outer end (``until``: the store's
  budget for the run). Every request's connect and read time-outs are clamped to the time left, the socket's
  time-out again before each body read, and a pause that would end past the deadline is not taken; a
  watchdog shuts the connection when the deadline passes, so a drip of the status line, the headers or a
  chunk-size line (read by http.client a line at a time, each ``recv`` within the time-out) ends there too
  (:mod:`scrapers.fetch_watchdog`, mounted on the session passed in by
  :func:`~scrapers.fetch_watchdog.watch_session`).

The network (a :class:`requests.Session`) and the clock are passed in, so tests run against a local
server with a clock that does not really sleep.
"""

from __future__ import annotations

import email.utils
import threading
from collections.abc import Mapping
from datetime import UTC
from urllib.parse import urljoin

import requests

from kb.errors import FetchError
from scrapers.deadlines import PageDeadline
from scrapers.fetch_body import read_body
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
from scrapers.fetch_robots import RobotsRules, _Host
from scrapers.fetch_watchdog import Watchdog, watch_session

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


class PoliteFetcher(RobotsRules):
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
        watch_session(session)
        self.clock = clock or SystemClock()
        self.policy = policy
        self._hosts: dict[str, _Host] = {}
        self._hosts_lock = threading.Lock()
        self.requests_made = 0

    # -- fetching -------------------------------------------------------------------------------------
    def fetch(
        self,
        url: str,
        *,
        validators: Validators | None = None,
        policy: FetchPolicy | None = None,
        headers: Mapping[str, str] | None = None,
        until: float | None = None,
    ) -> FetchResult:
        """Fetch ``url``; returns a 2xx page or a 304 (``not_modified``).

        The whole fetch (every retry and redirect) ends within ``policy.max_page_s`` of its first request,
        and by ``until`` (a monotonic time of the fetcher's clock: the store's budget end) if given.
        Raises :class:`RobotsDisallowed`, :class:`PageTooLarge` or :class:`FetchError` (any other status,
        timeouts and connection failures after the retries, too many redirects, the deadline passed: kind
        ``timeout``, or the budget's end: kind ``store_budget_spent``).
        """
        policy = policy or self.policy
        deadline = PageDeadline(policy.max_page_s, until)
        extra = dict(headers or {})
        if validators is not None:
            extra.update(validators.headers())
        current = url
        redirects = 0
        seen = {url}
        while True:
            key, host = self._host(current)
            with host.lock:
                delay = self._check_robots(current, key, host, policy, until)
                result = self._request(
                    current, host, policy, extra, deadline, delay_s=delay, follow_redirects=False
                )
            if result.status in REDIRECT_STATUSES and result.final_url == current:
                raise tagged_error(FetchError, url, "redirect_loop", f"{current} redirects to itself")
            if result.status in REDIRECT_STATUSES and result.final_url != current:
                redirects += 1
                if result.final_url in seen:
                    raise tagged_error(
                        FetchError, url, "redirect_loop", f"redirect {redirects} leads back to {result.final_url}"
                    )
                seen.add(result.final_url)
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

    def _wait_turn(self, url: str, host: _Host, delay_s: float, deadline: PageDeadline) -> None:
        """Wait for the host's turn, unless the wait would outlast the deadline; then start the deadline."""
        wait = self._until_turn(host, delay_s)
        deadline.may_wait(url, self.clock.monotonic(), wait)
        if wait > 0:
            self.clock.sleep(wait)
        deadline.start(self.clock.monotonic())

    def _request(
        self,
        url: str,
        host: _Host,
        policy: FetchPolicy,
        headers: Mapping[str, str],
        deadline: PageDeadline,
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
            self._wait_turn(url, host, delay_s, deadline)
            retry_after: float | None = None
            status: int | None = None  # of this attempt's answer, for the reason of a pause cut short
            try:
                result = self._once(url, policy, headers, deadline)
            except FetchError as err:
                host.last_end = self.clock.monotonic()
                if (
                    getattr(err, "kind", "") not in ("timeout", "connection_failed")
                    or attempts > policy.max_retries
                    or deadline.passed(self.clock.monotonic())
                ):
                    if attempts > 1:
                        err.reason = f"{err.reason} after {attempts} attempts"
                        err.args = (f"{err.url}: {err.reason}",)
                    raise
            else:
                host.last_end = self.clock.monotonic()
                result.attempts = attempts
                if result.status in REDIRECT_STATUSES and follow_redirects and result.final_url == url:
                    raise tagged_error(FetchError, url, "redirect_loop", "the page redirects to itself")
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
                retry_after, status = self._retry_after(result, policy), result.status
            backoff = policy.backoff_s * 2 ** (attempts - 1)
            pause = max(backoff, retry_after or 0.0)
            # The host delay is counted from the end of the last request; sleep whatever more the backoff needs.
            extra = pause - self._until_turn(host, delay_s)
            if extra > 0:
                after = f" after HTTP {status}" if status is not None else " after a failed attempt"
                why = ("the server's Retry-After" if retry_after and retry_after >= backoff else "the back-off") + after
                deadline.may_wait(url, self.clock.monotonic(), extra, why)
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

    def _once(
        self, url: str, policy: FetchPolicy, headers: Mapping[str, str], deadline: PageDeadline
    ) -> FetchResult:
        """Exactly one HTTP exchange, under a watchdog that shuts its connection when the deadline passes
        (:mod:`scrapers.fetch_watchdog`); whatever a cut exchange gave is discarded for the deadline's error."""
        left = deadline.left(url, self.clock.monotonic())
        self.requests_made += 1
        result: FetchResult | None = None
        with Watchdog(left) as dog:
            try:
                result = self._exchange(url, policy, headers, deadline, left)
            except FetchError:
                if not dog.fired:
                    raise
        if dog.fired or result is None:
            raise deadline.error(url, self.clock.monotonic())
        return result

    def _exchange(
        self, url: str, policy: FetchPolicy, headers: Mapping[str, str], deadline: PageDeadline, left: float
    ) -> FetchResult:
        """The request and its answer: time-outs clamped to the ``left`` seconds of the deadline, body
        streamed under the size cap."""
        send = {"User-Agent": policy.user_agent, "Accept-Encoding": "gzip, deflate", **headers}
        try:
            resp = self.session.get(
                url,
                headers=send,
                timeout=(min(policy.connect_timeout_s, left), min(policy.read_timeout_s, left)),
                stream=True,
                allow_redirects=False,
            )
        except requests.Timeout:
            if deadline.passed(self.clock.monotonic()):
                raise deadline.error(url, self.clock.monotonic()) from None
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
                body = read_body(url, resp, policy, deadline, self.clock)
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
