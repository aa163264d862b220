"""Label/value pairs of a page's visible text lines, in many languages.

Real stores write a measurement as a label and a value: in a table row (``<th>Gewicht</th><td>4,7 kg</td>``),
a definition list, a bullet (``Product Dimensions : 9.25 x 3 x 14.85 inches; 10.56 Ounces``), on two
lines (``Altura:`` / ``61 cm``), several on one line (``Altura: 61 cm Largura: 158 cm``), a header row of
labels over a row of values, or with the unit in the label (``Výška [mm]: 516``). :func:`pairs_from_lines`
turns the visible lines (:attr:`scrapers.page.Page.lines`) into :class:`Pair` s whose label
:func:`scrapers.labels.classify_label` (or :func:`~scrapers.labels.classify_other`) recognises; the
``spec_table`` adapter reads their values (:func:`scrapers.adapters.spec_table.observations_from_pairs`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from scrapers.labels import AXES, LabelInfo, classify_label, classify_other
from scrapers.page import Line
from scrapers.quantities import clean_text, length_unit, mass_unit, parse_length, parse_mass, unit_hint
from scrapers.sizes import parse_dims

__all__ = [
    "DIGIT", "LENGTH_KINDS", "MAX_PAIRS", "Pair", "family_of", "has_unit", "is_unit", "lists_variants", "own_part_pairs", "pairs_from_lines",
    "split_inline",
]

#: Reading stops after this many recognised measurement pairs. Real product pages state at most a few
#: dozen (23 on the richest page measured); a page with thousands is a parts list or a spec dump, and the
#: product's own values come first.
MAX_PAIRS = 400
_AXIS_LETTER_END = re.compile(r"(?<=\s)[HWDLBT]\.?\s*$")
_PUNCT_ONLY = re.compile(r"[\W_]+")
_BARE_NUMBER = re.compile(r"\d+(?:[.,]\d+)*")
_SEPARATOR = re.compile(r"\s*(?::|\s[—–]\s|=)\s*")
DIGIT = re.compile(r"\d")
_MAX_LABEL_WORDS = 6
#: The last field bar before a label (``| lens height:``, ``• Weight:``): the label's words start after it.
_FIELD_BAR = re.compile(r"[|•·](?!.*[|•·])\s*")
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


def split_inline(text: str) -> list[tuple[str, str, LabelInfo]]:
    """Recognised ``label: value`` pairs within one line (several per line allowed), or a label followed
    directly by a number (``Gewicht 4,7 kg``).

    Before each separator (``:``, a spaced dash, ``=``) the longest run of up to six words that
    :func:`classify_label` recognises is the label; its value runs to where the next label starts (the
    last word before the next separator when that one is not recognised)."""
    text = clean_text(text)
    seps = list(_SEPARATOR.finditer(text))
    labelled: list[tuple[str, LabelInfo, int]] = []  # label, what it names, where its value starts
    starts: list[int] = []  # where each separator's label starts
    prev_end = 0
    for k, sep in enumerate(seps):
        bar = _FIELD_BAR.search(text, prev_end, sep.start()) if k > 0 else None
        if bar:
            prev_end = bar.end()  # "70mm | lens height: 42mm": a new field starts at "|"
        first_field = k == 0 or bar is not None
        words = list(re.finditer(r"\S+", text[prev_end : sep.start()]))
        label_start = bar.start() if bar else prev_end + words[-1].start() if words else sep.start()
        # Before a field's first separator every word is the label's: "Cable length: 75 cm" names a part,
        # not a length ("length" alone is only the label when nothing precedes it).
        shortest = max(1, len(words)) if first_field and len(words) <= _MAX_LABEL_WORDS else 1
        for n in range(min(_MAX_LABEL_WORDS, len(words)), shortest - 1, -1):
            first = words[-n].group(0)
            if k > 0 and (DIGIT.search(first) or is_unit(first.rstrip(";,|"))):
                continue  # "Weight: 2 kg Height: 30 cm", "Height: 30 cm; Width: 20 cm": "kg", "cm;" end the
                # previous value, they start no label
            cand_start = prev_end + words[-n].start()
            info = classify_label(text[cand_start : sep.start()])
            if info is not None:
                labelled.append((text[cand_start : sep.start()], info, sep.end()))
                label_start = cand_start
                break
        else:
            if first_field and words and (other := classify_other(text[prev_end + words[0].start() : sep.start()])):
                labelled.append((text[prev_end + words[0].start() : sep.start()], other, sep.end()))
                label_start = prev_end + words[0].start()
        starts.append(label_start)
        prev_end = sep.end()
    out: list[tuple[str, str, LabelInfo]] = []
    value_starts = {start for _, _, start in labelled}
    recognised = [sep.end() in value_starts for sep in seps]
    for label, info, value_start in labelled:
        end = _value_end(text, value_start, starts, recognised)
        value = text[value_start:end].strip(" ;,|•·")
        if DIGIT.search(value):
            out.append((label, value, info))
    if not seps:
        # "Gewicht 4,7 kg"; "Length 70 cm, chest width 52 cm, in size L": each clause a label and a number
        # "サイズ 文庫判/ページ数 170p/高さ 16cm": fields separated by slashes, each its own clause
        fields = _FIELD_SLASH.search(text) is not None
        clauses = _FIELD_SLASH.split(text) if fields else _CLAUSE.split(text)
        for clause in clauses:
            found = _label_then_number(clause)
            if found is None:
                if clause is clauses[0] and not fields:
                    break
                continue
            out.append(found if len(clauses) == 1 else (found[0], found[1].strip(" ,;"), found[2]))
    return out


# A clause boundary: a comma or semicolon, a space and a word ("4,7 kg", "H21.6, W9.1" have none).
#: A slash between fields (``文庫判/ページ数 170p/高さ 16cm``): followed by two letters, so ``30/20/10 cm`` and
#: ``cm/inch`` are not split.
_FIELD_SLASH = re.compile(r"\s*/\s*(?=[^\W\d_]{2})(?![^\W\d_]{1,6}\b\s*$)")
_CLAUSE = re.compile(r"[;,]\s+(?=[^\W\d_]{2})")


_MEASURED = re.compile(r"\d\s*(?:([^\W\d_]{1,12}\.?)(?![^\W_])|([\"'″]))")


def has_unit(text: str) -> bool:
    """Whether ``text`` holds a number followed by a unit (``2 kg``, ``30"``, ``20"W``)."""
    return any(m.group(2) or is_unit(m.group(1).rstrip(".")) for m in _MEASURED.finditer(text))


def _value_end(text: str, value_start: int, starts: list[int], recognised: list[bool]) -> int:
    """Where a value that starts at ``value_start`` ends: where the next label starts. An unrecognised
    "label" before a separator ends it only once the value holds a measured number (``Weight: Surface
    Pro 9 i5, i7: 879 g`` keeps ``i7: 879 g``; ``Weight: 2 kg Colour: red`` stops before ``Colour``)."""
    for start, known in zip(starts, recognised, strict=True):
        if start >= value_start and (known or has_unit(text[value_start:start])):
            return start
    return len(text)


def _label_then_number(text: str) -> tuple[str, str, LabelInfo] | None:
    m = DIGIT.search(text)
    if not m or m.start() == 0:
        return None
    cut = m.start()
    letter = _AXIS_LETTER_END.search(text[:cut])  # "Size H21.6, W9.1, D1.5cm": H belongs to the value
    if letter:
        cut = letter.start()
    label = text[:cut]
    info = classify_label(label) or classify_other(label)
    return (label.strip(), text[cut:], info) if info is not None else None


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
    (``<br>``-separated) or both marked as list entries (``- 13,3 x 21,2 cm``). A table row's cells are
    neither: a row of values per model (``Width | 30.41 cm | 34.04 cm``) keeps its first cell the product's."""
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


def _with_heading_unit(pair: Pair, headings: dict[str, tuple[str, str, int]], i: int) -> Pair:
    """``pair`` with the unit of the heading above it when its label states none (a Play.com style
    ``Dimensions (mm)`` block of ``Width: 923`` rows)."""
    if pair.info.unit is not None or pair.info.role != "product":
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
    the labels are not as many values."""
    labels = []
    j = i
    while j < len(lines) and _label_line(lines[j]) and len(labels) < 12:
        labels.append(lines[j])
        j += 1
    values = lines[j : j + len(labels)]
    if len(values) < len(labels) or not all(DIGIT.search(v.text) and classify_label(v.text) is None for v in values):
        return []
    return [
        Pair(lab.text, val.text, classify_label(lab.text), lab.package or val.package, val.index, val.group)
        for lab, val in zip(labels, values, strict=False)
    ]


def is_unit(text: str) -> bool:
    return len(text) <= 12 and (length_unit(text) is not None or mass_unit(text) is not None)


def _stem(word: str) -> str:
    return word[:-1] if len(word) > 3 and word.endswith("s") else word


#: A screen's size is its diagonal, never an extent of the product, even on a monitor's page ("IPS Display").
_SCREEN = re.compile(r"display|screen|bildschirm|écran|ecran|pantalla|schermo|tela|ekran|экран|panel", re.IGNORECASE)


_TITLE_BAR = re.compile(r"\s[|｜]\s")  # a title's name | a tagline or the store's name


def own_part_pairs(pairs: list[Pair], title: str | None) -> list[Pair]:
    """Pairs whose part's label names the product itself (``Robot Weight`` on a robot vacuum's page,
    ``Speaker Dimensions`` on a speaker's: every word of the part in the page title) as the product's,
    when no label of the page states the product's own value of that feature (mass or size): a fallback,
    so a robot's ``Base Dimensions`` beside its ``Dimensions`` stays the base's. The title's name ends at a bar
    (``Desk Converter | Compact, Adjustable Keyboard Tray``: a tagline's feature stays a part)."""
    words = {_stem(w) for w in re.findall(r"[^\W\d_]+", _TITLE_BAR.split(title or "")[0].lower())}
    if not words:
        return pairs

    def feature(info) -> str:
        return "mass" if info.kind == "weight" else "dims"

    stated = {feature(p.info) for p in pairs if p.info.role == "product" and not (p.package or p.info.package)}
    out = []
    for p in pairs:
        info = p.info
        if (
            info.role == "component"
            and info.part
            and feature(info) not in stated
            and {_stem(w) for w in info.part.split()} <= words
            and not (feature(info) == "dims" and _SCREEN.search(info.part))
        ):
            p = replace(p, info=replace(info, role="product", part=None))
        out.append(p)
    return out
