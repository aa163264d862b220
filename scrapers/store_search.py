"""Reading a store's search answer: which product pages it lists, and where its next page is.

A store's ``search`` (see :mod:`scrapers.sources`) answers either

- **an HTML results page**: the product links are the ``url`` of every ``ItemList`` entry in its
  schema.org JSON-LD when it has one (stores that mark up their results say which links are results),
  else the links of the page's main content (``<main>``, or
  the body without its ``header``, ``nav``, ``footer`` and ``aside``) that stay on the store's host, pass
  the store's include/exclude patterns and are not search pages themselves; the next page is the
  ``rel="next"`` link (``<a>`` or ``<link>``). A page with no such links is a no-results page;
- **or JSON**: every ``url`` (or ``href``) string in it that names a page of the store, in document order
  (Shopify's ``/search/suggest.json`` ``resources.results.products[].url``, or a plain list of objects).

Pure functions over a body already fetched: no network here.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import urljoin, urlsplit

from kb.errors import ExtractionError
from scrapers.sources import StoreSource

__all__ = ["SearchPage", "parse_search_page"]

_SKIP = {"header", "nav", "footer", "aside", "script", "style", "form"}


@dataclass
class SearchPage:
    """The product page URLs one search answer lists (in its order, no repeats) and its next page."""

    product_urls: list[str] = field(default_factory=list)
    next_url: str | None = None


def _same_store(url: str, store: StoreSource, search_path: str) -> bool:
    parts = urlsplit(url)
    if parts.scheme not in ("http", "https") or parts.netloc != urlsplit(store.base_url).netloc:
        return False
    return parts.path != search_path and store.wants(url)


def _json_urls(data: Any) -> Iterator[str]:
    if isinstance(data, dict):
        for key, value in data.items():
            if key in ("url", "href") and isinstance(value, str):
                yield value
            else:
                yield from _json_urls(value)
    elif isinstance(data, list):
        for item in data:
            yield from _json_urls(item)


def _item_list_urls(root) -> list[str]:
    """The entries' URLs of the schema.org ItemLists in the page's JSON-LD (``url`` or ``item.url`` /
    ``item["@id"]`` of each ``itemListElement``); [] when there are none or the JSON is broken."""
    urls: list[str] = []
    for script in root.xpath('//script[@type="application/ld+json"]'):
        try:
            data = json.loads(script.text or "")
        except ValueError:
            continue
        stack = [data]
        while stack:
            node = stack.pop(0)
            if isinstance(node, list):
                stack.extend(node)
            elif isinstance(node, dict):
                if node.get("@type") == "ItemList":
                    for entry in node.get("itemListElement") or []:
                        item = entry.get("item") if isinstance(entry, dict) else None
                        found = (entry.get("url") if isinstance(entry, dict) else None) or (
                            (item.get("url") or item.get("@id")) if isinstance(item, dict) else item
                        )
                        if isinstance(found, str):
                            urls.append(found)
                else:
                    stack.extend(v for v in node.values() if isinstance(v, (dict, list)))
    return urls


def _content_links(root) -> Iterator[Any]:
    main = root.find(".//main")
    scope = main if main is not None else root.find(".//body")
    if scope is None:
        scope = root
    for el in scope.iter("a"):
        if not any(anc.tag in _SKIP for anc in el.iterancestors()) and el.get("rel") not in ("next", "prev"):
            yield el


def parse_search_page(body: bytes, url: str, content_type: str | None, store: StoreSource) -> SearchPage:
    """The product links and next page of one search answer fetched from ``url`` (see the module
    docstring). Raises :class:`~kb.errors.ExtractionError` when the body is neither HTML nor JSON."""
    search_path = urlsplit(url).path
    found: list[str] = []
    next_url = None
    text = body.decode("utf-8", errors="replace")
    if "json" in (content_type or "").lower() or text.lstrip()[:1] in ("{", "["):
        try:
            data = json.loads(text)
        except ValueError as err:
            raise ExtractionError(f"{url}: search answer is not valid JSON ({err})") from None
        candidates = [urljoin(url, u) for u in _json_urls(data)]
    else:
        import lxml.html

        try:
            root = lxml.html.document_fromstring(text)
        except Exception as err:  # noqa: BLE001 - lxml raises several kinds on garbage
            raise ExtractionError(f"{url}: search answer is not an HTML page ({err})") from None
        listed = _item_list_urls(root)
        links = listed or [a.get("href") for a in _content_links(root) if a.get("href")]
        candidates = [urljoin(url, href) for href in links]
        nexts = root.xpath('//a[@rel="next"]/@href | //link[@rel="next"]/@href')
        if nexts:
            next_url = urljoin(url, nexts[0])
    for cand in candidates:
        cand = cand.split("#", 1)[0]
        if cand not in found and _same_store(cand, store, search_path):
            found.append(cand)
    return SearchPage(found, next_url)
