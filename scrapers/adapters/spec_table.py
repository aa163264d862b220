"""Spec tables, definition lists, detail bullets and label/value lines, in many languages.

Real stores write a measurement as a label and a value: in a table row (``<th>Gewicht</th><td>4,7 kg</td>``),
a definition list, a bullet (``Product Dimensions : 9.25 x 3 x 14.85 inches; 10.56 Ounces``), on two
lines (``Altura:`` / ``61 cm``), several on one line (``Altura: 61 cm Largura: 158 cm``) or with the
unit in the label (``Výška [mm]: 516``, ``Габариты (ВхШхГ), см: 184х54х60``). This module turns the
page's visible text lines (:attr:`scrapers.page.Page.lines`) into (label, value) pairs, keeps those whose
label :func:`scrapers.labels.classify_label` recognises, and reads their values. Separate length, width,
height... fields become one dimensions observation (see :func:`observations_from_pairs`).

The ``embedded_json`` adapter (:mod:`scrapers.adapters.embedded_json`) reads the page's embedded state into
the same pairs.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from kb.features import MAX_DIM_CM, MAX_MASS_G
from scrapers.adapters import Observation, adapter
from scrapers.labels import AXES, LabelInfo, classify_label, classify_other
from scrapers.normalize import material_from_text
from scrapers.page import Line, Page
from scrapers.quantities import (
    clean_text,
    length_unit,
    mass_unit,
    parse_dims,
    parse_length,
    parse_length_range,
    parse_mass,
    third_axis,
)

__all__ = ["MAX_PAIRS", "Pair", "observations_from_pairs", "pairs_from_lines", "split_inline"]

#: Separate axis fields further apart than this many lines are not one product's dimensions.
AXIS_GROUP_GAP = 8
#: Reading stops after this many recognised measurement pairs. Real product pages state at most a few
#: dozen (23 on the richest page measured); a page with thousands is a parts list or a spec dump, and the
#: product's own values come first.
MAX_PAIRS = 400
#: A weight range no wider than this ratio (``1,2 – 1,5 kg``: a handmade piece) gives its midpoint; a wider
#: one (``1.01 - 7.2 lbs``: variants of different sizes) is not used.
NARROW_RANGE = 1.5
_AXIS_LETTER_END = re.compile(r"(?<=\s)[HWDLBT]\.?\s*$")
_PUNCT_ONLY = re.compile(r"[\W_]+")
_BARE_NUMBER = re.compile(r"\d+(?:[.,]\d+)*")
_SEPARATOR = re.compile(r"\s*(?::|\s[—–]\s|=)\s*")
_DIGIT = re.compile(r"\d")
_MAX_LABEL_WORDS = 6
_CODE = re.compile(r"[{}<>;]|\":|:\s*\"")  # JSON, CSS or markup inside a string is not a spec line


@dataclass(frozen=True)
class Pair:
    """A label and its value text as the page shows them, with the line context."""

    label: str
    value: str
    info: LabelInfo
    package: bool = False
    order: int = 0
    group: int | None = None


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
        words = list(re.finditer(r"\S+", text[prev_end : sep.start()]))
        label_start = prev_end + words[-1].start() if words else sep.start()
        # Before a line's first separator every word is the label's: "Cable length: 75 cm" names a part,
        # not a length ("length" alone is only the label when nothing precedes it).
        shortest = max(1, len(words)) if k == 0 and len(words) <= _MAX_LABEL_WORDS else 1
        for n in range(min(_MAX_LABEL_WORDS, len(words)), shortest - 1, -1):
            first = words[-n].group(0)
            if k > 0 and (_DIGIT.search(first) or _is_unit(first)):
                continue  # "Weight: 2 kg Height: 30 cm": "kg" ends the previous value, it starts no label
            cand_start = prev_end + words[-n].start()
            info = classify_label(text[cand_start : sep.start()])
            if info is not None:
                labelled.append((text[cand_start : sep.start()], info, sep.end()))
                label_start = cand_start
                break
        else:
            if k == 0 and words and (other := classify_other(text[prev_end + words[0].start() : sep.start()])):
                labelled.append((text[prev_end + words[0].start() : sep.start()], other, sep.end()))
                label_start = prev_end + words[0].start()
        starts.append(label_start)
        prev_end = sep.end()
    out: list[tuple[str, str, LabelInfo]] = []
    for label, info, value_start in labelled:
        end = next((s for s in starts if s >= value_start), len(text))
        value = text[value_start:end].strip(" ;,|")
        if _DIGIT.search(value):
            out.append((label, value, info))
    if not seps:
        # "Gewicht 4,7 kg"; "Length 70 cm, chest width 52 cm, in size L": each clause a label and a number
        clauses = _CLAUSE.split(text)
        for clause in clauses:
            found = _label_then_number(clause)
            if found is None:
                if clause is clauses[0]:
                    break
                continue
            out.append(found if len(clauses) == 1 else (found[0], found[1].strip(" ,;"), found[2]))
    return out


# A clause boundary: a comma or semicolon, a space and a word ("4,7 kg", "H21.6, W9.1" have none).
_CLAUSE = re.compile(r"[;,]\s+(?=[^\W\d_]{2})")


def _label_then_number(text: str) -> tuple[str, str, LabelInfo] | None:
    m = _DIGIT.search(text)
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
    n = len(lines)
    column_values: set[int] = set()  # value lines already paired by a header row
    for i, line in enumerate(lines):
        if len(pairs) >= MAX_PAIRS:
            break
        if i in column_values:
            continue
        text = line.text
        info = (classify_label(text) or classify_other(text)) if len(text) <= 80 else None
        if info is not None and info.role == "product" and i + 1 < n and _label_line(lines[i + 1]) and not (i and _label_line(lines[i - 1])):
            header = _header_row(lines, i)
            if header:
                pairs.extend(header)
                column_values.update(p.order for p in header)
                continue
        if info is not None:
            j = i + 1
            while j < n and j <= i + 2 and _PUNCT_ONLY.fullmatch(lines[j].text):
                j += 1
            if j < n:
                nxt = lines[j]
                value = nxt.text
                if _DIGIT.search(value) and classify_label(value) is None:
                    if j + 1 < n and _BARE_NUMBER.fullmatch(value) and _is_unit(lines[j + 1].text):
                        value = f"{value} {lines[j + 1].text}"
                    pairs.append(Pair(text, value, info, line.package or nxt.package, line.index, nxt.group))
                    continue  # the value line is still read for pairs of its own ("Width: 30 cm")
        if _DIGIT.search(text) and len(text) <= 600:
            for label, value, label_info in split_inline(text):
                pairs.append(Pair(label, value, label_info, line.package, line.index, line.group))
    return pairs


def _label_line(line: Line) -> bool:
    return len(line.text) <= 80 and not _DIGIT.search(line.text) and classify_label(line.text) is not None


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
    if len(values) < len(labels) or not all(_DIGIT.search(v.text) and classify_label(v.text) is None for v in values):
        return []
    return [
        Pair(lab.text, val.text, classify_label(lab.text), lab.package or val.package, val.index, val.group)
        for lab, val in zip(labels, values, strict=False)
    ]


def mass_unit_of_range(value: str, label_unit: str | None) -> bool:
    """Whether a range's unit (written after it, or the label's) is a mass unit."""
    m = re.search(r"\d\s*([^\W\d_]+)\.?\s*(?:\(|$|[,;])", clean_text(value))
    unit = m.group(1) if m else label_unit
    return mass_unit(unit) is not None if unit else False


def _is_unit(text: str) -> bool:
    return len(text) <= 12 and (length_unit(text) is not None or mass_unit(text) is not None)


def _plausible_mass(value: str, unit: str | None, dc: bool | None) -> tuple[float | None, str | None]:
    """The mass in ``value``; when that reading is absurd and the other decimal-mark reading is not,
    the other one, with a note."""
    mass = parse_mass(value, unit, dc)
    if mass is not None and mass > MAX_MASS_G:
        retry = parse_mass(value, unit, not dc)
        if retry is not None and retry <= MAX_MASS_G:
            mark = "decimal comma" if not dc else "decimal point"
            return retry, f"read {value.strip()!r} with a {mark} (the other reading is absurd)"
    return mass, None


def observations_from_pairs(
    pairs: Iterable[Pair], decimal_comma: bool | None, rank: int = 1
) -> list[Observation]:
    """Observations read from recognised pairs. Combined values (``A x B x C``, with a mass after ``;``)
    give one dims observation; single-axis fields in a row (length, width, height, depth, diameter,
    thickness; a new row starts when an axis repeats, the package context changes or the fields are
    more than :data:`AXIS_GROUP_GAP` lines apart) give one dims observation per row of two or more."""
    obs: list[Observation] = []
    axes: list[tuple[str, float, Pair, int, str | None]] = []
    for pair in pairs:
        info = pair.info
        raw = f"{pair.label}: {pair.value}"[:200]
        package = pair.package or info.package
        if info.role != "product":
            obs.extend(_other_observations(pair, raw, decimal_comma, rank))
            continue
        if info.kind in ("dimensions", "size"):
            dims = parse_dims(pair.value, info.unit, decimal_comma)
            rest = pair.value
            if dims:
                d = dims[0]
                note = None
                if max(d.values_cm) > MAX_DIM_CM:
                    again = parse_dims(pair.value, info.unit, not decimal_comma)
                    if again and max(again[0].values_cm) <= MAX_DIM_CM:
                        d, note = again[0], "read with a decimal comma (the other reading is absurd)"
                rest = pair.value.split(d.text.split()[-1], 1)[-1] if d.text else pair.value
                values, roles = d.values_cm, d.roles
                if len(info.order) == len(values) and set(roles) <= {"extent"}:
                    roles = info.order  # "Dimensions (H x W x D): 17.9 x 359.3 x 235.6 mm"
                if len(values) == 2:
                    extra = third_axis(rest, decimal_comma)  # "8\" x 10\" and is 3/4\" thick"
                    if extra is not None:
                        values, roles = (*values, extra), (*roles, "extent")
                obs.append(
                    Observation("dims", values, package, rank, pair.order, pair.group, raw, note, roles=roles)
                )
            if info.kind == "dimensions":
                mass, note = _plausible_mass(rest, None, decimal_comma)
                if mass is not None:
                    obs.append(Observation("mass", mass, package, rank, pair.order, pair.group, raw, note))
        elif info.kind == "weight":
            mass, note = _plausible_mass(pair.value, info.unit, decimal_comma)
            if mass is not None:
                obs.append(Observation("mass", mass, package, rank, pair.order, pair.group, raw, note))
            elif (rng := parse_length_range(pair.value, info.unit or "kg", decimal_comma)) is not None:
                low, high = rng
                if mass_unit_of_range(pair.value, info.unit) and high <= NARROW_RANGE * low:
                    # "ca. 1,2 – 1,5 kg" (a handmade piece): the midpoint, one rank weaker, with a note
                    obs.append(
                        Observation(
                            "mass", round((low + high) / 2, 6), package, rank + 1, pair.order, pair.group,
                            raw, f"weight given as a range ({raw}); took the midpoint",
                        )
                    )  # fmt: skip
                else:
                    obs.append(
                        Observation("warning", f"weight given as a range ({raw}); not used", order=pair.order)
                    )
        elif info.kind in AXES and (joint := _axes_in_one_value(pair, decimal_comma)) is not None:
            obs.append(joint)  # "Diameter 30cm x Height 15cm": one value naming its axes
        elif info.kind in AXES:
            length = parse_length(pair.value, info.unit, decimal_comma)
            note = None
            if length is None:
                rng = parse_length_range(pair.value, info.unit, decimal_comma)
                if rng is None:
                    continue
                length, note = range_extent(info.kind, rng, raw)
            axes.append((info.kind, length, pair, rank if note is None else rank + 1, note))
    obs.extend(_group_axes(axes))
    return obs


def _axes_in_one_value(pair: Pair, decimal_comma: bool | None) -> Observation | None:
    """``Diameter 30cm x Height 15cm``, ``Width: 30 cm x Height 20 cm``: an axis label whose value goes
    on with more axes, read as one size with each extent's role; None otherwise."""
    if " x " not in clean_text(pair.value):
        return None
    found = parse_dims(f"{pair.label} {pair.value}", pair.info.unit, decimal_comma)
    if not found or "extent" in found[0].roles:
        return None
    d = found[0]
    raw = f"{pair.label}: {pair.value}"[:200]
    return Observation("dims", d.values_cm, pair.package, 1, pair.order, pair.group, raw, roles=d.roles)


def _other_observations(pair: Pair, raw: str, decimal_comma: bool | None, rank: int) -> list[Observation]:
    """A component's or capacity's value as a candidate that is not the product's (the chooser lists it
    as an alternative and never picks it)."""
    info = pair.info
    if info.kind == "weight":
        mass = parse_mass(pair.value, info.unit, decimal_comma)
        found = [("mass", mass, ())] if mass is not None else []
    elif info.kind in ("dimensions", "size"):
        dims = parse_dims(pair.value, info.unit, decimal_comma)
        found = [("dims", dims[0].values_cm, dims[0].roles)] if dims else []
    else:
        length = parse_length(pair.value, info.unit, decimal_comma)
        found = [("dims", (length,), (info.kind,))] if length is not None else []
    return [
        Observation(f, v, pair.package, rank, pair.order, pair.group, raw, roles=r, role=info.role)
        for f, v, r in found
    ]


def range_extent(kind: str, rng: tuple[float, float], raw: str) -> tuple[float, str]:
    """The extent a range of one axis gives, with the note saying so. A narrow range (high at most
    :data:`NARROW_RANGE` x low: ``30-32 cm``, ``adjustable from 90 to 110 cm``, a tolerance or the
    object's own adjustment) gives its **upper** bound, the most room the object needs; a wide one
    (``15.5" - 116.5"``: a pendant's hanging reach, variants of different sizes) gives its lower bound,
    the object's own extent."""
    low, high = rng
    if high <= NARROW_RANGE * low:
        return high, f"{kind} given as a range ({raw}); took the upper bound {high:g} cm"
    return low, f"{kind} given as a wide range ({raw}); took the lower bound {low:g} cm (the object's own)"


def _group_axes(axes: list[tuple[str, float, Pair, int, str | None]]) -> Iterator[Observation]:
    """Rows of single-axis fields as dims observations (see :func:`observations_from_pairs`). When no row
    has two axes, a lone axis is still the product's one stated dimension (``Diameter: 12 cm``), one
    rank weaker."""
    rows: list[list[tuple[str, float, Pair, int, str | None]]] = []
    for item in axes:
        kind, _, pair, _, _ = item
        row = rows[-1] if rows else None
        if row:
            last = row[-1][2]
            package_changed = (last.package or last.info.package) != (pair.package or pair.info.package)
            if kind in {k for k, *_ in row} or package_changed or pair.order - last.order > AXIS_GROUP_GAP:
                row = None
        if row is None:
            rows.append([item])
        else:
            row.append(item)
    multi = [r for r in rows if len(r) >= 2]
    for row in multi or rows[:1]:
        first = row[0][2]
        extents = [(k, v) for k, v, *_ in row]
        if len(extents) > 3:
            # a pan's "Diameter 26 cm" next to its length, width and height: the diameter is a part's
            extents = [(k, v) for k, v in extents if k != "diameter"]
        raw = "; ".join(f"{p.label}: {p.value}" for _, _, p, _, _ in row)[:300]
        notes = "; ".join(n for *_, n in row if n) or None
        package = any(p.package or p.info.package for _, _, p, _, _ in row)
        rank = max(r for *_, r, _ in row) + (0 if multi else 1)
        yield Observation(
            "dims", tuple(v for _, v in extents), package, rank, first.order, first.group, raw, notes,
            roles=tuple(k for k, _ in extents),
        )  # fmt: skip


_MATERIAL_HINT = re.compile(
    r"ateri|atéri|atièr|werkstoff|атериал|materyal|malzeme|材質|材质|素材|재질|소재", re.IGNORECASE
)
_MATERIAL_LABEL = re.compile(
    r"(?:primary |main |frame |body |product |top )?(?:material|materials|materiał(?: wykonania)?|matériau|"
    r"matériaux|matière|werkstoff|materiale|materiali|materiais|material principal|материал|материал корпуса|"
    r"materyal|malzeme|materiál|材質|材质|素材|재질|소재)"
    # the product's (or its frame's) material, not a part's: "Материал изделия", "Material de la estructura"
    r"(?: (?:изделия|товара|корпуса|produktu|výrobku|del producto|del artículo|de la estructura|"
    r"de l'article|du produit|dell'articolo|do produto|des produkts|des artikels|principal|główny|ana))?",
    re.IGNORECASE,
)


def material_observations(lines: list[Line]) -> list[Observation]:
    """``Material: Plástico`` lines (label and value on one line or two), first known material first."""
    obs = []
    for i, line in enumerate(lines):
        if not _MATERIAL_HINT.search(line.text):
            continue
        text = clean_text(line.text)
        label, _, value = text.partition(":")
        if not value.strip():
            if i + 1 >= len(lines) or len(text) > 40:
                continue
            value = lines[i + 1].text
        if _MATERIAL_LABEL.fullmatch(label.strip().rstrip(":").strip()):
            material = material_from_text(value[:120])
            if material:
                obs.append(Observation("material", material, order=line.index, raw=f"{label}: {value}"[:200]))
    return obs


def selected_variant(page: Page) -> list[Observation]:
    """The size of the variant a page has selected (``<option selected>Mattress 2'6" x 6'6" (75 x 200 x 22
    cm)</option>``): a page that sells several sizes shows the product's in its picker, while its size
    table lists every variant. The most complete size in the option's text, rank 0 (it beats the table's
    rows); nothing when the option names no size."""
    tree = page.tree
    if tree is None:
        return []
    obs = []
    for option in tree.xpath("//select//option[@selected]")[:20]:
        text = " ".join(option.itertext()).strip()[:300]
        found = parse_dims(text, None, page.decimal_comma) if _DIGIT.search(text) else []
        if found:
            best = max(found, key=lambda d: len(d.values_cm))
            obs.append(
                Observation(
                    "dims", best.values_cm, rank=0, raw=f"selected option: {text}"[:200], roles=best.roles,
                    note=f"the size of the selected variant ({text[:80]!r})",
                )
            )  # fmt: skip
    return obs[:1]


@adapter("spec_table", priority=50)
def spec_table(page: Page) -> list[Observation]:
    """Spec tables, definition lists, detail bullets and label/value lines of the visible page, and the
    size of the selected variant."""
    obs = observations_from_pairs(pairs_from_lines(page.lines), page.decimal_comma)
    return obs + selected_variant(page) + material_observations(page.lines)
