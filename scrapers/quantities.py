"""Single lengths and masses as storefront pages write them (``67,7 cm``, ``Gewicht 4,7 kg``, ``1 lb 2 oz``,
``1 kg 450 g``), ranges (``15.5" - 116.5"``), a third axis in prose (``3/4" thick``) and units stated in
labels (``Weight (kg)``), converted to catalog units (cm, g).

The reading of numbers, units and page text is shared (:mod:`kb.measures`); sizes ``A x B x C`` are in
:mod:`scrapers.sizes` (re-exported here). Every public function takes any text and never raises: a text
without a quantity gives None or [].
"""

from __future__ import annotations

import math
import re

from kb.measures.numbers import DECIMAL_COMMA_LANGUAGES, DOT_GROUPED, decimal_comma_for, parse_number
from kb.measures.numbers import NUMBER_PATTERN as _NUMBER
from kb.measures.text import MAX_TEXT, clean_text
from kb.measures.units import UNIT_PATTERN as _UNIT
from kb.measures.units import combine, is_smaller_unit, length_unit, lookup, mass_unit, volume_unit
from scrapers.signs import minus_before
from scrapers.sizes import AXIS_LETTER_ROLES, Dims, parse_dims

__all__ = [
    "AXIS_LETTER_ROLES",
    "DECIMAL_COMMA_LANGUAGES",
    "Dims",
    "clean_text",
    "decimal_comma_for",
    "length_unit",
    "mass_unit",
    "parse_dims",
    "parse_length",
    "parse_length_range",
    "parse_mass",
    "parse_number",
    "third_axis",
    "unit_hint",
]

# One mass in two units: "1 lb 2 oz", Amazon India's "1 kg 450 g" (and "1 kg 450 grams", "2 кг 300 г").
_TWO_UNITS = re.compile(
    rf"(?P<a>{_NUMBER})\s*(?P<ua>{_UNIT}),?\s*(?:and\s+)?(?P<b>{_NUMBER})\s*(?P<ub>{_UNIT})"
)
_QUANTITY_RE = re.compile(rf"(?P<n>{_NUMBER})\s*(?P<u>{_UNIT})?")
_RANGE_RE = re.compile(rf"{_NUMBER}\s*(?:{_UNIT})?\s*(?:-|–|—|~|to|bis|a|à)\s*{_NUMBER}")


def unit_hint(label: str) -> str | None:
    """A unit stated in a label: ``Výška [mm]``, ``Grubość (w mm)``, ``Габариты, см``, ``Weight (kg)``,
    ``Width in cm``, ``Dimension (HxWxD, mm)``. Returns the unit token or None."""
    text = clean_text(label[:MAX_TEXT]).lower()
    for pattern in (
        r"[\[(]\s*(?:(?:w|in|en|em)\s+)?([^\W\d_]+\.?|''|\")\s*[\])]",  # "(w mm)", "(inches)": not in + "ches"
        # one item of a bracketed list: "(HxWxD, mm)", "(mm; W x H x D)"
        r"[\[(][^\])]{0,30}[,;]\s*([^\W\d_]+\.?)\s*[\])]",
        r"[\[(]\s*([^\W\d_]+\.?)\s*[,;][^\])]{0,30}[\])]",
        r",\s*([^\W\d_]+)\s*:?\s*$",
        r"\b(?:in|en|em)\s+([^\W\d_]+)\s*:?\s*$",
    ):
        for m in re.finditer(pattern, text):
            unit = m.group(1)
            if length_unit(unit) is not None or mass_unit(unit) is not None:
                return unit
    return None


def _mass_in_two_units(s: str, decimal_comma: bool | None) -> float | None:
    """Grams of the first mass written in two units (:func:`kb.measures.units.combine`), negative after a
    minus sign, NaN when it is refused ("2 lb 20 oz": not one mass, and the first unit alone would not be
    what the page says), or None when there is none ("1 kg 2 lb", "1.5 kg, 200 g" are two masses)."""
    for m in _TWO_UNITS.finditer(s):
        unit, sub_unit = lookup(m["ua"]), lookup(m["ub"])
        if unit is None or sub_unit is None or unit.kind != "mass":
            continue
        value, sub_value = parse_number(m["a"], decimal_comma), parse_number(m["b"], decimal_comma)
        if value is None or sub_value is None:
            continue
        one = combine(value, unit, sub_value, sub_unit)
        if not isinstance(one, str):
            return round((-1.0 if minus_before(s, m.start("a")) else 1.0) * one * unit.factor, 6)
        if is_smaller_unit(unit, sub_unit) and value == int(value):
            return math.nan  # the units make one quantity, but the second value is a whole first unit or more
    return None


def _parse_single(text: str, convert, default_unit: str | None, decimal_comma: bool | None) -> float | None:
    s = clean_text(text[:MAX_TEXT])
    if convert is mass_unit:
        grams = _mass_in_two_units(s, decimal_comma)
        if grams is not None:
            return None if math.isnan(grams) or grams == 0 else grams
    if _RANGE_RE.search(s):
        return None
    for m in _QUANTITY_RE.finditer(s):
        unit = m.group("u")
        factor = convert(unit) if unit else None
        if factor is None and unit and default_unit and len(unit.rstrip(".")) > 0:
            # a word after the number that is not our unit ("6 Liter"): only a label unit can save it
            if convert(default_unit) is None:
                continue
            other = length_unit(unit) or mass_unit(unit)
            if other is not None or volume_unit(unit) is not None:
                continue
        if factor is None and default_unit:
            factor = convert(default_unit)
        if factor is None:
            continue
        number = m.group("n")
        if factor <= 1.0 and decimal_comma is not False and DOT_GROUPED.fullmatch(number):
            # "1.200 g", "1.500 mm": a thousandth of a gram or millimetre is not how shops write sizes
            value = float(number.replace(".", ""))
        else:
            value = parse_number(number, decimal_comma)
        if value is None or value <= 0:
            continue
        return round((-1.0 if minus_before(s, m.start("n")) else 1.0) * value * factor, 6)
    return None


def parse_length(
    text: str, default_unit: str | None = None, decimal_comma: bool | None = None
) -> float | None:
    """The first length in ``text`` in cm (``"67,7 cm"`` -> 67.7), or None; a range (``15.5 - 116.5"``) is
    not one length. A length stated with a minus sign (``-5 cm``, :mod:`scrapers.signs`) is returned
    negative, for the catalog limits to refuse it with its reason."""
    try:
        return _parse_single(text, length_unit, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001
        return None


def parse_mass(text: str, default_unit: str | None = None, decimal_comma: bool | None = None) -> float | None:
    """The first mass in ``text`` in grams (``"Gewicht 4,7 kg"`` -> 4700.0), or None; ranges are refused,
    and a mass stated with a minus sign is returned negative (as :func:`parse_length`)."""
    try:
        return _parse_single(text, mass_unit, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001
        return None


_RANGE_PARTS = re.compile(
    rf"(?P<a>{_NUMBER})\s*(?P<ua>{_UNIT})?\s*(?:-|–|—|~|to|bis|a|à)\s*(?P<b>{_NUMBER})\s*(?P<ub>{_UNIT})?"
)


def parse_length_range(
    text: str, default_unit: str | None = None, decimal_comma: bool | None = None
) -> tuple[float, float] | None:
    """A range written as ``15.5" - 116.5"`` or ``0.5 - 5 mm`` as (low, high) in the unit's catalog unit
    (cm for lengths; for a mass unit, grams), or None."""
    try:
        s = clean_text(text[:MAX_TEXT])
        m = _RANGE_PARTS.search(s)
        if not m:
            return None
        unit = m.group("ub") or m.group("ua") or default_unit
        factor = length_unit(unit) or mass_unit(unit) if unit else None
        if factor is None:
            return None
        a, b = parse_number(m.group("a"), decimal_comma), parse_number(m.group("b"), decimal_comma)
        if a is None or b is None or a <= 0 or b < a:
            return None
        return round(a * factor, 6), round(b * factor, 6)
    except Exception:  # noqa: BLE001
        return None


_THIRD_AXIS = re.compile(
    rf"(?P<q>{_NUMBER}\s*(?:''|[\"″]|[^\W\d_]+\.?))\s+(?:thick|deep|tall|high|in (?:height|depth|thickness)|"
    r"dick|tief|hoch|d'épaisseur|d'epaisseur|de profondeur|de haut|de grosor|de espesor|de alto|di spessore)\b",
    re.IGNORECASE,
)


def third_axis(text: str, decimal_comma: bool | None = None) -> float | None:
    """The single axis a sentence adds to a two-value size (``8" x 10" and is 3/4" thick`` -> 1.905), in
    cm, or None."""
    try:
        m = _THIRD_AXIS.search(clean_text(text[:MAX_TEXT]))
        return parse_length(m.group("q"), None, decimal_comma) if m else None
    except Exception:  # noqa: BLE001
        return None
