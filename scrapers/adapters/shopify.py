"""Shopify product JSON: ``/products/<handle>.json`` (``{"product": {...}}``) or ``.js`` (the product
object itself), also when a storefront page embeds it in a script.

Mass comes from the variants: ``grams`` (``0`` means unknown, not weightless), else ``weight`` with
``weight_unit`` (g, kg, lb, oz). The first variant with a known mass is the product's; variants that
differ are reported. Shopify has no dimension fields; the description (``body_html``) is read like a
spec table, so "Dimensions: 20 x 10 x 5 cm" there is found.
"""

from __future__ import annotations

from typing import Any

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import observations_from_pairs, pairs_from_lines
from scrapers.page import Page
from scrapers.quantities import mass_unit

__all__ = ["read_shopify_product"]


def _shopify_product(data: Any) -> dict | None:
    if isinstance(data, dict):
        inner = data.get("product")
        if isinstance(inner, dict) and isinstance(inner.get("variants"), list):
            return inner
        if isinstance(data.get("variants"), list) and ("handle" in data or "title" in data):
            return data
    return None


def _variant_mass(variant: dict) -> tuple[float | None, str]:
    grams = variant.get("grams")
    if isinstance(grams, (int, float)) and not isinstance(grams, bool) and grams != 0:  # < 0: refused later
        return float(grams), f"grams: {grams}"
    weight, unit = variant.get("weight"), variant.get("weight_unit")
    if isinstance(weight, str):
        try:
            weight = float(weight)
        except ValueError:
            weight = None
    if isinstance(weight, (int, float)) and not isinstance(weight, bool) and weight != 0:
        # the .js product format gives "weight" in grams with no unit
        factor = mass_unit(str(unit)) if unit else (1.0 if "grams" not in variant else None)
        if factor is not None:
            return round(weight * factor, 6), f"weight: {weight} {unit}"
    return None, ""


def read_shopify_product(product: dict, decimal_comma: bool | None) -> list[Observation]:
    """Observations of one Shopify product object."""
    obs: list[Observation] = []
    title = product.get("title")
    if isinstance(title, str) and title.strip():
        obs.append(Observation("name", title.strip(), rank=0, raw=title))
    variants = [v for v in product.get("variants") or [] if isinstance(v, dict)]
    masses = [(m, raw) for m, raw in map(_variant_mass, variants) if m is not None]
    if masses:
        mass, raw = masses[0]
        note = None
        if any(abs(m - mass) > 0.01 * mass for m, _ in masses[1:]):
            note = f"variants differ in mass ({', '.join(f'{m:g} g' for m, _ in masses[:5])}); took the first"
        obs.append(Observation("mass", mass, rank=0, raw=raw, note=note))
    elif variants and any("grams" in v for v in variants):
        obs.append(Observation("warning", "Shopify variants state grams: 0 (unknown mass)"))
    for variant in variants[:1]:
        barcode = variant.get("barcode")
        if isinstance(barcode, str) and barcode.strip().isdigit() and len(barcode.strip()) in (8, 12, 13, 14):
            obs.append(Observation("gtin", barcode.strip(), rank=0, raw=barcode))
    body = product.get("body_html") or product.get("description")
    if isinstance(body, str) and body.strip():
        sub = Page(f"<html><body>{body}</body></html>", "")
        for o in observations_from_pairs(pairs_from_lines(sub.lines), decimal_comma, rank=1):
            o.note = "from the product description" if o.note is None else o.note
            obs.append(o)
    return obs


@adapter("shopify", priority=30)
def shopify(page: Page) -> list[Observation]:
    """Shopify product JSON (``/products/<handle>.json``), served as JSON or embedded in a page."""
    if page.is_json:
        product = _shopify_product(page.json)
        return read_shopify_product(product, page.decimal_comma) if product else []
    if '"variants"' not in page.text:
        return []
    for payload in page.script_payloads:
        product = _shopify_product(payload)
        if product is not None:
            return read_shopify_product(product, page.decimal_comma)
    return []
