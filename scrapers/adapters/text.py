"""Free text: sizes written in the product's name (``Panel 60 x 30 cm``, ``Table, 235x100 cm``), the page's
title and canonical URL (``text``), and sizes, weight and material in sentences of the description
(``free_text``, a fallback).

The lowest priority: a size in a name is often only two of three dimensions, or a variant's; it is
used only when nothing better states the dimensions, always with a note. The name itself comes from
here when structured data has none.
"""

from __future__ import annotations

import re

from kb.measures.units import units_pattern
from scrapers.adapters import Observation, adapter
from scrapers.inline_pairs import DIGIT
from scrapers.normalize import material_from_text
from scrapers.page import Page, lines_matching
from scrapers.quantities import parse_dims, parse_length, parse_mass, third_axis
from scrapers.signs import minus_before

__all__ = ["MAX_PROSE_LINES", "free_text", "text"]

#: Only the first this many visible lines are read as prose (the description comes early; a page of
#: thousands of lines is a catalogue or a spec dump, and reading it all would cost seconds).
MAX_PROSE_LINES = 5000


@adapter("text", priority=90)
def text(page: Page) -> list[Observation]:
    """The page title (name, and a size written in it), the canonical URL and "made of ..." material."""
    obs: list[Observation] = []
    title = page.title
    for i, candidate in enumerate(page.titles):  # later ones stand in when one breaks the name rules
        obs.append(Observation("name", candidate, rank=2, order=i, raw=candidate))
    if title:
        dims = parse_dims(title, None, page.decimal_comma)
        if dims:
            obs.append(
                Observation(
                    "dims",
                    dims[0].values_cm,
                    rank=2,
                    raw=title,
                    roles=dims[0].roles,
                    note=f"dimensions read from the product name ({title!r})",
                )
            )
        else:
            obs.extend(_title_diameter(title, page.decimal_comma))
        obs.extend(_title_mass(title, page.decimal_comma))
    prose = page.lines[:MAX_PROSE_LINES]
    said = lines_matching(prose, _MADE_OF) | lines_matching(prose, _SOLID)
    for k, line in enumerate(prose):
        if len(line.text) > 600 or k not in said:
            continue
        material = None
        for pattern in (_MADE_OF, _SOLID):
            for made in pattern.finditer(line.text):
                material = material_from_text(made.group("m"))
                if material:
                    break
            if material:
                break
        if material:
            obs.append(Observation("material", material, rank=2, order=line.index, raw=line.text[:200]))
            break
    if page.canonical_url:
        obs.append(Observation("canonical_url", page.canonical_url, rank=2, raw=page.canonical_url))
    return obs


#: A count times a quantity (``12 x 250g``, ``2×1 kg``): the name sells a pack, its mass is not one item's.
_TIMES = re.compile(r"\d\s*[x×*]\s*\d", re.IGNORECASE)


#: Ounces in the name of a vessel are its capacity (``Water Bottle 32oz``), not its mass.
_VESSEL = re.compile(
    r"\b(?:bottles?|tumblers?|cups?|mugs?|flasks?|jugs?|pitchers?|thermos|jars?|canteens?|glass(?:es)?|"
    r"carafes?|kettles?|shakers?|growlers?|containers?|pots?|pans?|bowls?|cans?|canisters?)\b",
    re.IGNORECASE,
)
_OUNCES = re.compile(r"\d\s*(?:oz|ounces?)\b", re.IGNORECASE)


def _title_mass(title: str, decimal_comma: bool | None) -> list[Observation]:
    """A net quantity written in the product's name (``Almonds - 13oz``, ``Qualità Oro, 250g Dose``): the
    lowest-ranked mass, used only when nothing on the page states one. None from a pack's name, nor
    ounces in a vessel's name (a capacity)."""
    if _TIMES.search(title) or (_OUNCES.search(title) and _VESSEL.search(title)):
        return []
    grams = parse_mass(title, None, decimal_comma)
    if grams is None:
        return []
    note = f"mass read from the product name ({title!r})"
    return [Observation("mass", grams, rank=2, raw=title, note=note, role="name")]


_QTY = rf"\d+(?:[.,]\d+)*\s*(?:{units_pattern('length')}|\"|'')"  # a length, its unit from the one table

#: Round pans, named so in any of the supported languages: a single length in such a name is the pan's
#: diameter (``SKÄNKA Frying pan - gray, 11"``, ``Lodge 12" Cast Iron Skillet``). A bare "pan" is not
#: enough (a sheet pan's 18" is its length), nor is any other name: a screen's 27" is its diagonal.
_ROUND_PAN = re.compile(
    r"\b(?:skillets?|(?:frying|fry|saut[ée]|crepe|crêpe|omelette?|grill|paella) pans?|woks?|(?:brat|grill|wok)?pfannen?|"
    r"po[êe]les?|sart[ée]n(?:es)?|padell[ae])\b",
    re.IGNORECASE,
)


def _title_diameter(title: str, decimal_comma: bool | None) -> list[Observation]:
    """A round pan's diameter written in its name (see :data:`_ROUND_PAN`): every length the name states is
    that one value; the lowest-ranked size, used only when nothing on the page states the product's."""
    if not _ROUND_PAN.search(title):
        return []
    lengths = [parse_length(m.group(0), None, decimal_comma) for m in re.finditer(_QTY, title, re.IGNORECASE)]
    lengths = [v for v in lengths if v is not None]
    if not lengths or any(abs(v - lengths[0]) > 0.02 * lengths[0] for v in lengths):
        return []
    note = f"a round pan's diameter read from the product name ({title!r})"
    return [Observation("dims", (lengths[0],), rank=2, raw=title, note=note, roles=("diameter",), role="name")]

_AXIS_WORDS = {
    "long": "length", "in length": "length", "de long": "length", "de largo": "length", "lang": "length",
    "wide": "width", "in width": "width", "de large": "width", "de ancho": "width", "breit": "width",
    "tall": "height", "high": "height", "in height": "height", "de haut": "height", "de alto": "height",
    "hoch": "height", "deep": "depth", "in depth": "depth", "tief": "depth", "thick": "thickness",
    "dick": "thickness", "across": "diameter", "in diameter": "diameter", "de diamètre": "diameter",
    "de diámetro": "diameter", "im durchmesser": "diameter",
}  # fmt: skip
_AXIS_PHRASE = re.compile(
    rf"(?P<q>{_QTY})\s+(?P<axis>{'|'.join(sorted(map(re.escape, _AXIS_WORDS), key=len, reverse=True))})\b",
    re.IGNORECASE,
)
_MEASURES = re.compile(
    r"\b(?:measures?|measuring|dimensions?|size|mide|misura|mede|mesure|misst|размеры|размер|габариты|"
    r"wymiary|rozměry|rozmery|boyutlar[ıi]?|afmetingen)\b",
    re.IGNORECASE,
)
#: A measuring verb right before one axis phrase: "It measures 89 cm high", "Il mesure 89 cm de haut".
_MEASURES_ONE = re.compile(
    rf"\b(?:measures?|mesure|mide|misura|mede|misst|is|est|ist|es)\s+(?:about |approximately |environ |ca\. |etwa )?"
    rf"{_QTY}\s+(?:{'|'.join(sorted(map(re.escape, _AXIS_WORDS), key=len, reverse=True))})\b",
    re.IGNORECASE,
)
_WEIGHS = re.compile(
    r"\b(?:weighs?|weighing|weight of|wiegt|pesa|pèse|waży|весит|weegt|váží|váži)\s+(?:just |only |about "
    r"|approx\.? |approximately |roughly |around |ca\.? |nur |etwa |environ |unos |circa |cerca de |около "
    r"|примерно |około |asi |přibližně |ongeveer |à peine |seulement |tout juste |knapp |lediglich |apenas "
    r"|solo |appena |soltanto )?(?P<q>\d+(?:[.,]\d+)*\s*[^\W\d_]+\.?)",
    re.IGNORECASE,
)
#: A comparison right after the weight a sentence states: the weight is a difference from another model's
#: ("weighs 30g, or ~5% lighter than the LCD model", "weighs 200 g less than", "wiegt 300 g weniger"), never
#: the product's own.
_COMPARED = re.compile(
    r"[\s,;]{0,3}(?:or\s+|oder\s+|soit\s+|ou\s+)?(?:~|about\s+|around\s+|roughly\s+|ca\.?\s+|etwa\s+)?"
    r"(?:\d+(?:[.,]\d+)?\s*%\s*)?(?:(?:lighter|heavier|leichter|schwerer|plus\s+l[ée]g[eè]re?s?|plus\s+lourde?s?)\b|"
    r"(?:less|more|weniger|mehr|de\s+moins|de\s+plus|en\s+moins|en\s+plus|menos|más|in\s+meno|in\s+più)"
    r"(?=\s*(?:than|als|que|di)\b|\s*[.!;]|\s*$))",
    re.IGNORECASE,
)
#: A sentence saying who wears which size ("Model is 189cm tall and wearing a size M", "Model is 6'0\" and
#: wears size M", "Das Model ist 1,89 m groß und trägt Größe M", "Le mannequin mesure 1,89 m et porte une
#: taille M"): a garment page's note on the wearer; its lengths are the wearer's, never the product's.
_WEARER = re.compile(
    r"\b(?:wears?|wearing|trägt|tragt|porte|lleva|indossa|veste|draagt|nosi|bär)\s+(?:a\s+|the\s+|une\s+|la\s+|"
    r"die\s+|eine\s+|een\s+|maat\s+)?(?:size|grö(?:ß|ss)e|taille|talla|taglia|tamanho|maat|rozmiar|storlek|størrelse)\b",
    re.IGNORECASE,
)
_SENTENCE_END = re.compile(r"[.!?;]\s|\s/\s|\s\|\s")


def _wearers_sentence(text: str, at: int) -> bool:
    """Whether the sentence of ``text`` around position ``at`` says who wears which size (:data:`_WEARER`)."""
    start = max((m.end() for m in _SENTENCE_END.finditer(text, 0, at)), default=0)
    end = next((m.start() for m in _SENTENCE_END.finditer(text, at)), len(text))
    return _WEARER.search(text, start, end) is not None


_MADE_OF = re.compile(
    r"\b(?:made (?:of|from|out of)|crafted (?:of|from)|carved (?:from|out of)|cut from|cast in|constructed (?:of|from)|"
    r"aus|hergestellt aus|fabricado en|realizzato in|feito de|fait en|en)\s+"
    r"(?:a single (?:piece|slab|block) of |solid |pure |massivem? |100% )?"
    r"(?P<m>[^\W\d_]+(?:\s+[^\W\d_]+)?)",
    re.IGNORECASE,
)
# "a solid marble mortar", "pure copper", "massivem Eichenholz": a material word right after "solid".
_SOLID = re.compile(
    r"\b(?:solid|pure|massive|massivem?|massiv|massif|macizo|maciza|massiccio|maciço)\s+(?P<m>[^\W\d_]+)",
    re.IGNORECASE,
)


@adapter("free_text", priority=80, fallback=True)
def free_text(page: Page) -> list[Observation]:
    """Sizes and weight in sentences of the description ("30 cm long, 6 cm wide", "weighs 45 g",
    "measures 7 x 7 x 7 cm", "made of olive wood"); used only when nothing better states them."""
    obs: list[Observation] = []
    dc = page.decimal_comma
    note = "read from the description text"
    for line in page.lines[:MAX_PROSE_LINES]:
        text = line.text
        if not 15 <= len(text) <= 600:
            continue
        if DIGIT.search(text) is None and (text.isascii() or not any(ch.isdigit() for ch in text)):
            continue  # (an ASCII text's digits are DIGIT's; any other text keeps str.isdigit's, "²" too)
        raw = text[:200]
        if _MEASURES.search(text):
            dims = parse_dims(text, None, dc)
            if dims:
                values, roles = dims[0].values_cm, dims[0].roles
                extra = third_axis(text.split(dims[0].text, 1)[-1], dc) if len(values) == 2 else None
                if extra is not None:
                    values, roles = (*values, extra), (*roles, "extent")
                obs.append(
                    Observation("dims", values, rank=2, order=line.index, raw=raw, note=note, roles=roles)
                )
        axes: dict[str, float] = {}
        for m in _AXIS_PHRASE.finditer(text):
            if _wearers_sentence(text, m.start()):
                continue  # "Model is 189cm tall and wearing a size M": the wearer's height
            kind = _AXIS_WORDS[m.group("axis").lower()]
            value = parse_length(m.group("q"), None, dc)
            if value is not None and minus_before(text, m.start("q")):
                value = -value  # "-30 cm long": stated negative, refused by the limits
            if value is not None and kind not in axes:
                axes[kind] = value
        if len(axes) >= 2 or (len(axes) == 1 and _MEASURES_ONE.search(text)):
            # "30 cm long, 6 cm wide"; one axis only after a measuring verb ("Il mesure 89 cm de haut")
            obs.append(
                Observation(
                    "dims", tuple(axes.values()), rank=2 if len(axes) >= 2 else 3, order=line.index, raw=raw,
                    note=note, roles=tuple(axes),
                )
            )  # fmt: skip
        weighs = _WEIGHS.search(text)
        if weighs and _COMPARED.match(text, weighs.end()):
            weighs = None  # "weighs 30g, or ~5% lighter than the LCD model": a difference, not its weight
        if weighs:
            mass = parse_mass(weighs.group("q"), None, dc)
            if mass is not None:
                obs.append(Observation("mass", mass, rank=2, order=line.index, raw=raw, note=note))
    for o in obs:
        o.site_wide = page.site_wide_line(o.order)
    return obs
