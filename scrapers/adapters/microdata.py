"""schema.org Product in microdata (``itemscope itemtype=".../Product"`` with ``itemprop`` children).

The first Product item that is not itself a property of another item is the page's product; it is
turned into the same dict shape as JSON-LD and read by :func:`scrapers.adapters.jsonld.read_product`.
Nested items (``weight`` as a QuantitativeValue, ``additionalProperty`` PropertyValues) are kept;
nested Products (``isSimilarTo``) are other products and are ignored by the reader.

The ``opengraph`` adapter reads the product weight that Open Graph / catalog meta tags state.
"""

from __future__ import annotations

from typing import Any

from scrapers.adapters import Observation, adapter
from scrapers.adapters.jsonld import PRODUCT_TYPES, read_product
from scrapers.page import Page, text_content
from scrapers.quantities import parse_mass

__all__ = ["item_dict"]

_LIST_PROPS = {"additionalProperty"}


def _owner(el):
    parent = el.getparent()
    while parent is not None:
        if parent.get("itemscope") is not None:
            return parent
        parent = parent.getparent()
    return None


def _value(el) -> Any:
    if el.get("itemscope") is not None:
        return item_dict(el)
    for attr in ("content", "value"):
        if el.get(attr) is not None:
            return el.get(attr)
    if el.tag in ("a", "link"):
        return el.get("href")
    if el.tag in ("img", "source"):
        return el.get("src")
    if el.tag == "time" and el.get("datetime"):
        return el.get("datetime")
    return text_content(el)


def item_dict(item) -> dict:
    """A microdata item as a JSON-LD-shaped dict (``@type`` plus its properties)."""
    d: dict[str, Any] = {"@type": (item.get("itemtype") or "").strip().rsplit("/", 1)[-1]}
    for el in item.iterdescendants():
        if not isinstance(el.tag, str) or el.get("itemprop") is None or _owner(el) is not item:
            continue
        value = _value(el)
        for name in el.get("itemprop").split():
            if name in _LIST_PROPS:
                d.setdefault(name, []).append(value)
            else:
                d.setdefault(name, value)
    return d


@adapter("microdata", priority=20)
def microdata(page: Page) -> list[Observation]:
    """schema.org Product in microdata."""
    tree = page.tree
    if tree is None:
        return []
    for item in tree.xpath("//*[@itemscope][@itemtype]"):
        itemtype = (item.get("itemtype") or "").strip().rsplit("/", 1)[-1].lower()
        if itemtype in PRODUCT_TYPES and item.get("itemprop") is None:
            obs = read_product(item_dict(item), 1, page.decimal_comma)
            if _hidden_weight(item):
                for o in obs:
                    o.hidden = o.hidden or (o.feature == "mass" and o.raw.startswith("weight:"))
            return obs
    return []


def _hidden_weight(item) -> bool:
    """Whether ``item``'s ``weight`` is a ``<meta>`` field the page does not show (Shopware's buybox
    ``<meta itemprop="weight" content="6.5 kg">``, its postage weight), also as a QuantitativeValue whose
    ``value`` is one; a shown ``<span itemprop="weight">`` is not."""
    for el in item.iterdescendants():
        if isinstance(el.tag, str) and "weight" in (el.get("itemprop") or "").split() and _owner(el) is item:
            if el.get("itemscope") is None:
                return el.tag == "meta"
            values = [v for v in el.iterdescendants() if isinstance(v.tag, str) and v.get("itemprop") == "value"]
            return bool(values) and values[0].tag == "meta"
    return False


_OG_WEIGHTS = (("product:weight", False), ("product:shipping_weight", True), ("og:weight", False))


@adapter("opengraph", priority=25)
def opengraph(page: Page) -> list[Observation]:
    """Open Graph / Facebook catalog product meta: ``product:weight:value`` with ``:units`` (and the
    shipping weight, a package value). Shown nowhere on the page, the weight is a hidden field
    (``Observation.hidden``): shop systems fill it with the postage weight (PrestaShop's ``1.1 KG`` for a
    graphics card), so it is the product's only where a shown statement agrees."""
    tree = page.tree
    if tree is None or "weight:value" not in page.text:
        return []
    meta = {}
    for el in tree.xpath("//meta[@property][@content]"):
        meta.setdefault(el.get("property").strip().lower(), el.get("content").strip())
    obs = []
    for prefix, package in _OG_WEIGHTS:
        value, units = meta.get(f"{prefix}:value"), meta.get(f"{prefix}:units")
        if value and units:
            mass = parse_mass(f"{value} {units}", None, False)
            if mass is not None:
                # the product's weight only when a shown line agrees (Observation.hidden); the shipping one is a package's
                obs.append(Observation("mass", mass, package, rank=0, raw=f"{prefix}: {value} {units}", hidden=not package))
    return obs
