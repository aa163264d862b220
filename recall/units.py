"""Unit words to catalog units, with factors computed by pint once (never per token).

:func:`unit_table` builds, on first use, one :class:`Unit` per unit word of :mod:`recall.lexicon`
(``"inches"`` -> length, 2.54 cm). Only the lexicon's pint unit *names* reach pint, never the text of a
description: pint reads "quarter" as a mass unit and would happily turn number words into units.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal

from recall.lexicon import LENGTH_UNITS, MASS_UNITS, VOLUME_UNITS

__all__ = ["CATALOG_UNITS", "Unit", "convert", "unit_table"]

Kind = Literal["length", "mass", "volume"]
#: The catalog unit of each kind of quantity (volume is contents, turned into grams by the parser).
CATALOG_UNITS: dict[str, str] = {"length": "centimeter", "mass": "gram", "volume": "milliliter"}
_SYMBOL = {"length": "cm", "mass": "g", "volume": "ml"}


@dataclass(frozen=True)
class Unit:
    """One unit word: its kind and the factor to the catalog unit of that kind."""

    word: str
    kind: Kind
    pint_name: str
    factor: float  # catalog units per one of this unit

    @property
    def catalog_symbol(self) -> str:
        return _SYMBOL[self.kind]


@functools.cache
def unit_table() -> MappingProxyType[str, Unit]:
    """Unit word (lower case) -> :class:`Unit`; built with one pint registry, once per process."""
    import pint

    ureg = pint.UnitRegistry()
    factors: dict[str, float] = {}
    table: dict[str, Unit] = {}
    for kind, words in (("length", LENGTH_UNITS), ("mass", MASS_UNITS), ("volume", VOLUME_UNITS)):
        target = CATALOG_UNITS[kind]
        for word, name in words.items():
            if name not in factors:
                factors[name] = float(ureg.Quantity(1.0, name).to(target).magnitude)
            table[word] = Unit(word=word, kind=kind, pint_name=name, factor=factors[name])  # type: ignore[arg-type]
    return MappingProxyType(table)


def convert(value: float, word: str) -> tuple[str, float]:
    """(kind, value in catalog units) of ``value`` ``word`` ("3", "inches" -> ("length", 7.62)).

    Raises KeyError for a word that is not a unit."""
    unit = unit_table()[word.lower()]
    return unit.kind, value * unit.factor
