"""Where page state keeps a measurement's unit when the value is a bare number: in a unit key beside it
(``"weight": 3.2, "weightUnit": "kg"``, ``"peso": 1.2, "unidad_peso": "kg"``, ``"breite": 30, "einheit":
"cm"``), inside a value object (``{"value": 3.2, "unitOfMeasure": "KG"}``, ``{"wert": 3.2, "einheit":
"kg"}``, ``{"number": 1.2, "unit": "kg"}``), or one level up, beside the key holding the measurements
(``"dimensions": {"width": 30, ...}, "dimensionUnit": "cm"``).

A unit key is named by a unit word in any of the store languages (``unit``, ``uom``, ``Einheit``,
``unité``, ``unidad``, ``unità``, ``jednostka``, ``eenheid``, ``enhet``, ``birim``, ``единица``) and holds
a length or mass unit (a string, or an object naming it: ``{"symbol": "kg"}``). A unit is taken only for a
measurement of its family: a ``"unit": "cm"`` never makes a bare ``"weight": 3`` a mass.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import Any

from scrapers.label_vocabulary import fold
from scrapers.quantities import length_unit, mass_unit

__all__ = ["BARE_NUMBER", "UNIT_WORDS", "family", "is_unit_key", "key_words", "unit_for", "unit_keys", "unit_text", "value_object"]

#: A bare number, as a JSON number prints or a store writes it in a string (``"24"``, ``"3,2"``).
BARE_NUMBER = re.compile(r"\s*\d+(?:[.,]\d+)?\s*")
_CAMEL = re.compile(r"(?<=[a-z])(?=[A-Z])|[_\-.\s]+")

#: Words that name a unit key, folded (:func:`scrapers.label_vocabulary.fold`).
UNIT_WORDS = frozenset(
    fold(w)
    for w in "unit units uom uoms unitcode unittext einheit masseinheit unite unité unidad unidade unita unità "
    "jednostka eenheid enhet enheter yksikkö birim birimi единица единицы symbol".split()
)
#: Keys holding a value object's number (``{"value": 3.2, "unit": "kg"}``), in order of preference.
VALUE_WORDS = ("value", "amount", "number", "quantity", "magnitude", "wert", "valeur", "valor", "valore",
               "waarde", "wartosc", "wartość", "val")  # fmt: skip
#: Keys of an object naming a unit (``{"symbol": "kg"}``, ``{"name": "Kilogramm", "code": "KGM"}``).
_UNIT_NAME_KEYS = ("symbol", "abbreviation", "abbr", "code", "name", "value", "text", "label")


@lru_cache(maxsize=16384)
def key_words(key: str) -> frozenset[str]:
    """A JSON key's words, folded: ``unidad_peso`` -> {unidad, peso}, ``weightUnit`` -> {weight, unit}."""
    return frozenset(fold(w) for w in _CAMEL.split(key) if w)


@lru_cache(maxsize=16384)
def is_unit_key(key: str) -> bool:
    return len(key) <= 40 and bool(key_words(key) & UNIT_WORDS)


def family(unit: str) -> str | None:
    """``"length"`` or ``"mass"`` for a unit word, symbol or code; None for anything else."""
    if length_unit(unit) is not None:
        return "length"
    return "mass" if mass_unit(unit) is not None else None


def unit_text(x: Any) -> str | None:
    """The length or mass unit ``x`` names (a string, or an object's ``symbol``/``name``...), or None."""
    if isinstance(x, dict):
        x = next((x[k] for k in _UNIT_NAME_KEYS if isinstance(x.get(k), str) and family(x[k].strip())), None)
    if isinstance(x, str) and 0 < len(x.strip()) <= 20 and family(x.strip()):
        return x.strip()
    return None


def unit_keys(node: dict) -> list[tuple[frozenset[str], str, str]]:
    """The unit keys of a state object: (the key's other words, family, unit) each."""
    out = []
    for k, v in node.items():
        if isinstance(k, str) and is_unit_key(k) and (unit := unit_text(v)) is not None:
            out.append((key_words(k) - UNIT_WORDS, family(unit), unit))
    return out


#: Words a unit key may hold beside its unit word and still be the object's one unit (``unitOfMeasure``,
#: ``unidad_medida``, ``unitCode``).
_PLAIN = frozenset("measure measurement measurements of medida mesure misura code text string name symbol type".split())


def unit_for(key: str, kind_family: str, units: list[tuple[frozenset[str], str, str]]) -> str | None:
    """The unit of a bare number under ``key`` (a measurement of ``kind_family``) among ``units``: the unit
    key of that family naming the same word (``weightUnit`` for ``weight``, ``unidad_peso`` for ``peso``),
    else the one unit of that family the object states (``"einheit": "cm"`` beside ``breite``), else None
    (two different ones and none naming the key: which is whose is not said)."""
    same = [u for u in units if u[1] == kind_family]
    words = key_words(key)
    named = {u[2] for u in same if u[0] & words}
    if len(named) == 1:
        return named.pop()
    plain = {u[2] for u in same if u[0] <= _PLAIN}
    if len(plain) == 1:
        return plain.pop()
    return same[0][2] if len({u[2] for u in same}) == 1 else None


def _number(x: Any) -> float | int | str | None:
    if isinstance(x, bool):
        return None
    if isinstance(x, (int, float)):
        return x
    if isinstance(x, str) and BARE_NUMBER.fullmatch(x):
        return x.strip()
    return None


def value_object(node: dict) -> str | None:
    """``{"value": 3.2, "unit": "kg"}`` (any value word, any unit key) as ``"3.2 kg"``, or None."""
    number = next((n for k in VALUE_WORDS if (n := _number(node.get(k))) is not None), None)
    if number is None:
        return None
    units = {u[2] for u in unit_keys(node)}
    return f"{number} {units.pop()}" if len(units) == 1 else None
