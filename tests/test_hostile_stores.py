"""Issue 25, part 2: hostile stores beside a good one, over real HTTP on loopback and a real DuckDB file.

Every store is ingested once in good mode, then again hostile: each hostile page gets its reason in
``page_events``, the run finishes with no crash in bounded time (page deadline 1 s here), the good store's
pages are read as usual, and the catalog stays as it was for every hostile page (its object's values, and
its source's observations). Wall time per store is printed (``-s``); memory is measured by
``benchmarks/hostile_bench.py``, not asserted here.
"""

from __future__ import annotations

import time

import pytest
import requests
from hostile_store import HostileStore, product_page
from hostile_stores import PAGE_KINDS, PageStore, sources_text

from kb.catalog import KnowledgeBase
from scrapers.discovery import MAX_SITEMAP_URLS
from scrapers.ingest import run_ingestion
from scrapers.sources import parse_sources

#: What each hostile page of a PageStore is rejected with (reason prefix), or "extracted" when it is read
#: right despite its bytes (the wrong and the missing charset; a redirect to another host is followed).
EXPECTED = {
    "drip": "timeout: page took longer than 1 s (its deadline)",
    "drip-status": "timeout: page took longer than 1 s (its deadline)",
    "drip-headers": "timeout: page took longer than 1 s (its deadline)",
    "drip-chunked": "timeout: page took longer than 1 s (its deadline)",
    "redirect-endless": "too_many_redirects",
    "redirect-circle": "redirect_loop",
    "redirect-other-port": "robots_unavailable",  # the other port's robots.txt cannot be read: disallowed
    "redirect-other-host": "extracted",
    "gzip-bomb": "too_large",
    "deflate-bomb": "too_large",
    "nested": "no_product",
    "jsonld-10000": "no_product",
    "wrong-charset": "extracted",
    "missing-charset": "extracted",
    "error-page": "no_product",
}


def _catalog(kb):
    with kb.connect() as con:
        objects = sorted(con.execute("SELECT name, a_cm, b_cm, c_cm, mass_g FROM objects").fetchall())
        observations = sorted(
            con.execute("SELECT source, feature, value_num, value_text FROM observations").fetchall(),
            key=repr,
        )
        run = con.execute("SELECT max(id) FROM ingestion_runs").fetchone()[0]
        events = con.execute("SELECT url, stage, reason FROM page_events WHERE run_id = ?", [run]).fetchall()
    return objects, observations, events


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    kb = KnowledgeBase.open(tmp_path_factory.mktemp("hostile-stores") / "catalog.duckdb")
    good_pages = {f"/p/good-{i}": product_page(f"Good Store Mug {i}", "9 x 9 x 10 cm", "320 g").encode() for i in range(3)}
    with (
        PageStore() as pages,
        PageStore(robots_hang_s=4.0) as robots,
        PageStore(sitemap_urls=1_000_000) as sitemap,
        HostileStore(good_pages) as good,
        requests.Session() as session,
    ):
        stores = {"pages": pages, "robots-hang": robots, "huge-sitemap": sitemap}
        text = sources_text(stores) + (
            f'[[stores]]\nname = "good"\nbase_url = "{good.base_url}"\nsitemaps = ["{{base_url}}/sitemap.xml"]\n'
        )
        sources = parse_sources(text)
        first = run_ingestion(kb, sources, session=session)
        before = _catalog(kb)
        for store in stores.values():
            store.mode = "hostile"
        times: dict[str, float] = {}
        started = time.monotonic()

        def progress(done, total, url):
            for name, store in [*stores.items(), ("good", good)]:
                if url.startswith(store.base_url):
                    times[name] = time.monotonic() - started

        second = run_ingestion(kb, sources, session=session, progress=progress)
        wall = time.monotonic() - started
    print(f"\nhostile run: {wall:.2f} s wall; last page done per store (s): "
          + ", ".join(f"{k} {v:.2f}" for k, v in sorted(times.items())))  # fmt: skip
    return first, before, second, _catalog(kb), pages


def _reasons(events, base_url: str) -> dict[str, str]:
    return {url.removeprefix(base_url): f"{stage}:{reason}" for url, stage, reason in events if url.startswith(base_url)}


def test_the_good_run_reads_every_page(runs):
    first, *_ = runs
    assert first.rejected == 0 and first.extracted == len(PAGE_KINDS) + 1 + 3 + 3


@pytest.mark.parametrize("kind", PAGE_KINDS)
def test_each_hostile_page_gets_its_reason_or_is_read_right(runs, kind):
    *_, second, (_, _, events), pages = runs
    reasons = _reasons(events, pages.base_url)
    expected = EXPECTED[kind]
    if expected == "extracted":
        assert f"/p/{kind}" not in reasons
    else:
        stage, reason = reasons[f"/p/{kind}"].split(":", 1)
        assert reason.startswith(expected), (kind, reason)
        assert stage == ("extract" if expected == "no_product" else "fetch")


def test_a_robots_txt_that_hangs_is_cut_by_the_deadline_and_disallows_its_host(runs):
    # Its sitemap is behind it too, so the store's page is not even discovered this run (it stays as it was).
    *_, (_, _, events), _ = runs
    (event,) = [e for e in events if e[1] == "discover" and "robots.txt unavailable" in e[2]]
    url, stage, reason = event
    assert url.endswith("/sitemap.xml") and stage == "discover"
    assert reason.startswith("robots_unavailable") and "timeout: page took longer than 1 s" in reason


def test_a_sitemap_of_a_million_urls_is_capped_with_a_reason(runs):
    *_, second, (_, _, events), _ = runs
    (reason,) = [r for _, stage, r in events if r.startswith("sitemap_truncated")]
    assert f"more than {MAX_SITEMAP_URLS} URLs" in reason
    assert second.status == "ok_with_errors"


def test_the_good_store_beside_them_is_read_and_nothing_crashes(runs):
    _, _, second, (_, _, events), _ = runs
    first = runs[0]
    assert not [e for e in events if "/p/good-" in e[0]]
    assert second.pages == first.pages - 1  # all but the page behind the hanging robots.txt
    # the good store, the capped sitemap's pages and the three read right: unchanged bytes are not parsed
    assert second.extracted + second.not_modified == 3 + 3 + 3 and second.extracted == 2


def test_the_catalog_stays_as_it_was_for_every_hostile_page(runs):
    _, (objects, observations, _), _, (objects_after, observations_after, _), _ = runs
    assert objects_after == objects
    moved = [o for o in observations_after if o not in observations]
    assert all(o[0].startswith("http://localhost/") for o in moved)  # the page that moved to another host
    assert set(observations) <= set(observations_after)


def _urlset(n: int) -> bytes:
    locs = "".join(f"<url><loc>http://s.example/p/{i}</loc></url>" for i in range(n))
    return f'<urlset xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">{locs}</urlset>'.encode()


@pytest.mark.parametrize(("n", "more"), [(4, False), (5, False), (6, True)])
def test_a_sitemap_is_read_up_to_its_cap_and_says_when_more_were_left(n, more):
    from scrapers.discovery import sitemap_locs

    kind, locs, left = sitemap_locs(_urlset(n), cap=5)
    assert kind == "urlset" and locs == [f"http://s.example/p/{i}" for i in range(min(n, 5))] and left is more


def test_a_sitemap_index_keeps_its_kind():
    from scrapers.discovery import sitemap_locs

    body = b'<sitemapindex><sitemap><loc>http://s.example/a.xml</loc></sitemap></sitemapindex>'
    assert sitemap_locs(body) == ("sitemapindex", ["http://s.example/a.xml"], False)
