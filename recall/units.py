"""Unit words to catalog units, with factors computed by pint (never per token, and not at every start).

:func:`unit_table` gives one :class:`Unit` per unit word of :mod:`recall.lexicon` (``"inches"`` ->
length, 2.54 cm). Only the lexicon's pint unit *names* reach pint, never the text of a description:
pint reads "quarter" as a mass unit and would happily turn number words into units.

Building the table with pint costs 135-170 ms (most of it pint's registry), so it is built once, when
the lexicon's units change, and stored as package data (``recall/data/units.json``, written by
``python -m recall.units --write``); :func:`unit_table` reads it when it lists exactly the lexicon's unit
words with the same pint names, and builds the table with pint otherwise. A test checks that the stored
table equals a freshly built one, factor for factor.
"""

from __future__ import annotations

import argparse
import functools
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any, Literal

from recall.lexicon import LENGTH_UNITS, MASS_UNITS, VOLUME_UNITS

__all__ = ["CATALOG_UNITS", "STORED_TABLE", "Unit", "build_unit_table", "convert", "unit_table"]

Kind = Literal["length", "mass", "volume"]
#: The catalog unit of each kind of quantity (volume is contents, turned into grams by the parser).
CATALOG_UNITS: dict[str, str] = {"length": "centimeter", "mass": "gram", "volume": "milliliter"}
_SYMBOL = {"length": "cm", "mass": "g", "volume": "ml"}
#: The table built with pint, stored as package data.
STORED_TABLE = Path(__file__).resolve().parent / "data" / "units.json"
_LEXICON: dict[str, Mapping[str, str]] = {"length": LENGTH_UNITS, "mass": MASS_UNITS, "volume": VOLUME_UNITS}


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
    """Unit word (lower case) -> :class:`Unit`: the stored table when it matches the lexicon, else built
    with pint; once per process."""
    stored = _read_stored(STORED_TABLE)
    return MappingProxyType(stored if stored is not None else build_unit_table())


def build_unit_table() -> dict[str, Unit]:
    """The table computed with one pint registry."""
    import pint

    ureg = pint.UnitRegistry()
    factors: dict[str, float] = {}
    table: dict[str, Unit] = {}
    for kind, words in _LEXICON.items():
        target = CATALOG_UNITS[kind]
        for word, name in words.items():
            if name not in factors:
                factors[name] = float(ureg.Quantity(1.0, name).to(target).magnitude)
            table[word] = Unit(word=word, kind=kind, pint_name=name, factor=factors[name])  # type: ignore[arg-type]
    return table


def _read_stored(path: Path) -> dict[str, Unit] | None:
    """The stored table, or None when it is missing, unreadable or not the lexicon's units."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return table_from_json(data)
    except (OSError, ValueError, TypeError, KeyError):
        return None


def table_from_json(data: Any) -> dict[str, Unit] | None:
    """The table stored as ``{"units": {word: [kind, pint name, factor]}}``, or None unless it lists
    exactly the lexicon's unit words, each with its kind and pint name, and a positive finite factor."""
    rows = data["units"]
    expected = {word: (kind, name) for kind, words in _LEXICON.items() for word, name in words.items()}
    if set(rows) != set(expected):
        return None
    table: dict[str, Unit] = {}
    for word, (kind, name) in expected.items():  # the lexicon's order, as build_unit_table
        row_kind, row_name, factor = rows[word]
        if (row_kind, row_name) != (kind, name) or not isinstance(factor, float) or not 0 < factor < math.inf:
            return None
        table[word] = Unit(word=word, kind=kind, pint_name=name, factor=factor)  # type: ignore[arg-type]
    return table


def table_to_json(table: Mapping[str, Unit]) -> str:
    """The stored form: one line per unit word, ``"word": [kind, pint name, factor]``."""
    import pint

    rows = ",\n".join(
        f"  {json.dumps(w, ensure_ascii=False)}: {json.dumps([u.kind, u.pint_name, u.factor])}"
        for w, u in table.items()
    )
    note = "written by `python -m recall.units --write` from recall/lexicon.py with pint; do not edit"
    head = f' "note": {json.dumps(note)},\n "pint": {json.dumps(pint.__version__)},\n'
    return "{\n" + head + ' "units": {\n' + rows + "\n }\n}\n"



def convert(value: float, word: str) -> tuple[str, float]:
    """(kind, value in catalog units) of ``value`` ``word`` ("3", "inches" -> ("length", 7.62)).

    Raises KeyError for a word that is not a unit."""
    unit = unit_table()[word.lower()]
    return unit.kind, value * unit.factor


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m recall.units", description="Build the unit table with pint.")
    ap.add_argument("--write", action="store_true", help=f"store it as {STORED_TABLE.name} (package data)")
    args = ap.parse_args(argv)
    text = table_to_json(build_unit_table())
    if args.write:
        STORED_TABLE.write_text(text, encoding="utf-8")
        print(f"wrote {STORED_TABLE}")
    else:
        print(text, end="")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
