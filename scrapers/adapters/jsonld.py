"""schema.org Product in JSON-LD.

Each ``<script type="application/ld+json">`` block is parsed on its own (HTML comments, CDATA and
trailing commas tolerated), so one malformed block is reported as a warning and does not hide the
others. Products are found at the top of a block, in arrays and in ``@graph``; a ProductGroup's
``hasVariant`` products are read when the group itself states no size. Products nested under
``isSimilarTo``/``isRelatedTo``/``isAccessoryOrSparePartFor`` are other products and are not read.

``weight``/``width``/``height``/``depth`` may be a QuantitativeValue (``value`` with ``unitCode``, a
UN/CEFACT code like CMT MMT MTR INH FOT GRM KGM LBR ONZ, or ``unitText``), a plain string (``"28 cm"``)
or a number with no unit (refused: a number without a unit is not a measurement). ``additionalProperty``
PropertyValues go through the spec-table label vocabulary.
"""

from __future__ import annotations

from typing import Any

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import Pair, observations_from_pairs
from scrapers.labels import classify_label
from scrapers.page import Page
from scrapers.quantities import length_unit, mass_unit, parse_dims, parse_length, parse_mass, parse_number

__all__ = ["product_nodes", "read_product"]

PRODUCT_TYPES = {"product", "productgroup", "productmodel", "individualproduct", "someproducts", "vehicle"}
_GTIN_KEYS = ("gtin13", "gtin", "gtin12", "gtin14", "gtin8", "ean")


def _types(node: dict) -> set[str]:
    t = node.get("@type")
    items = t if isinstance(t, list) else [t]
    return {str(x).rsplit("/", 1)[-1].lower() for x in items if x}


def product_nodes(data: Any, depth: int = 0) -> list[dict]:
    """Top-level product nodes of a JSON-LD document (arrays, ``@graph``, ``mainEntity``)."""
    if depth > 6:
        return []
    if isinstance(data, list):
        return [p for item in data for p in product_nodes(item, depth + 1)]
    if not isinstance(data, dict):
        return []
    if _types(data) & PRODUCT_TYPES:
        return [data]
    found = []
    for key in ("@graph", "mainEntity", "itemOffered", "about"):
        if key in data:
            found.extend(product_nodes(data[key], depth + 1))
    return found


def _text(value: Any) -> str | None:
    if isinstance(value, list):
        value = next((v for v in value if v), None)
    if isinstance(value, dict):
        value = value.get("name") or value.get("@value") or value.get("value")
    if isinstance(value, (str, int, float)) and not isinstance(value, bool):
        text = str(value).strip()
        return text or None
    return None


def quantity(value: Any, kind: str) -> tuple[float | None, str]:
    """A schema.org quantity (QuantitativeValue, string or list) in cm (kind "length") or g ("mass"),
    with the raw text; (None, reason) when absent or unreadable."""
    convert = length_unit if kind == "length" else mass_unit
    parse = parse_length if kind == "length" else parse_mass
    if isinstance(value, list):
        value = next((v for v in value if v not in (None, "", {})), None)
    if value is None or value == "":
        return None, ""
    if isinstance(value, dict):
        number = value.get("value")
        if number is None:
            number = value.get("maxValue")
        unit = value.get("unitCode") or value.get("unitText")
        raw = f"{number} {unit or ''}".strip()
        if number is None or number == "":
            return None, raw
        if isinstance(number, str):
            text = number if unit is None else f"{number} {unit}"
            return parse(text, None, None), raw
        if isinstance(number, bool) or not isinstance(number, (int, float)):
            return None, raw
        factor = convert(str(unit)) if unit else None
        if factor is None or number == 0:
            return None, raw
        return round(float(number) * factor, 6), raw  # a negative number stays negative, to be refused
    if isinstance(value, str):
        return parse(value, None, None), value
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return None, f"{value} (no unit)"
    return None, str(value)[:80]


def whole_size(value: Any, axis: str, order: int) -> Observation | None:
    """A single-dimension field (``width``) whose text states a whole size (``"5000 x 8 x 8 cm"``): the
    size, every extent of it (for the limits to refuse when one is absurd), rank 1 as a ``size`` field;
    None when the field holds one length."""
    if isinstance(value, list):
        value = next((v for v in value if v not in (None, "", {})), None)
    if isinstance(value, dict):
        unit = value.get("unitCode") or value.get("unitText")
        value = value.get("value") if unit is None else f"{value.get('value')} {unit}"
    if not isinstance(value, str):
        return None
    found = parse_dims(value, None, None)
    if not found or len(found[0].values_cm) < 2:
        return None
    note = f"JSON-LD {axis} states a whole size ({value[:60]!r}); read as the size"
    raw = f"{axis}: {value[:80]}"
    return Observation(
        "dims", found[0].values_cm, rank=1, order=order, raw=raw, note=note, roles=found[0].roles
    )


def read_product(node: dict, order: int, decimal_comma: bool | None) -> list[Observation]:
    """Observations of one product node (schema.org vocabulary, JSON-LD or microdata shaped alike)."""
    obs: list[Observation] = []
    name = _text(node.get("name"))
    if name:
        obs.append(Observation("name", name, rank=0, order=order, raw=name))
    for key in _GTIN_KEYS:
        gtin = _text(node.get(key))
        if gtin and parse_number(gtin.replace(" ", "")) is not None:
            obs.append(Observation("gtin", gtin.replace(" ", ""), rank=0, order=order, raw=gtin))
            break
    url = _text(node.get("url")) or _text(node.get("@id"))
    if url and url.startswith("http"):
        obs.append(Observation("canonical_url", url, rank=0, order=order, raw=url))
    material = _text(node.get("material"))
    if material:
        obs.append(Observation("material", material, rank=0, order=order, raw=material))
    axes = []
    for axis in ("depth", "width", "height"):
        if axis in node and (whole := whole_size(node.get(axis), axis, order)) is not None:
            obs.append(whole)  # "width": "5000 x 8 x 8 cm": the whole size, never its last figure alone
        elif axis in node:
            value, raw = quantity(node.get(axis), "length")
            if value is not None:
                axes.append((value, f"{axis}: {raw}", axis))
            elif raw:
                obs.append(
                    Observation("warning", f"JSON-LD {axis} {raw!r} unreadable; not used", order=order)
                )
    if len(axes) >= 2:
        obs.append(
            Observation(
                "dims",
                tuple(v for v, _, _ in axes),
                rank=0,
                order=order,
                raw="; ".join(r for _, r, _ in axes),
                roles=tuple(a for _, _, a in axes),
            )
        )
    else:
        size = _text(node.get("size")) if isinstance(node.get("size"), str) else None
        found = parse_dims(size, None, decimal_comma) if size else []
        if found:  # "size": "30 x 20 x 10 cm" (schema.org's size is free text; a clothing size is no dims)
            obs.append(
                Observation(
                    "dims", found[0].values_cm, rank=1, order=order, raw=f"size: {size[:80]}",
                    roles=found[0].roles,
                )
            )  # fmt: skip
        elif len(axes) == 1:  # a partial size: the one extent stated, one rank weaker
            obs.append(
                Observation(
                    "dims", (axes[0][0],), rank=2, order=order, raw=axes[0][1], roles=(axes[0][2],)
                )
            )  # fmt: skip
    if "weight" in node:
        value, raw = quantity(node.get("weight"), "mass")
        if value is not None:
            obs.append(Observation("mass", value, rank=0, order=order, raw=f"weight: {raw}"))
        elif raw:
            obs.append(Observation("warning", f"JSON-LD weight {raw!r} unreadable; not used", order=order))
    props = node.get("additionalProperty")
    if isinstance(props, dict):
        props = [props]
    if isinstance(props, list):
        pairs = []
        for i, prop in enumerate(props):
            if not isinstance(prop, dict):
                continue
            label, value = _text(prop.get("name")), prop.get("value")
            unit = prop.get("unitText") or prop.get("unitCode") or ""
            info = classify_label(label) if label else None
            if info is not None and isinstance(value, (str, int, float)) and not isinstance(value, bool):
                pairs.append(Pair(label, f"{value} {unit}".strip(), info, order=order * 1000 + i))
        for o in observations_from_pairs(pairs, decimal_comma, rank=0):
            o.order = order
            obs.append(o)
    return obs


@adapter("jsonld", priority=10)
def jsonld(page: Page) -> list[Observation]:
    """schema.org Product in JSON-LD blocks (each block parsed on its own)."""
    obs: list[Observation] = []
    order = 0
    for i, (data, error) in enumerate(page.jsonld_blocks):
        if error:
            obs.append(Observation("warning", f"JSON-LD block {i + 1}: {error}"))
            continue
        for node in product_nodes(data):
            order += 1
            if order > 1:
                # the page's product is its first Product node; later ones are other products (lists, carousels)
                continue
            own = read_product(node, order, page.decimal_comma)
            if not any(o.feature in ("dims", "mass") for o in own):
                variants = node.get("hasVariant")
                variants = (
                    variants
                    if isinstance(variants, list)
                    else [variants]
                    if isinstance(variants, dict)
                    else []
                )
                for variant in variants[:1]:
                    if isinstance(variant, dict):
                        for o in read_product(variant, order, page.decimal_comma):
                            if o.feature in ("dims", "mass"):
                                o.note = "from the first variant of a product group"
                                own.append(o)
            obs.extend(own)
    return obs
