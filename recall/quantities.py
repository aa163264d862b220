"""Stage 4 of the description parser (the paper's Fig. 2): reading the chunks into quantities.

:class:`QuantityReader` walks one sentence's chunk tree: a QUANT chunk is read into a
:class:`recall.reading.Quantity` (hedge, number or range by :mod:`kb.measures.words`, unit by
:mod:`kb.measures.units`); a DIM chunk gives a dimension statement (a role and its quantity), a MULTI chunk a tuple or list of extents;
a quantity outside them is a mass, contents (in a sentence with a contents word) or an unlabelled
length. Everything read is collected, in text order, in a :class:`recall.reading.Reading` that the
resolution stages (:mod:`recall.dimensions`, :mod:`recall.mass`, :mod:`recall.categories`) turn into
features.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from kb.measures.units import Unit, combine, description_units
from kb.measures.words import number_value
from recall import lexicon as lx
from recall.chunks import size
from recall.quantities_joins import fraction_of, join_chunks, tail_unit
from recall.quantities_unnumbered import VAGUE_REASON, read_unnumbered, vague_before
from recall.reading import DimStatement, Quantity, Reading
from recall.tags import UNIT_TAGS
from recall.tokens import Token
from recall.toolkit import Tree

__all__ = ["QuantityReader"]


@dataclass(frozen=True, slots=True)
class _Sentence:
    """The sentence being read: its tokens, the index of its contents word (None without one) and the
    reading it adds to."""

    segment: list[Token]
    fill: int | None
    reading: Reading


class QuantityReader:
    """Reads chunk trees into a :class:`Reading`, with the unit table (built once); thread-safe."""

    def __init__(self) -> None:
        self._units = description_units()

    def join(self, tree: Tree) -> Tree:
        """One sentence's chunk tree with adjacent chunks that state one quantity joined
        (:func:`recall.quantities_joins.join_chunks`: "2 m 30", "half a million grams")."""
        return join_chunks(tree, self._units)

    def read(self, tree: Tree, segment: list[Token], base: int, reading: Reading) -> None:
        """Read one sentence's chunks (``segment`` its tokens, ``base`` the index of its first token)."""
        sent = _Sentence(segment, _fill_context(segment), reading)
        k = 0
        for idx, child in enumerate(tree):
            if isinstance(child, Tree):
                n = size(child)
                toks = segment[k : k + n]
                vague = vague_before(segment, k, [t.low for t in toks])
                if vague is not None and child.label() in ("QUANT", "DIM"):
                    quant = size(child[0]) if child.label() == "DIM" else n
                    reading.refuse(vague, toks[quant - 1].end, VAGUE_REASON)  # "a few hundred grams"
                    reading.in_dim_chunk.update(range(base + k, base + k + n))
                    k += n
                    continue
                if child.label() == "QUANT" and idx + 1 < len(tree) and _noun_took_other_unit(tree[idx + 1]):
                    # "~ 10cm diameter ~ 0.8 kg": the noun's value is the length before it, not the mass
                    q = self._quantity(child, toks, base + k, reading)
                    role = lx.DIMENSION_WORDS.get(segment[k + n].low, "size")
                    if (
                        q is not None
                        and q.unit is not None
                        and q.unit.kind == "length"
                        and role in _NOUN_ROLES
                    ):
                        self._add_dim(reading, role, [q], segment[k : k + n + 1], base + k)
                        k += n
                        continue
                self._read_chunk(child, toks, base + k, sent, k)
                k += n
            else:
                k += 1
        read_unnumbered(segment, base, reading, self._units)

    def _read_chunk(self, chunk: Tree, toks: list[Token], pos: int, sent: _Sentence, k: int) -> None:
        label = chunk.label()
        if label == "QUANT":
            q = self._quantity(chunk, toks, pos, sent.reading)
            if q is not None:
                self._free_quantity(q, toks, sent, k)
            return
        if label == "MULTI":
            self._read_multi(chunk, toks, pos, sent, k)
            return
        if label == "DIM":
            self._read_dim(chunk, toks, pos, sent, k)

    def _children(
        self, chunk: Tree, toks: list[Token], pos: int, sent: _Sentence
    ) -> Iterator[tuple[Any, int, int]]:
        """The parts of a DIM or MULTI chunk in order: (its :class:`Quantity`, start, end) for each QUANT
        read, (the :class:`Token`, j, j + 1) for each word (token indexes within ``toks``)."""
        j = 0
        for sub in chunk:
            if isinstance(sub, Tree):
                n = size(sub)
                if sub.label() == "QUANT":
                    q = self._quantity(sub, toks[j : j + n], pos + j, sent.reading, extent=True)
                    if q is not None:
                        yield q, j, j + n
                j += n
            else:
                yield toks[j], j, j + 1
                j += 1

    def _not_extents(self, quants: list[Quantity], toks: list[Token], sent: _Sentence, k: int) -> bool:
        """True (and each quantity with a unit read on its own) when one of them is not a length: "tall,
        about 300 g" is not a dimension."""
        if not any(q.unit is not None and q.unit.kind != "length" for q in quants):
            return False
        for q in quants:
            if q.unit is not None:
                self._free_quantity(q, toks, sent, k)
        return True

    def _read_dim(self, chunk: Tree, toks: list[Token], pos: int, sent: _Sentence, k: int) -> None:
        """A dimension chunk: "<dimension noun> [is|of|:] <quantity>" or "<quantity> [in|of] <dimension
        word>"."""
        reading, segment = sent.reading, sent.segment
        quants: list[Quantity] = []
        role = "size"
        dim_word: Token | None = None
        dim_first = False
        for part, _a, _b in self._children(chunk, toks, pos, sent):
            if isinstance(part, Quantity):
                quants.append(part)
            elif part.tag in ("DIM", "DIMN"):
                dim_word = part
                dim_first = not quants
                role = lx.DIMENSION_WORDS.get(part.low, "size")
        if not quants:
            if any(toks[0].start <= a and b <= toks[-1].end for a, b in reading.refused):
                reading.in_dim_chunk.update(range(pos, pos + len(toks)))  # "-5 cm long": no long shape
            return
        if self._not_extents(quants, toks, sent, k):
            return
        if dim_word is not None and dim_word.low in lx.WEAK_DIMENSION_WORDS:
            if dim_first or quants[0].unit is None:
                return  # "a large bottle, 2": no dimension
            role = "size"
        if dim_word is not None and dim_word.low in lx.UNIT_ONLY_DIMENSION_WORDS:
            if dim_first or quants[0].unit is None:
                return  # "10 square", "square 5": not "9 cm square"
        end = k + len(toks)
        if role in ("length", "height") and end < len(segment) and segment[end].tag == "DIM":
            if lx.DIMENSION_WORDS.get(segment[end].low) == "overall":
                role = "overall"  # "30 cm long overall", "48 cm long with the handle"
        self._add_dim(reading, role, quants, toks, pos)

    @staticmethod
    def _add_dim(reading: Reading, role: str, quants: list[Quantity], toks: list[Token], pos: int) -> None:
        for i in range(pos, pos + len(toks)):
            reading.in_dim_chunk.add(i)
        for q in quants:
            if q.unit is not None:
                reading.length_units.append((q.pos, q.unit))
        stmt = DimStatement(role, quants, toks[0].start, toks[-1].end)
        if role == "multi":
            reading.multis.append(stmt)
        elif role == "size":
            reading.sizes.append(stmt)
        else:
            reading.dims.append(stmt)

    def _read_multi(self, chunk: Tree, toks: list[Token], pos: int, sent: _Sentence, k: int) -> None:
        """A tuple ("10 x 5 x 2 cm", "7.5 cm long by 5 by 5", "L 20 x W 10 x H 5 cm") or a list ("20, 10
        and 5 cm"). Numbers without a unit take the unit of the next one in the tuple that has one, else
        of the previous one. A tuple whose every value has its own dimension word ("10 cm long by 3 cm in
        diameter") is read as those dimensions; a list counts only when its last value has a length
        unit, otherwise its values are read one by one."""
        reading = sent.reading
        quants: list[Quantity] = []
        roles: list[str | None] = []
        spans: list[tuple[int, int]] = []
        is_list = False
        for part, a, b in self._children(chunk, toks, pos, sent):
            if isinstance(part, Quantity):
                quants.append(part)
                roles.append(None)
                spans.append((a, b))
            elif part.tag in ("DIM", "DIMN") and quants and roles[-1] is None:
                roles[-1] = lx.DIMENSION_WORDS.get(part.low, "size")
                spans[-1] = (spans[-1][0], b)
            elif part.tag in ("CM", "AND"):
                is_list = True
        if not quants:
            return
        if is_list and (quants[-1].unit is None or quants[-1].unit.kind != "length"):
            for q in quants:  # "300 g, 20 cm and 5": not one list of extents
                self._free_quantity(q, toks, sent, k)
            return
        _inherit_units(quants)
        if self._not_extents(quants, toks, sent, k):
            return
        if len(quants) < 2:
            return
        if len(quants) > 3:  # "3 x 2 x 1 x 7 cm": no object has four extents; which three were meant is a guess
            reading.refuse(quants[0].start, quants[-1].end, f"{len(quants)} extents in one size: an object has three")
            return
        weak = lx.WEAK_DIMENSION_WORDS | lx.UNIT_ONLY_DIMENSION_WORDS
        if not is_list and len(quants) == 2 and set(roles) in ({"diameter", None}, {"radius", None}, {"circumference", None}):
            roles = [r or "length" for r in roles]  # "7 cm dia x 12 cm": the other extent of a cylinder
        if not is_list and all(r is not None and r != "size" for r in roles):
            for q, role, (a, b) in zip(quants, roles, spans, strict=True):
                if role is not None and role not in weak:
                    self._add_dim(reading, role, [q], toks[a:b], pos + a)
            return
        self._add_dim(reading, "multi", quants, toks, pos)

    def _free_quantity(self, q: Quantity, toks: list[Token], sent: _Sentence, k: int) -> None:
        """A quantity outside any dimension chunk: a mass, contents, or an unlabelled length."""
        reading, fill, segment = sent.reading, sent.fill, sent.segment
        if q.unit is None:
            return
        other = _other_object(segment, k)
        if other == "compared":
            return  # "it sits next to my 2 kg dumbbell": another object's mass or size
        if other == "owned" and q.unit.kind == "mass":
            reading.other_masses.append(q)  # "my 2 kg dumbbell": the object itself only if nothing else
            return
        contents = fill is not None and (fill < k or segment[fill].low not in lx.WEAK_FILL_WORDS)
        if q.unit.kind == "mass":
            if contents:
                # "filled with 16 oz of water" is contents; "full of water, about a pound and a half" is
                # the stated total: only a mass right after the contents word or before "of" is contents
                end = k + len(toks)
                after_of = end < len(segment) and segment[end].low == "of"
                right_after = fill is not None and 0 < k - fill <= 2
                contents = after_of or right_after
            reading.masses.append((q, contents))
        elif q.unit.kind == "volume":
            if contents:
                reading.contents.append(q)
        elif q.unit.kind == "length":
            reading.length_units.append((q.pos, q.unit))
            reading.sizes.append(DimStatement("size", [q], q.start, q.end))

    def _quantity(
        self, chunk: Tree, toks: list[Token], pos: int, reading: Reading, extent: bool = False
    ) -> Quantity | None:
        """Read a QUANT chunk: hedge, number or range, unit. A negative or zero value, or a second unit not
        smaller than one of the first ("5 ft 12 in"), is refused: None, and recorded in
        ``reading.refused`` when the quantity has a unit or is an ``extent`` (a value in a dimension)."""
        parts = self._parts(chunk, toks)
        if parts is None:
            return None
        qualifier, numbers, unit, problem = parts
        start, end = toks[0].start, toks[-1].end
        if problem is None and min(numbers[:2]) <= 0:
            problem = "negative" if min(numbers[:2]) < 0 else "zero"
            problem += ": a size or a mass is more than zero"
        if problem is not None:
            if unit is not None or extent:
                reading.refuse(start, end, problem)
            return None
        if len(numbers) >= 2:
            lo, hi = sorted(numbers[:2])
            return Quantity((lo + hi) / 2, lo, hi, "range", unit, start, end, pos)
        value = numbers[0]
        low = value if qualifier == "at_least" else None
        high = value if qualifier == "at_most" else None
        return Quantity(value, low, high, qualifier, unit, start, end, pos)

    def _parts(self, chunk: Tree, toks: list[Token]) -> tuple[str, list[float], Unit | None, str | None] | None:
        """(qualifier, numbers, unit, why the quantity is refused or None) of a QUANT chunk; None when it
        has no well-formed number."""
        qualifier = "exact"
        plus = False
        numbers: list[float] = []
        unit: Unit | None = None
        problem: str | None = None
        j = 0
        for sub in chunk:
            if isinstance(sub, Tree):
                n = size(sub)
                part = toks[j : j + n]
                label = sub.label()
                if label == "HEDGE":
                    qualifier = _hedge_qualifier(part)
                elif label == "NUM":
                    value = _num(part)
                    if value is None:
                        return None
                    if plus and numbers:
                        numbers[-1] += value  # "an inch and a half"
                    else:
                        numbers.append(value)
                elif label == "RANGE":
                    values, range_unit = self._range(sub, part)
                    if values is None:
                        return None
                    numbers += values
                    unit = range_unit or unit
                elif label == "UNIT":
                    unit = self._units.get(part[0].low)
                elif label == "TAIL":  # "2 m 30", "5 ft 3": the tail in the smaller unit (joined chunks)
                    sub_unit, value = tail_unit(unit, self._units), _num(part)
                    one = combine(numbers[0], unit, value, sub_unit) if unit and sub_unit and value else None
                    numbers = [one] if isinstance(one, float) else numbers
                elif label == "SUB":  # "1 lb 2 oz", "5 ft 3 in": one quantity in two units
                    sub_unit = self._units.get(part[0].low)
                    if unit is not None and sub_unit is not None and len(numbers) == 2:
                        one = combine(numbers[0], unit, numbers[1], sub_unit)  # "5 ft 12 in" is refused
                        problem = one if isinstance(one, str) else problem
                        numbers = [numbers[0] if isinstance(one, str) else one]
                j += n
            else:
                if toks[j].tag == "HS":
                    qualifier = "about"
                plus = toks[j].tag == "UAND"
                j += 1
        return (qualifier, numbers, unit, problem) if numbers else None

    def _range(self, chunk: Tree, toks: list[Token]) -> tuple[list[float] | None, Unit | None]:
        """The numbers of a RANGE chunk (None when one is not well formed) and its inner unit ("3 cm to 4")."""
        numbers: list[float] = []
        unit: Unit | None = None
        r = 0
        for rsub in chunk:
            if isinstance(rsub, Tree):
                rn = size(rsub)
                if rsub.label() == "NUM":
                    value = _num(toks[r : r + rn])
                    if value is None:
                        return None, None
                    numbers.append(value)
                elif rsub.label() == "UNIT":
                    unit = self._units.get(toks[r].low)
                r += rn
            else:
                r += 1
        return numbers, unit


def _inherit_units(quants: list[Quantity]) -> None:
    """In a tuple, a number without a unit takes the unit of the next one that has one, else of the
    previous one ("7.5 x 7 x 4 cm")."""
    stated = [q.unit for q in quants]
    for i, q in enumerate(quants):
        if q.unit is None:
            after = next((u for u in stated[i + 1 :] if u is not None), None)
            before = next((u for u in reversed(stated[:i]) if u is not None), None)
            q.unit = after or before


_NOUN_ROLES = frozenset({*lx.LINEAR_ROLES, "diameter", "radius", "circumference"})


def _noun_took_other_unit(node: Any) -> bool:
    """True for a DIM chunk "<dimension noun> <quantity>" whose quantity is a mass or a volume."""
    if (
        not isinstance(node, Tree)
        or node.label() != "DIM"
        or isinstance(node[0], Tree)
        or node[0][1] != "DIMN"
    ):
        return False
    for sub in node:
        if isinstance(sub, Tree) and sub.label() == "QUANT":
            return any(
                isinstance(u, Tree) and u.label() == "UNIT" and u[0][1] in ("UMASS", "UVOL") for u in sub
            )
    return False


def _other_object(segment: list[Token], k: int) -> str | None:
    """For a quantity at ``k`` right after a possessive ("my 2 kg dumbbell", "my old 30 cm ruler"):
    "compared" when its sentence compares or places ("next to", "than", "beside", "heavier"), else
    "owned"; None without a possessive."""
    if not any(t.low in lx.POSSESSIVES for t in segment[max(0, k - 2) : k]):
        return None
    if any(w in lx.COMPARISON_WORDS for t in segment for w in t.low.split()):  # also "lighter than"
        return "compared"
    return "owned"


def _fill_context(segment: list[Token]) -> int | None:
    """Index in the segment of a contents word ("filled", "full", "contains": anywhere in the sentence;
    "with": before the volume, as "with 500 ml of ..."), or None; a capacity word ("capacity", "empty",
    "can hold") anywhere in the sentence cancels it."""
    found: int | None = None
    for i, tok in enumerate(segment):
        if tok.low in lx.CAPACITY_WORDS:
            return None
        if found is None and tok.low in lx.FILL_WORDS:
            if tok.low in lx.WEAK_FILL_WORDS:
                # "with 500 ml of water": only with "of" after the unit
                if not any(
                    t.low == "of" and segment[j - 1].tag in UNIT_TAGS
                    for j, t in enumerate(segment[i + 1 :], start=i + 1)
                ):
                    continue
            found = i
    return found


def _num(toks: Sequence[Token]) -> float | None:
    """The value of a NUM chunk's tokens, negative after a minus sign ("-10", "minus 5")."""
    words = [t.low for t in toks]
    if len(words) == 1 and words[0] in ("a", "an"):
        return 1.0
    value = number_value(words)
    if value is None:
        value = fraction_of(words)  # "half a million" (joined chunks)
    if value is not None and any(t.negative for t in toks):
        return -value
    return value


def _hedge_qualifier(toks: Sequence[Token]) -> str:
    quals = [lx.HEDGES.get(t.low, "about") for t in toks]
    for q in ("at_least", "at_most", "about"):
        if q in quals:
            return q
    return "exact"
