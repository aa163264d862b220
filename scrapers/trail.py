"""A product page's category trail: its breadcrumbs and its JSON-LD ``category`` values.

Ingestion names a stored object's kind from its title first, and from these when the title names no
household noun the lexicon knows (:func:`kb.kinds.assign_kind`): a store's title is often a brand and a
model ("Gastroback 42429 Design Pro", "KitchenAid 5KEK1722"), while its breadcrumbs say "Küche >
Wasserkocher". Read from the already parsed :class:`~scrapers.page.Page`, so it costs no second parse.

* breadcrumbs: a JSON-LD ``BreadcrumbList`` (its items by ``position``), else the links of the page's
  first element whose ``id`` or ``class`` contains "breadcrumb" (its list items, else its text split on
  the usual separators);
* categories: the ``category`` of every JSON-LD ``Product`` (a string, split on "/", ">" and the like;
  a list; or a ``Thing`` with a ``name``).

Texts without a letter ("21828") and URLs are left out; at most :data:`MAX_ITEMS` of each, each cut to
:data:`MAX_CHARS`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from scrapers.page import Page, text_content

__all__ = ["MAX_CHARS", "MAX_ITEMS", "CategoryTrail", "category_trail"]

MAX_ITEMS = 12
MAX_CHARS = 120
#: JSON-LD nodes walked at most (a page's graph can be large; the trail is near the top).
_MAX_NODES = 5000
_SEPARATORS = re.compile(r"\s*(?:/|>|›|»|\||\\|→)\s*")
_LETTER = re.compile(r"[^\W\d_]")


@dataclass(frozen=True)
class CategoryTrail:
    breadcrumbs: tuple[str, ...] = ()
    categories: tuple[str, ...] = ()


def category_trail(page: Page) -> CategoryTrail:
    """The page's breadcrumbs and JSON-LD categories (see the module docstring); empty when none."""
    crumbs: list[str] = []
    categories: list[str] = []
    for node in _jsonld_nodes(page):
        types = node.get("@type")
        types = types if isinstance(types, list) else [types]
        if "BreadcrumbList" in types and not crumbs:
            crumbs = _list_items(node.get("itemListElement"))
        if "category" in node and any(t in ("Product", "ProductGroup", "IndividualProduct") for t in types):
            categories += _category_texts(node["category"])
    if not crumbs and not page.is_json:
        crumbs = _html_crumbs(page)
    return CategoryTrail(_clean(crumbs), _clean(categories))


def _jsonld_nodes(page: Page):
    """Every JSON object in the page's JSON-LD blocks (depth first, at most :data:`_MAX_NODES`)."""
    stack: list[Any] = [data for data, _ in page.jsonld_blocks if data is not None]
    seen = 0
    while stack and seen < _MAX_NODES:
        item = stack.pop()
        seen += 1
        if isinstance(item, dict):
            yield item
            stack.extend(v for v in item.values() if isinstance(v, (dict, list)))
        elif isinstance(item, list):
            stack.extend(reversed(item))


def _list_items(items: Any) -> list[str]:
    """Names of a BreadcrumbList's ``itemListElement`` entries, in ``position`` order."""
    if not isinstance(items, list):
        return []
    named = []
    for i, entry in enumerate(items):
        if not isinstance(entry, dict):
            continue
        name = entry.get("name")
        item = entry.get("item")
        if not isinstance(name, str) and isinstance(item, dict):
            name = item.get("name")
        position = entry.get("position")
        key = float(position) if isinstance(position, (int, float)) else float(i)
        if isinstance(name, str):
            named.append((key, i, name))
    return [name for _, _, name in sorted(named)]


def _category_texts(value: Any) -> list[str]:
    if isinstance(value, str):
        return [part for part in _SEPARATORS.split(value) if part] if not _is_url(value) else []
    if isinstance(value, dict):
        return _category_texts(value.get("name"))
    if isinstance(value, list):
        return [text for v in value[:MAX_ITEMS] for text in _category_texts(v)]
    return []


#: Elements whose class or id says "breadcrumb" in the cases pages write it (``breadcrumb``,
#: ``Breadcrumb``, ``BreadCrumb``, ``BREADCRUMB``), in document order. Testing the attributes and taking
#: their elements runs ~5x faster in libxml2 than a predicate on every element (``//*[...]``).
_CRUMB_WORDS = " or ".join(f"contains(., '{word}')" for word in ("readcrumb", "readCrumb", "READCRUMB"))
_CRUMB_PATH = f"//@class[{_CRUMB_WORDS}]/.. | //@id[{_CRUMB_WORDS}]/.."


def _html_crumbs(page: Page) -> list[str]:
    """The items of the first element whose id or class says "breadcrumb"."""
    tree = page.tree
    if tree is None:
        return []
    for el in tree.xpath(_CRUMB_PATH)[:20]:
        parts = [text_content(a) for a in el.xpath(".//a | .//li[not(.//a)]")]
        parts = [p for p in parts if p] or _SEPARATORS.split(text_content(el))
        parts = [p for p in parts if _LETTER.search(p)]
        if parts:
            return parts
    return []


def _is_url(text: str) -> bool:
    return text.lstrip().startswith(("/", "http:", "https:", "www."))


def _clean(texts: list[str]) -> tuple[str, ...]:
    out: list[str] = []
    for text in texts:
        text = " ".join(text.split())[:MAX_CHARS]
        if text and _LETTER.search(text) and not _is_url(text) and text not in out:
            out.append(text)
    return tuple(out[:MAX_ITEMS])
