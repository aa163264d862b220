"""WooCommerce product pages.

The "Additional information" attributes table (``table.woocommerce-product-attributes`` or the older
``table.shop_attributes``): its weight row (``1.2 kg``) and dimensions row (``L × W × H unit``, e.g.
``20 × 10 × 5 cm``), plus any other row whose label the spec vocabulary knows. Variable products carry
a variations JSON (``form.variations_form[data-product_variations]``) with ``weight_html`` and
``dimensions_html`` per variation; it is read when the table states nothing (first variation, with a
note when variations differ).
"""

from __future__ import annotations

import html
import json

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import Pair, observations_from_pairs
from scrapers.labels import LabelInfo, classify_label
from scrapers.page import Page, text_content

__all__ = ["woocommerce"]

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
        found: list[list[Observation]] = []
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
            found.append(observations_from_pairs(vp, page.decimal_comma, rank=1))
        found = [f for f in found if f]
        if found:
            first = found[0]
            differ = any(
                sorted((o.feature, o.value) for o in f) != sorted((o.feature, o.value) for o in first)
                for f in found[1:]
            )
            for o in first:
                o.note = "variations differ; took the first" if differ else "from the variations JSON"
            obs.extend(first)
        break
    return obs
