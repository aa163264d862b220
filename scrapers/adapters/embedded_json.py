"""The page's embedded state: product data that stores ship inside script tags (JSON or JavaScript object
literals, read by :attr:`scrapers.page.Page.script_payloads`), for values no visible table states.

Label/value entries (``{"title": "Overall Weight", "value": "8", "unit_string": "lb."}``, tabs rendered by
JavaScript), ``"Width: 12\\""`` strings, and measurement keys of the product's own state object
(``"itemWeight": "1.2 kg"``, ``"width": {"value": 30, "unit": "cm"}``) become the same label/value pairs the
spec tables give (:func:`scrapers.adapters.spec_table.observations_from_pairs`). Objects named like another
product (a recommendation in the state) are not read.
"""

from __future__ import annotations

import re
from dataclasses import replace
from typing import Any

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import observations_from_pairs
from scrapers.labels import classify_label
from scrapers.page import Page
from scrapers.spec_pairs import CODE, DIGIT, Pair, has_unit, split_inline

__all__ = ["NAME_MATCH", "embedded_json"]

_LABEL_KEYS = ("title", "name", "label", "key", "attributeName", "attribute", "displayName", "property")
#: Inline markup inside a state string (``"<B>Weight:</B> 8.5 Pounds"``, a store's bullet list): read as text.
_INLINE_TAG = re.compile(r"</?(?:b|strong|i|em|u|span|br|p|li|small)\b[^<>]{0,40}>", re.IGNORECASE)
_UNIT_KEYS = ("unit_string", "unit", "unitText", "unitCode", "units", "uom")
_MAX_NODES = 200_000


_CAMEL = re.compile(r"(?<=[a-z])(?=[A-Z])|[_\-.]+")
_NAME_KEYS = ("name", "title", "productName", "product_name", "displayName")
_TOKEN = re.compile(r"[^\W\d_]{3,}")
#: Share of a state object's name words that must appear in the page title for its keyed values to count
#: as the product's (page state also holds recommended and recently viewed products).
NAME_MATCH = 0.6


def _key_label(key: str) -> str:
    """A JSON key as label words: ``itemWeight`` -> ``item Weight``, ``product_width`` -> ``product width``."""
    return _CAMEL.sub(" ", key).strip()


def _names_product(name: str, title_words: frozenset[str]) -> bool:
    words = [w.lower() for w in _TOKEN.findall(name)]
    return bool(words) and sum(w in title_words for w in words) >= NAME_MATCH * len(words)


def _text_of(x: Any) -> str | None:
    """A label or value as text: a string, or the name of an object naming it (``{"name": "Boyut"}``)."""
    if isinstance(x, str):
        return x
    if isinstance(x, dict):
        return next((x[k] for k in ("name", "value", "text", "label", "displayName") if isinstance(x.get(k), str)), None)
    return None


#: Keys holding a label's value in a state object (``{"name": "Weight", "displayValue": "2 kg"}``,
#: ``{"label": "Width", "values": ["30 cm"]}``), in order of preference.
_VALUE_KEYS = ("value", "displayValue", "formattedValue", "valueText", "attributeValue", "values")


def _value_of(node: dict) -> Any:
    """The value of a label/value entry: the first value key present; a list only when it holds one value
    (several are variants' or a list of options, not the product's)."""
    for k in _VALUE_KEYS:
        v = node.get(k)
        if isinstance(v, list):
            v = v[0] if len(v) == 1 else None
        if v is not None:
            return v
    return None


def _keyed_value(node: dict, key: str, value: Any) -> str | None:
    """The value text of a measurement key: a string as it is, a number with its unit from a sibling key
    (``weightUnit``, ``unit``) or a ``{"value": 1.2, "unit": "kg"}`` object; None without a unit."""
    if isinstance(value, dict):
        inner = value.get("value", value.get("amount"))
        unit = next((value[k] for k in _UNIT_KEYS if isinstance(value.get(k), str)), None)
        return f"{inner} {unit}" if isinstance(inner, (int, float, str)) and unit else None
    if isinstance(value, str) and has_unit(value):
        return value if len(value) < 200 else None
    if isinstance(value, str) or (isinstance(value, (int, float)) and not isinstance(value, bool)):
        # a number without a unit, as a number or a string ("width": "24", "sizes": "16x16": an icon's
        # pixels as often as a size), is a measurement only with its unit in a sibling key
        for k in (f"{key}Unit", f"{key}_unit", f"{key}Uom", *_UNIT_KEYS):
            if isinstance(node.get(k), str) and node[k].strip():
                return f"{value} {node[k]}"
    return None


def _keyed_pairs(node: dict, order: int) -> list[Pair]:
    """``{"itemWeight": "1.2 kg", "width": {"value": 30, "unit": "cm"}}``: keys that are measurement labels."""
    pairs = []
    for key, value in node.items():
        if not isinstance(key, str) or len(key) > 60 or key in _UNIT_KEYS or key == "value":
            continue
        if isinstance(value, (list, bool)) or value is None:
            continue
        info = classify_label(_key_label(key))
        if info is None:
            continue
        text = _keyed_value(node, key, value)
        if text is not None:
            pairs.append(Pair(_key_label(key), text, info, order=order))
    return pairs


def _json_pairs(data: Any, title: str | None = None) -> list[Pair]:
    """Label/value pairs of page state: ``{"title": "Overall Weight", "value": "8", "unit_string": "lb."}``
    entries, ``"Width: 12\""`` strings, and measurement keys (:func:`_keyed_pairs`) of objects that are
    the product's: objects under a named object count only when that name is the product's (its words in
    the page ``title``, :data:`NAME_MATCH`)."""
    title_words = frozenset(w.lower() for w in _TOKEN.findall(title or ""))
    pairs: list[Pair] = []
    stack: list[tuple[Any, bool]] = [(data, True)]
    seen = 0
    order = 0
    while stack and seen < _MAX_NODES:
        node, own = stack.pop()
        seen += 1
        order += 1
        if isinstance(node, dict):
            label = next((text for k in _LABEL_KEYS if (text := _text_of(node.get(k)))), None)
            value = _value_of(node) if label else None
            if isinstance(value, dict):
                value = _text_of(value)  # {"key": {"name": "Boyut/Ebat"}, "value": {"name": "140 x 180 cm"}}
            if label and isinstance(value, (str, int, float)) and not isinstance(value, bool):
                info = classify_label(label)
                if info is not None:
                    unit = next((node[k] for k in _UNIT_KEYS if isinstance(node.get(k), str)), "")
                    pairs.append(Pair(label, f"{value} {unit}".strip(), info, order=order))
            name = next((node[k] for k in _NAME_KEYS if isinstance(node.get(k), str)), None)
            if name and title_words and classify_label(name) is None:
                own = _names_product(name, title_words)
            if own:
                pairs.extend(_keyed_pairs(node, order))
            stack.extend((child, own) for child in reversed(list(node.values())))
        elif isinstance(node, list):
            stack.extend((child, own) for child in reversed(node))
        elif (
            own
            and isinstance(node, str)
            and 3 < len(node) < 200
            and ":" in node
            and DIGIT.search(node)
            and not CODE.search(node := _INLINE_TAG.sub(" ", node).strip())
        ):
            for label, value, info in split_inline(node):
                pairs.append(Pair(label, value, info, order=order))
    return pairs


#: A label of the product's that states this many different values in one state object lists variants
#: (a rug store's ``"Size": "2'x3'"``, ``"3'x5'"``, ``"5'x7'"``... one per size sold).
VARIANT_VALUES = 3


def _variants_apart(pairs: list[Pair]) -> list[Pair]:
    """``pairs`` with the product's labels that state :data:`VARIANT_VALUES` or more different values
    marked as variants' (none of them is the product's)."""
    values: dict[str, set[str]] = {}
    for p in pairs:
        if p.info.role == "product":
            values.setdefault(p.label.strip().lower(), set()).add(re.sub(r"\s+", "", p.value.lower()))
    listed = {label for label, vs in values.items() if len(vs) >= VARIANT_VALUES}
    if not listed:
        return pairs
    return [replace(p, info=replace(p.info, role="variant")) if p.info.role == "product"
            and p.label.strip().lower() in listed else p for p in pairs]  # fmt: skip


@adapter("embedded_json", priority=60, fallback=True)
def embedded_json(page: Page) -> list[Observation]:
    """Label/value data shipped as JSON inside the page's scripts (tabs rendered by JavaScript)."""
    obs: list[Observation] = []
    for payload in page.script_payloads:
        pairs = _variants_apart(_json_pairs(payload, page.title))
        if pairs:
            # JSON order is not visual order: group axes only among neighbouring entries.
            obs.extend(observations_from_pairs(pairs, page.decimal_comma, rank=1))
    return obs
