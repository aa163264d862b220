"""Issue 25, part 1: the total deadline of one page and a store's budget per run, pinned at their
boundaries (just under passes, just over is rejected), over real HTTP on loopback with a clock whose sleeps
only advance its time; and the sources file / CLI settings that configure them."""

from __future__ import annotations

import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

import pytest
import requests
from hostile_store import HostileStore, product_page
from hostile_stores import PageStore
from hypothesis import given
from hypothesis import strategies as st
from test_fetcher import FakeClock
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.errors import FetchError, SourcesError
from kb.service.cli import app
from scrapers.deadlines import BUDGET_SPENT, PageDeadline, StoreBudget
from scrapers.fetch_watchdog import Watchdog, WatchedAdapter
from scrapers.fetcher import FetchPolicy, PoliteFetcher, fetch_error_kind
from scrapers.ingest import run_ingestion
from scrapers.sources import DEFAULT_STORE_BUDGET_S, parse_sources

URL = "http://127.0.0.1:1/p"
times = st.floats(min_value=0, max_value=1e6, allow_nan=False)
spans = st.floats(min_value=1e-3, max_value=1e4, allow_nan=False)


# ---------------------------------------------------------------------------------------------- the rules
def test_a_request_is_sent_only_while_time_is_left():
    d = PageDeadline(10.0)
    d.start(100.0)
    assert d.left(URL, 109.5) == pytest.approx(0.5)
    with pytest.raises(FetchError) as info:
        d.left(URL, 110.0)  # exactly at the end: no time left
    assert fetch_error_kind(info.value) == "timeout" and "longer than 10 s" in str(info.value)


def test_a_wait_ending_at_the_deadline_is_not_taken():
    d = PageDeadline(10.0)
    d.start(0.0)
    d.may_wait(URL, 5.0, 4.999)
    with pytest.raises(FetchError):
        d.may_wait(URL, 5.0, 5.0)


def test_before_its_first_request_a_page_may_wait_for_its_turn_up_to_the_budget_end_only():
    d = PageDeadline(1.0, until=10.0)
    d.may_wait(URL, 0.0, 9.999)  # the host's delay is the store's pace: the page's own clock has not started
    with pytest.raises(FetchError) as info:
        d.may_wait(URL, 0.0, 10.0)
    assert fetch_error_kind(info.value) == BUDGET_SPENT


def test_the_budget_names_the_cut_when_it_ends_first_or_with_the_deadline():
    at_once = PageDeadline(10.0, until=10.0)
    at_once.start(0.0)
    assert fetch_error_kind(at_once.error(URL, 10.0)) == BUDGET_SPENT
    later = PageDeadline(10.0, until=10.001)
    later.start(0.0)
    assert fetch_error_kind(later.error(URL, 10.0)) == "timeout"


@given(limit=spans, start=times, after=st.floats(min_value=0, max_value=2e4, allow_nan=False))
def test_time_left_is_the_limit_less_the_time_since_the_start(limit, start, after):
    d = PageDeadline(limit)
    d.start(start)
    d.start(start + 1.0)  # a deadline starts once
    now = start + after
    if start + limit <= now:
        assert d.passed(now)
        with pytest.raises(FetchError):
            d.left(URL, now)
    else:
        assert not d.passed(now) and d.left(URL, now) == pytest.approx(start + limit - now)


@given(budget=spans, start=times, after=st.floats(min_value=0, max_value=2e4, allow_nan=False))
def test_a_budget_is_spent_from_its_end_on(budget, start, after):
    b = StoreBudget(budget)
    assert not b.spent(start)  # not started
    assert b.start(start) == start + budget and b.start(start + 5) == start + budget
    assert b.spent(start + after) == (start + after >= start + budget)


def test_a_budget_is_spent_exactly_at_its_end():
    b = StoreBudget(3.0)
    b.start(0.0)
    assert not b.spent(2.999) and b.spent(3.0)


# ---------------------------------------------------------------------------------------------- retries under the deadline
class _Flaky(BaseHTTPRequestHandler):
    """503 for the first ``fails`` requests to a path, then a page."""

    protocol_version = "HTTP/1.1"
    counts: dict[str, int] = {}
    fails = 2

    def log_message(self, *args):
        pass

    def do_GET(self):  # noqa: N802
        if self.path == "/robots.txt":
            body, status = b"", 404
        else:
            n = self.counts[self.path] = self.counts.get(self.path, 0) + 1
            body, status = (b"busy", 503) if n <= self.fails else (b"<html>ok</html>", 200)
        self.send_response(status)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


@pytest.fixture(scope="module")
def flaky():
    server = ThreadingHTTPServer(("127.0.0.1", 0), _Flaky)
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


@pytest.mark.parametrize(("limit", "fetched"), [(30.0, False), (30.5, True)])
def test_retries_and_their_backoff_count_against_the_page_deadline(flaky, limit, fetched):
    # Attempts at t=0 and t=10 (backoff 10 s) answer 503; the third would start at t=30 (backoff 20 s).
    clock = FakeClock()
    policy = FetchPolicy(delay_s=0, max_retries=5, backoff_s=10.0, max_page_s=limit, read_timeout_s=5)
    fetcher = PoliteFetcher(requests.Session(), clock=clock, policy=policy)
    url = f"{flaky}/retry-{limit}"
    if fetched:
        assert fetcher.fetch(url).body == b"<html>ok</html>"
        assert clock.sleeps == [10.0, 20.0]
    else:
        with pytest.raises(FetchError) as info:
            fetcher.fetch(url)
        assert fetch_error_kind(info.value) == "timeout" and "deadline" in str(info.value)
        assert clock.sleeps == [10.0] and _Flaky.counts[f"/retry-{limit}"] == 2  # no sleep past the end


#: How far past a 1 s deadline a drip may still be rejected here. The rejection comes when the watchdog's
#: timer fires at the deadline, or at the next body read (one drip interval, 50 ms) if it is the per-read
#: clamp that sees it; the rest is thread scheduling, tens of ms even on a loaded CI runner. 4 s leaves room
#: for a runner paused for seconds, and still fails by 25 s a fetch the drip holds for its whole 30 s (as
#: the status-line and header drips were held before the watchdog). The exact figure is printed here and
#: measured by benchmarks/hostile_bench.py (default deadline 30 s).
DRIP_MARGIN_S = 4.0


@pytest.fixture(scope="module")
def dripping():
    with PageStore(drip_s=30.0) as store:
        store.mode = "hostile"
        yield store


@pytest.mark.parametrize("kind", ["drip", "drip-status", "drip-headers", "drip-chunked"])
@pytest.mark.parametrize("kept_alive", [False, True], ids=["new-connection", "kept-alive"])
def test_a_drip_is_cut_at_the_page_deadline_although_each_byte_comes_within_the_read_timeout(
    dripping, kind, kept_alive
):
    # The body, the status line, a header line or a chunk-size line, a byte every 50 ms; read time-out 5 s.
    # Kept alive: robots.txt is read first and the page is asked on the same connection.
    policy = FetchPolicy(
        delay_s=0, read_timeout_s=5.0, max_page_s=1.0, max_retries=3, backoff_s=0, obey_robots=kept_alive
    )
    with requests.Session() as session:
        fetcher = PoliteFetcher(session, policy=policy)
        if kept_alive:
            fetcher.robots(dripping.base_url + "/")
        peers = set(dripping.peers)
        started = time.monotonic()
        with pytest.raises(FetchError) as info:
            fetcher.fetch(f"{dripping.base_url}/p/{kind}")
        elapsed = time.monotonic() - started
    assert fetch_error_kind(info.value) == "timeout"
    assert info.value.reason == "page took longer than 1 s (its deadline)"
    assert fetcher.requests_made == 1 + kept_alive  # a passed deadline is not retried
    assert (dripping.peers == peers) is kept_alive  # the page went over robots.txt's connection, or a new one
    assert elapsed < policy.max_page_s + DRIP_MARGIN_S
    print(f"\n{kind}: rejected after {elapsed:.3f} s wall (deadline 1 s, a byte every 50 ms, read timeout 5 s)")


def test_the_watchdog_is_mounted_on_stock_adapters_only():
    with requests.Session() as session:
        PoliteFetcher(session)
        assert all(isinstance(session.adapters[p], WatchedAdapter) for p in ("http://", "https://"))

        class Custom(requests.adapters.HTTPAdapter):
            pass

        custom = Custom()
        session.mount("http://", custom)
        PoliteFetcher(session)
        assert session.adapters["http://"] is custom  # another transport (a test's) is the caller's choice


def test_a_watchdog_shuts_its_sockets_when_it_fires_and_closes_its_duplicates_after():
    import gc
    import os
    import socket
    import warnings

    def open_fds() -> set[str]:
        return set(os.listdir("/proc/self/fd"))

    a, b = socket.socketpair()
    c, d = socket.socketpair()
    with a, b, c, d:
        gc.collect()  # earlier tests' dropped sockets close now, not during the count (it flaked 1 run in 3)
        before = open_fds()
        a.settimeout(10.0)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ResourceWarning)
            with Watchdog(0.05) as dog:
                dog.watch(a)
                assert a.recv(1) == b""  # the blocked read returns once the watchdog fires
                assert dog.fired
            with Watchdog(30.0) as calm:
                calm.watch(c)
            gc.collect()
        # closed by the watchdog, not dropped unclosed (a dropped socket closes its descriptor too, but warns)
        assert not [w for w in caught if issubclass(w.category, ResourceWarning)]
        assert not calm.fired and c.send(b"x") == 1 and d.recv(1) == b"x"  # one that does not fire leaves it be
        assert not open_fds() - before  # the watchdogs' duplicate descriptors are closed (none left open)


# ---------------------------------------------------------------------------------------------- the store budget
def _budget_run(tmp_path, budget: float):
    pages = {f"/p/mug-{i}": product_page(f"Mug {i}", "9 x 9 x 10 cm", "320 g").encode() for i in range(6)}
    text = (
        f"[defaults]\ndelay_s = 1.0\nmax_retries = 0\nread_timeout_s = 5.0\nbudget_s = {budget}\n"
        '[[stores]]\nname = "mugs"\nbase_url = "http://127.0.0.1:1"\nsitemaps = ["{base_url}/sitemap.xml"]\n'
    )
    kb = KnowledgeBase.open(tmp_path / f"budget-{budget}.duckdb")
    with HostileStore(pages) as store, requests.Session() as session:
        report = run_ingestion(kb, parse_sources(text, base_url=store.base_url), session=session, clock=FakeClock())
    with kb.connect() as con:
        events = con.execute("SELECT url, stage, reason FROM page_events ORDER BY url").fetchall()
    return report, events


@pytest.mark.parametrize(("budget", "extracted"), [(4.0, 2), (4.5, 3)])
def test_a_store_stops_fetching_when_its_budget_is_spent_and_records_the_rest(tmp_path, budget, extracted):
    # Requests one delay (1 s) apart from t=0: robots.txt, the sitemap, then the pages at t=2, 3, 4, ...
    report, events = _budget_run(tmp_path, budget)
    assert report.pages == 6 and report.extracted == extracted
    assert report.rejected_reasons == {BUDGET_SPENT: 6 - extracted}
    assert len(events) == 6 - extracted
    assert all(stage == "fetch" and reason.startswith(BUDGET_SPENT) for _, stage, reason in events)
    assert report.status == "ok"


# ---------------------------------------------------------------------------------------------- configuration
STORE = '[[stores]]\nname = "s"\nbase_url = "http://127.0.0.1:1"\n'


def test_the_sources_file_sets_the_page_deadline_and_the_store_budget():
    (default,) = parse_sources(STORE).stores
    assert default.policy.max_page_s == 30.0 and default.budget_s == DEFAULT_STORE_BUDGET_S
    (store,) = parse_sources("[defaults]\nmax_page_s = 12\nbudget_s = 90\n" + STORE).stores
    assert store.policy.max_page_s == 12.0 and store.budget_s == 90.0
    (cli,) = parse_sources("[defaults]\nbudget_s = 90\n" + STORE, max_page_s=5, budget_s=60).stores
    assert cli.policy.max_page_s == 5.0 and cli.budget_s == 60.0


@pytest.mark.parametrize(
    ("text", "kwargs", "message"),
    [
        (STORE + "budget_s = 0\n", {}, "budget_s must be > 0"),
        (STORE + "budget_s = -1\n", {}, "budget_s must be > 0"),
        (STORE + "max_page_s = 0\n", {}, "max_page_s must be > 0"),
        (STORE + 'budget_s = "1h"\n', {}, "budget_s must be a number"),
        (STORE, {"budget_s": 0.0}, "--store-budget"),
        (STORE, {"max_page_s": 0.0}, "--page-deadline"),
    ],
)
def test_a_deadline_or_budget_that_is_not_positive_is_refused_by_name(text, kwargs, message):
    with pytest.raises(SourcesError, match=message):
        parse_sources(text, **kwargs)


def test_a_tiny_budget_is_accepted(tmp_path):
    (store,) = parse_sources(STORE + "budget_s = 0.001\nmax_page_s = 0.001\n").stores
    assert store.budget_s == 0.001 and store.policy.max_page_s == 0.001


def test_the_cli_options_reach_every_store(tmp_path):
    sources = tmp_path / "s.toml"
    sources.write_text(STORE, encoding="utf-8")
    result = CliRunner().invoke(
        app, ["ingest", "--sources", str(sources), "--db", str(tmp_path / "c.duckdb"), "--store-budget", "0"]
    )
    assert result.exit_code == 1 and "--store-budget" in result.stderr
    result = CliRunner().invoke(
        app,
        ["ingest", "--sources", str(sources), "--db", str(tmp_path / "c.duckdb"), "--page-deadline", "-1", "--json"],
    )
    assert result.exit_code == 1 and "--page-deadline" in result.stderr


def test_the_watched_adapter_keeps_a_pool_per_store_crawled_at_once():
    from scrapers.crawl import MAX_CRAWLING
    from scrapers.fetch_watchdog import HOSTS_AT_ONCE

    assert HOSTS_AT_ONCE >= MAX_CRAWLING
    with requests.Session() as session:
        PoliteFetcher(session)
        assert session.adapters["http://"]._pool_connections == HOSTS_AT_ONCE
        session.mount("http://", requests.adapters.HTTPAdapter(pool_connections=32))
        PoliteFetcher(session)
        assert session.adapters["http://"]._pool_connections == 32  # a larger pool is kept
