"""The demo storefront over real HTTP: routes, robots.txt, sitemap, validators, broken pages, truth table."""

from __future__ import annotations

import csv
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import requests

import kb
from kb.features import MATERIALS, normalize_name
from scrapers.demo_store import BROKEN_PAGES, PRODUCTS, DemoStore

SEED_CSV = Path(kb.__file__).parent / "data" / "seed_catalog.csv"


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=0.5, slow_s=0.6) as s:
        yield s


def _seed_names() -> set[str]:
    with open(SEED_CSV, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    names = {normalize_name(r["name"]) for r in rows}
    for r in rows:
        names.update(normalize_name(a) for a in (r.get("aliases") or "").split(";") if a.strip())
    return names


def test_truth_table_covers_the_formats_languages_and_catalog():
    assert len(PRODUCTS) >= 30
    formats = {p.fmt for p in PRODUCTS}
    assert formats >= {"jsonld", "jsonld_graph", "microdata", "shopify", "woocommerce", "amazon", "ikea",
                       "spec_table", "spec_dl", "free_text"}  # fmt: skip
    assert {p.lang for p in PRODUCTS} >= {"en", "de", "fr", "es", "it", "pt"}
    assert {p.dim_unit for p in PRODUCTS} >= {"cm", "mm", "in"}
    assert {p.mass_unit for p in PRODUCTS} >= {"g", "kg", "oz", "lb"}
    seed = _seed_names()
    in_seed = [p for p in PRODUCTS if p.name in seed]
    assert {p.handle for p in in_seed} == {p.handle for p in PRODUCTS if p.in_seed}
    assert 4 <= len(in_seed) <= 7 and len(PRODUCTS) - len(in_seed) >= 25
    for p in PRODUCTS:
        assert list(p.dims_cm) == sorted(p.dims_cm, reverse=True) and 0 < p.dims_cm[0] <= 500
        assert p.mass_g is None or 0 < p.mass_g < 10_000
        assert p.material is None or p.material in MATERIALS
    assert len({p.handle for p in PRODUCTS}) == len(PRODUCTS)
    assert len({p.name for p in PRODUCTS}) == len(PRODUCTS)


def test_truth_in_catalog_units():
    by = {p.handle: p for p in PRODUCTS}
    assert by["rolling-pin"].dims_cm == (45.72, 5.08, 5.08)
    assert by["rolling-pin"].mass_g == pytest.approx(317.51, abs=0.01)
    assert by["cast-iron-skillet"].dims_cm == (43.5, 27.3, 5.1)
    assert by["cork-yoga-block"].mass_g == pytest.approx(680.39, abs=0.01)


def test_robots_and_sitemap(store):
    robots = requests.get(store.url("/robots.txt"), timeout=5).text
    assert "Disallow: /private/" in robots and "Crawl-delay: 0.5" in robots
    assert f"Sitemap: {store.base_url}/sitemap.xml" in robots
    sitemap = requests.get(store.url("/sitemap.xml"), timeout=5).text
    locs = re.findall(r"<loc>(.*?)</loc>", sitemap)
    assert len(locs) == len(set(locs)) == len(store.sitemap_paths())
    for prod in PRODUCTS:
        assert store.url(prod.path) in locs
    for broken in BROKEN_PAGES:
        assert store.url(broken.path) in locs


def test_every_product_page_names_its_product_and_has_validators(store):
    for prod in PRODUCTS:
        resp = requests.get(store.url(prod.path), timeout=5)
        assert resp.status_code == 200, prod.path
        assert resp.headers["ETag"].startswith('"') and resp.headers["Last-Modified"]
        assert f"<title>{prod.title.replace('&', '&amp;').replace(chr(39), '&#x27;')}" in resp.text
        assert f'rel="canonical" href="{store.url(prod.path)}"' in resp.text


def test_formats_look_like_the_stores_they_imitate(store):
    by: dict = {}
    for prod in PRODUCTS:
        by.setdefault(prod.fmt, prod)
    graph = requests.get(store.url(by["jsonld_graph"].path), timeout=5).text
    assert '"@graph"' in graph and '"unitCode": "MMT"' in graph
    amazon = requests.get(store.url(by["amazon"].path), timeout=5).text
    assert "\u200f : \u200e" in amazon and "Product Dimensions" in amazon
    woo = requests.get(store.url(by["woocommerce"].path), timeout=5).text
    assert "woocommerce-product-attributes-item--dimensions" in woo and "data-product_variations=" in woo
    shop = by["shopify"]
    data = requests.get(store.url(f"/products/{shop.handle}.json"), timeout=5).json()
    variant = data["product"]["variants"][0]
    assert variant["grams"] == round(shop.mass_g) and variant["weight_unit"] in ("g", "kg", "lb", "oz")
    planter = requests.get(store.url("/products/hand-thrown-planter.json"), timeout=5).json()
    assert planter["product"]["variants"][0]["grams"] == 0  # "unknown" in Shopify's terms
    german = requests.get(store.url("/de/p/wasserkocher-edelstahl.html"), timeout=5).text
    assert "<th>Gewicht</th><td>1,3 kg</td>" in german
    assert requests.get(store.url("/products/not-a-product.json"), timeout=5).status_code == 404


def test_conditional_requests_and_updates(store):
    path = "/p/bamboo-serving-tray.html"
    first = requests.get(store.url(path), timeout=5)
    etag, modified = first.headers["ETag"], first.headers["Last-Modified"]
    assert requests.get(store.url(path), headers={"If-None-Match": etag}, timeout=5).status_code == 304
    assert (
        requests.get(store.url(path), headers={"If-Modified-Since": modified}, timeout=5).status_code == 304
    )
    store.update_product("bamboo-serving-tray", mass=0.9)
    try:
        changed = requests.get(store.url(path), headers={"If-None-Match": etag}, timeout=5)
        assert changed.status_code == 200 and changed.headers["ETag"] != etag
        assert '<span itemprop="value">0.9</span>' in changed.text
    finally:
        store.update_product("bamboo-serving-tray", mass=0.85)


def test_broken_pages(store):
    assert requests.get(store.url("/p/server-error.html"), timeout=5).status_code == 500
    with pytest.raises(requests.Timeout):
        requests.get(store.url("/p/slow-teapot.html"), timeout=0.2)
    with requests.get(store.url("/p/huge-catalogue.html"), stream=True, timeout=5) as resp:
        assert resp.status_code == 200 and "Content-Length" not in resp.headers
        got = 0
        for chunk in resp.iter_content(1 << 16):
            got += len(chunk)
            if got > 3_000_000:
                break
        assert got > 3_000_000  # it keeps coming: generated while streaming, never stored
    moved = requests.get(store.url("/old/cast-iron-pan.html"), allow_redirects=False, timeout=5)
    assert moved.status_code == 301 and moved.headers["Location"] == "/p/cast-iron-skillet.html"
    broken = requests.get(store.url("/p/broken-jsonld.html"), timeout=5).text
    block = re.search(
        r'<script type="application/ld\+json">(\{"@context": "https://schema.org", "@type": "Product".*?)</script>',
        broken,
    )
    with pytest.raises(json.JSONDecodeError):
        json.loads(block.group(1))
    dup = requests.get(store.url("/collections/kitchen/products/linen-tea-towel"), timeout=5).text
    assert f'rel="canonical" href="{store.url("/products/linen-tea-towel")}"' in dup


def test_flaky_page_asks_to_retry_once():
    with DemoStore(crawl_delay=None) as s:
        first = requests.get(s.url("/p/flaky-glass-carafe.html"), timeout=5)
        assert first.status_code == 503 and first.headers["Retry-After"] == "1"
        assert requests.get(s.url("/p/flaky-glass-carafe.html"), timeout=5).status_code == 200


def test_module_runs_as_a_server_process():
    proc = subprocess.Popen(
        [sys.executable, "-m", "scrapers.demo_store", "--port", "0", "--crawl-delay", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        base = proc.stdout.readline().strip()
        assert base.startswith("http://127.0.0.1:")
        assert "Crawl-delay: 0" in requests.get(base + "/robots.txt", timeout=5).text
    finally:
        proc.terminate()
        proc.wait(timeout=10)
