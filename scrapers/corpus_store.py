"""A store on loopback that sells the real-page corpus: captured product pages behind a small store's search.

The search page is written here; the product pages are the corpus's own bytes (:mod:`scrapers.corpus`),
each served at its original address's path on 127.0.0.1 (``/ViewSonic-VX3276-4K-MHD-.../dp/B07SRDX1Z1``),
so that an extractor reading the URL sees what it would see at the store (a page saved without its
address is at ``/page/<id>``).

``/search?q=<words>`` is a word-overlap search over what a store's own search indexes of a product
(:func:`index_texts`): its title, its brand, its category trail (breadcrumbs, JSON-LD ``category``) and its
description text (JSON-LD and microdata ``description``, the page's meta description and keywords), each
in the page's own language, as the page states them. A page is found when one query word (lower case,
plural ``s`` dropped: :func:`scrapers.demo_store.search.query_words`) is one of its indexed words; results
are ordered by relevance (:func:`relevance`: each query word the page holds counts its rarity among the
store's products, ``log(1 + N / n)``, times :data:`FIELD_WEIGHTS` of the best field holding it: a word of
the name or brand counts double), then the shorter title first (more of it is what was asked for), then by
title, :data:`RESULTS_SHOWN` to a results page (``&page=<n>``, with a ``rel="next"`` link while more
follow). Only product pages whose labels state a size or a mass are sold (a description can state nothing
of the others).

>>> with CorpusStore(load_corpus()) as store:                              # doctest: +SKIP
...     requests.get(store.base_url + "/search?q=walkie+talkie").text
"""

from __future__ import annotations

import html
import math
import re
import threading
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs, quote, urlsplit

from scrapers.corpus import CorpusPage, load_corpus
from scrapers.demo_store.search import query_words

__all__ = ["FIELD_WEIGHTS", "CorpusStore", "StoreItem", "index_texts", "items_of", "relevance", "search", "sold"]

#: Results listed on the search page (a lookup reads its store's ``search_results`` first ones).
RESULTS_SHOWN = 10
#: What a query word found in each indexed field of a product weighs (times its rarity): a store ranks a
#: product whose name or brand holds the word above one whose trail or description text mentions it.
FIELD_WEIGHTS = {"title": 2.0, "brand": 2.0, "trail": 1.0, "text": 1.0}
#: Characters of one description text indexed (a long description's first part).
TEXT_CHARS = 3000


@dataclass(frozen=True)
class StoreItem:
    """One corpus page on sale: the page, the path it is served at, its title's words and every indexed
    word with the weight of the best field holding it (:data:`FIELD_WEIGHTS`)."""

    page: CorpusPage
    path: str
    words: frozenset[str]
    indexed: dict[str, float] = field(default_factory=dict, compare=False)

    @property
    def title(self) -> str:
        return self.page.truth["title"]


def sold(page: CorpusPage) -> bool:
    """Whether the store sells ``page``: a product page whose labels state a size or a mass."""
    truth = page.truth or {}
    return truth.get("is_product_page") is not False and bool(truth.get("dims_cm") or truth.get("mass_g"))


def _path_of(page: CorpusPage) -> str:
    parts = urlsplit(page.url or "")
    path = parts.path if parts.netloc and len(parts.path) > 1 else ""
    return quote(path, safe="/-._~%!$&'()*+,;=:@") if path else f"/page/{page.id}"


def items_of(pages: Iterable[CorpusPage]) -> list[StoreItem]:
    """The pages the store sells (:func:`sold`), each at its own path (a second page on a path already
    taken goes to ``/page/<id>``)."""
    items: list[StoreItem] = []
    taken: set[str] = set()
    for page in pages:
        if not sold(page):
            continue
        path = _path_of(page)
        if path in taken:
            path = f"/page/{page.id}"
        taken.add(path)
        title = frozenset(query_words(page.truth["title"]))
        indexed: dict[str, float] = {}
        for name, texts in index_texts(page).items():
            for word in query_words(" ".join(texts)):
                indexed[word] = max(indexed.get(word, 0.0), FIELD_WEIGHTS[name])
        indexed.update({w: FIELD_WEIGHTS["title"] for w in title})
        items.append(StoreItem(page, path, title, indexed))
    return items


def index_texts(page: CorpusPage) -> dict[str, list[str]]:
    """What a store's search indexes of ``page``, by field (:data:`FIELD_WEIGHTS`), as the page states it:
    ``title`` (the labelled title), ``brand`` (JSON-LD and microdata ``brand``, ``product:brand``),
    ``trail`` (:func:`scrapers.trail.category_trail`) and ``text`` (JSON-LD and microdata
    ``description``, meta description, ``og:description`` and keywords; tags dropped, each cut to
    :data:`TEXT_CHARS`)."""
    from scrapers.page import Page, text_content
    from scrapers.trail import category_trail

    doc = Page(page.path.read_bytes(), page.url or "http://127.0.0.1/")
    brand: list[str] = []
    text: list[str] = []
    for node in _product_nodes([data for data, _ in doc.jsonld_blocks if data is not None]):
        value = node.get("brand")
        value = value.get("name") if isinstance(value, dict) else value
        brand += [value] if isinstance(value, str) else []
        text += [node["description"]] if isinstance(node.get("description"), str) else []
    tree = doc.tree
    if tree is not None:
        brand += tree.xpath('//meta[@property="product:brand"]/@content')
        brand += [el.get("content") or text_content(el) for el in tree.xpath('//*[@itemprop="brand"]')]
        text += tree.xpath('//meta[@name="description" or @property="og:description" or @name="keywords"]/@content')
        text += [el.get("content") or text_content(el) for el in tree.xpath('//*[@itemprop="description"]')]
    trail = category_trail(doc)
    return {"title": [page.truth["title"]], "brand": [b for b in brand if b],
            "trail": [*trail.breadcrumbs, *trail.categories],
            "text": [re.sub(r"<[^>]+>", " ", t)[:TEXT_CHARS] for t in text if t]}  # fmt: skip


def _product_nodes(data, depth: int = 0) -> Iterable[dict]:
    """The JSON-LD nodes typed Product (or ProductGroup) anywhere in ``data``."""
    if depth > 12:
        return
    if isinstance(data, list):
        for node in data:
            yield from _product_nodes(node, depth + 1)
    elif isinstance(data, dict):
        types = data.get("@type")
        types = types if isinstance(types, list) else [types]
        if any(t in ("Product", "ProductGroup", "IndividualProduct") for t in types):
            yield data
        for value in data.values():
            if isinstance(value, (dict, list)):
                yield from _product_nodes(value, depth + 1)


def relevance(items: Sequence[StoreItem], words: set[str]) -> dict[int, float]:
    """Each found item's relevance to the query ``words`` (by its index in ``items``): the sum over the
    query words it holds of the word's rarity among the items, ``log(1 + N / n)``, times the weight of
    the best field holding it."""
    df = Counter(w for it in items for w in words if w in it.indexed)
    idf = {w: math.log(1.0 + len(items) / n) for w, n in df.items()}
    scores: dict[int, float] = {}
    for i, it in enumerate(items):
        held = [w for w in words if w in it.indexed]
        if held:
            scores[i] = round(sum(idf[w] * it.indexed[w] for w in held), 9)
    return scores


def search(items: Sequence[StoreItem], query: str) -> list[StoreItem]:
    """The items ``query`` finds, best first (module docstring); no words find nothing."""
    scores = relevance(items, set(query_words(query)))
    order = sorted(scores, key=lambda i: (-scores[i], len(items[i].words), items[i].title))
    return [items[i] for i in order]


def _results_page(query: str, hits: Sequence[StoreItem], page: int = 1) -> bytes:
    e = html.escape
    shown = hits[(page - 1) * RESULTS_SHOWN : page * RESULTS_SHOWN]
    cards = "".join(f'<li class="product"><a href="{e(it.path)}">{e(it.title)}</a></li>\n'
                    for it in shown)  # fmt: skip
    more = len(hits) > page * RESULTS_SHOWN
    nav = f'<nav><a rel="next" href="/search?q={quote(query)}&amp;page={page + 1}">Next</a></nav>' if more else ""
    main = (f'<h1>Search results for “{e(query)}”</h1>\n<p>{len(hits)} results</p>\n<ul class="results">\n{cards}</ul>{nav}'
            if shown else f'<h1>No results for “{e(query)}”</h1>')  # fmt: skip
    return (f'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>Search: {e(query)}</title>'
            f'<meta name="robots" content="noindex"></head><body><main>{main}</main></body></html>').encode()  # fmt: skip


class CorpusStore:
    """The store, served from a background thread on ``host`` (``port=0``: a free port); ``base_url`` once
    started. ``log`` holds every path requested."""

    def __init__(self, pages: Iterable[CorpusPage] | None = None, host: str = "127.0.0.1", port: int = 0):
        self.items = items_of(load_corpus() if pages is None else pages)
        self.by_path = {it.path: it for it in self.items}
        self.host, self.requested_port = host, port
        self.log: list[str] = []
        self._server: ThreadingHTTPServer | None = None

    @property
    def base_url(self) -> str:
        assert self._server is not None, "the store is not started"
        return f"http://{self.host}:{self._server.server_address[1]}"

    def url_of(self, page_id: str) -> str:
        """The address the store serves the page ``page_id`` at."""
        return self.base_url + next(it.path for it in self.items if it.page.id == page_id)

    def sources_toml(self, search_results: int = 3) -> str:
        """A sources file that reads this store's search (delay 0: loopback)."""
        return (f'[[stores]]\nname = "corpus"\nbase_url = "{self.base_url}"\n'
                f'search = "{{base_url}}/search?q={{query}}"\ndelay_s = 0\nsearch_results = {search_results}\n')  # fmt: skip

    def _handler(self):
        store = self

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, *args) -> None:
                pass

            def do_GET(self) -> None:  # noqa: N802
                parts = urlsplit(self.path)
                store.log.append(self.path)
                if parts.path == "/robots.txt":
                    body, ctype = b"User-agent: *\nAllow: /\n", "text/plain"
                elif parts.path == "/search":
                    args = parse_qs(parts.query)
                    query, page = args.get("q", [""])[0], args.get("page", ["1"])[0]
                    page = int(page) if page.isdigit() and int(page) > 0 else 1
                    body = _results_page(query, search(store.items, query), page)
                    ctype = "text/html; charset=utf-8"
                elif parts.path in store.by_path:
                    body, ctype = store.by_path[parts.path].page.path.read_bytes(), "text/html; charset=utf-8"
                else:
                    self.send_error(404)
                    return
                self.send_response(200)
                self.send_header("Content-Type", ctype)
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

        return Handler

    def __enter__(self) -> CorpusStore:
        self._server = ThreadingHTTPServer((self.host, self.requested_port), self._handler())
        threading.Thread(target=self._server.serve_forever, daemon=True, name="corpus-store").start()
        return self

    def __exit__(self, *exc) -> None:
        assert self._server is not None
        self._server.shutdown()
        self._server.server_close()
        self._server = None
