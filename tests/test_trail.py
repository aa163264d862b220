"""A page's category trail (scrapers.trail): breadcrumbs and JSON-LD categories, and the kind and English
alias ingestion gives an object from them when its title names no household noun."""

from __future__ import annotations

import functools
import http.server
import json
import threading
from pathlib import Path

import pytest
import requests
from conftest import SHARED_PAGES as REAL_PAGES

from kb.catalog import KnowledgeBase
from kb.kinds import assign_kind
from scrapers.extract import extract_page
from scrapers.page import Page
from scrapers.trail import MAX_CHARS, MAX_ITEMS, category_trail

REPO = Path(__file__).resolve().parents[1]


def _ld(*blocks: object, body: str = "") -> str:
    scripts = "".join(f'<script type="application/ld+json">{json.dumps(b)}</script>' for b in blocks)
    return f"<html><head><title>t</title>{scripts}</head><body>{body}</body></html>"


def trail_of(html: str):
    return category_trail(Page(html, "https://shop.example/p"))


def test_jsonld_breadcrumb_list_in_position_order_and_item_names():
    crumbs = {
        "@type": "BreadcrumbList",
        "itemListElement": [
            {"@type": "ListItem", "position": 3, "name": "Wasserkocher"},
            {"@type": "ListItem", "position": 1, "item": {"@id": "/", "name": "Startseite"}},
            {"@type": "ListItem", "position": 2, "name": "Küche"},
            "not an item",
        ],
    }
    assert trail_of(_ld(crumbs)).breadcrumbs == ("Startseite", "Küche", "Wasserkocher")


def test_jsonld_breadcrumbs_win_over_html_and_nest_in_a_graph():
    graph = {"@graph": [{"@type": "WebPage"}, {"@type": "BreadcrumbList", "itemListElement": [{"name": "Kitchen"}]}]}
    html = _ld(graph, body='<nav class="breadcrumbs"><a href="/">Home</a> / <a href="/x">Garden</a></nav>')
    assert trail_of(html).breadcrumbs == ("Kitchen",)


def test_product_category_string_list_and_thing():
    product = {"@type": "Product", "name": "Modell 4711", "category": "Home > Küche > Wasserkocher"}
    assert trail_of(_ld(product)).categories == ("Home", "Küche", "Wasserkocher")
    product["category"] = ["Teekanne", {"@type": "Thing", "name": "Tee"}, 42]
    assert trail_of(_ld(product)).categories == ("Teekanne", "Tee")
    product["@type"] = ["Product", "Thing"]
    assert trail_of(_ld(product)).categories == ("Teekanne", "Tee")


def test_a_category_of_another_type_numbers_and_urls_are_left_out():
    assert trail_of(_ld({"@type": "Offer", "category": "Kitchen"})).categories == ()
    product = {"@type": "Product", "category": ["21828", "/podlogi/panele,a3259.html", "https://x.example/c"]}
    assert trail_of(_ld(product)).categories == ()


def test_html_breadcrumbs_links_list_items_or_split_text():
    html = '<html><body><nav class="BreadCrumbs"><a href="/">Home</a> › <a href="/k">Kitchen</a></nav></body></html>'
    assert trail_of(html).breadcrumbs == ("Home", "Kitchen")
    html = '<html><body><ol id="breadcrumb-trail"><li>Home</li><li>Tea</li></ol></body></html>'
    assert trail_of(html).breadcrumbs == ("Home", "Tea")
    html = '<html><body><div class="breadcrumb">Home &gt; Kitchen &gt; Kettles</div></body></html>'
    assert trail_of(html).breadcrumbs == ("Home", "Kitchen", "Kettles")
    assert trail_of("<html><body><p>Home / Kitchen</p></body></html>").breadcrumbs == ()


def test_limits_duplicates_and_malformed_jsonld():
    items = [{"position": i, "name": f"level {i} " + "x" * 200} for i in range(MAX_ITEMS + 5)]
    crumbs = trail_of(_ld({"@type": "BreadcrumbList", "itemListElement": items})).breadcrumbs
    assert len(crumbs) == MAX_ITEMS and all(len(c) == MAX_CHARS for c in crumbs)
    dup = {"@type": "BreadcrumbList", "itemListElement": [{"name": "Home"}, {"name": " Home "}, {"name": "A"}]}
    assert trail_of(_ld(dup)).breadcrumbs == ("Home", "A")
    broken = '<html><head><script type="application/ld+json">{"@type": "BreadcrumbList", </script></head></html>'
    assert trail_of(broken) == trail_of("<html><body></body></html>")


def test_extracted_record_carries_the_trail():
    product = {"@type": "Product", "name": "Gastroback 42429 Design Pro", "category": "Küche/Wasserkocher",
               "weight": {"@type": "QuantitativeValue", "value": 1.4, "unitCode": "KGM"}}  # fmt: skip
    record = extract_page(_ld(product), "https://shop.example/p")
    assert record.categories == ("Küche", "Wasserkocher")
    assert list(record.to_dict()["categories"]) == ["Küche", "Wasserkocher"]


@pytest.mark.skipif(not REAL_PAGES.is_dir(), reason="the real store pages are not here")
def test_real_pages_trails():
    """On the real store pages: the trail never fails, stays within its limits, and where a page's title
    names no noun its breadcrumbs or categories can ("Filzstift FIBRALO" -> category Marker)."""
    pages = sorted(REAL_PAGES.glob("*.html")) + sorted(REAL_PAGES.glob("batch2/*.html"))
    found = 0
    for path in pages:
        page = Page(path.read_bytes(), path.as_uri(), "text/html")
        trail = category_trail(page)
        for texts in (trail.breadcrumbs, trail.categories):
            assert len(texts) <= MAX_ITEMS and all(0 < len(t) <= MAX_CHARS for t in texts)
        found += bool(trail.breadcrumbs)
    assert found >= len(pages) // 2
    kettle = REAL_PAGES / "batch2" / "metahari_amazon_de_gastroback_kettle.html"
    if kettle.is_file():
        trail = category_trail(Page(kettle.read_bytes(), kettle.as_uri(), "text/html"))
        assert trail.breadcrumbs[-1] == "Wasserkocher"
    jumbo = REAL_PAGES / "peb-15944e4fe5.html"
    if jumbo.is_file():
        page = Page(jumbo.read_bytes(), jumbo.as_uri(), "text/html")
        trail = category_trail(page)
        got = assign_kind(page.title or "", breadcrumbs=trail.breadcrumbs, categories=trail.categories)
        assert got is not None and got.noun == "marker" and got.provenance.startswith("category: Marker")


@pytest.mark.skipif(not REAL_PAGES.is_dir(), reason="the real store pages are not here")
def test_real_pages_brand_words_make_no_kind():
    """On the real store pages: a brand in capitals ("APPLE iMac") or a quoted model name ("»K 3 Full
    Control«") gives no kind; every page's kind agrees with its trail's whenever the trail names one."""
    from kb.kinds import ancestors

    wrong = {"peb-453f5cc079.html": "fruit", "peb-040c3ea5ea.html": "electronics"}
    for name, kind in wrong.items():
        path = REAL_PAGES / name
        if path.is_file():
            page = Page(path.read_bytes(), path.as_uri(), "text/html")
            trail = category_trail(page)
            got = assign_kind(page.title or "", breadcrumbs=trail.breadcrumbs, categories=trail.categories)
            assert got is None or got.kind != kind, name
    pages = sorted(REAL_PAGES.glob("*.html")) + sorted(REAL_PAGES.glob("batch2/*.html"))
    for path in pages:
        page = Page(path.read_bytes(), path.as_uri(), "text/html")
        trail = category_trail(page)
        filed = assign_kind("", breadcrumbs=trail.breadcrumbs, categories=trail.categories)
        got = assign_kind(page.title or "", breadcrumbs=trail.breadcrumbs, categories=trail.categories)
        if filed is not None:
            assert got.kind in ancestors(filed.kind) or filed.kind in ancestors(got.kind), path.name


PRODUCT_PAGE = """<html lang="de"><head><title>Gastroback 42429 Design Advanced Pro</title>
<script type="application/ld+json">{"@context": "https://schema.org", "@type": "Product",
 "name": "Gastroback 42429 Design Advanced Pro",
 "weight": {"@type": "QuantitativeValue", "value": 1.6, "unitCode": "KGM"},
 "depth": {"@type": "QuantitativeValue", "value": 22, "unitCode": "CMT"},
 "width": {"@type": "QuantitativeValue", "value": 17, "unitCode": "CMT"},
 "height": {"@type": "QuantitativeValue", "value": 25, "unitCode": "CMT"}}</script>
</head><body><nav class="breadcrumbs"><a href="/">Startseite</a> / <a href="/k">Küche</a> /
<a href="/k/w">Wasserkocher</a></nav><h1>Gastroback 42429 Design Advanced Pro</h1></body></html>"""


def test_ingestion_names_a_brand_title_from_its_breadcrumbs(tmp_path):
    """Over real HTTP on loopback: a product whose title is a brand and a model gets its kind and English
    alias from the page's breadcrumbs, with that provenance, and the recall finds it by that name."""
    from recall.engine import Recaller
    from scrapers.ingest import run_ingestion
    from scrapers.sources import parse_sources

    site = tmp_path / "site"
    site.mkdir()
    (site / "gastroback.html").write_text(PRODUCT_PAGE, encoding="utf-8")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    base = f"http://127.0.0.1:{server.server_address[1]}"
    (site / "sitemap.xml").write_text(
        f'<?xml version="1.0"?><urlset xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">'
        f"<url><loc>{base}/gastroback.html</loc></url></urlset>",
        encoding="utf-8",
    )
    sources = parse_sources(
        f'[defaults]\ndelay_s = 0\nmax_retries = 0\n[[stores]]\nname = "crumbs"\nbase_url = "{base}"\n'
        'sitemaps = ["{base_url}/sitemap.xml"]\n',
        origin="test",
    )
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        kb = KnowledgeBase.open(tmp_path / "crumbs.duckdb")
        kb.import_csv(REPO / "kb" / "data" / "seed_catalog.csv")
        with requests.Session() as session:
            report = run_ingestion(kb, sources, session=session)
    finally:
        server.shutdown()
        server.server_close()
    assert report.new == 1, report
    with kb.connect() as con:
        aliases = dict(con.execute("SELECT a.alias, o.name FROM object_aliases a JOIN objects o ON o.id = a.object_id").fetchall())
        events = [r[0] for r in con.execute("SELECT reason FROM page_events WHERE stage = 'naming'").fetchall()]
    assert aliases["electric kettle"] == "gastroback 42429 design advanced pro"
    assert any("breadcrumb: Wasserkocher" in e and "electric kettle" in e for e in events), events
    assert Recaller.from_db(tmp_path / "crumbs.duckdb").recall_text("an electric kettle").best.name.startswith(
        "gastroback"
    )
