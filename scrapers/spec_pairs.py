"""Label/value pairs of a page's visible text lines, in many languages.

Real stores write a measurement as a label and a value: in a table row (``<th>Gewicht</th><td>4,7 kg</td>``),
a definition list, a bullet (``Product Dimensions : 9.25 x 3 x 14.85 inches; 10.56 Ounces``), on two
lines (``Altura:`` / ``61 cm``), several on one line (``Altura: 61 cm Largura: 158 cm``), a header row of
labels over a row of values, or with the unit in the label (``Výška [mm]: 516``). :func:`pairs_from_lines`
turns the visible lines (:attr:`scrapers.page.Page.lines`) into :class:`Pair` s whose label
:func:`scrapers.labels.classify_label` (or :func:`~scrapers.labels.classify_other`) recognises; the
``spec_table`` adapter reads their values (:func:`scrapers.adapters.spec_table.observations_from_pairs`).
Pairs within one line are :mod:`scrapers.inline_pairs`' (re-exported here); whose value a pair states once
all are read, :mod:`scrapers.pair_roles`'.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from scrapers.inline_pairs import DIGIT, has_unit, is_unit, split_inline
from scrapers.label_vocabulary import QUALIFIERS, fold
from scrapers.labels import AXES, LabelInfo, classify_label, classify_other
from scrapers.page import Line
from scrapers.quantities import length_unit, mass_unit, parse_length, parse_mass, unit_hint
from scrapers.sizes import parse_dims

__all__ = [
    "CODE", "DIGIT", "LENGTH_KINDS", "MAX_PAIRS", "Pair", "family_of", "has_unit", "is_unit", "lists_variants",
    "pairs_from_lines", "split_inline",
]

#: Reading stops after this many recognised measurement pairs. Real product pages state at most a few
#: dozen (23 on the richest page measured); a page with thousands is a parts list or a spec dump, and the
#: product's own values come first.
MAX_PAIRS = 400
_PUNCT_ONLY = re.compile(r"[\W_]+")
_BARE_NUMBER = re.compile(r"\d+(?:[.,]\d+)*")
CODE = re.compile(r"[{}<>;]|\":|:\s*\"")  # JSON, CSS or markup inside a string is not a spec line


@dataclass(frozen=True)
class Pair:
    """A label and its value text as the page shows them, with the line context."""

    label: str
    value: str
    info: LabelInfo
    package: bool = False
    order: int = 0
    group: int | None = None
    #: Where the unit of a value written without one comes from (a heading line ``Dimensions (mm)`` above
    #: the pairs), for ``--explain``; None when the label or the value states it.
    unit_context: str | None = None



def pairs_from_lines(lines: list[Line]) -> list[Pair]:
    """Label/value pairs from visible text lines: a label line followed by a value line (a lone ``:``
    between them is skipped; a unit alone on the line after a bare number joins it), or pairs within
    one line."""
    pairs: list[Pair] = []
    column_values: set[int] = set()  # value lines already paired by a header row
    headings: dict[str, tuple[str, str, int]] = {}  # unit family -> (unit, heading text, line)
    for i, line in enumerate(lines):
        if len(pairs) >= MAX_PAIRS:
            break
        if i in column_values:
            continue
        text = line.text
        if DIGIT.search(text) is None and _reads_nothing(text):
            continue  # most lines (menus, prose) start no pair and state no heading
        if (heading := _heading_unit(text)) is not None and not _labels_a_value(lines, i):
            headings[heading[0]] = (heading[1], text, i)
        elif (heading := _column_unit(lines, i)) is not None:
            headings[heading[0]] = (heading[1], f"{text} {lines[i + 1].text}", i + 1)
        before = len(pairs)
        _pairs_at(lines, i, pairs, column_values)
        if headings and len(pairs) > before:
            pairs[before:] = [_with_heading_unit(p, headings, i) for p in pairs[before:]]
    return pairs


def _reads_nothing(text: str) -> bool:
    """Whether a line without a digit is no label (:func:`classify_label`, :func:`classify_other`) and no unit
    heading (:func:`_heading_unit`): then it starts nothing in :func:`pairs_from_lines` (the same tests, cheaply)."""
    if len(text) > 80:
        return True
    if classify_label(text) is not None or classify_other(text) is not None:
        return False
    return len(text) > 60 or _UNIT_HINT_MARK.search(text) is None


def _pairs_at(lines: list[Line], i: int, pairs: list[Pair], column_values: set[int]) -> None:
    """The pairs line ``i`` starts, appended to ``pairs``."""
    n = len(lines)
    line = lines[i]
    text = line.text
    info = (classify_label(text) or classify_other(text)) if len(text) <= 80 else None
    if info is not None and info.role == "product" and i + 1 < n and _label_line(lines[i + 1]) and not (i and _label_line(lines[i - 1])):
        header = _header_row(lines, i)
        if header:
            pairs.extend(header)
            column_values.update(p.order for p in header)
            column_values.update(range(i + 1, i + len(header)))  # its other labels: no label/value pair of their own
            return
    if info is not None:
        j = i + 1
        while j < n and j <= i + MAX_FILLER_LINES and _filler(lines[j].text):
            j += 1
        if j < n:
            nxt = lines[j]
            value = nxt.text
            if DIGIT.search(value) and classify_label(value) is None:
                if j + 1 < n and _BARE_NUMBER.fullmatch(value) and is_unit(lines[j + 1].text):
                    value = f"{value} {lines[j + 1].text}"
                elif info.role == "product" and j + 1 < n and _listed(nxt, lines[j + 1]) and lists_variants(
                    value, lines[j + 1].text, info
                ):
                    info = replace(info, role="variant")  # "Dimensions:" over "- 13,3 x 21,2 cm", "- 18 x 30,2 cm"
                pairs.append(Pair(text, value, info, line.package or nxt.package, line.index, nxt.group))
                return  # the value line is still read for pairs of its own ("Width: 30 cm")
    if DIGIT.search(text) and len(text) <= 600:
        for label, value, label_info in split_inline(text):
            pairs.append(Pair(label, value, label_info, line.package, line.index, line.group))


def _quantity(text: str, info: LabelInfo) -> tuple[float, ...] | None:
    """What a value line states for a label of ``info``'s kind: its mass, or its size's extents, largest first."""
    if info.kind == "weight":
        mass = parse_mass(text, info.unit)
        return None if mass is None else (mass,)
    dims = parse_dims(text, info.unit)
    if dims:
        return tuple(sorted(dims[0].values_cm, reverse=True))
    length = parse_length(text, info.unit)
    return None if length is None else (length,)


_LIST_MARK = re.compile(r"\s*[-–•*·]\s")


def _listed(line: Line, following: Line) -> bool:
    """Whether two value lines are entries of one list, one under the other: lines of one element
    (``<br>``-separated), options of one variant picker (``Line.picker``; an option the page marks
    selected is the product's, never listed), or both marked as list entries (``- 13,3 x 21,2 cm``). A
    table row's cells are none of these: a row of values per model (``Width | 30.41 cm | 34.04 cm``) keeps
    its first cell the product's."""
    if line.picker and (line.selected or line.picker == following.picker):
        return not line.selected
    if line.group == following.group:
        return True
    return bool(_LIST_MARK.match(line.text) and _LIST_MARK.match(following.text))


def lists_variants(value: str, following: str, info: LabelInfo) -> bool:
    """Whether a label's value line and the line after it are two of a list of values (one per variant):
    the next line holds no label of its own, and both state a quantity of the label's kind that differ by
    more than 2 % (``2 kg`` over ``4.4 lb`` is one weight written twice, not two variants)."""
    if not DIGIT.search(following) or len(following) > 120 or split_inline(following):
        return False
    if classify_label(following) is not None or classify_other(following) is not None:
        return False
    a, b = _quantity(value, info), _quantity(following, info)
    if a is None or b is None:
        return False
    return len(a) != len(b) or any(abs(x - y) > 0.02 * max(x, y) for x, y in zip(a, b, strict=True))


#: A heading's unit applies to the pairs of the next this many lines (one spec block).
HEADING_SCOPE = 40
LENGTH_KINDS = frozenset({*AXES, "dimensions", "size"})


def family_of(info: LabelInfo) -> str:
    """``"length"`` for a label of an extent (:data:`LENGTH_KINDS`), ``"mass"`` otherwise."""
    return "length" if info.kind in LENGTH_KINDS else "mass"


#: What a label stating its unit has (``(mm)``, ``, см``, ``in cm``): a cheap test before :func:`unit_hint`.
_UNIT_HINT_MARK = re.compile(r"[(\[（,]|\s(?:in|en|em)\s", re.IGNORECASE)


def _heading_unit(text: str) -> tuple[str, str] | None:
    """("length" or "mass", unit) for a heading line that states a unit for what follows and holds no
    value (``Dimensions (mm)``, ``Maße in cm``, ``Weight (kg)``, ``寸法(mm)``), else None."""
    if len(text) > 60 or DIGIT.search(text) or not _UNIT_HINT_MARK.search(text):
        return None
    unit = unit_hint(text)
    if unit is None or (classify_label(text) is None and not _value_heading(text)):
        return None
    if length_unit(unit) is not None:
        return "length", unit
    return ("mass", unit) if mass_unit(unit) is not None else None


#: Column headings that name a table's values, not a measurement: ``Value (cm)``, ``Wert [mm]``.
_VALUE_HEADINGS = frozenset("value values wert werte valeur valeurs valor valores valore valori wartość wartosc waarde".split())


def _value_heading(text: str) -> bool:
    """Whether ``text`` is a value column's heading with a unit in brackets (``Value (cm)``, ``Wert [mm]``)."""
    head = re.split(r"[(\[（]", text, maxsplit=1)[0].strip(" :").lower()
    return head in _VALUE_HEADINGS and head != text.strip().lower()


def _labels_a_value(lines: list[Line], i: int) -> bool:
    """Whether line ``i`` (a label stating a unit) is followed by its own value (``Verpackung - Höhe in cm``
    over ``49,00``): a row's label, not a heading for the rows below."""
    if i + 1 >= len(lines) or not DIGIT.search(nxt := lines[i + 1].text) or len(nxt) > 80:
        return False
    return classify_label(nxt) is None and not split_inline(nxt)  # "Width: 923" under it is a row of its own


def _column_unit(lines: list[Line], i: int) -> tuple[str, str] | None:
    """("length" or "mass", unit) when line ``i`` is a measurement label without a value and the next line
    is a unit alone: a table's header row whose column states the unit (``Dimension | cm | inch`` over
    ``Width | 30 | 11.8``, ``Weight | kg``). The first unit column is the one the values are read in."""
    if i + 1 >= len(lines):
        return None
    unit = lines[i + 1].text.strip("()[] ")
    if not _label_line(lines[i]) or not is_unit(unit):  # the cheap test first (labels are cached)
        return None
    if length_unit(unit) is not None:
        return "length", unit
    return ("mass", unit) if mass_unit(unit) is not None else None


_WORD = re.compile(r"[^\W\d_]{2,}")


def figures_only(value: str) -> bool:
    """Whether ``value`` (after a sub-label's colon) holds figures and no word but units and qualifiers
    (``923``, ``ca. 30 x 20``, ``5.20(w) x 8.00(h)``): a value a heading's unit may complete. A value naming
    something (``Eco Genuino 122 NT``: a variant table's model cell under the ``Gewicht (kg)`` column) is not
    a figure in that unit."""
    tail = value.rsplit(": ", 1)[-1]
    return all(is_unit(w) or fold(w) in QUALIFIERS for w in _WORD.findall(tail))


def _with_heading_unit(pair: Pair, headings: dict[str, tuple[str, str, int]], i: int) -> Pair:
    """``pair`` with the unit of the heading above it when its label states none (a Play.com style
    ``Dimensions (mm)`` block of ``Width: 923`` rows) and its value is figures (:func:`figures_only`)."""
    if pair.info.unit is not None or pair.info.role != "product" or not figures_only(pair.value):
        return pair
    family = family_of(pair.info)
    found = headings.get(family)
    if found is None or i - found[2] > HEADING_SCOPE or found[2] == pair.order:
        return pair
    unit, heading, _ = found
    return replace(pair, info=replace(pair.info, unit=unit), unit_context=f"the unit of the heading {heading!r}")


#: Lines a label's value may follow after: an info icon's letter, a tooltip's ``?``, ``approx.`` (sibling
#: elements between the label's and the value's: ``<span>Weight</span><span class=tip>i</span><p>3.2 kg``).
MAX_FILLER_LINES = 3
_MAX_FILLER_CHARS = 12


def _filler(text: str) -> bool:
    """Whether a line between a label and its value is filler: punctuation, or a short text without a
    digit that names no measurement (:func:`classify_label`, :func:`classify_other`)."""
    if _PUNCT_ONLY.fullmatch(text):
        return True
    return (len(text) <= _MAX_FILLER_CHARS and not DIGIT.search(text) and classify_label(text) is None
            and classify_other(text) is None)  # fmt: skip


def _label_line(line: Line) -> bool:
    return len(line.text) <= 80 and not DIGIT.search(line.text) and classify_label(line.text) is not None


def _header_row(lines: list[Line], i: int) -> list[Pair]:
    """A header row of labels and the row under it (``Width | Height | Depth`` over ``30 cm | 20 cm |
    10 cm``, or ``dt dt dt dd dd dd``): label k pairs with value k of the **first** row only (later rows are
    variants or other products). Pairs carry the value line's index as their order. [] when the lines after
    the labels are not as many values, or when a label repeats (a header row names each column once: a review
    form's ``Height`` legend over its ``Height`` title and the brackets ``<5ft``, ``5ft-5ft3``... is a list)."""
    labels = []
    j = i
    while j < len(lines) and _label_line(lines[j]) and len(labels) < 12:
        labels.append(lines[j])
        j += 1
    if len({fold(lab.text).strip(" :：") for lab in labels}) < len(labels):
        return []  # "Height" over "Height": a label written twice (a filter's legend and its title), no columns
    values = lines[j : j + len(labels)]
    if len(values) < len(labels) or not all(DIGIT.search(v.text) and classify_label(v.text) is None for v in values):
        return []
    return [
        Pair(lab.text, val.text, classify_label(lab.text), lab.package or val.package, val.index, val.group)
        for lab, val in zip(labels, values, strict=False)
    ]
