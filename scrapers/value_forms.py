"""How stores write a value, and how the spec-table reader takes it (:func:`written_value`): the metric
figure when both are stated, a unit in brackets after the number, a narrow range inside a size, axis words
each with a number inside one value (:func:`axis_segments`), a size of one length.
"""

from __future__ import annotations

import re

from kb.measures.units import units_pattern
from scrapers.label_vocabulary import (
    BODY_WORDS,
    INCLUDING,
    NEGATIONS,
    OVERALL,
    PACKAGE_WORDS,
    QUALIFIERS,
    fold,
)
from scrapers.labels import AXES, classify_label, classify_other, without_order_hint
from scrapers.quantities import clean_text, length_unit, mass_unit, parse_length

__all__ = [
    "NARROW_RANGE", "axis_segments", "bound_value", "branded_part", "fluid_ounces", "for_one_size", "keyed_variant", "metric_figure", "note_words", "one_length", "packed_value",
    "placeholder_size", "sentence_value", "written_value",
]

#: A range no wider than this ratio is the object's own adjustment or a tolerance (``30-32 cm``, ``1,2 – 1,5
#: kg``); a wider one spans variants of different sizes.
NARROW_RANGE = 1.5

_SEGMENT_SPLIT = re.compile(r"\s+|[、，,;/／|]+")

#: The name of the one size an article comes in (``One Size``, ``Taille unique``, ``Talla única``, ``Taglia
#: unica``, ``Tamanho único``, ``Einheitsgröße``, ``Uniwersalny``, ``Univerzální``, ``Onesize``, ``Free size``,
#: ``Beden: Tek Ebat``), named after the size word: a value "for" that size is the product's.
_ONE_SIZE = (
    r"(?:one[\s-]*size|onesize|os|unique|[uú]nic[ao]|uni|universal\w*|uniwersaln\w*|univerz[aá]ln\w*|"
    r"free(?:[\s-]*size)?|einheitsgr\w*|tek|unisize)\b"
)
#: A value stated for one size of the garment or article (``Gesamtlänge: 72 cm bei Größe S``, ``Length:
#: 70 cm in size M``, ``Longueur : 68 cm en taille 38``, ``71 cm (talla M)``): a variant's, not the product's;
#: not when that size is the only one (``27 cm (talla One Size)``, :data:`_ONE_SIZE`).
_FOR_ONE_SIZE = re.compile(
    r"\d.*?(?:\b(?:bei|in|für|fuer|for|at|en|pour|na|em|w|i|på|ve|v|voor|bij|op)\s+(?:der\s+|la\s+|a\s+|de\s+)?"
    r"|[(（]\s*)(?:gr(?:ö|oe)(?:ß|ss)e|size|taille|talla|taglia|maat|rozmiarze|rozmiar|tamanho|storlek|"
    rf"størrelse|velikosti|koko|méret|beden)\b(?!\s*[:：]?\s*{_ONE_SIZE})",
    re.IGNORECASE,
)


def for_one_size(value: str) -> bool:
    """Whether a measured value says it is for one size of the article (:data:`_FOR_ONE_SIZE`)."""
    return len(value) < 200 and _FOR_ONE_SIZE.search(value) is not None


#: A bracket after a measured number with no figure inside: a qualifier of that value (``5,197 kg [inkl.
#: Verpackung]``, ``1.65 lb (Body Only)``, ``5.60kg (mit Standfuß)``), not another value.
_VALUE_BRACKET = re.compile(r"\d[^(\[（]*?[(\[（]([^)\]）\d]{1,80})[)\]）]")
#: Words that say a value includes what follows (the labels' words, and German's written-out forms).
_INCLUDING = INCLUDING | {fold(w) for w in ("einschl", "einschließlich")}


def packed_value(value: str) -> bool:
    """Whether a measured value says in a bracket after its number that it includes the packaging
    (``5.197kg [Eigenmessung inkl. Verpackung & Beilagen]``, ``2 kg (incl. packaging)``, ``(with box)``):
    the label's package rule (``Gewicht inkl. Verpackung``) read where the store writes it after the value.
    A negation first (``(ohne Verpackung)``, ``(without packaging)``) keeps it the product's, and so does a
    part it includes (``(mit Standfuß)``)."""
    if len(value) > 200:
        return False
    for m in _VALUE_BRACKET.finditer(value):
        words = [w for w in re.split(r"[\W_]+", fold(m.group(1))) if w]
        including = False
        for w in words:
            if w in NEGATIONS:
                break
            if w in _INCLUDING:
                including = True
            elif including and w in PACKAGE_WORDS:
                return True
    return False


def note_words(value: str) -> frozenset[str]:
    """The folded words of the brackets after a value's figures (``160 x 680 x 440 mm [Eigenmessung]``:
    ``{"eigenmessung"}``), what the store says of how or what it measured."""
    if len(value) > 200:
        return frozenset()
    return frozenset(w for m in _VALUE_BRACKET.finditer(value) for w in re.split(r"[\W_]+", fold(m.group(1))) if w)


#: ``(Body Only)``, ``(nur Gehäuse)``, ``(boîtier seul)``, ``(solo cuerpo)``: a bracket after the value
#: restricting it to one part of what is sold, the part named in one to three words beside an "only" word.
_ONLY_WORDS = "only nur seul seule seulement uniquement solo sólo solamente soltanto apenas somente só tylko alleen"
_ONLY = re.compile(
    rf"^(?:(?P<before>[^\W\d_]+(?:\s+[^\W\d_]+){{0,2}})\s+(?:{'|'.join(_ONLY_WORDS.split())})"
    rf"|(?:{'|'.join(_ONLY_WORDS.split())})\s+(?P<after>[^\W\d_]+(?:\s+[^\W\d_]+){{0,2}}))$",
    re.IGNORECASE,
)
#: A name that sells more than one part: ``Camera with 24-120mm Lens``, ``Kamera mit Objektiv``, ``Kit``,
#: ``Body + Lens``, ``Bundle``.
_KIT_NAME = re.compile(r"\b(?:with|w/|mit|avec|con|com|inkl|incl|including|kit|bundle|combo)\b|\s\+\s", re.IGNORECASE)


def only_part(value: str, title: str | None) -> str | None:
    """The part a value says in a bracket it is of alone (``1.65 lb / 750 g (Body Only)``: ``body``), when
    the page's name sells more than that part (``Nikon D750 DSLR Camera with 24-120mm Lens``): then it is a
    component's value, not the product's. On a page selling the part alone (``Nikon D750 Body``) None."""
    if len(value) > 200 or not title or not _KIT_NAME.search(title):
        return None
    for m in _VALUE_BRACKET.finditer(value):
        only = _ONLY.match(m.group(1).strip())
        if only:
            return (only["before"] or only["after"]).lower()
    return None


#: A value that starts with the name of the variant it is for (``1-inch: 71"L x 24"W``, ``Queen: 60 x 80 in``,
#: ``Modell S: 30 cm``): a short key with a letter, a colon, then the number.
_KEYED = re.compile(r"^\s*[-–•*]?\s*([^:\n]{1,24}?)\s*[:：]\s*(?=[\d½¼¾⅓⅔⅛])")


def keyed_variant(value: str) -> bool:
    """Whether a measured value is keyed by the variant it is for (:data:`_KEYED`): its key names neither
    a measurement (``Height: 30 cm`` inside a dimensions field is the product's axis) nor the whole
    product (``Overall: 30 x 20 cm``, ``approx.: 2 kg``)."""
    m = _KEYED.match(value)
    if m is None or not re.search(r"[^\W\d_]", m.group(1)) or len(m.group(1).split()) > 3:
        return False
    key = m.group(1)
    if classify_label(key) is not None or classify_other(key) is not None:
        return False
    words = [w for w in re.split(r"[\W_]+", fold(key)) if w]
    return not all(w in QUALIFIERS or w in OVERALL or w in BODY_WORDS for w in words)


#: Words before a labelled value's first figure from which the value is a sentence, not the field's value.
PROSE_WORDS = 4
_WORD = re.compile(r"[^\W\d_]+")


def sentence_value(value: str) -> bool:
    """Whether a labelled value is a sentence under the label (a photo caption under ``Dimensions``: ``The
    keyboard is placed on a 900 x 400 mm desk pad``), not the field's value: :data:`PROSE_WORDS` or more words
    before its first figure, with no colon among them (a sub-label: ``Set Size(WXDXH) with Stand: 923``) and
    not themselves a measurement label (``Breite x Höhe x Tiefe 30 x 20 x 10``); an axis-order hint is no
    word (``(B x H x T) 305 x 17,9 x 196 mm``)."""
    m = re.search(r"\d", value)
    if m is None or re.search(r"[:：]", value[: m.start()]):
        return False
    head = value[: m.start()]
    if len(_WORD.findall(without_order_hint(head))) < PROSE_WORDS:  # ``(B x H x T) 305 x 17,9 x 196 mm``
        return False
    return classify_label(head) is None and classify_other(head) is None


_BOUND = re.compile(r"\s*(?:[<>≤≥＜＞≦≧]|&lt;|&gt;)\s*=?\s*\d")
#: Words written before a figure that make it a bound: "at most", "under", "over" in the store languages
#: (``Up to 9.9 cm``, ``bis 58,5 cm``, ``jusqu'à 30 cm``, ``hasta 5 kg``, ``fino a 30 cm``, ``até 2 kg``,
#: ``do 30 cm``, ``nad 50 cm``, ``tot 30 cm``, ``upp till 2 kg``, ``max. 5 kg``, ``unter 32 Zoll``, ``最大30cm``).
#: Not a lower bound's "from" (``Starting at 2.8 lb``: the lightest configuration, the product's own).
_BOUND_BEFORE = (
    "up to|upto|no more than|not more than|at most|less than|more than|under|below|over|above|"  # en
    "bis zu|bis|höchstens|hoechstens|maximal|minimal|unter|über|ueber|mehr als|weniger als|"  # de
    "jusqu'à|jusqu'a|jusqu’à|jusqu’a|jusque|au plus|moins de|plus de|"  # fr
    "hasta|como máximo|menos de|más de|mas de|"  # es
    "fino a|fino al|al massimo|meno di|più di|piu di|oltre|"  # it
    "até|no máximo|mais de|"  # pt
    "tot|maximaal|minder dan|meer dan|boven|onder|"  # nl
    "do|maksymalnie|poniżej|ponizej|powyżej|powyzej|ponad|nad|pod|"  # pl, cs
    "až do|až|nejvýše|méně než|více než|"  # cs
    "upp till|högst|opptil|inntil|op til|højst|enintään|yli|alle|"  # sv, no, da, fi
    "at least|mindestens|au moins|al menos|como mínimo|almeno|pelo menos|minstens|minimalnie|nejméně|minst|"
    "vähintään|maximum|minimum|max|maks|máx|mín|min|"  # and every language's abbreviations
    "最大|最小|최대|최소"  # ja, zh, ko
)
_BOUND_WORD = re.compile(
    rf"\s*(?:ca\.?\s*|approx\.?\s*)?(?:{_BOUND_BEFORE})(?<=\w)\.?\s*[:：]?\s*(?:ca\.?\s*)?\d", re.IGNORECASE
)
#: An open end after the figure (``30 cm & above``, ``6ft4+ (193cm)``, ``30 cm oder mehr``, ``et plus``,
#: ``o más``, ``e oltre``, ``ou mais``, ``i więcej``, ``en meer``, ``och mer``, ``30cm以上``, ``30cm 이하``).
_FIGURE = r"\d+(?:[.,]\d+)?\s*[^\W\d_\s]{0,6}\.?"
_BOUND_AFTER = re.compile(
    rf"\s*(?:ca\.?|approx\.?|約|约)?\s*{_FIGURE}(?:\s*{_FIGURE})?\s*(?:"
    r"(?:&|and|or|und|oder|et|ou|o|y|e|i|en|of|och|og|eller|a|lub|nebo)\s+(?:above|over|more|higher|larger|"
    r"mehr|größer|groesser|höher|plus|más|mas|oltre|più|piu|mais|więcej|wiecej|meer|mer|více|vice)\b"
    r"|\+\s*(?:[(（]|$)|(?:以上|以下|未満|未满|이상|이하|미만))",
    re.IGNORECASE,
)


def bound_value(value: str) -> bool:
    """Whether a measured value is a bound, not a measurement of the product: a comparison sign before its
    figure (``<5ft (152cm)``, ``> 30 cm``, ``≤ 2 kg``: a review form's height brackets), a bound word before it
    (:data:`_BOUND_BEFORE`: ``Up to 9.9 cm``, a store's search filter; ``bis 58,5 cm``; ``max. 5 kg``), or an
    open end right after it (``30 cm & above``, ``30cm以上``: :data:`_BOUND_AFTER`)."""
    head = value[:200]
    return any(pattern.match(head) is not None for pattern in (_BOUND, _BOUND_WORD, _BOUND_AFTER))


_OUNCES = re.compile(r"\d\s*(?:oz|ounces?)\b\.?", re.IGNORECASE)
_VOLUME = re.compile(r"\d\s*(?:ml|cl|dl|l|liters?|litres?)\b", re.IGNORECASE)


def fluid_ounces(value: str) -> bool:
    """Whether a value's ounces are a volume: written beside a volume (``4oz / 118ml / X Small``, a cup's
    capacity; ``12 fl oz``), not a weight."""
    return re.search(r"\bfl\.?\s*oz\b", value, re.IGNORECASE) is not None or (
        _OUNCES.search(value) is not None and _VOLUME.search(value) is not None
    )


def branded_part(value: str) -> str | None:
    """The branded thing a measured value names before its figure (``Thickness: Vibram® 5mm``: the sole, a
    maker's part or material named by its trademark), else None: a value naming a trademarked component
    measures that component, not the product (a product's own name is its title, not its value)."""
    m = re.search(r"\d", value)
    head = value[: m.start()] if m else ""
    found = re.search(r"([^\W\d_][\w-]*)\s*[®™]", head)
    return found.group(1) if found else None


_ONE = r"(?<![\d.,])1(?:[.,]0+)?(?:\s*[^\W\d_]{0,6}\.?|\s*[\"'″])?\s*"
#: ``1 × 1 × 1 in``, ``1x1x1 cm``: what a shop system shows when nobody entered a size.
_PLACEHOLDER = re.compile(rf"{_ONE}x\s*{_ONE}x\s*1(?:[.,]0+)?(?![\d.,])")


def placeholder_size(raw: str) -> bool:
    """Whether a size's text is the shop system's placeholder (:data:`_PLACEHOLDER`), not a measurement."""
    return _PLACEHOLDER.search(clean_text(raw.split(": ", 1)[-1])) is not None


def axis_segments(value: str, unit: str | None, decimal_comma: bool | None) -> list[tuple[str, float]]:
    """The extents of a value written as axis words each followed by a number (``幅30cm 奥行20cm 高さ10cm``,
    ``W 30 cm, D 20 cm``): (axis, cm) per segment, [] unless every axis is named once."""
    found: list[tuple[str, float]] = []
    text = clean_text(value)
    if len(text) > 200:
        return []
    for segment in _SEGMENT_SPLIT.split(text):
        m = re.match(r"([^\W\d_]+)\s*(?:約|约)?\s*(\d.*)$", segment)
        if not m:
            continue
        info = classify_label(m.group(1))
        if info is None or info.kind not in AXES:
            continue
        length = parse_length(m.group(2), unit, decimal_comma)
        if length is not None:
            found.append((info.kind, length))
    kinds = [k for k, _ in found]
    return found if len(set(kinds)) == len(kinds) <= 3 else []


def one_length(value: str, unit: str | None, decimal_comma: bool | None) -> float | None:
    """The one length a size value states before any other word (``19cm／240p``), else None."""
    head = re.split(r"[／/|;,、]", clean_text(value), maxsplit=1)[0]
    return parse_length(head, unit, decimal_comma) if len(head) <= 30 else None


# A figure with an imperial or a metric length or mass unit (the words of the one unit table).
_IMPERIAL = re.compile(rf"\d\s*(?:\"|(?:{units_pattern('length', 'mass', imperial=True)})\b)", re.IGNORECASE)
_METRIC = re.compile(rf"\d\s*(?:{units_pattern('length', 'mass', imperial=False)})\b", re.IGNORECASE)
_BRACKETED = re.compile(r"[(（]([^()（）]{1,80})[)）]")


_TILDE_RANGE = re.compile(r"(?<![\d.,])(\d+(?:[.,]\d+)?)\s*[~～〜]\s*(\d+(?:[.,]\d+)?)(?![\d.,])")
_BRACKETED_UNIT = re.compile(r"[(（]\s*([^\W\d_]{1,12}\.?)\s*[)）]")


def written_value(value: str) -> tuple[str, str | None]:
    """A value as the readers take it, with a note when it was rewritten: the metric figure when both are
    stated (:func:`metric_figure`), a unit in brackets after the number (``0.35 (pounds)``), and a
    narrow range inside a size (ASUS' ``31.18 x 22.25 x 1.49 ~ 1.69 cm``: the upper bound, the most room
    the object needs, as :func:`range_extent` takes one)."""
    note = None
    metric = metric_figure(value)
    if metric is not None:
        value = metric  # "Height: 0.61 inch (1.56 cm)": the metric figure
    if "(" in value or "（" in value:
        value = _BRACKETED_UNIT.sub(lambda m: f" {m.group(1)}" if _is_unit_word(m.group(1)) else m.group(0), value)
    if " x " in clean_text(value) and _TILDE_RANGE.search(value):
        def upper(m: re.Match) -> str:
            low, high = (float(g.replace(",", ".")) for g in m.groups())
            return m.group(2) if 0 < low <= high <= NARROW_RANGE * low else m.group(0)

        rewritten = _TILDE_RANGE.sub(upper, value)
        if rewritten != value:
            note, value = f"a range inside the size ({value[:80]}); took the upper bound", rewritten
    return value, note


def _is_unit_word(word: str) -> bool:
    return length_unit(word) is not None or mass_unit(word) is not None


def metric_figure(value: str) -> str | None:
    """The metric figure of a value that states both (``0.61 inch (1.56 cm)``, ``2.8 lb (1.27 kg)``,
    ``12.32 x 8.72 in (312.8 x 221.6 mm)``): the bracketed metric part when the rest is imperial, else
    None (the value is read as written). Computer makers round each figure separately; the metric one
    is the product's own."""
    if "(" not in value and "（" not in value:
        return None
    m = _BRACKETED.search(value)
    if not m or not _METRIC.search(m.group(1)) or _IMPERIAL.search(m.group(1)):
        return None
    outside = value[: m.start()]
    if not _IMPERIAL.search(outside) or _METRIC.search(outside):
        return None
    return m.group(1)
