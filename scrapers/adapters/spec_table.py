"""Spec tables, definition lists, detail bullets and label/value lines, in many languages: their values.

The pairs themselves (a label and its value text, in table rows, lists, bullets, header rows) are found
by :mod:`scrapers.spec_pairs`; this module reads their values into observations (units, ranges, a
metric figure beside an imperial one, axis words inside a value, whose value it is). Separate length,
width, height... fields become one dimensions observation (see :func:`observations_from_pairs`).

The ``embedded_json`` adapter (:mod:`scrapers.adapters.embedded_json`) reads the page's embedded state into
the same pairs.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import replace

from kb.features import MAX_DIM_CM, MAX_MASS_G
from scrapers.adapters import Observation, adapter
from scrapers.axis_rows import AXIS_GROUP_GAP, group_axes, whole_product_weights
from scrapers.labels import AXES
from scrapers.normalize import material_from_text
from scrapers.page import Line, Page, lines_matching
from scrapers.pair_roles import (
    adjustable_extents,
    highest_settings,
    measured_packed,
    only_part_pairs,
    own_part_pairs,
)
from scrapers.quantities import (
    clean_text,
    mass_unit,
    parse_dims,
    parse_length,
    parse_length_range,
    parse_mass,
    third_axis,
)
from scrapers.sizes import AXIS_WORD_AFTER
from scrapers.spec_pairs import (
    DIGIT,
    LENGTH_KINDS,
    MAX_PAIRS,
    Pair,
    pairs_from_lines,
    split_inline,
)
from scrapers.unitless import UNITLESS_LETTERED, unitless_millimetres
from scrapers.value_forms import (
    NARROW_RANGE,
    axis_segments,
    bound_value,
    branded_part,
    fluid_ounces,
    for_one_size,
    keyed_variant,
    one_length,
    packed_value,
    sentence_value,
    written_value,
)

__all__ = ["AXIS_GROUP_GAP", "MAX_PAIRS", "Pair", "observations_from_pairs", "pairs_from_lines", "split_inline"]



def mass_unit_of_range(value: str, label_unit: str | None) -> bool:
    """Whether a range's unit (written after it, or the label's) is a mass unit."""
    m = re.search(r"\d\s*([^\W\d_]+)\.?\s*(?:\(|$|[,;])", clean_text(value))
    unit = m.group(1) if m else label_unit
    return mass_unit(unit) is not None if unit else False



def _plausible_mass(value: str, unit: str | None, dc: bool | None) -> tuple[float | None, str | None]:
    """The mass in ``value``; when that reading is absurd and the other decimal-mark reading is not,
    the other one, with a note. Ounces written beside a volume are a capacity, no mass (``4oz / 118ml``)."""
    if fluid_ounces(value):
        return None, None
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
    for pair in whole_product_weights(list(pairs)):
        n_axes = len(axes)
        found = _pair_observations(pair, decimal_comma, rank, axes)
        if (note := written_value(pair.value)[1]) is not None:
            for o in found:
                o.note = "; ".join(filter(None, [o.note, note]))
        if pair.unit_context:
            said = f"no unit beside the value ({pair.label}: {pair.value}): {pair.unit_context}"
            for o in found:
                o.note = "; ".join(filter(None, [o.note, said]))
            if len(axes) > n_axes:
                kind, length, p, r, note = axes[-1]
                axes[-1] = (kind, length, p, r, "; ".join(filter(None, [note, said])))
        unread = not found and len(axes) == n_axes
        if unread and pair.info.role == "product" and UNITLESS_LETTERED.fullmatch(clean_text(pair.value)):
            found = [Observation("warning", f"{pair.label}: {pair.value}: no unit stated (not in the value, "
                                 "its label or a heading above it); not used", order=pair.order)]
        if pair.info.shipping:
            for o in found:
                if o.feature in ("dims", "mass"):
                    o.role = "shipping"  # a shipment's value: kept apart from the product's box
        obs.extend(found)
    obs.extend(group_axes(axes))
    return obs


def _pair_observations(pair: Pair, decimal_comma: bool | None, rank: int, axes: list) -> list[Observation]:
    """The observations one recognised pair gives; single-axis fields are appended to ``axes`` instead."""
    out: list[Observation] = []
    info = pair.info
    raw = f"{pair.label}: {pair.value}"[:200]
    package = pair.package or info.package or packed_value(pair.value)
    if info.role == "product" and bound_value(pair.value):  # "Height: <5ft (152cm)": a limit, not a size
        info = replace(info, role="capacity")
        pair = replace(pair, info=info)
    value, written = written_value(pair.value)
    if value != pair.value:
        pair = replace(pair, value=value)
    if info.role == "product" and (for_one_size(pair.value) or keyed_variant(pair.value)):
        # "72 cm bei Größe S", "1-inch: 71"L x 24"W": one size's value, never the product's
        info = replace(info, role="variant")
        pair = replace(pair, info=info)
    if info.role == "product" and (brand := branded_part(pair.value)) is not None:
        info = replace(info, role="component", part=brand)  # "Thickness: Vibram® 5mm": the sole's
        pair = replace(pair, info=info)
    if info.role != "product":
        out.extend(_other_observations(pair, raw, decimal_comma, rank))
        return out
    if sentence_value(pair.value):  # a caption under "Dimensions": "The keyboard is placed on a 900 x 400 mm pad"
        return [Observation("warning", f"{raw[:80]}: a sentence under the label, not its value; not used",
                            order=pair.order)]  # fmt: skip
    if info.kind in ("dimensions", "size"):
        out.extend(_dims_pair_observations(pair, package, raw, decimal_comma, rank))
    elif info.kind == "weight":
        mass, note = _plausible_mass(pair.value, info.unit, decimal_comma)
        if mass is not None:
            out.append(Observation("mass", mass, package, rank, pair.order, pair.group, raw, note))
        elif (rng := parse_length_range(pair.value, info.unit or "kg", decimal_comma)) is not None:
            low, high = rng
            if mass_unit_of_range(pair.value, info.unit) and high <= NARROW_RANGE * low:
                # "ca. 1,2 – 1,5 kg" (a handmade piece): the midpoint, one rank weaker, with a note
                out.append(
                    Observation(
                        "mass", round((low + high) / 2, 6), package, rank + 1, pair.order, pair.group,
                        raw, f"weight given as a range ({raw}); took the midpoint",
                    )
                )  # fmt: skip
            else:
                out.append(
                    Observation("warning", f"weight given as a range ({raw}); not used", order=pair.order)
                )
    elif info.kind in AXES and (joint := _axes_in_one_value(pair, decimal_comma)) is not None:
        out.append(joint)  # "Diameter 30cm x Height 15cm": one value naming its axes
    elif info.kind in AXES and (size := parse_dims(pair.value, info.unit, decimal_comma)):
        # "Width: 5000 x 8 x 8 cm": a whole size in a single-dimension field is read as the size (every
        # extent, for the limits to judge), never as one of its figures
        d = size[0]
        note = f"a whole size in a {info.kind} field ({pair.value[:60]!r}); read as the size"
        out.append(Observation("dims", d.values_cm, package, rank, pair.order, pair.group, raw, note, roles=d.roles))
    elif info.kind in AXES:
        length = parse_length(pair.value, info.unit, decimal_comma)
        note = None
        if length is None:
            rng = parse_length_range(pair.value, info.unit, decimal_comma)
            if rng is None:
                return out
            length, note = range_extent(info.kind, rng, raw)
        axes.append((info.kind, length, pair, rank if note is None else rank + 1, note))
    return out

def _after_size(value: str, size_text: str) -> str:
    """What ``value`` says after the size :func:`parse_dims` read as ``size_text`` (a third axis, a mass);
    the reader writes axis words as letters ("inches high" -> "inches H"), so then it ends at the last
    axis word."""
    if not size_text:
        return value
    last = size_text.split()[-1]
    if last in value:
        return value.split(last, 1)[-1]
    words = list(AXIS_WORD_AFTER.finditer(value))
    return value[words[-1].end() :] if words else value


def _dims_pair_observations(
    pair: Pair, package: bool, raw: str, decimal_comma: bool | None, rank: int
) -> list[Observation]:
    """A dimensions or size pair: its ``A x B x C`` value with roles (the label's axis order when the value
    names none), a third axis written after a two-value size, the extents of axis words in the value
    (``幅30cm 奥行20cm 高さ10cm``) when they say more, and a mass after ``;`` for a dimensions label."""
    out: list[Observation] = []
    info = pair.info
    dims = parse_dims(pair.value, info.unit, decimal_comma)
    rest = pair.value
    segments = axis_segments(pair.value, info.unit, decimal_comma)
    if dims:
        d = dims[0]
        note = None
        if max(d.values_cm) > MAX_DIM_CM:
            again = parse_dims(pair.value, info.unit, not decimal_comma)
            if again and max(again[0].values_cm) <= MAX_DIM_CM:
                d, note = again[0], "read with a decimal comma (the other reading is absurd)"
        rest = _after_size(pair.value, d.text)
        values, roles = d.values_cm, d.roles
        if len(info.order) == len(values) and set(roles) <= {"extent"}:
            roles = info.order  # "Dimensions (H x W x D): 17.9 x 359.3 x 235.6 mm"
        if len(values) == 2:
            extra = third_axis(rest, decimal_comma)  # "8\" x 10\" and is 3/4\" thick"
            if extra is not None:
                values, roles = (*values, extra), (*roles, "extent")
        if len(segments) > len(values):
            values, roles = tuple(v for _, v in segments), tuple(k for k, _ in segments)
        out.append(Observation("dims", values, package, rank, pair.order, pair.group, raw, note, roles=roles))
    elif len(segments) >= 2:
        values, roles = tuple(v for _, v in segments), tuple(k for k, _ in segments)
        out.append(Observation("dims", values, package, rank, pair.order, pair.group, raw, roles=roles))
    elif (length := one_length(pair.value, info.unit, decimal_comma)) is not None:
        # "サイズ：19cm／240p" (a book's height), "Size: 45 cm": one unnamed extent, one rank weaker
        out.append(Observation("dims", (length,), package, rank + 1, pair.order, pair.group, raw, roles=("extent",)))
    if info.kind == "dimensions":
        mass, note = _plausible_mass(rest, None, decimal_comma)
        if mass is not None:
            out.append(Observation("mass", mass, package, rank, pair.order, pair.group, raw, note))
    elif not out and (mass := _plausible_mass(pair.value, None, decimal_comma)[0]) is not None:
        # "Size: 275g": a net content, the product's weight only beside a mass in its name (the chooser)
        out.append(Observation("mass", mass, package, rank, pair.order, pair.group, raw, role="content",
                               note="a net content in a size row, beside the weight in the product's name"))  # fmt: skip
    return out


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
        Observation(f, v, pair.package, rank, pair.order, pair.group, raw, roles=r, role=info.role, part=info.part)
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
    hinted = lines_matching(lines, _MATERIAL_HINT)
    for i, line in enumerate(lines):
        if i not in hinted:
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
    cm)</option>``, or a picker's button, swatch or ``role=option`` the page marks chosen: ``aria-checked``,
    ``class="selected"``, :attr:`scrapers.page_lines.Line.selected`): a page that sells several sizes shows
    the product's in its picker, while its size table lists every variant. The most complete size in the
    option's text, rank 0 (it beats the table's rows); nothing when the option names no size with a unit."""
    tree = page.tree
    if tree is None:
        return []
    texts = [" ".join(option.itertext()).strip()[:300] for option in tree.xpath("//select//option[@selected]")[:20]]
    texts += [line.text[:300] for line in page.lines if line.selected and not line.site_wide][:20]
    for text in texts:
        found = parse_dims(text, None, page.decimal_comma) if DIGIT.search(text) else []
        if found:
            best = max(found, key=lambda d: len(d.values_cm))
            return [
                Observation(
                    "dims", best.values_cm, rank=0, raw=f"selected option: {text}"[:200], roles=best.roles,
                    note=f"the size of the selected variant ({text[:80]!r})",
                )
            ]  # fmt: skip
    return []


#: Regions whose stores write lengths in inches when they write no unit (Barnes & Noble's
#: ``5.20(w) x 8.00(h) x 0.40(d)``). Only a declared region counts (``en-US``, ``og:locale en_US``).
INCH_REGIONS = frozenset({"us"})


def _inch_locale(lang: str | None) -> bool:
    parts = re.split(r"[-_]", (lang or "").strip().lower())
    return len(parts) > 1 and parts[0] == "en" and parts[1] in INCH_REGIONS


def _with_locale_inches(pair: Pair, lang: str | None) -> Pair:
    """A length pair written with no unit anywhere, read in inches on a page of an inch locale (said so)."""
    if pair.info.unit is not None or pair.info.kind not in LENGTH_KINDS or pair.info.role != "product":
        return pair
    if not UNITLESS_LETTERED.fullmatch(clean_text(pair.value)):
        return pair
    return replace(pair, info=replace(pair.info, unit="in"),
                   unit_context=f"inches, the unit of the page's locale ({lang})")  # fmt: skip


@adapter("spec_table", priority=50)
def spec_table(page: Page) -> list[Observation]:
    """Spec tables, definition lists, detail bullets and label/value lines of the visible page, and the
    size of the selected variant."""
    pairs = only_part_pairs(own_part_pairs(pairs_from_lines(page.lines), page.title), page.title)
    pairs, adjusted = adjustable_extents(pairs)
    if _inch_locale(page.lang):
        pairs = [_with_locale_inches(p, page.lang) for p in pairs]
    pairs = unitless_millimetres(pairs, page.decimal_comma)
    obs = measured_packed(highest_settings(observations_from_pairs(pairs, page.decimal_comma)))
    for o in obs:
        o.site_wide = page.site_wide_line(o.order)
    return obs + adjusted + selected_variant(page) + material_observations(page.lines)
