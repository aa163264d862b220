"""The multilingual label vocabulary of spec tables: which label names which measurement.

:func:`classify_label` reads a label as stores write it (``Item Dimensions LxWxH``, ``Artikelgewicht``,
``Masse der Verpackung (LxBxH)``, ``Hmotnosť [kg]``, ``Вес без упаковки (нетто), кг``, ``重量``) and
returns what it measures, whether it is about the package, and a unit the label states.

The rule is a whitelist, for precision: after removing a unit in brackets or after a comma and an
order hint (``L x W x H``, ``ВхШхГ``), every word of the label must be a measurement word, a package
word, a negation, or a harmless qualifier (``item``, ``product``, ``overall``, ``net``, ``de``, ...).
So ``Schlauchlänge`` (hose length), ``Peso suportado`` (supported load), ``Max Height``, ``Chain Length``
and ``Durchmesser Stiftspitze`` (tip diameter) are not the product's measurements. A package word
(``Verpackung``, ``embalagem``, ``shipping``, ``упаковка``, ``包裝``...) marks a package value unless a
negation (``without``, ``ohne``, ``sin``, ``без``...) precedes it: ``Вес без упаковки`` is the product.

Languages: en, de, fr, es, it, pt, nl, pl, cs, sk, ru/uk/kk, bg, sl/hr/sr, ro, hu, el, tr, lv, lt, et, fi,
sv/da/no, id, he, ar, zh (traditional and simplified), ja, ko.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from functools import lru_cache

from scrapers.label_forms import cjk_component, cjk_kinds, compound_kind, has_cjk, split_compound
from scrapers.label_vocabulary import (
    BODY_WORDS,
    CAPACITY_WORDS,
    CJK_CAPACITY,
    CJK_LABELS,
    COMPOUND_SUFFIXES,
    INCLUDING,
    KIND_WORDS,
    NEGATIONS,
    OVERALL,
    PACKAGE_WORDS,
    PART_WORDS,
    QUALIFIERS,
    SHIPPING_STEMS,
    SHIPPING_WORDS,
    SHORT_LABELS,
    fold,
)
from scrapers.quantities import clean_text, length_unit, mass_unit, unit_hint

__all__ = ["AXES", "KINDS", "LabelInfo", "classify_label", "classify_other"]

#: Single-axis kinds (one length each); "dimensions" is a combined A x B x C value, "size" too but never
#: a mass (``Size: 10 Ounce (Pack of 1)`` is a net content), "weight" is a mass.
AXES: tuple[str, ...] = ("length", "width", "height", "depth", "diameter", "thickness")
KINDS: tuple[str, ...] = (*AXES, "dimensions", "size", "weight")


# Wayfair's "Overall Height - Top to Bottom", "Overall Depth - Front to Back": the direction is not a word
# of the label, but only an overall value is the product's ("Body Height - Top to Bottom" is a lamp shade's).
_DIRECTION = re.compile(
    r"^((?:overall|assembled|product|item)\b.*?)\s*[-–—]\s*(?:top|side|front|left|back|end)\s+to\s+"
    r"(?:bottom|side|back|right|front|end)\s*$",
    re.IGNORECASE,
)
_ORDER_HINT = re.compile(r"\b[a-zа-я](?:\s*[x×хX*/]\s*[a-zа-я]\b){1,2}", re.IGNORECASE)
_ORDER_WORD = re.compile(r"[a-zа-я](?:[xх][a-zа-я]){1,2}")
_BRACKETS = re.compile(r"[\[(（][^\])）]{0,30}[\])）]")
_MAX_WORDS = 8


@dataclass(frozen=True)
class LabelInfo:
    """What a label measures: ``kind`` (one of :data:`KINDS`), ``package`` (a package or shipping value),
    ``unit`` (a unit the label states, e.g. ``mm`` from ``Výška [mm]``, else None)."""

    kind: str
    package: bool = False
    unit: str | None = None
    #: For a dimensions label, the axes it names in order (``Dimensions (H x W x D)`` -> height, width,
    #: depth; ``Largo x Ancho x Alto``); () when it names none or is ambiguous (``L x L x H``).
    order: tuple[str, ...] = ()
    #: "product" for every label :func:`classify_label` accepts; "component" (a part's extent or weight:
    #: ``Cable length``, ``Battery Weight``, ``Schlauchlänge``) or "capacity" (a capacity or rating:
    #: ``Fassungsvermögen 8 kg``, ``Max Height``, ``容量``) from :func:`classify_other`.
    role: str = "product"
    #: A package value that is the shipment's (``Shipping Weight``, ``Bruttogewicht``, ``発送重量``: the
    #: parcel sent, gross) rather than the product in its own box; kept apart from package values.
    shipping: bool = False
    #: For a component's label, the part it names (``cable`` of ``Cable length``), else None.
    part: str | None = None
    #: For a product's label that leaves a part out (``Depth Without Handle``, ``Gewicht ohne Akku``), the
    #: words it excludes: a value of another configuration, used when no label states the whole product's.
    excludes: str | None = None
    #: For a product's label that names a part it includes (``Gewicht mit Ständer``, ``Height including
    #: stand``, ``Weight (incl. battery)``), the words it includes: the whole product as sold, which wins
    #: over a label of the same axis that says nothing, or leaves the part out.
    includes: str | None = None

    @property
    def configuration(self) -> int:
        """2 for a label that includes a part, 1 for one that says nothing, 0 for one that leaves it out."""
        return 2 if self.includes else 0 if self.excludes else 1


#: Axis letters of order hints (en, de: B = Breite, T = Tiefe; ru: В высота, Ш ширина, Г глубина, Д длина).
_ORDER_LETTERS = {
    "l": "length", "w": "width", "b": "width", "h": "height", "d": "depth", "t": "depth",
    "в": "height", "ш": "width", "г": "depth", "д": "length",
}  # fmt: skip


def without_order_hint(text: str) -> str:
    """``text`` with its axis-order hints (``(B x H x T)``, ``L x W x H``) blanked out."""
    return _ORDER_HINT.sub(" ", text)


def _order_of(text: str, kinds: list[str]) -> tuple[str, ...]:
    """The axes a dimensions label names in order (see :attr:`LabelInfo.order`)."""
    m = _ORDER_HINT.search(text) or _ORDER_WORD.search(text.lower())
    if m:
        letters = re.sub(r"\s+", "", m.group(0))[::2]  # "H x W x D", "ВхШхГ", "B/H/T": every other char
        roles = tuple(_ORDER_LETTERS.get(ch.lower(), "") for ch in letters)
    else:
        roles = tuple(k for k in kinds if k in AXES)
    if len(roles) < 2 or "" in roles or len(set(roles)) < len(roles):
        return ()
    return roles


def classify_label(label: object) -> LabelInfo | None:
    """The measurement ``label`` names, or None when it names none (or something else, like a load)."""
    if isinstance(label, str):
        return _classify_cached(label) if len(label) <= 200 else None
    try:
        return _classify(label)
    except Exception:  # noqa: BLE001
        return None


#: Every label :func:`_classify` accepts holds one of these words (a kind word, the suffix of a compound,
#: an "overall" word, a short label) or a CJK character: a text with none is no label, decided without
#: the full reading (most of a page's lines are menus, buttons and prose).
_ANY_KIND = re.compile("|".join(sorted({re.escape(w) for w in (*KIND_WORDS, *OVERALL, *SHORT_LABELS)}, key=len,
                                       reverse=True)))  # fmt: skip


def _may_be_a_label(label: str) -> bool:
    folded = fold(label)
    return _ANY_KIND.search(folded) is not None or has_cjk(folded)


@lru_cache(maxsize=16384)
def _classify_cached(label: str) -> LabelInfo | None:
    if not _may_be_a_label(label):
        return None
    try:
        return _classify(label)
    except Exception:  # noqa: BLE001 - a label we cannot read is simply not a measurement label
        return None


def _classify(label: object) -> LabelInfo | None:
    text = clean_text(label)
    if not text or len(text) > 80 or text[0].isdigit():
        return None  # a label does not start with a number ("1 kg" is a value)
    unit = unit_hint(text)
    original = text
    text = text.rstrip(" :：-–—=").strip()
    if any(_names_a_capacity(m.group(0)) for m in _BRACKETS.finditer(text)):
        return None  # "Weight (maximum)": another configuration's or a rating, see classify_other
    if bracket_part(text) is not None:
        return None  # "Size (Main Display)": the display's size, see classify_other
    text = _DIRECTION.sub(r"\1", _BRACKETS.sub(_bracket_words, text).strip()).strip()
    text = _EN_BOY.sub("width x length", text)  # Turkish "En x Boy" before "en" is read as a preposition
    text = _FROM_WALL.sub(" ", _ORDER_HINT.sub(" ", text))
    folded = fold(text)
    squashed = re.sub(r"[\W_]+", "", folded)
    if squashed in CJK_LABELS:
        kind, package = CJK_LABELS[squashed]
        return LabelInfo(kind, package, unit, shipping=_ships(package, [squashed]))
    if has_cjk(squashed):
        if unit is None and (m := _TRAILING_UNIT.search(text)) and (length_unit(m.group(1)) or mass_unit(m.group(1))):
            unit = m.group(1)  # "本体サイズ（H×W×D） mm"
        return _classify_cjk(squashed, unit)
    words = [w for w in re.split(r"[\W_]+", folded) if w]
    if not words or len(words) > _MAX_WORDS:
        return None
    if len(words) == 1 and words[0] in SHORT_LABELS:
        return LabelInfo(SHORT_LABELS[words[0]], False, unit)  # Turkish "En: 30 cm"
    kinds: list[str] = []
    package = False
    negated = False
    unknown: list[str] = []
    excluded: list[str] = []
    including = False
    included: list[str] = []
    has_body = any(w in BODY_WORDS for w in words)
    for word in words:
        if word in KIND_WORDS:
            kinds.append(KIND_WORDS[word])
        elif word in PACKAGE_WORDS:
            package = package or not negated
        elif word in NEGATIONS:
            negated = True
        elif word in INCLUDING and not negated:
            including = True
        elif word in QUALIFIERS:
            continue
        elif _unit_word(word):
            if len(word) >= 2:
                unit = unit or word  # "Höhe cm", "Gewicht kg" (never "Size M": a garment size)
            continue
        elif _ORDER_WORD.fullmatch(word):
            continue  # "LxWxH", "ВхШхГ" written as one word
        else:
            compound = split_compound(word)
            if compound is None and negated:
                excluded.append(word)  # what the value leaves out: "Weight without the cable"
                continue
            if compound is None and including and word in PART_WORDS:
                included.append(word)  # what the value includes: "Gewicht mit Ständer", "Weight with stand"
                continue
            if compound is None:
                unknown.append(word)
                if not has_body or len(unknown) > 2:
                    return None  # an unknown word names something else (the rule is _names_the_body)
                continue
            kind, is_package = compound
            kinds.append(kind)
            package = package or (is_package and not negated)
    if unknown and not _names_the_body(words, unknown):
        return None
    if not kinds:
        if set(words) <= OVERALL:
            return LabelInfo("size", package, unit)  # Wayfair's "Overall: 15.5'' H x 12'' W x 12'' D"
        return None
    # "Item Package Dimensions", "Product size": the most specific kind wins; weight beats dimensions
    # only when no axis or dimension word is present.
    if len({k for k in kinds if k in AXES}) >= 2:
        # "Width x Height x Depth", "Largo x Ancho x Alto"
        order = _order_of(original, kinds)
        return _excluding(excluded, included, LabelInfo("dimensions", package, unit, order, shipping=_ships(package, words)))
    for kind in (*AXES, "dimensions", "size", "weight"):
        if kind in kinds:
            if kind in ("dimensions", "size") and "weight" in kinds:
                # "Weight & Dimensions"
                return _excluding(excluded, included, LabelInfo("dimensions", package, unit, shipping=_ships(package, words)))
            order = _order_of(original, kinds) if kind in ("dimensions", "size") else ()
            return _excluding(excluded, included, LabelInfo(kind, package, unit, order, shipping=_ships(package, words)))
    return None




def bracket_part(text: str) -> str | None:
    """The part a label's brackets name (``Size (Main Display)``, ``Dimensions (Pendant)``): a part word
    (:data:`PART_WORDS`) with nothing that keeps the label the whole product's (what it includes, what it
    leaves out, its body). None otherwise: units, axis orders and qualifiers in brackets change nothing."""
    for m in _BRACKETS.finditer(text):
        inner = m.group(0)[1:-1].strip()
        words = [w for w in re.split(r"[\W_]+", fold(inner)) if w]
        if any(w in INCLUDING or w in NEGATIONS or w in BODY_WORDS for w in words):
            continue
        if any(w in PART_WORDS for w in words):
            return inner
    return None


def _excluding(excluded: list[str], included: list[str], info: LabelInfo) -> LabelInfo:
    """``info`` with the words its label leaves out and the words it includes."""
    if excluded:
        info = replace(info, excludes=" ".join(excluded))
    return replace(info, includes=" ".join(included)) if included else info


def _bracket_words(m: re.Match) -> str:
    """A bracket's text kept as label words when it says what the value includes or leaves out
    (``Weight (incl. battery)``, ``Höhe (ohne Fuß)``); any other bracket (a unit, an axis order) is dropped."""
    inner = m.group(0)[1:-1]
    words = [w for w in re.split(r"[\W_]+", fold(inner)) if w]
    return f" {inner} " if any(w in INCLUDING or w in NEGATIONS for w in words) else " "


_TRAILING_UNIT = re.compile(r"(?<![A-Za-z])([A-Za-z]{2,3})\s*$")
_EN_BOY = re.compile(r"\ben\s*[x×*/]\s*boy\b", re.IGNORECASE)
#: Directions that do not change what a label measures: a wall light's "Depth of fitting from wall".
_FROM_WALL = re.compile(r"\b(?:from|to|off)\s+(?:the\s+)?(?:wall|ceiling)\b", re.IGNORECASE)


@lru_cache(maxsize=8192)
def _unit_word(word: str) -> bool:
    """Whether a label word is a length or mass unit (cached: labels repeat the same few words)."""
    return length_unit(word) is not None or mass_unit(word) is not None


def _names_the_body(words: list[str], unknown: list[str]) -> bool:
    """Whether a label's unknown words only name the object whose main body it measures: a body word
    (``body``, ``fitting``, ``Gehäuse``...) is present, no unknown word is a part word, and at most two
    are unknown (``Body of lamp width``, ``Lamp body width``)."""
    return (
        any(w in BODY_WORDS for w in words)
        and len(unknown) <= 2
        and all(w.isalpha() and w not in PART_WORDS for w in unknown)
    )


def _ships(package: bool, words: list[str]) -> bool:
    """Whether a package label names the shipment (gross, the parcel) rather than the product's box."""
    if not package:
        return False
    return any(w in SHIPPING_WORDS or any(stem in w for stem in SHIPPING_STEMS) for w in words)




def _classify_cjk(squashed: str, unit: str | None) -> LabelInfo | None:
    read = cjk_kinds(squashed)
    if read is None or not read[0]:
        return None
    kinds, package = read
    shipping = _ships(package, [squashed])
    if len({k for k in kinds if k in AXES}) >= 2 or "dimensions" in kinds:
        return LabelInfo("dimensions", package, unit, shipping=shipping)
    return LabelInfo(kinds[0], package, unit, shipping=shipping)


@lru_cache(maxsize=16384)
def classify_other(label: object) -> LabelInfo | None:
    """A measurement label that is *not* the product's (:attr:`LabelInfo.role` says whose), for the
    chooser's alternatives; None for the product's own labels and for labels that name no measurement.
    A capacity without a kind word is read as a weight (a washer's ``Fassungsvermögen: 8 kg``)."""
    try:
        if not isinstance(label, str) or len(label) > 80 or classify_label(label) is not None:
            return None
        text = clean_text(label).rstrip(" :：-–—=").strip()
        if not text or any(ch.isdigit() for ch in text) or ":" in text:
            return None  # a label holds no number ("Weight: 1.1 kg" is a pair, not a label)
        folded = fold(_BRACKETS.sub(" ", text))
        if any(token in folded for token in CJK_CAPACITY):
            return LabelInfo("weight", role="capacity")
        if has_cjk(folded):
            return _cjk_component(re.sub(r"[\W_]+", "", folded))
        words = [w for w in re.split(r"[\W_]+", folded) if w]
        if not words or len(words) > _MAX_WORDS:
            return None
        kinds = [KIND_WORDS[w] for w in words if w in KIND_WORDS]
        kinds += [k for w in words if w not in KIND_WORDS for k in [compound_kind(w)] if k]
        if any(w in CAPACITY_WORDS for w in words) or _names_a_capacity(text):
            kind = kinds[0] if kinds else "weight"
            return LabelInfo("dimensions" if kind == "size" else kind, role="capacity")
        if kinds:
            part = " ".join(w for w in words if w not in KIND_WORDS and w not in QUALIFIERS and not compound_kind(w))
            part = part or next((w[: -len(s)] for w in words for s in COMPOUND_SUFFIXES if w.endswith(s)), "")
            part = bracket_part(text) or part
            return LabelInfo("dimensions" if kinds[0] == "size" else kinds[0], role="component", part=part or None)
    except Exception:  # noqa: BLE001 - a label we cannot read is no measurement
        return None
    return None


def _names_a_capacity(text: str) -> bool:
    return any(w in CAPACITY_WORDS for w in re.split(r"[\W_]+", fold(text)) if w)


def _cjk_component(squashed: str) -> LabelInfo | None:
    """A CJK label naming a part's extent (:func:`scrapers.label_forms.cjk_component`): a component's value."""
    found = cjk_component(squashed)
    return None if found is None else LabelInfo(found[0], role="component", part=found[1])
