"""The demo store's search: which products a query finds, and the results pages in the store's own markup.

``/search?q=<words>&page=<n>`` answers an HTML results page the way storefronts write them: a heading with
the query, a count, product cards (title link, price, a thumbnail line), ``rel="prev"``/``rel="next"``
pagination links (:data:`PAGE_SIZE` results a page), and a no-results page that suggests other searches.
``/search.json?q=<words>`` answers the same results as JSON (Shopify's ``/search/suggest.json`` shape:
``resources.results.products[]`` with ``title``, ``handle``, ``url``).

A product is found when every query word (lower case, plural ``s`` dropped) is one of its words (title,
handle, material as the page says it, and its search keywords); results are ordered by how many query words
the title itself holds, then by title.
"""

from __future__ import annotations

import html
import json
import re
from collections.abc import Iterable
from urllib.parse import quote_plus

from scrapers.demo_store.page_parts import STORE_NAME, furnished_page, price_text
from scrapers.demo_store.products import DemoProduct

__all__ = ["PAGE_SIZE", "find", "query_words", "render_results", "render_results_json"]

#: Results per page of the HTML results.
PAGE_SIZE = 4
_WORD = re.compile(r"[^\W_]+")
_E = html.escape


def query_words(text: str) -> list[str]:
    """Lower-case words of ``text``, a plural ``s`` dropped ("teapots" finds "teapot")."""
    words = []
    for word in _WORD.findall(text.lower()):
        if len(word) > 3 and word.endswith("s") and not word.endswith("ss"):
            word = word[:-1]
        words.append(word)
    return words


def _words_of(prod: DemoProduct) -> set[str]:
    text = " ".join([prod.title, prod.handle.replace("-", " "), prod.material_text or "",
                     str(prod.extra.get("keywords", ""))])  # fmt: skip
    return set(query_words(text))


def find(products: Iterable[DemoProduct], query: str) -> list[DemoProduct]:
    """The products ``query`` finds, best first (see the module docstring); no words find nothing."""
    words = query_words(query)
    if not words:
        return []
    hits = [p for p in products if set(words) <= _words_of(p)]
    return sorted(hits, key=lambda p: (-len(set(words) & set(query_words(p.title))), p.title))


def _link(query: str, page: int) -> str:
    return f"/search?q={quote_plus(query)}&amp;page={page}"


def render_results(hits: list[DemoProduct], query: str, page: int, base: str) -> str:
    """One HTML results page (``page`` from 1); past the last page, or no hits, the no-results page."""
    pages = max(1, -(-len(hits) // PAGE_SIZE))
    shown = hits[(page - 1) * PAGE_SIZE : page * PAGE_SIZE] if page >= 1 else []
    canonical = f"{base}/search?q={quote_plus(query)}"
    if not shown:
        main = (
            f'<h1 class="search-title">No results for “{_E(query)}”</h1>\n'
            '<p class="no-results">Check the spelling or try fewer words. Popular searches: '
            '<a href="/search?q=mug">mug</a>, <a href="/search?q=board">board</a>.</p>'
        )
        return furnished_page(f"Search: {query}", "en", canonical, '<meta name="robots" content="noindex">\n', main)
    cards = "".join(
        f'<li class="product-card"><a class="product-card__link" href="{_E(p.path)}">{_E(p.title)}</a> '
        f'<span class="price">€{price_text(p)}</span> '
        f'<span class="product-card__note">{_E(p.material_text or "")}</span></li>\n'
        for p in shown
    )
    nav = []
    if page > 1:
        nav.append(f'<a rel="prev" href="{_link(query, page - 1)}">Previous</a>')
    nav.append(f'<span class="page-current">Page {page} of {pages}</span>')
    if page < pages:
        nav.append(f'<a rel="next" href="{_link(query, page + 1)}">Next</a>')
    main = (
        f'<h1 class="search-title">Search results for “{_E(query)}”</h1>\n'
        f'<p class="results-count">{len(hits)} result{"s" if len(hits) != 1 else ""}</p>\n'
        f'<ul class="search-results">\n{cards}</ul>\n<nav class="pagination">{" ".join(nav)}</nav>'
    )
    head = '<meta name="robots" content="noindex">\n'
    return furnished_page(f"Search: {query} | page {page}", "en", canonical, head, main)


def render_results_json(hits: list[DemoProduct], query: str, base: str) -> str:
    """The results as Shopify's search suggestions JSON (every hit, no pagination)."""
    products = [
        {"title": p.title, "handle": p.handle, "url": base + p.path, "price": price_text(p), "vendor": STORE_NAME}
        for p in hits
    ]
    return json.dumps({"resources": {"results": {"products": products}}, "query": query}, ensure_ascii=False)
