"""Whose value a spec pair states, decided from the other pairs and the page's name: a part that names the
product itself (``Robot Weight`` on a robot vacuum's page, :func:`own_part_pairs`), a value said to be one part's alone on a kit's page
(``750 g (Body Only)``), an adjustable product's two bounds of one axis (``Min. height`` / ``Max.
height``) or its highest setting beside its lowest (``(höchste Position)``), and a size measured with the packed
weight (``[Eigenmessung]`` beside ``[Eigenmessung inkl. Verpackung]``)."""

from __future__ import annotations

import re
from dataclasses import replace

from scrapers.adapters import Observation
from scrapers.labels import AXES, classify_label
from scrapers.spec_pairs import Pair
from scrapers.value_forms import note_words, only_part, packed_value

__all__ = ["adjustable_extents", "highest_settings", "measured_packed", "only_part_pairs", "own_part_pairs"]


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


#: A size said to be an adjustable product's highest or lowest setting in its own text (``mit Standfuß
#: (höchste Position)``, ``with stand (lowest position)``, ``position la plus haute``).
_HIGHEST = re.compile(
    r"\b(?:h(?:ö|oe)chste[rn]?|oberste[rn]?|maximale[rn]?|highest|tallest|maximum|max\.?)\s+"
    r"(?:position|stellung|einstellung|setting)\b|\bposition\s+(?:la\s+plus\s+haute|haute|maximale)\b",
    re.IGNORECASE,
)
_LOWEST = re.compile(
    r"\b(?:niedrigste[rn]?|unterste[rn]?|minimale[rn]?|lowest|minimum|min\.?)\s+"
    r"(?:position|stellung|einstellung|setting)\b|\bposition\s+(?:la\s+plus\s+basse|basse|minimale)\b",
    re.IGNORECASE,
)


def highest_settings(obs: list[Observation]) -> list[Observation]:
    """``obs`` with the product's sizes that say they are the highest setting (``60.84 x 19.04 x 49.32 cm - mit
    Standfuß (höchste Position)``) made another configuration's (role ``variant``), when the page also states
    a size at the lowest setting: the lowest setting is the product's own size, as for two bounds written as
    labels (:func:`adjustable_extents`). A lone highest setting is left as it is."""
    sizes = [o for o in obs if o.feature == "dims" and o.role == "product"]
    if not any(_LOWEST.search(o.raw) and not _HIGHEST.search(o.raw) for o in sizes):
        return obs
    for o in sizes:
        if _HIGHEST.search(o.raw) and not _LOWEST.search(o.raw):
            o.role = "variant"
            o.note = "; ".join(filter(None, [o.note, "the highest setting of an adjustable product; the page "
                                             "states the lowest, the product's own size"]))  # fmt: skip
    return obs


def measured_packed(obs: list[Observation]) -> list[Observation]:
    """``obs`` with a product size made a package value when its bracket note is part of a weight's note
    that says the packaging is included (``Außenmaße: 160 x 680 x 440 mm [Eigenmessung]`` beside ``Gewicht:
    5.197kg [Eigenmessung inkl. Verpackung & Beilagen]``): one measurement of one thing, the boxed item."""
    packed = [note_words(o.raw) for o in obs if o.feature == "mass" and o.package and packed_value(o.raw)]
    for o in obs:
        if o.feature != "dims" or o.role != "product" or o.package:
            continue
        words = note_words(o.raw)
        if words and any(words < p for p in packed):
            o.package = True
            o.note = "; ".join(filter(None, [o.note, "measured with the weight that includes the packaging"]))
    return obs


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
