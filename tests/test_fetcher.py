"""The polite fetcher against the demo store over real HTTP on 127.0.0.1 (no mocks), with a fake clock."""

from __future__ import annotations

import email.utils
import threading
import time
from datetime import UTC, datetime, timedelta
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import pytest
import requests

from kb.errors import FetchError, PageTooLarge, RobotsDisallowed
from scrapers.demo_store import DemoStore
from scrapers.fetcher import USER_AGENT, FetchPolicy, PoliteFetcher, Validators, fetch_error_kind


class FakeClock:
    """A clock whose sleeps only advance its time: delays and backoffs are recorded, not waited for."""

    def __init__(self) -> None:
        self.t = 1000.0
        self.sleeps: list[float] = []
        self.wall = datetime(2026, 11, 22, 3, 0, tzinfo=UTC)

    def monotonic(self) -> float:
        return self.t

    def sleep(self, seconds: float) -> None:
        self.sleeps.append(seconds)
        self.t += seconds

    def now(self) -> datetime:
        return self.wall + timedelta(seconds=self.t - 1000.0)


def logged(store: DemoStore, path: str, expected: int | None = None) -> int:
    """Requests the store logged for ``path``. The server logs after sending its answer, so the client may
    be a moment ahead: wait (briefly) for ``expected``."""
    deadline = time.monotonic() + 2.0
    while True:
        n = sum(1 for e in store.log if e.path == path)
        if expected is None or n >= expected or time.monotonic() > deadline:
            return n
        time.sleep(0.01)


FAST = FetchPolicy(delay_s=0, read_timeout_s=0.5, connect_timeout_s=2, max_retries=1, backoff_s=0.0)


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None, slow_s=1.5, huge_bytes=50 * 1024 * 1024) as s:
        yield s


@pytest.fixture
def session():
    with requests.Session() as s:
        yield s


def test_fetches_a_page_with_validators_and_user_agent(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FAST)
    result = fetcher.fetch(store.url("/p/coffee-mug.html"))
    assert result.status == 200 and not result.not_modified
    assert b"Coffee Mug" in result.body
    assert result.etag and result.last_modified
    assert result.content_type.startswith("text/html")
    logged(store, "/p/coffee-mug.html", 1)
    sent = [e for e in store.log if e.path == "/p/coffee-mug.html"][-1]
    assert sent.user_agent == USER_AGENT
    assert USER_AGENT.startswith("objrecall/") and "+https://" in USER_AGENT


def test_conditional_request_gives_not_modified_without_body(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FAST)
    first = fetcher.fetch(store.url("/p/tennis-ball.html"))
    again = fetcher.fetch(store.url("/p/tennis-ball.html"), validators=first.validators)
    assert again.not_modified and again.body is None
    by_date = fetcher.fetch(
        store.url("/p/tennis-ball.html"), validators=Validators(last_modified=first.last_modified)
    )
    assert by_date.not_modified
    stale = fetcher.fetch(store.url("/p/tennis-ball.html"), validators=Validators(etag='"something-else"'))
    assert stale.status == 200 and stale.body == first.body
    assert logged(store, "/p/tennis-ball.html", 4) == 4
    assert [e for e in store.log if e.path == "/p/tennis-ball.html"][1].if_none_match == first.etag


def test_robots_disallow_is_obeyed_without_requesting_the_page(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FAST)
    before = logged(store, "/private/staff-lamp.html")
    with pytest.raises(RobotsDisallowed) as info:
        fetcher.fetch(store.url("/private/staff-lamp.html"))
    assert fetch_error_kind(info.value) == "robots_disallowed"
    assert logged(store, "/private/staff-lamp.html") == before
    assert fetcher.sitemaps(store.url("/")) == [store.url("/sitemap.xml")]


def test_robots_is_fetched_once_per_host(session):
    # a store of its own: the shared one may still be logging an earlier test's requests (it logs after
    # answering), which made the count before this test's fetches race under load
    paths = ("/p/coffee-mug.html", "/p/rolling-pin.html", "/about.html")
    with DemoStore(crawl_delay=None) as store:
        fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FAST)
        for path in paths:
            fetcher.fetch(store.url(path))
        for path in paths:  # every page logged, so a robots.txt asked for before any of them is too
            assert logged(store, path, expected=1) == 1
        assert logged(store, "/robots.txt") == 1


def test_crawl_delay_and_host_delay_are_waited_for(session):
    with DemoStore(crawl_delay=2.5) as store:
        clock = FakeClock()
        fetcher = PoliteFetcher(session, clock=clock, policy=FetchPolicy(delay_s=1.0, max_retries=0))
        for path in ("/p/coffee-mug.html", "/p/rolling-pin.html", "/p/tennis-ball.html"):
            fetcher.fetch(store.url(path))
        # robots.txt, then three pages: each page waits for the Crawl-delay (larger than our 1 s delay).
        assert len(clock.sleeps) == 3
        assert all(s == pytest.approx(2.5) for s in clock.sleeps)
        assert fetcher.crawl_delay(store.url("/")) == 2.5


def test_our_delay_wins_when_larger_than_crawl_delay(session):
    with DemoStore(crawl_delay=0.5) as store:
        clock = FakeClock()
        fetcher = PoliteFetcher(session, clock=clock, policy=FetchPolicy(delay_s=3.0))
        fetcher.fetch(store.url("/p/coffee-mug.html"))
        fetcher.fetch(store.url("/p/rolling-pin.html"))
        assert clock.sleeps == [pytest.approx(3.0), pytest.approx(3.0)]


def test_retry_after_is_honoured_then_page_served(session):
    with DemoStore(crawl_delay=None) as store:
        clock = FakeClock()
        fetcher = PoliteFetcher(
            session, clock=clock, policy=FetchPolicy(delay_s=0, max_retries=2, backoff_s=0.1)
        )
        result = fetcher.fetch(store.url("/p/flaky-glass-carafe.html"))
        assert result.status == 200 and result.attempts == 2
        assert max(clock.sleeps) == pytest.approx(1.0)  # Retry-After: 1 beats the 0.1 s backoff


def test_server_errors_are_retried_with_backoff_then_fail(store, session):
    clock = FakeClock()
    fetcher = PoliteFetcher(session, clock=clock, policy=FetchPolicy(delay_s=0, max_retries=3, backoff_s=0.5))
    before = logged(store, "/p/server-error.html")
    with pytest.raises(FetchError) as info:
        fetcher.fetch(store.url("/p/server-error.html"))
    assert fetch_error_kind(info.value) == "http_500"
    assert "4 attempt" in str(info.value)
    assert logged(store, "/p/server-error.html", before + 4) == before + 4
    assert clock.sleeps == [pytest.approx(0.5), pytest.approx(1.0), pytest.approx(2.0)]


def test_not_found_is_not_retried(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_retries=3))
    with pytest.raises(FetchError) as info:
        fetcher.fetch(store.url("/no/such/page"))
    assert fetch_error_kind(info.value) == "http_404"
    assert logged(store, "/no/such/page", 1) == 1


def test_slow_page_times_out(store, session):
    fetcher = PoliteFetcher(
        session, clock=FakeClock(), policy=FAST.__class__(delay_s=0, read_timeout_s=0.3, max_retries=0)
    )
    with pytest.raises(FetchError) as info:
        fetcher.fetch(store.url("/p/slow-teapot.html"))
    assert fetch_error_kind(info.value) == "timeout"


def test_huge_page_is_refused_while_streaming(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_bytes=1_000_000))
    with pytest.raises(PageTooLarge) as info:
        fetcher.fetch(store.url("/p/huge-catalogue.html"))
    assert "cap of 1000000" in str(info.value)
    # The default cap (10 MB) refuses the 50 MB page too, long before it is all sent.
    with pytest.raises(PageTooLarge):
        PoliteFetcher(session, clock=FakeClock(), policy=FAST).fetch(store.url("/p/huge-catalogue.html"))


def test_declared_content_length_over_cap_is_refused_before_reading(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_bytes=500))
    with pytest.raises(PageTooLarge) as info:
        fetcher.fetch(store.url("/p/coffee-mug.html"))
    assert "declared" in str(info.value)


def test_redirects_are_followed_and_limited(store, session):
    fetcher = PoliteFetcher(session, clock=FakeClock(), policy=FAST)
    result = fetcher.fetch(store.url("/old/cast-iron-pan.html"))
    assert result.final_url == store.url("/p/cast-iron-skillet.html") and result.redirects == 1
    strict = PoliteFetcher(session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_redirects=0))
    with pytest.raises(FetchError) as info:
        strict.fetch(store.url("/old/cast-iron-pan.html"))
    assert fetch_error_kind(info.value) == "too_many_redirects"


def test_one_request_at_a_time_per_host(session):
    with DemoStore(crawl_delay=None) as store:
        fetcher = PoliteFetcher(session, policy=FetchPolicy(delay_s=0))
        paths = [p for p in store.product_pages() if "flaky" not in p][:12]
        threads = [threading.Thread(target=fetcher.fetch, args=(store.url(p),)) for p in paths]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        deadline = time.monotonic() + 2
        while sum(1 for e in store.log if e.status == 200) < len(paths) + 1 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert store.max_in_flight == 1
        assert sum(1 for e in store.log if e.status == 200) == len(paths) + 1  # + robots.txt


def test_unreachable_host_is_a_fetch_error(session):
    fetcher = PoliteFetcher(
        session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_retries=1, connect_timeout_s=0.5)
    )
    # Port 9 (discard) on loopback is closed: robots.txt cannot be read, so the host is off limits.
    with pytest.raises(FetchError) as info:
        fetcher.fetch("http://127.0.0.1:9/p/x.html")
    assert fetch_error_kind(info.value) == "robots_unavailable"
    no_robots = PoliteFetcher(
        session, clock=FakeClock(), policy=FetchPolicy(delay_s=0, max_retries=1, obey_robots=False)
    )
    with pytest.raises(FetchError) as info:
        no_robots.fetch("http://127.0.0.1:9/p/x.html")
    assert fetch_error_kind(info.value) == "connection_failed"


@pytest.mark.parametrize("url", ["ftp://example.org/x", "not a url", "http:///nohost"])
def test_bad_urls_are_clear_errors(session, url):
    with pytest.raises(FetchError) as info:
        PoliteFetcher(session, clock=FakeClock()).fetch(url)
    assert fetch_error_kind(info.value) == "invalid_url"


def test_retry_after_as_http_date(session):
    """A Retry-After given as a date is turned into seconds against the passed-in clock."""
    clock = FakeClock()
    when = email.utils.format_datetime(clock.now() + timedelta(seconds=7), usegmt=True)
    calls = {"n": 0}

    class Handler(BaseHTTPRequestHandler):
        def log_message(self, *args):
            pass

        def do_GET(self):  # noqa: N802
            calls["n"] += 1
            if self.path == "/robots.txt":
                self.send_response(404)
                self.send_header("Content-Length", "0")
                self.end_headers()
                return
            status = 429 if calls["n"] == 2 else 200
            body = b"ok"
            self.send_response(status)
            if status == 429:
                self.send_header("Retry-After", when)
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        fetcher = PoliteFetcher(
            session, clock=clock, policy=FetchPolicy(delay_s=0, max_retries=1, backoff_s=0.1)
        )
        result = fetcher.fetch(f"http://127.0.0.1:{server.server_address[1]}/page")
        assert result.body == b"ok" and result.attempts == 2
        assert clock.sleeps == [pytest.approx(7.0)]
    finally:
        server.shutdown()
        server.server_close()


def test_policy_refuses_nonsense():
    with pytest.raises(ValueError):
        FetchPolicy(delay_s=-1)
    with pytest.raises(ValueError):
        FetchPolicy(max_bytes=0)
    with pytest.raises(ValueError):
        FetchPolicy(read_timeout_s=0)


def test_a_dripping_body_is_cut_off_by_the_page_time_limit(session):
    """Each byte comes well within the read timeout, but the whole body would take far too long."""

    class Drip(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.0"

        def log_message(self, *args):
            pass

        def do_GET(self):  # noqa: N802
            if self.path == "/robots.txt":
                self.send_response(404)
                self.end_headers()
                return
            self.send_response(200)
            self.send_header("Content-Type", "text/html")
            self.end_headers()
            try:
                for _ in range(200):
                    self.wfile.write(b"<p>drip</p>\n")
                    self.wfile.flush()
                    time.sleep(0.05)
            except OSError:
                pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), Drip)
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        policy = FetchPolicy(delay_s=0, read_timeout_s=2, max_page_s=0.5, max_retries=0)
        fetcher = PoliteFetcher(session, policy=policy)
        started = time.monotonic()
        with pytest.raises(FetchError) as info:
            fetcher.fetch(f"http://127.0.0.1:{server.server_address[1]}/drip")
        assert fetch_error_kind(info.value) == "timeout" and "longer than 0.5 s" in str(info.value)
        assert time.monotonic() - started < 5
    finally:
        server.shutdown()
        server.server_close()


def test_gzip_bodies_are_decoded_and_the_cap_counts_decoded_bytes(session):
    import gzip

    page = b"<html><body>" + b"<p>mug 12 x 8 cm</p>" * 100 + b"</body></html>"
    bomb = gzip.compress(b"\0" * (30 * 1024 * 1024), compresslevel=9)  # 30 MB of zeros in ~30 KB

    class Gz(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.1"

        def log_message(self, *args):
            pass

        def do_GET(self):  # noqa: N802
            body = gzip.compress(page) if self.path == "/page" else bomb if self.path == "/bomb" else b""
            self.send_response(200 if body else 404)
            self.send_header("Content-Encoding", "gzip")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

    server = ThreadingHTTPServer(("127.0.0.1", 0), Gz)
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{server.server_address[1]}"
    try:
        fetcher = PoliteFetcher(session, policy=FetchPolicy(delay_s=0, max_retries=0, max_bytes=1_000_000))
        assert fetcher.fetch(base + "/page").body == page
        with pytest.raises(PageTooLarge):
            fetcher.fetch(base + "/bomb")  # under the cap on the wire, 30x over it decoded
    finally:
        server.shutdown()
        server.server_close()


def test_a_retry_after_past_the_deadline_says_so_in_the_reason(session):
    # the flaky carafe answers 503 with Retry-After: 1 first; with a 0.5 s deadline the pause would run over
    with DemoStore(crawl_delay=None) as store:
        clock = FakeClock()
        policy = FetchPolicy(delay_s=0, max_retries=2, backoff_s=0.1, max_page_s=0.5)
        with pytest.raises(FetchError) as info:
            PoliteFetcher(session, clock=clock, policy=policy).fetch(store.url("/p/flaky-glass-carafe.html"))
    reason = str(info.value)
    assert fetch_error_kind(info.value) == "timeout" and "page took longer than 0.5 s" in reason
    assert "the server's Retry-After after HTTP 503 (1 s) would end past it" in reason
    assert clock.sleeps == []  # given up at once, not after sleeping
