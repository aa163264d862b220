"""Adjacent chunks that state one quantity, joined before the quantities are read (:mod:`recall.quantities`).

The chunk grammar (:mod:`recall.chunks`) closes a quantity at its unit, so two ways people write one
quantity come out as two chunks:

* **a compound with a bare tail**: "2 m 30", "1 kg 200", "5 ft 3", "1 lb 4": a whole number in a unit
  that has a customary smaller unit (metre -> centimetre, kilogram -> gram, foot -> inch, pound -> ounce,
  :data:`TAIL_UNITS`), then a whole number with no unit, less than one of the first unit. The tail is in the
  smaller unit ("2 m 30" is 230 cm, "5 ft 3" is 63 inches), as in "5 ft 3 in". The first chunk becomes
  ``(QUANT (NUM ..) (UNIT ..) (TAIL (NUM ..)))``, the tail's words moved into it (into the dimension chunk
  the tail opened: "2 m 30 long"). A tail with a unit ("2 m 30 cm") is the grammar's own SUB; a tail worth
  a whole first unit or more ("5 ft 14") is not joined.
* **a fraction of a scale word**: "half a million grams", "a quarter million", "half a dozen centimetres",
  "one and a half million", "three quarters of a million": a number with a fraction ("half", "1/2", "½",
  "one and a half") then [of] a number that opens with a scale word ("hundred", "thousand", "million",
  "billion", "dozen", after its article). The fraction scales it: the two NUM chunks become one, whose
  value :func:`fraction_of` reads. Not a fraction before another number ("half a 2 kg bag").
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from kb.measures.units import Unit, combine
from kb.measures.words import MAGNITUDE_WORDS, number_value
from recall.toolkit import Tree

__all__ = ["SCALE_WORDS", "TAIL_UNITS", "fraction_of", "join_chunks", "tail_unit"]

#: The customary smaller unit a bare tail is in, by the first unit's pint name ("2 m 30": centimetres).
TAIL_UNITS: dict[str, str] = {"meter": "cm", "kilogram": "g", "foot": "in", "pound": "oz"}
#: Words a fraction scales when a number opens with them ("half a million", "half a dozen").
SCALE_WORDS = frozenset({*MAGNITUDE_WORDS, "dozen"})
_ARTICLES = ("a", "an")


def tail_unit(unit: Unit | None, units: Mapping[str, Unit]) -> Unit | None:
    """The smaller unit a bare tail after ``unit`` is in (:data:`TAIL_UNITS`), or None."""
    if unit is None or unit.pint_name not in TAIL_UNITS:
        return None
    return units.get(TAIL_UNITS[unit.pint_name])


def fraction_of(words: Sequence[str]) -> float | None:
    """The value of a fraction followed by [of] a number that opens with a scale word: ``["half", "a",
    "million"]`` is 500000.0, ``["one", "and", "a", "half", "million"]`` 1500000.0; None for any other
    words."""
    i = next((n for n, word in enumerate(words) if word in SCALE_WORDS), None)
    if i is None:
        return None
    k = i - 1 if i > 0 and words[i - 1] in _ARTICLES else i  # where the scaled number opens
    j = k - 1 if k > 0 and words[k - 1] == "of" else k
    if j == 0:
        return None
    fraction, rest = number_value(words[:j]), number_value(words[k:])
    if fraction is None or rest is None or not math.isfinite(fraction) or _whole(fraction):
        return None
    return fraction * rest


def _leaves(node: Any) -> list[tuple[str, str]]:
    return node.leaves() if isinstance(node, Tree) else [node]


def _labels(node: Any) -> list[str]:
    return [c.label() if isinstance(c, Tree) else c[1] for c in node] if isinstance(node, Tree) else []


def _whole(value: float) -> bool:
    return value == int(value)


def _hedged(labels: list[str], core: list[str]) -> bool:
    """Whether a chunk's child labels are ``core``, after hedges ("about 2 m", "roughly half")."""
    n = len(core)
    return labels[-n:] == core and all(label == "HEDGE" for label in labels[:-n])


def _value(num: Tree) -> float | None:
    return number_value([w.lower() for w, _t in num.leaves()])


def _opening_quant(node: Any) -> tuple[Tree, int] | None:
    """The QUANT a node opens with: the node itself, or the first child of a dimension chunk; with its
    index in its parent (-1: the node)."""
    if isinstance(node, Tree) and node.label() == "QUANT":
        return node, -1
    if isinstance(node, Tree) and node.label() == "DIM" and isinstance(node[0], Tree) and node[0].label() == "QUANT":
        return node[0], 0
    return None


def _with_quant(node: Tree, index: int, quant: Tree) -> Tree:
    if index < 0:
        return quant
    return Tree(node.label(), [*node[:index], quant, *node[index + 1 :]])


def _is_fraction(num: Tree) -> bool:
    value = _value(num)
    last = num.leaves()[-1]
    return value is not None and math.isfinite(value) and not _whole(value) and (last[1] == "FRC" or "/" in last[0])


def _opens_with_scale(num: Tree) -> bool:
    words = [w.lower() for w, _t in num.leaves()]
    first = words[1] if len(words) > 1 and words[0] in _ARTICLES else words[0]
    return first in SCALE_WORDS


def _join_fraction(first: Any, of: Any, second: Any) -> Tree | None:
    """"half" + "a million grams" -> one chunk "half a million grams" (``of``: the "of" leaf between, or
    None)."""
    if not isinstance(first, Tree) or first.label() != "QUANT" or not _hedged(_labels(first), ["NUM"]):
        return None
    if not _is_fraction(first[-1]):
        return None
    opening = _opening_quant(second)
    if opening is None or not isinstance(opening[0][0], Tree) or opening[0][0].label() != "NUM":
        return None
    quant, index = opening
    if not _opens_with_scale(quant[0]):
        return None
    between = [of] if of is not None else []
    num = Tree("NUM", [*first[-1].leaves(), *between, *quant[0].leaves()])
    return _with_quant(second, index, Tree("QUANT", [*first[:-1], num, *quant[1:]]))


def _closing_quant(node: Any) -> tuple[Tree, int] | None:
    """The QUANT a node ends with (the node, or a dimension chunk's last child), with its index (-1: the node)."""
    if isinstance(node, Tree) and node.label() == "QUANT":
        return node, -1
    if isinstance(node, Tree) and node.label() == "DIM" and isinstance(node[-1], Tree) and node[-1].label() == "QUANT":
        return node[-1], len(node) - 1
    return None


def _join_tail(first: Any, second: Any, units: Mapping[str, Unit]) -> Tree | None:
    """"2 m" + "30 long" -> "2 m 30 long" as one quantity (the tail in centimetres), when it is one."""
    closing, opening = _closing_quant(first), _opening_quant(second)
    if closing is None or opening is None or (closing[1] >= 0 and opening[1] >= 0):
        return None
    quant, tail = closing[0], opening[0]
    if not _hedged(_labels(quant), ["NUM", "UNIT"]) or _labels(tail) != ["NUM"]:
        return None
    unit = units.get(quant[-1].leaves()[0][0].lower())
    sub = tail_unit(unit, units)
    whole, part = _value(quant[-2]), _value(tail[0])
    if unit is None or sub is None or whole is None or part is None:
        return None
    if not (math.isfinite(whole) and math.isfinite(part) and _whole(part) and part > 0):
        return None
    if isinstance(combine(whole, unit, part, sub), str):
        return None  # "5 ft 14", "1.5 m 20": not one quantity
    joined = Tree("QUANT", [*quant, Tree("TAIL", tail[0].leaves())])
    if closing[1] >= 0:  # "length 2 m" + "30"
        return _with_quant(first, closing[1], joined)
    return _with_quant(second, opening[1], joined)


def join_chunks(tree: Tree, units: Mapping[str, Unit]) -> Tree:
    """``tree`` with each pair of adjacent chunks that state one quantity joined (module docstring); the
    tree itself when there is none."""
    out: list[Any] = []
    changed = False
    i = 0
    while i < len(tree):
        node = tree[i]
        nxt = tree[i + 1] if i + 1 < len(tree) else None
        of = nxt if nxt is not None and not isinstance(nxt, Tree) and nxt[0].lower() == "of" else None
        after_of = tree[i + 2] if of is not None and i + 2 < len(tree) else None
        joined = None
        if nxt is not None:
            joined = _join_tail(node, nxt, units) or _join_fraction(node, None, nxt)
        if joined is None and after_of is not None:
            joined = _join_fraction(node, of, after_of)
            i += 1 if joined is not None else 0
        if joined is None:
            out.append(node)
            i += 1
            continue
        out.append(joined)
        changed = True
        i += 2
    return Tree(tree.label(), out) if changed else tree
