"""Single-axis fields (``Breite: 51,3 cm``, ``Höhe mit Standfuß: 37,3 cm``) grouped into rows of one size.

A row is one side's (the product's or the package's) run of different axes no further apart than
:data:`AXIS_GROUP_GAP` lines; per axis and side only the most whole configuration stated counts
(:attr:`scrapers.labels.LabelInfo.configuration`), and the same rule picks among the product's weight fields.
"""

from __future__ import annotations

from collections.abc import Iterator

from scrapers.adapters import Observation
from scrapers.spec_pairs import Pair

__all__ = ["AXIS_GROUP_GAP", "group_axes", "whole_product_weights"]

#: Separate axis fields further apart than this many lines are not one product's dimensions.
AXIS_GROUP_GAP = 8


def _chosen_rows(rows: list[list]) -> list[tuple[list, bool]]:
    """The rows that state a size, in page order, with whether their side has a row of two axes or more:
    the product's and the package's sides apart, each its rows of two axes or more, else its first lone
    axis (a product's ``Diameter: 5"`` beside the package's height, width and length is still the
    product's size). A row never mixes the sides (:func:`_group_axes` starts a new one)."""
    chosen = []
    for package in (False, True):
        side = [r for r in rows if (r[0][2].package or r[0][2].info.package) == package]
        multi = [r for r in side if len(r) >= 2]
        chosen += [(row, bool(multi)) for row in multi or side[:1]]
    return sorted(chosen, key=lambda item: item[0][0][2].order)


def _side(p: Pair) -> bool:
    return bool(p.package or p.info.package)


def _whole_product_axes(axes: list[tuple[str, float, Pair, int, str | None]]) -> list:
    """``axes`` with, per axis and side, only the fields of the most whole configuration stated
    (:attr:`LabelInfo.configuration`): ``Höhe mit Standfuß`` over ``Höhe``, ``Depth`` over ``Depth Without
    Handle``."""
    best: dict[tuple[str, bool], int] = {}
    for kind, _, p, _, _ in axes:
        key = (kind, _side(p))
        best[key] = max(best.get(key, 0), p.info.configuration)
    return [a for a in axes if a[2].info.configuration == best[(a[0], _side(a[2]))]]


def whole_product_weights(pairs: list[Pair]) -> list[Pair]:
    """``pairs`` without the product's weight fields of a less whole configuration than another weight
    field of the same side (``Gewicht: 2,9 kg`` beside ``Gewicht mit Standfuß: 3,5 kg``; ``Gewicht ohne
    Ständer`` beside ``Gewicht mit Ständer``)."""
    weights = [p for p in pairs if p.info.kind == "weight" and p.info.role == "product"]
    best: dict[bool, int] = {}
    for p in weights:
        best[_side(p)] = max(best.get(_side(p), 0), p.info.configuration)
    return [p for p in pairs if not (p in weights and p.info.configuration < best[_side(p)])]


def group_axes(axes: list[tuple[str, float, Pair, int, str | None]]) -> Iterator[Observation]:
    """Rows of single-axis fields as dims observations (see :func:`observations_from_pairs`). When no row
    of its side (the product's or the package's) has two axes, a lone axis is still that side's one
    stated dimension (``Diameter: 12 cm``), one rank weaker."""
    rows: list[list[tuple[str, float, Pair, int, str | None]]] = []
    # Each side keeps its open row: a package's fields between the product's ("Höhe mit Verpackung"
    # between "Breite" and "Höhe mit Standfuß") do not end the product's row, nor the reverse; the gap is
    # counted from the side's last field, kept or not (a field of a less whole configuration bridges it).
    current: dict[bool, list] = {}
    last_order: dict[bool, int] = {}
    kept = {id(a) for a in _whole_product_axes(axes)}
    for item in axes:
        kind, _, pair, _, _ = item
        side, previous = _side(pair), last_order.get(_side(pair))
        last_order[side] = pair.order
        if id(item) not in kept:
            continue
        row = current.get(side)
        if row and (kind in {k for k, *_ in row} or pair.order - (previous or 0) > AXIS_GROUP_GAP):
            row = None
        if row is None:
            row = current[side] = [item]
            rows.append(row)
        else:
            row.append(item)
    for row, multi in _chosen_rows(rows):
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
            role="shipping" if any(p.info.shipping for _, _, p, _, _ in row) else "product",
        )  # fmt: skip
