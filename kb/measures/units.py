"""The one unit table: unit words to catalog units (cm, g; ml for contents), factors computed by pint.

:func:`unit_table` gives one :class:`Unit` per word of :data:`kb.measures.aliases.ALIASES` (``"inches"``
-> length, 2.54 cm), for every language or for the ones asked (the parser asks for
:data:`~kb.measures.aliases.PARSER_LANGUAGES`). Only the aliases' pint unit *names* reach pint, never
the text of a page or a description (pint reads "quarter" as a mass unit).

Building the table with pint costs 135-170 ms (most of it pint's registry), so it is built once, when
the aliases change, and stored as package data (``kb/measures/data/units.json``, written by ``python -m
kb.measures.units --write``); :func:`unit_table` reads it when it lists exactly the aliases' words with
the same kinds and pint names, and builds the table with pint otherwise. A test checks that the stored
table equals a freshly built one, factor for factor.

:func:`length_unit` and :func:`mass_unit` look a unit token up the way pages write it (any case, a
trailing dot, accents or not); :func:`combine` is the rule for one quantity written in two units
("1 lb 2 oz", "5 ft 3 in", "1 kg 450 g").
"""

from __future__ import annotations

import argparse
import functools
import json
import math
import re
import unicodedata
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any, Literal

from kb.measures.aliases import (
    ALIASES,
    DESCRIPTION_ALIASES,
    DESCRIPTION_KINDS,
    ENGLISH_HOMOGRAPHS,
    IMPERIAL,
    KINDS,
    PARSER_LANGUAGES,
)

__all__ = [
    "CATALOG_UNITS",
    "STORED_TABLE",
    "UNIT_PATTERN",
    "Unit",
    "aliases_of",
    "build_unit_table",
    "combine",
    "description_aliases_of",
    "description_units",
    "is_smaller_unit",
    "words_pattern",
    "convert",
    "length_unit",
    "lookup",
    "mass_unit",
    "strip_accents",
    "symbol",
    "unit_key",
    "unit_table",
    "unit_words",
    "units_pattern",
    "volume_unit",
]

Kind = Literal["length", "mass", "volume"]
#: The catalog unit of each kind of quantity (volume is contents, turned into grams by the parser).
CATALOG_UNITS: dict[str, str] = {"length": "centimeter", "mass": "gram", "volume": "milliliter"}
_SYMBOL = {"length": "cm", "mass": "g", "volume": "ml"}
#: The table built with pint, stored as package data.
STORED_TABLE = Path(__file__).resolve().parent / "data" / "units.json"
#: A unit token after a number: a word (any script), a CJK unit character, an inch or foot mark; "lb." ends
#: with a dot.
UNIT_PATTERN = r"(?:''|[\"″′']|(?![xX]\b)[^\W\d_]+\.?)"
_MARKS = frozenset({"''", '"', "'", "″", "′"})


@dataclass(frozen=True)
class Unit:
    """One unit word: its kind, its pint unit, the factor to the catalog unit of that kind, its language
    (``""``: every language)."""

    word: str
    kind: Kind
    pint_name: str
    factor: float  # catalog units per one of this unit
    language: str = ""

    @property
    def catalog_symbol(self) -> str:
        return _SYMBOL[self.kind]


def _rows(aliases, kinds) -> tuple[tuple[str, str, str, str], ...]:
    """(word, kind, pint name, language) for every word of an alias table, in its order."""
    return tuple(
        (word.replace("_", " "), kinds[name], name, lang)
        for name, by_lang in aliases.items()
        for lang, words in by_lang.items()
        for word in words.split()
    )


@functools.cache
def _alias_rows() -> tuple[tuple[str, str, str, str], ...]:
    """(word, kind, pint name, language) for every alias, in the aliases' order (once per process)."""
    return _rows(ALIASES, KINDS)


@functools.cache
def _description_rows() -> tuple[tuple[str, str, str, str], ...]:
    """(word, kind, pint name, language) for every word of :data:`DESCRIPTION_ALIASES`."""
    return _rows(DESCRIPTION_ALIASES, DESCRIPTION_KINDS)


def unit_words() -> list[str]:
    """Every unit word of every language, in the aliases' order (without pint or the stored table)."""
    return [w for w, _k, _n, _l in _alias_rows()]


def words_pattern(*pint_names: str) -> str:
    """A regular expression alternation of every word (not the marks) of these pint units, in every
    language and also without accents, longest first: for rules that need one unit's words."""
    words = {w for w, _k, n, _l in _alias_rows() if n in pint_names and w not in _MARKS and w not in "”’"}
    words |= {strip_accents(w) for w in words}
    return "|".join(re.escape(w) for w in sorted(words, key=lambda w: (-len(w), w)))


def units_pattern(*kinds: str, imperial: bool | None = None) -> str:
    """:func:`words_pattern` for every unit of these kinds, of one system when ``imperial`` is given."""
    names = [n for n, k in KINDS.items() if k in kinds and (imperial is None or (n in IMPERIAL) == imperial)]
    return words_pattern(*names)


def aliases_of(kind: str, languages: frozenset[str] | None = None) -> dict[str, str]:
    """Word -> pint name for the ``kind``'s words in ``languages`` (all when None), without pint."""
    return {w: n for w, k, n, lang in _alias_rows() if k == kind and (languages is None or lang in languages)}


@functools.cache
def unit_table(languages: frozenset[str] | None = None) -> MappingProxyType[str, Unit]:
    """Unit word (lower case) -> :class:`Unit`, for ``languages`` (every language when None): the stored
    table when it matches the aliases, else built with pint; once per process."""
    if languages is not None:
        full = unit_table()
        return MappingProxyType({w: u for w, u in full.items() if u.language in languages})
    stored = _read_stored(STORED_TABLE)
    return MappingProxyType(stored if stored is not None else build_unit_table())


@functools.cache
def description_units() -> MappingProxyType[str, Unit]:
    """The description parser's unit words: every word of the one table (each language's, less the
    :data:`~kb.measures.aliases.ENGLISH_HOMOGRAPHS`; the parser's own languages first, so they win a
    word) and the description-only units of :data:`~kb.measures.aliases.DESCRIPTION_ALIASES` ("t", "km",
    "stone"), their factors stored beside the table's (built with pint when missing); once per process."""
    full = unit_table()
    table = {w: u for w, u in full.items() if u.language in PARSER_LANGUAGES}
    for w, u in full.items():
        if w not in ENGLISH_HOMOGRAPHS:
            table.setdefault(w, u)
    extra = _read_description(STORED_TABLE)
    for w, u in (extra if extra is not None else build_unit_table(description=True)).items():
        table.setdefault(w, u)
    return MappingProxyType(table)


def description_aliases_of(kind: str) -> dict[str, str]:
    """Word -> pint name of the ``kind``'s words in :func:`description_units`."""
    return {w: u.pint_name for w, u in description_units().items() if u.kind == kind}


def build_unit_table(description: bool = False) -> dict[str, Unit]:
    """The table computed with one pint registry, factors to 12 significant digits (``description``: of
    the description-only units). Raises ValueError when a word names two units."""
    import pint

    ureg = pint.UnitRegistry()
    factors: dict[str, float] = {}
    table: dict[str, Unit] = {}
    for word, kind, name, lang in _description_rows() if description else _alias_rows():
        if name not in factors:
            # 12 significant digits: the definitions' exact decimals (pint's foot is 30.479999999999997 cm)
            factors[name] = float(f"{ureg.Quantity(1.0, name).to(CATALOG_UNITS[kind]).magnitude:.12g}")
        if word in table and table[word].pint_name != name:
            raise ValueError(f"unit word {word!r} names both {table[word].pint_name} and {name}")
        table.setdefault(word, Unit(word, kind, name, factors[name], lang))  # type: ignore[arg-type]
    return table


def _read_stored(path: Path) -> dict[str, Unit] | None:
    """The stored table, or None when it is missing, unreadable or not the aliases' units."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return table_from_json(data)
    except (OSError, ValueError, TypeError, KeyError):
        return None


def _read_description(path: Path) -> dict[str, Unit] | None:
    """The stored description-only units, or None when missing, unreadable or not the aliases' units."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return table_from_json(data, description=True)
    except (OSError, ValueError, TypeError, KeyError):
        return None


def table_from_json(data: Any, description: bool = False) -> dict[str, Unit] | None:
    """The table stored as ``{"units": {word: [kind, pint name, factor, language]}}`` (``description``:
    its ``"description"`` rows), or None unless it lists exactly the aliases' words, each with its kind,
    pint name and language, and a positive finite factor."""
    rows = data["description" if description else "units"]
    expected: dict[str, tuple[str, str, str]] = {}
    for word, kind, name, lang in _description_rows() if description else _alias_rows():
        expected.setdefault(word, (kind, name, lang))
    if set(rows) != set(expected):
        return None
    table: dict[str, Unit] = {}
    for word, (kind, name, lang) in expected.items():  # the aliases' order, as build_unit_table
        row_kind, row_name, factor, row_lang = rows[word]
        if (row_kind, row_name, row_lang) != (kind, name, lang):
            return None
        if not isinstance(factor, float) or not 0 < factor < math.inf:
            return None
        table[word] = Unit(word, kind, name, factor, lang)  # type: ignore[arg-type]
    return table


def _json_rows(table: Mapping[str, Unit]) -> str:
    return ",\n".join(
        f"  {json.dumps(w, ensure_ascii=False)}: {json.dumps([u.kind, u.pint_name, u.factor, u.language], ensure_ascii=False)}"
        for w, u in table.items()
    )


def table_to_json(table: Mapping[str, Unit], description: Mapping[str, Unit] | None = None) -> str:
    """The stored form: one line per unit word, ``"word": [kind, pint name, factor, language]``; the
    description-only units (:func:`description_units`) under ``"description"``."""
    import pint

    note = "written by `python -m kb.measures.units --write` from kb/measures/aliases.py with pint; do not edit"
    head = f' "note": {json.dumps(note)},\n "pint": {json.dumps(pint.__version__)},\n'
    extra = "" if description is None else ',\n "description": {\n' + _json_rows(description) + "\n }"
    return "{\n" + head + ' "units": {\n' + _json_rows(table) + "\n }" + extra + "\n}\n"


def convert(value: float, word: str) -> tuple[str, float]:
    """(kind, value in catalog units) of ``value`` ``word`` ("3", "inches" -> ("length", 7.62)).

    Raises KeyError for a word that is not a unit."""
    unit = unit_table()[word.lower()]
    return unit.kind, value * unit.factor


# ------------------------------------------------------------------------------- lookups as pages write
def strip_accents(text: str) -> str:
    decomposed = unicodedata.normalize("NFKD", text)
    return "".join(ch for ch in decomposed if not unicodedata.combining(ch))


def unit_key(unit: str | None) -> str:
    """The lookup key of a unit token: lower case, without a trailing dot (marks kept as they are)."""
    if not unit:
        return ""
    u = unit.strip().lower()
    if u not in _MARKS:
        u = u.rstrip(".")
    return u


@functools.cache
def _index() -> dict[str, Unit]:
    """Every word of every language, and each written without its accents."""
    table = unit_table()
    index = {strip_accents(w): u for w, u in table.items()}
    index.update(table)
    return index


def lookup(unit: str | None) -> Unit | None:
    """The :class:`Unit` a token names, in any language (``"Cm."``, ``"centimetros"``), or None."""
    key = unit_key(unit)
    if not key:
        return None
    index = _index()
    found = index.get(key)
    return found if found is not None else index.get(strip_accents(key))


def _factor(unit: str | None, kind: str) -> float | None:
    found = lookup(unit)
    return found.factor if found is not None and found.kind == kind else None


def length_unit(unit: str | None) -> float | None:
    """Centimetres per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a length unit."""
    return _factor(unit, "length")


def mass_unit(unit: str | None) -> float | None:
    """Grams per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a mass unit."""
    return _factor(unit, "mass")


def volume_unit(unit: str | None) -> float | None:
    """Millilitres per ``unit``, or None if not a volume unit."""
    return _factor(unit, "volume")


def symbol(unit: Unit) -> str:
    """The unit's symbol: its first language-neutral word ("cm", "kg", "in"; "stone" has none)."""
    words = (ALIASES.get(unit.pint_name) or DESCRIPTION_ALIASES[unit.pint_name]).get("") or unit.pint_name
    return words.split()[0]


def is_smaller_unit(unit: Unit, sub_unit: Unit) -> bool:
    """True when ``sub_unit`` can follow ``unit`` in one quantity: same kind, same system, smaller."""
    return (
        unit.kind == sub_unit.kind
        and (unit.pint_name in IMPERIAL) == (sub_unit.pint_name in IMPERIAL)
        and sub_unit.factor < unit.factor
    )


def combine(value: float, unit: Unit, sub_value: float, sub_unit: Unit) -> float | str:
    """One quantity written in two units of a kind and system, the second smaller ("1 lb 2 oz", "5 ft 3 in",
    "1 kg 450 g"): the value in ``unit``, or the reason it is not one quantity (another kind, a second unit
    not smaller, metric and imperial units, as "1 kg 2 lb", a first value not whole, as "1.5 kg, 200 g",
    or a second value worth a whole first unit or more, as "5 ft 12 in"; 1e-9 absorbs pint's rounding)."""
    if not is_smaller_unit(unit, sub_unit):
        return f"{sub_unit.pint_name} is not a smaller unit of {unit.pint_name}'s kind and system"
    if value != int(value):
        return f"{value:g} {unit.pint_name} is not a whole number before {sub_unit.pint_name}"
    if sub_value * sub_unit.factor >= unit.factor * (1 - 1e-9):
        return f"{sub_value:g} {sub_unit.pint_name} is not less than 1 {unit.pint_name}"
    return value + sub_value * sub_unit.factor / unit.factor


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m kb.measures.units", description="Build the unit table with pint.")
    ap.add_argument("--write", action="store_true", help=f"store it as {STORED_TABLE.name} (package data)")
    args = ap.parse_args(argv)
    text = table_to_json(build_unit_table(), build_unit_table(description=True))
    if args.write:
        STORED_TABLE.parent.mkdir(exist_ok=True)
        STORED_TABLE.write_text(text, encoding="utf-8")
        print(f"wrote {STORED_TABLE}")
    else:
        print(text, end="")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
