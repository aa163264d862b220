"""Whose value a spec pair states, decided from the other pairs and the page's name (after
:func:`scrapers.spec_pairs.own_part_pairs`): a value said to be one part's alone on a kit's page
(``750 g (Body Only)``), and an adjustable product's two bounds of one axis (``Min. height`` / ``Max.
height``)."""

from __future__ import annotations

import re
from dataclasses import replace

from scrapers.adapters import Observation
from scrapers.labels import AXES, classify_label
from scrapers.spec_pairs import Pair
from scrapers.value_forms import only_part

__all__ = ["adjustable_extents", "only_part_pairs"]


def only_part_pairs(pairs: list[Pair], title: str | None) -> list[Pair]:
    """``pairs`` with the product's values that say they are one part's alone (``(Body Only)`` on a kit's
    page: :func:`scrapers.value_forms.only_part`) as that component's."""
    out = []
    for p in pairs:
        if p.info.role == "product" and (part := only_part(p.value, title)) is not None:
            p = replace(p, info=replace(p.info, role="component", part=part))
        out.append(p)
    return out


_MIN_WORDS = frozenset({"min", "minimum"})
_MAX_WORDS = frozenset({"max", "maximum"})


def _bound_of(pair: Pair) -> str | None:
    """``"min"`` or ``"max"`` for a capacity label that is a bound of the product's own axis (``Min. height``,
    ``Höhe max.``: the label without its min/max word is the product's ``height``); None otherwise
    (``Min. seat height`` is the seat's, ``Max load`` no axis)."""
    if pair.info.role != "capacity" or pair.info.kind not in AXES:
        return None
    words = re.findall(r"[^\W\d_]+", pair.label.lower())
    bound = {w for w in words if w in _MIN_WORDS | _MAX_WORDS}
    if len(bound) != 1:
        return None
    rest = classify_label(" ".join(w for w in words if w not in bound))
    if rest is None or rest.role != "product" or rest.kind != pair.info.kind:
        return None
    return "min" if bound <= _MIN_WORDS else "max"


def adjustable_extents(pairs: list[Pair]) -> tuple[list[Pair], list[Observation]]:
    """``pairs`` with an adjustable product's lowest setting of an axis as the product's extent, when the
    page states both bounds of that axis as labels (IKEA's ``Min. height: 50 3/4"`` / ``Max. height: 55
    1/8"``): the object's own size at its lowest, the range its adjustment (a lone ``Max. height`` stays a
    capacity's), with a warning naming both."""
    bounds: dict[str, dict[str, Pair]] = {}
    for p in pairs:
        if (b := _bound_of(p)) is not None:
            bounds.setdefault(p.info.kind, {}).setdefault(b, p)
    chosen = {id(b["min"]): b["max"] for b in bounds.values() if len(b) == 2}
    out, notes = [], []
    for p in pairs:
        if id(p) in chosen:
            high = chosen[id(p)]
            notes.append(Observation("warning", f"{p.info.kind}: adjustable ({p.label} {p.value}, {high.label} "
                                     f"{high.value}); the lowest setting read as the product's", order=p.order))  # fmt: skip
            p = replace(p, info=replace(p.info, role="product"))
        out.append(p)
    return out, notes
