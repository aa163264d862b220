"""WooCommerce product pages.

The "Additional information" attributes table (``table.woocommerce-product-attributes`` or the older
``table.shop_attributes``): its weight row (``1.2 kg``) and dimensions row (``L × W × H unit``, e.g.
``20 × 10 × 5 cm``), plus any other row whose label the spec vocabulary knows. Variable products carry
a variations JSON (``form.variations_form[data-product_variations]``) with ``weight_html`` and
``dimensions_html`` per variation; it is read when the table states nothing. When the variations'
values differ, the product's are the selected variation's (the options the form preselects, WooCommerce's
default attributes); with none selected each is a variant's value, never the product's (a seed shop's
``500g``, ``1kg``, ... ``25kg`` bags, "Choose an option"), the rule of the selected size in
``spec_table.selected_variant``.
"""

from __future__ import annotations

import html
import json

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import Pair, observations_from_pairs
from scrapers.labels import LabelInfo, classify_label
from scrapers.page import Page, text_content

__all__ = ["woocommerce"]

#: Variations listed as variants' values at most (a store may sell dozens).
MAX_VARIATIONS = 12

_TABLES = (
    "//table[contains(concat(' ', normalize-space(@class), ' '), ' woocommerce-product-attributes ')"
    " or contains(concat(' ', normalize-space(@class), ' '), ' shop_attributes ')]"
)


def _row_info(row_class: str, label: str) -> LabelInfo | None:
    if "--weight" in row_class or "weight" == label.strip().lower():
        return LabelInfo("weight")
    if "--dimensions" in row_class:
        return LabelInfo("dimensions")
    return classify_label(label)


@adapter("woocommerce", priority=40)
def woocommerce(page: Page) -> list[Observation]:
    """WooCommerce attributes table (weight, L × W × H) and variations JSON."""
    tree = page.tree
    if tree is None or ("woocommerce" not in page.text and "shop_attributes" not in page.text):
        return []
    pairs: list[Pair] = []
    for t, table in enumerate(tree.xpath(_TABLES)):
        for r, row in enumerate(table.xpath(".//tr")):
            th, td = row.xpath("./th"), row.xpath("./td")
            if not th or not td:
                continue
            label = text_content(th[0])
            value = text_content(td[0])
            info = _row_info(row.get("class") or "", label)
            if info is not None and value:
                pairs.append(Pair(label, value, info, order=t * 1000 + r))
    obs = observations_from_pairs(pairs, page.decimal_comma, rank=0)
    if any(o.feature in ("dims", "mass") for o in obs):
        return obs
    for form in tree.xpath("//form[@data-product_variations]"):
        try:
            variations = json.loads(form.get("data-product_variations") or "")
        except ValueError:
            obs.append(Observation("warning", "WooCommerce variations JSON is malformed"))
            continue
        if not isinstance(variations, list):
            continue
        found: list[tuple[dict, list[Observation]]] = []
        for v in variations:
            if not isinstance(v, dict):
                continue
            vp = []
            for key, info in (
                ("weight_html", LabelInfo("weight")),
                ("dimensions_html", LabelInfo("dimensions")),
            ):
                text = v.get(key)
                if isinstance(text, str) and text.strip() and "n/a" not in text.lower():
                    vp.append(Pair(key, html.unescape(text), info))
            found.append((v, observations_from_pairs(vp, page.decimal_comma, rank=1)))
        found = [(v, f) for v, f in found if f]
        if found:
            obs.extend(_variation_values(form, found))
        break
    return obs


def _selected_options(form) -> dict[str, str]:
    """The option each of the form's pickers preselects (``attribute_pa_size`` -> ``50-x-70``)."""
    out = {}
    for select in form.xpath(".//select[@name]"):
        chosen = select.xpath(".//option[@selected]/@value")
        if chosen and chosen[0].strip():
            out[select.get("name")] = chosen[0].strip()
    return out


def _selected(variation: dict, options: dict[str, str]) -> bool:
    """Whether the form's preselected options pick ``variation`` (an empty attribute means "any")."""
    attributes = variation.get("attributes")
    if not isinstance(attributes, dict) or not attributes or not options:
        return False
    return all(not v or options.get(k) == str(v) for k, v in attributes.items()) and any(
        options.get(k) == str(v) for k, v in attributes.items() if v
    )


def _variation_values(form, found: list[tuple[dict, list[Observation]]]) -> list[Observation]:
    """The product's values among the variations' (see the module doc): all alike, the first's; else the
    selected variation's; else every variation's value as a variant's."""
    def key(obs: list[Observation]) -> list:
        return sorted((o.feature, o.value) for o in obs)

    first = found[0][1]
    if all(key(f) == key(first) for _, f in found[1:]):
        for o in first:
            o.note = "from the variations JSON"
        return first
    options = _selected_options(form)
    picked = next((f for v, f in found if _selected(v, options)), None)
    if picked is not None:
        for o in picked:
            o.note = "the selected variation's (the variations differ)"
        return picked
    out = []
    for _, f in found[:MAX_VARIATIONS]:
        for o in f:
            o.role, o.note = "variant", "one variation's; the variations differ and none is selected"
            out.append(o)
    return out
