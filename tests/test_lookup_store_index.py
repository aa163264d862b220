"""What the loopback corpus store's search indexes (scrapers.corpus_store, issue 22): as a real store's search
does, a product's title, brand, category trail and description text, in the page's own language, so that
a product whose title shares no word with a person's description ("Crusher ANC 2" for Skullcandy
headphones, "Qualità Oro" for Lavazza coffee) is found by its brand or description; a rarer word counts
more, a word of the name or brand double. Pages written here, served on 127.0.0.1."""

from __future__ import annotations

import json

import pytest
import requests

from scrapers.corpus import CorpusPage
from scrapers.corpus_store import FIELD_WEIGHTS, CorpusStore, index_texts, items_of, search


def _page(tmp_path, pid: str, title: str, *, brand=None, crumbs=(), description=None, meta=None, lang="en"):
    product = {"@context": "https://schema.org", "@type": "Product", "name": title}
    if brand:
        product["brand"] = {"@type": "Brand", "name": brand}
    if description:
        product["description"] = description
    blocks = [product]
    if crumbs:
        blocks.append({"@type": "BreadcrumbList", "itemListElement": [
            {"@type": "ListItem", "position": i + 1, "name": c} for i, c in enumerate(crumbs)]})  # fmt: skip
    ld = "".join(f'<script type="application/ld+json">{json.dumps(b)}</script>' for b in blocks)
    head = f'<meta name="description" content="{meta}">' if meta else ""
    path = tmp_path / f"{pid}.html"
    path.write_text(f'<!doctype html><html lang="{lang}"><head><title>{title}</title>{head}{ld}</head>'
                    f"<body><h1>{title}</h1><p>Weight: 300 g</p></body></html>", encoding="utf-8")  # fmt: skip
    truth = {"title": title, "mass_g": 300.0, "is_product_page": True}
    return CorpusPage(pid, path, f"https://{pid}.example/p/{pid}", pid, lang, {}, truth)


@pytest.fixture
def pages(tmp_path):
    return [
        _page(tmp_path, "crusher", "Crusher ANC 2", brand="Skullcandy", crumbs=("Audio", "Headphones"),
              description="<p>Noise cancelling headphones with adjustable bass.</p>"),
        _page(tmp_path, "oro", "Qualità Oro - Perfect Symphony, 250g Dose", brand="Lavazza", lang="de",
              crumbs=("Kaffee", "Gemahlener Kaffee"), meta="Lavazza Qualità Oro, ein Kaffee für Kenner."),
        _page(tmp_path, "mug", "Coffee mug"),
        _page(tmp_path, "table", "Coffee table, oak"),
        _page(tmp_path, "grinder", "Coffee grinder, steel burrs"),
        _page(tmp_path, "kettle", "Enamel kettle for the stove, 2 L"),
        _page(tmp_path, "pot", "Pot", description="A kettle-sized enamel pot: a kettle for soup"),
    ]  # fmt: skip


def test_the_index_holds_title_brand_trail_and_description_text_as_the_page_states_them(pages):
    crusher, oro = index_texts(pages[0]), index_texts(pages[1])
    assert crusher["title"] == ["Crusher ANC 2"] and crusher["brand"] == ["Skullcandy"]
    assert crusher["trail"] == ["Audio", "Headphones"]
    assert any("Noise cancelling headphones" in t and "<p>" not in t for t in crusher["text"])  # tags dropped
    assert oro["brand"] == ["Lavazza"] and "Gemahlener Kaffee" in oro["trail"]  # in the page's language
    assert any("ein Kaffee" in t for t in oro["text"])
    assert index_texts(pages[2]) == {"title": ["Coffee mug"], "brand": [], "trail": [], "text": []}


def test_a_product_is_found_by_its_brand_or_description_when_its_title_shares_no_word(pages):
    items = items_of(pages)
    assert [it.page.id for it in search(items, "skullcandy headphone")] == ["crusher"]
    assert search(items, "gemahlener")[0].page.id == "oro"  # a trail word, as the page writes it
    assert search(items, "zzzz") == [] and search(items, "") == []


def test_a_rare_word_counts_more_than_a_common_one(pages):
    # "lavazza": one page (its brand); "coffee": three titles. The rarer word's page comes first, though
    # three pages hold "coffee" in their title and the Lavazza page holds it nowhere
    hits = search(items_of(pages), "lavazza ground coffee")
    assert hits[0].page.id == "oro" and {h.page.id for h in hits[1:]} == {"mug", "table", "grinder"}


def test_a_word_of_the_name_counts_double_a_word_of_the_description(pages):
    assert FIELD_WEIGHTS["title"] == FIELD_WEIGHTS["brand"] == 2 * FIELD_WEIGHTS["text"]
    # the pot's title is the shorter (which would win a tie); the kettle's title holds the word
    assert [h.page.id for h in search(items_of(pages), "kettle")] == ["kettle", "pot"]


def test_the_store_serves_the_ranked_results(pages):
    with CorpusStore(pages) as store:
        body = requests.get(store.base_url + "/search?q=skullcandy", timeout=5).text
        assert f'href="{store.url_of("crusher")}"'.replace(store.base_url, "") in body
        assert "Qualità" not in body
