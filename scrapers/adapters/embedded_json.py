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
from functools import lru_cache
from typing import Any

from scrapers.adapters import Observation, adapter
from scrapers.adapters.spec_table import observations_from_pairs
from scrapers.adapters.state_units import (
    BARE_NUMBER,
    is_unit_key,
    unit_for,
    unit_keys,
    unit_text,
    value_object,
)
from scrapers.labels import LabelInfo, classify_label
from scrapers.page import Page
from scrapers.spec_pairs import CODE, DIGIT, Pair, family_of, has_unit, split_inline

__all__ = ["NAME_MATCH", "embedded_json"]

_LABEL_KEYS = ("title", "name", "label", "key", "attributeName", "attribute", "displayName", "property", "feature",
               "featureName", "group", "groupName", "specName")
#: Inline markup inside a state string (``"<B>Weight:</B> 8.5 Pounds"``, a store's bullet list): read as text.
_INLINE_TAG = re.compile(r"</?(?:b|strong|i|em|u|span|br|p|li|small)\b[^<>]{0,40}>", re.IGNORECASE)
_UNIT_KEYS = ("unit_string", "unit", "unitText", "unitCode", "units", "uom", "unitOfMeasure", "unit_of_measure", "measureUnit",
              "measurementUnit", "unitSymbol", "einheit", "unidad", "unita", "unite")
_MAX_NODES = 200_000


_CAMEL = re.compile(r"(?<=[a-z])(?=[A-Z])|[_\-.]+")
_NAME_KEYS = ("name", "title", "productName", "product_name", "displayName")
_TOKEN = re.compile(r"[^\W\d_]{3,}")
#: Share of a state object's name words that must appear in the page title for its keyed values to count
#: as the product's (page state also holds recommended and recently viewed products).
NAME_MATCH = 0.6


@lru_cache(maxsize=16384)
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
_VALUE_KEYS = ("value", "displayValue", "formattedValue", "valueText", "attributeValue", "value_name", "valueName",
               "value_struct", "valueStruct", "values")


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


def _keyed_value(node: dict, key: str, value: Any, info, inherited: list) -> str | None:
    """The value text of a measurement key: a string stating its unit as it is; a bare number (or a string
    of one) with the unit its key names (``width_cm``, ``weightInGrams``), a unit key beside it
    (:func:`scrapers.adapters.state_units.unit_for`: ``weightUnit``, ``unidad_peso``, ``einheit``) or,
    failing those, beside the key holding this object (``inherited``); a value object (``{"value": 1.2,
    "unit": "kg"}``, ``{"wert": 3.2, "einheit": "kg"}``). None without a unit: a bare ``"width": 800``
    is an image's pixels as often as a size."""
    if isinstance(value, dict):
        return value_object(value)
    if isinstance(value, str) and has_unit(value):
        return value if len(value) < 200 else None
    if isinstance(value, (str, int, float)) and not isinstance(value, bool):
        if info.unit is not None:
            return f"{value} {info.unit}" if BARE_NUMBER.fullmatch(str(value)) else None
        unit = unit_for(key, family_of(info), unit_keys(node)) or unit_for(key, family_of(info), inherited)
        if unit is not None:
            return f"{value} {unit}"
    return None


def _keyed_pairs(node: dict, order: int, inherited: list) -> list[Pair]:
    """``{"itemWeight": "1.2 kg", "width": {"value": 30, "unit": "cm"}}``: keys that are measurement labels."""
    pairs = []
    for key, value in node.items():
        if not isinstance(key, str) or len(key) > 60 or key == "value" or is_unit_key(key):
            continue
        if isinstance(value, (list, bool)) or value is None:
            continue
        info = classify_label(_key_label(key))
        if info is None:
            continue
        text = _keyed_value(node, key, value, info, inherited)
        if text is not None:
            pairs.append(Pair(_key_label(key), text, info, order=order))
    return pairs


def _unit_of(x: Any) -> str | None:
    """An entry's unit: a string as written (``"lb."``), or the unit an object names (``{"symbol": "kg"}``)."""
    return x if isinstance(x, str) else unit_text(x)


def _entry(node: dict) -> tuple[str, Any, Any] | None:
    """A label/value entry's label, value and unit: ``{"title": "Overall Weight", "value": "8",
    "unit_string": "lb."}``, the label in an object (``{"key": {"name": "Boyut/Ebat"}, ...}``, Shopware's
    ``{"group": {"name": "Gewicht"}, "name": "1,2 kg"}``: the label is the first label key naming a
    measurement, the value the other name when no value key is present), the value in a value object
    (Mercado Libre's ``"value_struct": {"number": 1.2, "unit": "kg"}``)."""
    texts = [(k, t) for k in _LABEL_KEYS if (t := _text_of(node.get(k)))]
    if not texts:
        return None
    label_key, label = next(((k, t) for k, t in texts if classify_label(t) is not None), texts[0])
    value = _value_of(node)
    if isinstance(value, dict):
        value = value_object(value) or _text_of(value)  # {"key": {"name": "Boyut/Ebat"}, "value": {"name": "140 x 180 cm"}}
    if value is None:
        value = next((t for k, t in texts if k != label_key and DIGIT.search(t)), None)
    unit = next((u for k in _UNIT_KEYS if (u := _unit_of(node.get(k)))), "")
    return label, value, unit


def _list_pair(node: list) -> tuple[str, str] | None:
    """``["Weight", "3.2 kg"]``: a spec list written as two-item lists of label and value."""
    if len(node) == 2 and isinstance(node[0], str) and isinstance(node[1], (str, int, float)) and not isinstance(node[1], bool):
        if len(node[0]) <= 60 and classify_label(node[0]) is not None and DIGIT.search(str(node[1])):
            return node[0], str(node[1])
    return None


def _packed(pair: Pair, packed: LabelInfo | None) -> Pair:
    """``pair`` as a package (or shipping) value when it sits under a package key (Target's
    ``"package_dimensions": {"width": 7, "weight": 0.9, ...}``)."""
    if packed is None:
        return pair
    return replace(pair, package=True, info=replace(pair.info, package=True, shipping=pair.info.shipping or packed.shipping))


def _key_context(key: Any, packed: LabelInfo | None) -> tuple[bool, LabelInfo | None]:
    """Whether the object under ``key`` takes this object's unit keys (``key`` is a measurement label:
    ``dimensions`` beside ``dimensionUnit``), and the package label the object sits under."""
    info = classify_label(_key_label(key)) if isinstance(key, str) and len(key) <= 60 else None
    if info is not None and info.package and packed is None:
        packed = info
    return info is not None, packed


def _dict_pairs(node: dict, own: bool, inherited: list, order: int) -> list[Pair]:
    """The pairs one state object states itself: a label/value entry (:func:`_entry`) and, when it is the
    product's, its measurement keys (:func:`_keyed_pairs`)."""
    pairs = []
    entry = _entry(node)
    if entry is not None:
        label, value, unit = entry
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            info = classify_label(label)
            if info is not None:
                pairs.append(Pair(label, f"{value} {unit}".strip(), info, order=order))
    if own:
        pairs.extend(_keyed_pairs(node, order, inherited))
    return pairs


def _json_pairs(data: Any, title: str | None = None) -> list[Pair]:
    """Label/value pairs of page state: ``{"title": "Overall Weight", "value": "8", "unit_string": "lb."}``
    entries, ``"Width: 12\""`` strings, ``["Weight", "3.2 kg"]`` lists, and measurement keys
    (:func:`_keyed_pairs`) of objects that are the product's: objects under a named object count only when
    that name is the product's (its words in the page ``title``, :data:`NAME_MATCH`). Values under a
    package key (``package_dimensions``, ``shippingWeight``) are package values."""
    title_words = frozenset(w.lower() for w in _TOKEN.findall(title or ""))
    pairs: list[Pair] = []
    stack: list[tuple[Any, bool, list, LabelInfo | None]] = [(data, True, [], None)]
    seen = 0
    while stack and seen < _MAX_NODES:
        node, own, inherited, packed = stack.pop()
        seen += 1
        found: list[Pair] = []
        if isinstance(node, dict):
            name = next((node[k] for k in _NAME_KEYS if isinstance(node.get(k), str)), None)
            if name and title_words and classify_label(name) is None:
                own = _names_product(name, title_words)
            found = _dict_pairs(node, own, inherited, seen)
            units = unit_keys(node)
            for k, child in reversed(list(node.items())):
                measured, under = _key_context(k, packed)
                stack.append((child, own, units if measured else [], under))
        elif isinstance(node, list):
            if own and (two := _list_pair(node)) is not None:
                found = [Pair(two[0], two[1], classify_label(two[0]), order=seen)]
            else:
                stack.extend((child, own, [], packed) for child in reversed(node))
        elif (
            own
            and isinstance(node, str)
            and 3 < len(node) < 200
            and ":" in node
            and DIGIT.search(node)
            and not CODE.search(node := _INLINE_TAG.sub(" ", node).strip())
        ):
            found = [Pair(label, value, info, order=seen) for label, value, info in split_inline(node)]
        pairs.extend(_packed(p, packed) for p in found)
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
