"""Resolving dimensions: which stated extent is which of the catalog's a >= b >= c.

:func:`read_relations` finds extents stated relative to another ("twice as long as it is wide");
:func:`resolve_dims` assigns the statements of a :class:`recall.reading.Reading` (labelled extents,
tuples, diameters, sides, unlabelled lengths) to ``a_cm``, ``b_cm``, ``c_cm`` by the rules in
``recall/PARSER.md``, "Dimensions".
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

from kb.features import MAX_DIM_CM
from kb.measures.aliases import PARSER_LANGUAGES
from kb.measures.units import Unit, unit_table
from kb.measures.words import number_value
from recall import lexicon as lx
from recall.reading import DimStatement, Quantity, Reading, Relation, Stated, limit_refusal
from recall.tokens import Token

__all__ = ["MAX_STATED_LENGTH_CM", "read_relations", "resolve_dims"]


def read_relations(tokens: list[Token], reading: Reading) -> None:
    """Extents stated relative to another: "twice as long as it is wide", "three times as long", "half
    as wide as it is long"."""
    n = len(tokens)
    for i, tok in enumerate(tokens):
        if tok.low != "times" and (
            tok.low not in ("twice", "half") or i + 1 >= n or tokens[i + 1].low != "as"
        ):
            continue
        first = i
        if tok.low == "times":
            while first > 0 and tokens[first - 1].tag in ("CD", "NW"):
                first -= 1
            factor = number_value([t.low for t in tokens[first:i]]) if first < i else None
            if factor is None or not 1 < factor <= 20:
                continue
        else:
            factor = 2.0 if tok.low == "twice" else 0.5
        j = i + 1
        if j + 1 >= n or tokens[j].low != "as" or tokens[j + 1].tag not in ("DIM", "DIMN"):
            continue
        role = lx.DIMENSION_WORDS.get(tokens[j + 1].low)
        if role not in lx.LINEAR_ROLES:
            continue
        ref: str | None = None
        last = tokens[j + 1]
        if j + 2 < n and tokens[j + 2].low == "as":
            for t in tokens[j + 3 : j + 7]:
                if t.tag in ("CM", "SEP"):
                    break
                if t.tag in ("DIM", "DIMN"):
                    ref, last = lx.DIMENSION_WORDS.get(t.low), t
                    break
            if ref is None or ref == role:
                continue
        reading.relations.append(Relation(role, factor, ref, tokens[first].start, last.end))


def _unit_for(q: Quantity, reading: Reading) -> Unit | None:
    """The quantity's own unit, else the nearest length unit before it, else after it, else cm."""
    if q.unit is not None:
        return q.unit
    before = [u for p, u in reading.length_units if p < q.pos]
    if before:
        return before[-1]
    after = [u for p, u in reading.length_units if p > q.pos]
    if after:
        return after[0]
    return unit_table(PARSER_LANGUAGES)["cm"]


def _to_cm(q: Quantity, reading: Reading, stmt: DimStatement, scale: float = 1.0) -> Stated | None:
    unit = _unit_for(q, reading)
    if unit is None or unit.kind != "length":
        return None
    f = unit.factor * scale
    value = q.value * f
    reason = limit_refusal("a_cm", value)
    inside = stmt.start <= q.start and q.end <= stmt.end
    if reason is not None and _long_thing(q, stmt, value, inside):
        return Stated(MAX_DIM_CM, MAX_DIM_CM, None, "at_least", stmt.start, stmt.end)
    if reason is not None:  # the quantity's own words, or a relation's ("twenty times as long")
        start, end = (q.start, q.end) if inside else (stmt.start, stmt.end)
        reading.refuse(start, end, f"{value:.10g} cm: {reason}")
        return None
    return Stated(
        value,
        None if q.low is None else q.low * f,
        None if q.high is None else q.high * f,
        q.qualifier,
        stmt.start,
        stmt.end,
    )


#: A length stated in its own words ("a garden hose, 50 feet long") past the catalog's extent limit
#: (:data:`kb.features.MAX_DIM_CM`, 5 m) and at most this is the real length of a long flexible thing
#: (garden hoses, extension cords, ropes, chains and cables are sold at 10-30 m), not an absurd value;
#: the catalog holds no extent past its limit, so it is read as "at least" the limit. Only a length: a
#: width, height or diameter past 5 m ("a ball 10 m wide") and a length derived from a relation ("twenty
#: times as long") stay refused, and so do lengths past this ("9000 m long").
MAX_STATED_LENGTH_CM = 10_000.0


def _long_thing(q: Quantity, stmt: DimStatement, value: float, inside: bool) -> bool:
    """Whether ``value`` (cm) is a long flexible thing's length (:data:`MAX_STATED_LENGTH_CM`)."""
    return stmt.role == "length" and inside and q.unit is not None and MAX_DIM_CM < value <= MAX_STATED_LENGTH_CM


_ABC = ("a_cm", "b_cm", "c_cm")


@dataclass(frozen=True)
class _Cues:
    """What the description's words say about the object's form (the dimension rules' cues)."""

    cube: bool
    sphere: bool
    cylinder: bool
    disc: bool
    flat: bool
    rod: bool  # a long round thing (a pencil, a bottle), not flat and not a disc
    round: bool  # a sphere, cylinder, disc or round word


def _cues(words: set[str]) -> _Cues:
    sphere = bool(words & lx.SPHERE_WORDS)
    cylinder = bool(words & lx.CYLINDER_WORDS)
    disc = bool(words & lx.DISC_WORDS)
    flat = bool(words & lx.FLAT_WORDS)
    return _Cues(
        cube=bool(words & lx.CUBE_WORDS),
        sphere=sphere,
        cylinder=cylinder,
        disc=disc,
        flat=flat,
        rod=bool(words & lx.ROD_WORDS) and not flat and not disc,
        round=sphere or cylinder or bool(words & (lx.ROUND_WORDS | (lx.DISC_WORDS - {"flat", "cap"}))),
    )


def resolve_dims(reading: Reading) -> dict[str, Stated]:
    """Assign the stated extents to a >= b >= c (rules in recall/PARSER.md, "Dimensions"): the stated
    ones of ``a_cm``, ``b_cm``, ``c_cm`` with their values in cm."""
    cues = _cues(reading.cue_words)
    _add_relations(reading)
    by_role = _by_role(reading, cues)
    linear = [(by_role[r], r) for r in lx.LINEAR_ROLES if r in by_role]
    linear.sort(key=lambda dr: dr[0].start)
    multi = _tuple(reading, linear)
    names: Sequence[str] = _ABC
    if multi is not None:
        dims = _with_third_extent(multi, by_role)[:3]
    elif "side" in by_role:
        dims = [by_role["side"]] * 3
    elif "diameter" in by_role or "square" in by_role:
        names, dims = _round_extents(by_role, linear, cues)
    elif linear:
        names, dims = _straight_extents(linear, cues)
    elif reading.sizes:
        sizes = [d for stmt in reading.sizes[:3] if (d := _to_cm(stmt.quantities[0], reading, stmt))]
        dims = sizes * 3 if len(sizes) == 1 and (cues.cube or cues.sphere) else sizes
    else:
        return {}
    ordered = sorted(dims, key=lambda d: -d.value)
    return dict(zip(names, ordered, strict=False))


def _add_relations(reading: Reading) -> None:
    """Add the extents stated relative to another: "twice as long as it is wide, 11 cm wide" is 22 cm
    long (not when that extent is stated itself)."""
    for rel in reading.relations:
        if any(st.role == rel.role for st in reading.dims):
            continue
        if rel.ref is not None:
            source = next((st for st in reading.dims if st.role == rel.ref), None)
        else:
            source = next((st for st in reversed(reading.dims) if st.start < rel.start), None)
        if source is None or source.role == rel.role:
            continue
        q = source.quantities[0]
        derived = replace(
            q, value=q.value * rel.factor, low=None, high=None, qualifier="about", unit=_unit_for(q, reading)
        )
        reading.dims.append(DimStatement(rel.role, [derived], rel.start, rel.end))


#: Roles stated as something other than the diameter they give: a radius is half of it, a circumference
#: ("30 cm around", "a girth of 12 inches") pi times it.
_DIAMETER_SCALE = {"radius": 2.0, "circumference": 1.0 / math.pi}


def _by_role(reading: Reading, cues: _Cues) -> dict[str, Stated]:
    """The first statement of each role in cm: a radius doubled to a diameter, a circumference over pi, "across" a diameter of a
    round thing (or beside a stated width), the width of a round thing its diameter, and a length
    dropped when an overall extent is stated (it is a part's)."""
    by_role: dict[str, Stated] = {}
    stated_width = any(stmt.role == "width" for stmt in reading.dims)  # "65 cm across and 20 cm wide"
    squat = _squat(reading)
    for stmt in reading.dims:
        role = stmt.role
        if role in ("radius", "circumference"):
            role = "diameter"
        elif role == "across":
            role = "diameter" if cues.round or stated_width or squat else "width"
        if role in by_role:
            continue
        dim = _to_cm(stmt.quantities[0], reading, stmt, _DIAMETER_SCALE.get(stmt.role, 1.0))
        if dim is not None:
            by_role[role] = dim
    three = bool(by_role.keys() & {"length", "height", "overall"}) and bool(
        by_role.keys() & {"thickness", "depth"}
    )
    if cues.round and not cues.flat and "diameter" not in by_role and "width" in by_role and not three:
        by_role["diameter"] = by_role.pop("width")  # "a mug 8 cm wide": the width of a round thing
    if "overall" in by_role and "length" in by_role:
        del by_role["length"]  # "the blade is 20 cm long, 33 cm overall": the length of a part
    return by_role


#: The extents of a squat thing's height: "3 cm across and 1.5 cm tall" is a cap, a tin, a plate.
_SQUAT_ROLES = frozenset({"height", "thickness", "depth"})


def _squat(reading: Reading) -> bool:
    """Whether the text states an extent across and a smaller height, thickness or depth, and no length:
    then "across" is a diameter (a = b = across, c = the height), not one width. Measured on the
    development sets: every such description is of a round or square-footed thing (RECALL.md)."""
    roles = {stmt.role: stmt for stmt in reversed(reading.dims)}  # the first of each role
    across = roles.get("across")
    if across is None or roles.keys() & {"length", "overall", "width", "diameter", "radius", "circumference"}:
        return False
    wide = _cm_value(across.quantities[0], reading)
    lows = [_cm_value(roles[role].quantities[0], reading) for role in _SQUAT_ROLES & roles.keys()]
    return wide is not None and any(low is not None and low < wide for low in lows)


def _cm_value(q: Quantity, reading: Reading) -> float | None:
    """The quantity in cm, or None when it is no length (no refusal recorded: :func:`_to_cm` does that)."""
    unit = _unit_for(q, reading)
    return q.value * unit.factor if unit is not None and unit.kind == "length" else None


def _tuple(reading: Reading, linear: list[tuple[Stated, str]]) -> list[Stated] | None:
    """The first tuple's values in cm (a hedge on the first covers all), or None when it has fewer than
    two or is a pair beside three labelled extents."""
    if not reading.multis:
        return None
    stmt = reading.multis[0]
    multi = [d for q in stmt.quantities if (d := _to_cm(q, reading, stmt)) is not None]
    if multi and multi[0].qualifier == "about":  # "roughly 9.5 x 6 x 3.5 inches": the hedge covers all
        for d in multi[1:]:
            if d.qualifier == "exact":
                d.qualifier = "about"
    if len(multi) < 2 or (len(multi) == 2 and len(linear) >= 3):
        return None  # three labelled extents say more than a pair
    return multi


def _with_third_extent(multi: list[Stated], by_role: dict[str, Stated]) -> list[Stated]:
    """A pair with a labelled third extent whose value is not one of the pair: "21 x 15 cm, 1 cm thick",
    "23 cm tall, 7 x 7 cm base"."""
    if len(multi) == 2:
        for role in ("thickness", "depth", "height", "length", "overall", "width"):
            extra = by_role.get(role)
            if extra is not None and not any(abs(extra.value - d.value) <= 0.02 * d.value for d in multi):
                multi.append(extra)
                break
    return multi


def _round_extents(
    by_role: dict[str, Stated], linear: list[tuple[Stated, str]], cues: _Cues
) -> tuple[Sequence[str], list[Stated]]:
    """A diameter or a square cross-section: two equal extents, with the straight ones stated."""
    diameter = by_role.get("diameter") or by_role["square"]
    others = [d for d, _r in linear]
    if len(others) >= 2:  # a pan 28 across, 48 long with the handle, 5 deep: 48, 28, 5
        return _ABC, [diameter, others[0], others[1]]
    if others:
        return _ABC, [diameter, diameter, others[0]]
    if cues.sphere and "diameter" in by_role:
        return _ABC, [diameter, diameter, diameter]
    if cues.cylinder and not cues.disc and "diameter" in by_role:
        return ("b_cm", "c_cm"), [diameter, diameter]
    return ("a_cm", "b_cm"), [diameter, diameter]


_SLOT = {"length": "a_cm", "height": "a_cm", "overall": "a_cm", "width": "b_cm", "depth": "b_cm",
         "thickness": "c_cm"}  # fmt: skip


def _straight_extents(linear: list[tuple[Stated, str]], cues: _Cues) -> tuple[Sequence[str], list[Stated]]:
    """Length, overall, height, width, depth, thickness without a tuple or a diameter."""
    if len(linear) == 1 and (cues.cube or cues.sphere):
        d = linear[0][0]
        return _ABC, [d, d, d]
    if len(linear) >= 3:
        return _ABC, [d for d, _r in linear[:3]]
    if len(linear) == 1:
        d, role = linear[0]
        return [_SLOT[role]], [d]
    roles = {r for _d, r in linear}
    values = [d for d, _r in linear]
    if roles in ({"length", "thickness"}, {"overall", "thickness"}) and cues.rod:
        values = sorted(values, key=lambda d: -d.value)
        values.append(values[1])  # "a pencil 19 cm long and 7 mm thick": round, b = c
        return _ABC, values
    if "thickness" in roles:
        return ("a_cm", "c_cm") if roles & {"length", "height", "overall"} else ("b_cm", "c_cm"), values
    return ("a_cm", "b_cm"), values
