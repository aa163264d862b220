"""Store search as a source: the sources file's search template, the demo store's search endpoint over real
HTTP on 127.0.0.1, and reading search answers (scrapers.store_search)."""

from __future__ import annotations

import json
import re
from urllib.parse import urlsplit

import pytest
import requests
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.errors import ExtractionError, SourcesError
from scrapers.demo_store import DemoStore
from scrapers.demo_store.search import PAGE_SIZE, find, query_words
from scrapers.sources import parse_sources
from scrapers.store_search import parse_search_page


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None) as s:
        yield s


def source(base="http://127.0.0.1:1", extra=""):
    text = f'[[stores]]\nname = "s"\nbase_url = "{base}"\nsearch = "{{base_url}}/search?q={{query}}"\n{extra}'
    return parse_sources(text).stores[0]


def test_search_template_expands_and_encodes_the_words():
    s = source()
    assert s.search_url("glazed ceramic teapot") == "http://127.0.0.1:1/search?q=glazed+ceramic+teapot"
    assert s.search_url("a&b=c") == "http://127.0.0.1:1/search?q=a%26b%3Dc"
    assert s.search_results == 3 and "search" in s.to_dict()


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ('search = "{base_url}/search"', "has no {query}"),
        ('search = "ftp://x/{query}"', "not an http(s) URL"),
        ("search_results = 0", "search_results must be > 0"),
        ("search = 3", "search must be a str"),
    ],
)
def test_bad_search_settings_are_refused(extra, message):
    text = f'[[stores]]\nname = "s"\nbase_url = "http://127.0.0.1:1"\n{extra}\n'
    with pytest.raises(SourcesError, match=re.escape(message)):
        parse_sources(text)


def test_search_is_a_store_key_not_a_default():
    with pytest.raises(SourcesError, match="unknown key 'search'"):
        parse_sources('[defaults]\nsearch = "{base_url}/s?q={query}"\n[[stores]]\nname = "s"\nbase_url = "http://h"\n')
    assert parse_sources('[defaults]\nsearch_results = 1\n[[stores]]\nname = "s"\nbase_url = "http://h"\n').stores[0].search_results == 1


def test_query_words_and_matching_need_every_word():
    assert query_words("Glazed TEAPOTS, glass") == ["glazed", "teapot", "glass"]
    products = DemoStore().searchable()
    assert [p.handle for p in find(products, "ceramic teapot")] == ["glazed-ceramic-teapot"]
    assert {p.handle for p in find(products, "teapot")} == {"glazed-ceramic-teapot", "cast-iron-teapot"}
    assert find(products, "") == [] and find(products, "teapot hippo") == []


def test_results_pages_paginate_in_the_stores_markup(store):
    hits = find(store.searchable(), "steel")
    assert len(hits) > PAGE_SIZE
    first = requests.get(store.url("/search"), params={"q": "steel"}, timeout=5)
    second = requests.get(store.url("/search"), params={"q": "steel", "page": 2}, timeout=5)
    s = source(store.base_url)
    p1 = parse_search_page(first.content, first.url, first.headers["Content-Type"], s)
    p2 = parse_search_page(second.content, second.url, second.headers["Content-Type"], s)
    assert len(p1.product_urls) == PAGE_SIZE and p1.next_url.endswith("page=2")
    assert len(p2.product_urls) == len(hits) - PAGE_SIZE and p2.next_url is None
    assert [store.url(h.path) for h in hits] == p1.product_urls + p2.product_urls
    # nothing from the navigation, footer or the pagination itself
    assert not any(u.endswith(("/", "/about.html", "/cart")) or "/search" in u for u in p1.product_urls)


def test_no_results_page_lists_nothing(store):
    resp = requests.get(store.url("/search"), params={"q": "purple hippo"}, timeout=5)
    assert resp.status_code == 200 and "No results" in resp.text and "/search?q=mug" in resp.text
    s = source(store.base_url)
    page = parse_search_page(resp.content, resp.url, resp.headers["Content-Type"], s)
    assert page.product_urls == [] and page.next_url is None
    past = requests.get(store.url("/search"), params={"q": "steel", "page": 9}, timeout=5)
    assert "No results" in past.text


def test_json_search_answers_list_the_product_urls(store):
    resp = requests.get(store.url("/search.json"), params={"q": "teapot"}, timeout=5)
    data = resp.json()
    assert {p["handle"] for p in data["resources"]["results"]["products"]} == {"glazed-ceramic-teapot", "cast-iron-teapot"}
    page = parse_search_page(resp.content, resp.url, resp.headers["Content-Type"], source(store.base_url))
    assert sorted(page.product_urls) == sorted(store.url(p) for p in ("/p/glazed-ceramic-teapot.html", "/p/cast-iron-teapot.html"))


def test_search_answers_keep_to_the_stores_own_pages():
    body = json.dumps([{"url": "https://elsewhere.example/p/x"}, {"url": "/p/a.html"}, {"href": "/p/a.html#top"}])
    page = parse_search_page(body.encode(), "http://127.0.0.1:1/search?q=x", "application/json", source())
    assert page.product_urls == ["http://127.0.0.1:1/p/a.html"]
    include = source(extra='include = ["^/p/"]')
    html = b'<html><body><main><a href="/p/a.html">a</a><a href="/blog/b">b</a></main></body></html>'
    assert parse_search_page(html, "http://127.0.0.1:1/search?q=x", "text/html", include).product_urls == [
        "http://127.0.0.1:1/p/a.html"
    ]
    with pytest.raises(ExtractionError, match="not valid JSON"):
        parse_search_page(b"{nope", "http://127.0.0.1:1/s", "application/json", source())


def test_search_faults(store):
    with DemoStore(crawl_delay=None, search_fault="http_500") as bad:
        assert requests.get(bad.url("/search"), params={"q": "x"}, timeout=5).status_code == 500
    with DemoStore(crawl_delay=None, disallow_search=True) as shy:
        assert "Disallow: /search" in requests.get(shy.url("/robots.txt"), timeout=5).text
    assert "Disallow: /search" not in requests.get(store.url("/robots.txt"), timeout=5).text
    with pytest.raises(ValueError, match="search_fault"):
        DemoStore(search_fault="broken")


_links = st.lists(
    st.tuples(st.sampled_from(["/p/", "http://127.0.0.1:1/p/", "https://other.example/p/", "/search?q=", "#", ""]),
              st.text(min_size=0, max_size=12)),
    max_size=8,
)  # fmt: skip


@settings(max_examples=150, deadline=None)
@given(_links, st.sampled_from(["main", "body", "nav", "footer"]), st.booleans())
def test_any_results_page_lists_only_the_stores_own_non_search_pages(links, where, as_json):
    base = "http://127.0.0.1:1/search?q=x"
    if as_json:
        body = json.dumps({"items": [{"url": p + t} for p, t in links]}).encode()
    else:
        anchors = "".join(f'<a href="{p}{t}">x</a>' for p, t in links).replace("\x00", "")
        body = f"<html><body><{where}>{anchors}</{where}></body></html>".encode("utf-8", "replace")
    try:
        page = parse_search_page(body, base, "application/json" if as_json else "text/html", source())
    except ExtractionError:
        return
    assert len(page.product_urls) == len(set(page.product_urls))
    for url in page.product_urls:
        assert url.startswith("http://127.0.0.1:1/") and "#" not in url
        assert urlsplit(url).path != "/search"
    if where in ("nav", "footer") and not as_json:
        assert page.product_urls == []


@given(st.binary(max_size=300))
def test_garbage_search_answers_never_crash(body):
    try:
        parse_search_page(body, "http://127.0.0.1:1/search?q=x", None, source())
    except ExtractionError:
        pass


@given(st.text(max_size=40))
def test_query_words_are_lower_case_words(text):
    for word in query_words(text):
        assert word == word.lower() and word.strip() and " " not in word


def test_a_results_page_with_an_item_list_is_read_by_its_list():
    listing = {"@context": "https://schema.org", "@type": "ItemList", "itemListElement": [
        {"@type": "ListItem", "position": 1, "url": "/p/b.html"},
        {"@type": "ListItem", "position": 2, "item": {"@type": "Product", "url": "http://127.0.0.1:1/p/c.html"}},
        {"@type": "ListItem", "position": 3, "item": "/p/d.html"},
    ]}  # fmt: skip
    html = (
        f'<html><head><script type="application/ld+json">{json.dumps({"@graph": [listing]})}</script>'
        '<script type="application/ld+json">{broken</script></head>'
        '<body><main><a href="/p/promo.html">promo</a><a href="/p/b.html">b</a></main></body></html>'
    ).encode()
    page = parse_search_page(html, "http://127.0.0.1:1/search?q=x", "text/html", source())
    assert page.product_urls == ["http://127.0.0.1:1/p/b.html", "http://127.0.0.1:1/p/c.html", "http://127.0.0.1:1/p/d.html"]
