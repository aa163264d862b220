"""sources.toml: parsing, checks with clear errors, overrides, URL discovery from sitemaps and robots.txt."""

from __future__ import annotations

import pytest
import requests
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import SourcesError
from scrapers.demo_store import DemoStore
from scrapers.discovery import discover_urls
from scrapers.fetcher import FetchPolicy, PoliteFetcher
from scrapers.sources import StoreSource, load_sources, parse_sources

GOOD = """
[defaults]
delay_s = 2
max_retries = 1

[[stores]]
name = "demo"
base_url = "http://127.0.0.1:8765/"
sitemaps = ["{base_url}/sitemap.xml"]
include = ["^/p/"]
exclude = ["broken"]

[[stores]]
name = "other"
base_url = "https://shop.example.org"
urls = ["{base_url}/products/mug"]
adapter = "shopify"
delay_s = 5
"""


def test_parses_stores_with_defaults_and_expansion():
    sources = parse_sources(GOOD, origin="s.toml")
    demo, other = sources.stores
    assert demo.base_url == "http://127.0.0.1:8765"
    assert demo.sitemaps == ("http://127.0.0.1:8765/sitemap.xml",)
    assert demo.policy.delay_s == 2 and demo.policy.max_retries == 1
    assert other.policy.delay_s == 5 and other.adapter == "shopify"
    assert other.urls == ("https://shop.example.org/products/mug",)
    assert sources.describe() == "s.toml: demo, other"


def test_overrides_for_base_url_and_delay():
    sources = parse_sources(GOOD, base_url="http://127.0.0.1:9999", delay_s=0)
    assert all(s.base_url == "http://127.0.0.1:9999" for s in sources.stores)
    assert sources.stores[0].sitemaps == ("http://127.0.0.1:9999/sitemap.xml",)
    assert all(s.policy.delay_s == 0 for s in sources.stores)


def test_include_and_exclude():
    store = parse_sources(GOOD).stores[0]
    assert store.wants("http://127.0.0.1:8765/p/mug.html")
    assert not store.wants("http://127.0.0.1:8765/about.html")
    assert not store.wants("http://127.0.0.1:8765/p/broken-jsonld.html")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("stores = [", "not valid TOML"),
        ("", "no stores"),
        ("[[stores]]\nname = 'a'\n", "missing base_url"),
        ("[[stores]]\nbase_url = 'http://x'\n", "missing name"),
        ("[[stores]]\nname = 'a'\nbase_url = 'ftp://x'\n", "not an http(s) URL"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\ndelay = 1\n", "unknown key 'delay'"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\ndelay_s = 'slow'\n", "delay_s must be a number"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\ndelay_s = -1\n", "delay_s must be >= 0"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\nmax_pages = 0\n", "max_pages must be > 0"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\nadapter = 'magic'\n", "adapter 'magic' unknown"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\ninclude = ['(']\n", "not a valid regex"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\nurls = 'http://x/a'\n", "urls must be a list"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\nurls = ['/relative']\n", "not an http(s) URL"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\n[[stores]]\nname = 'a'\nbase_url = 'http://y'\n",
         "two stores are named 'a'"),
        ("[defaults]\nname = 'x'\n[[stores]]\nname = 'a'\nbase_url = 'http://x'\n", "unknown key 'name'"),
        ("[[stores]]\nname = 'a'\nbase_url = 'http://x'\nmax_bytes = true\n", "max_bytes must be a whole number"),
        ("shops = []\n", "unknown key 'shops'"),
    ],
)  # fmt: skip
def test_bad_files_get_clear_errors(text, message):
    with pytest.raises(SourcesError) as info:
        parse_sources(text, origin="bad.toml")
    assert str(info.value).startswith("bad.toml: ") and message in str(info.value)


def test_missing_file(tmp_path):
    with pytest.raises(SourcesError, match="no such sources file"):
        load_sources(tmp_path / "nope.toml")


def test_demo_sources_file_is_valid():
    from pathlib import Path

    import scrapers

    sources = load_sources(
        Path(scrapers.__file__).parent / "demo_sources.toml", base_url="http://127.0.0.1:4444"
    )
    assert [s.name for s in sources.stores] == ["demo", "demo-shopify-json"]
    assert sources.stores[0].sitemaps == ("http://127.0.0.1:4444/sitemap.xml",)


def test_discovery_from_sitemap_and_from_robots():
    with DemoStore(crawl_delay=None) as store, requests.Session() as session:
        fetcher = PoliteFetcher(session, policy=FetchPolicy(delay_s=0))
        via_robots = StoreSource(name="d", base_url=store.base_url, policy=FetchPolicy(delay_s=0))
        events: list = []
        urls = discover_urls(fetcher, via_robots, events)
        assert urls == [store.url(p) for p in store.sitemap_paths()] and not events
        shopify = StoreSource(
            name="s", base_url=store.base_url, include=(r"^/products/",), adapter="shopify", max_pages=2,
            sitemaps=(store.url("/sitemap.xml"), store.url("/missing-sitemap.xml")),
        )  # fmt: skip
        urls = discover_urls(fetcher, shopify, events)
        assert urls == [
            store.url("/products/linen-tea-towel.json"),
            store.url("/products/soy-wax-candle.json"),
        ]
        assert events == [
            (store.url("/missing-sitemap.xml"), "discover", "http_404: HTTP 404 after 1 attempt(s)")
        ]
        not_xml = StoreSource(name="x", base_url=store.base_url, sitemaps=(store.url("/about.html"),))
        events = []
        assert discover_urls(fetcher, not_xml, events) == []
        assert events[0][2].startswith("bad_sitemap")


@given(st.text(max_size=300))
def test_any_text_is_sources_or_a_clear_error(text):
    try:
        sources = parse_sources(text, origin="fuzz.toml")
    except SourcesError as err:
        assert str(err).startswith("fuzz.toml")
    else:
        assert sources.stores


@given(
    st.dictionaries(
        st.sampled_from(["name", "base_url", "delay_s", "max_pages", "urls", "adapter", "include", "max_bytes"]),
        st.one_of(st.integers(-5, 5), st.floats(allow_nan=True), st.text(max_size=20), st.booleans(),
                  st.lists(st.text(max_size=10), max_size=3)),
    )
)  # fmt: skip
def test_any_store_table_is_a_store_or_a_clear_error(table):
    import tomllib

    lines = ["[[stores]]"]
    for key, value in table.items():
        lines.append(f"{key} = {_toml(value)}")
    text = "\n".join(lines) + "\n"
    try:
        tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return
    try:
        (store,) = parse_sources(text, origin="t.toml").stores
    except SourcesError as err:
        assert str(err).startswith("t.toml")
    else:
        assert store.name and store.base_url.startswith("http") and store.max_pages > 0


def _toml(value) -> str:
    import json

    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value != value:
        return "nan"
    if isinstance(value, float) and value in (float("inf"), float("-inf")):
        return "inf" if value > 0 else "-inf"
    return json.dumps(value)


@given(st.text(max_size=60))
def test_retry_after_of_any_header_is_bounded_or_ignored(header):
    from scrapers.fetcher import FetchResult, SystemClock

    fetcher = PoliteFetcher(requests.Session(), clock=SystemClock())
    result = FetchResult(url="http://x/", final_url="http://x/", status=503, body=None, content_type=None,
                         etag=None, last_modified=None, fetched_at=None, retry_after=header)  # fmt: skip
    policy = FetchPolicy(max_retry_after_s=30)
    seconds = fetcher._retry_after(result, policy)
    assert seconds is None or 0 <= seconds <= 30
