"""Numbers and physical quantities as storefront pages write them, converted to catalog units (cm, g).

Handles what real pages do: decimal commas and thousands separators (``4,7 kg``, ``61,800 kg``,
``1,643,215``), invisible marks (U+200E, U+200F, zero-width spaces, NBSP), full-width characters
(``：``, ``１``), the times signs ``x``, ``×``, ``*``, ``✕`` and Cyrillic ``х``, inch marks ``"``, ``''``
and ``″``, a unit after every term (``19 cm x 17 cm x 2 cm``) or only after the last, letter suffixes
(``23L x 13,8W x 30H centímetros``), unit words in many languages and the UN/CEFACT codes used by
schema.org (CMT MMT MTR INH FOT GRM KGM LBR ONZ).

Every public function takes any text and never raises: a text without a quantity gives None or [].

Decimal commas: a comma followed by other than exactly three digits is a decimal comma (``4,7``); with
both ``.`` and ``,`` the last one is the decimal mark; ``1,643,215`` is grouped. A single comma followed
by exactly three digits (``61,800``) is ambiguous: it is read as a decimal comma when the page's
language writes decimal commas (``decimal_comma=True``, see :func:`decimal_comma_for`), else as a
thousands separator. A single dot followed by exactly three digits (``1.200``) is read as a thousands
separator only in a decimal-comma language and when the integer part is not 0.
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass

__all__ = [
    "LENGTH_UNITS",
    "MASS_UNITS",
    "Dims",
    "clean_text",
    "decimal_comma_for",
    "length_unit",
    "mass_unit",
    "parse_dims",
    "parse_length",
    "parse_mass",
    "parse_number",
    "third_axis",
    "unit_hint",
]

# Invisible formatting characters pages sprinkle into values (LRM/RLM, embeddings, isolates, zero widths).
_INVISIBLE = dict.fromkeys(
    map(
        ord,
        "\u200b\u200c\u200d\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\ufeff\u00ad",
    ),
    None,
)
# Hebrew unit abbreviations are written with a gershayim (or a plain double quote) inside: ס"מ = cm.
_HEBREW_UNIT_NAMES = {"סמ": "cm", "ממ": "mm", "קג": "kg"}
_HEBREW_UNITS = re.compile(r"(?<![\u0590-\u05ff])([סמק][\"\u05f4][מג])(?![\u0590-\u05ff])")
_SPACES = re.compile(r"[\s\u00a0\u2000-\u200a\u202f\u205f\u3000]+")

#: Length units -> centimetres per unit. Keys are lower case, accents kept (matching strips them too).
LENGTH_UNITS: dict[str, float] = {}
#: Mass units -> grams per unit.
MASS_UNITS: dict[str, float] = {}


def _add(table: dict[str, float], factor: float, *names: str) -> None:
    for name in names:
        table[name] = factor
        table[_strip_accents(name)] = factor


def _strip_accents(text: str) -> str:
    decomposed = unicodedata.normalize("NFKD", text)
    return "".join(ch for ch in decomposed if not unicodedata.combining(ch))


_add(
    LENGTH_UNITS,
    0.1,
    "mm",
    "mmt",
    "millimeter",
    "millimeters",
    "millimetre",
    "millimetres",
    "milímetro",
    "milímetros",
    "millimètre",
    "millimètres",
    "millimetri",
    "millimetro",
    "milimetr",
    "milimetrów",
    "мм",
    "毫米",
    "公釐",
    "ミリ",
    "ミリメートル",
    "milimetrů",
    "milimetre",
)
_add(
    LENGTH_UNITS,
    1.0,
    "cm",
    "cmt",
    "centimeter",
    "centimeters",
    "centimetre",
    "centimetres",
    "zentimeter",
    "centímetro",
    "centímetros",
    "centimètre",
    "centimètres",
    "centimetri",
    "centimetro",
    "centymetr",
    "centymetrów",
    "см",
    "公分",
    "厘米",
    "釐米",
    "センチ",
    "センチメートル",
    "сантиметр",
    "сантиметров",
    "centimetrů",
    "santim",
    "santimetre",
)
_add(
    LENGTH_UNITS,
    100.0,
    "m",
    "mtr",
    "meter",
    "meters",
    "metre",
    "metres",
    "metro",
    "metros",
    "mètre",
    "mètres",
    "metri",
    "м",
    "米",
    "公尺",
    "メートル",
    "метр",
    "метра",
    "метров",
)
_add(
    LENGTH_UNITS,
    2.54,
    "in",
    "inh",
    "inch",
    "inches",
    '"',
    "''",
    "″",
    "zoll",
    "pulgada",
    "pulgadas",
    "pouce",
    "pouces",
    "pollice",
    "pollici",
    "polegada",
    "polegadas",
    "дюйм",
    "дюйма",
    "дюймов",
    "吋",
    "英寸",
)
_add(LENGTH_UNITS, 30.48, "ft", "fot", "foot", "feet", "fuß", "pies", "pieds", "piedi", "pés", "'", "′")

_add(MASS_UNITS, 0.001, "mg", "mgm", "milligram", "milligrams", "milligramm", "мг")
_add(
    MASS_UNITS,
    1.0,
    "g",
    "grm",
    "gr",
    "gram",
    "grams",
    "gramm",
    "gramme",
    "grammes",
    "gramo",
    "gramos",
    "grammo",
    "grammi",
    "grama",
    "gramas",
    "gramów",
    "gramy",
    "gramů",
    "gramu",
    "г",
    "гр",
    "грамм",
    "грамма",
    "граммов",
    "克",
    "公克",
    "グラム",
)
_add(
    MASS_UNITS,
    1000.0,
    "kg",
    "kgm",
    "kgs",
    "kilo",
    "kilos",
    "kilogram",
    "kilograms",
    "kilogramm",
    "kilogramme",
    "kilogrammes",
    "kilogramo",
    "kilogramos",
    "chilogrammo",
    "chilogrammi",
    "quilograma",
    "quilogramas",
    "quilo",
    "quilos",
    "kilogramów",
    "kilogramy",
    "kilogramů",
    "килограмм",
    "килограмма",
    "килограммов",
    "кило",
    "кг",
    "公斤",
    "千克",
    "キログラム",
    "キロ",
)
_add(
    MASS_UNITS,
    453.59237,
    "lb",
    "lbs",
    "lbr",
    "pound",
    "pounds",
    "pfund",
    "libra",
    "libras",
    "livre",
    "livres",
    "фунт",
)
_add(
    MASS_UNITS,
    28.349523125,
    "oz",
    "onz",
    "ounce",
    "ounces",
    "unze",
    "unzen",
    "onza",
    "onzas",
    "once",
    "onces",
    "oncia",
    "oncie",
)

# Arabic and Hebrew unit words (Hebrew abbreviations with a gershayim are rewritten by clean_text).
_add(LENGTH_UNITS, 1.0, "سم", "سنتيمتر")
_add(LENGTH_UNITS, 0.1, "مم", "ملم")
_add(MASS_UNITS, 1000.0, "كجم", "كغ", "كيلو", "كيلوغرام", "קילו", "кгр")
_add(MASS_UNITS, 1.0, "جم", "غ", "غرام", "جرام", "גרם")

#: Only the first this many characters of a value are read (values are short; this bounds the work).
MAX_TEXT = 2000
# A number starts at a digit (atomic: no backtracking), or is a leading-dot decimal like ".5" after a
# space, an opening bracket or a colon.
_NUMBER = r"(?:(?<![\d.,])(?>\d+(?:[.,]\d+)*)|(?<![^\s(:])(?>\.\d+))"
# Unit tokens: words (any script), CJK unit characters, inch and foot marks. "lb." ends with a dot.
_UNIT = r"(?:''|[\"″′']|(?![xX]\b)[^\W\d_]+\.?)"
_DOT_GROUPED = re.compile(r"\d{1,3}(?:\.\d{3})+")
_TIMES = r"(?:\s*\bx\b\s*)"  # clean_text writes every times sign as " x "

_DIMS_RE = re.compile(
    rf"(?P<n1>{_NUMBER})\s*(?P<u1>{_UNIT})?\s*(?P<l1>\(?\b(?![xX]\b)[a-zA-Z]\b\)?)?"
    rf"{_TIMES}(?P<n2>{_NUMBER})\s*(?P<u2>{_UNIT})?\s*(?P<l2>\(?\b(?![xX]\b)[a-zA-Z]\b\)?)?"
    rf"(?:{_TIMES}(?P<n3>{_NUMBER})\s*(?P<u3>{_UNIT})?)?"
)
# An axis letter or word written before a number inside a dimensions value.
_AXIS_PREFIX = re.compile(
    r"(?:(?<=^)|(?<=[\s(:;,*×✕xх]))(?:[LWHDBTPlwhdbtp]|長|长|寬|宽|高|深|厚|幅|奥行き?|高さ|長さ|(?i:length|width|height|depth|thickness|"
    r"länge|breite|höhe|tiefe|longueur|largeur|hauteur|profondeur|largo|ancho|alto|altura|profundidad))"
    r"\.?\s*[:=]?\s*(?:約|约)?\s*(?=\d)"
)
_DIAMETER_PREFIX = re.compile(
    rf"(?:(?<=^)|(?<=[\s(:;,]))(?:直径|直徑|[ØøΦφ⌀]|dia\.|diameter|durchmesser|diamètre|diámetro|diametro|"
    rf"диаметр|średnica|průměr|priemer)\s*[:=]?\s*(?P<n>{_NUMBER})",
    re.IGNORECASE,
)
_POUNDS_OUNCES = re.compile(
    r"(?<![\d.])((?>\d+(?:\.\d+)?))\s*(?:lbs?|pounds?)\.?,?\s*(?:and\s+)?((?>\d+(?:\.\d+)?))\s*(?:oz|ounces?)\b",
    re.IGNORECASE,
)
# Amazon India's "1 kg 450 g" (and "1 kg 450 grams", "2 кг 300 г").
_KILOS_GRAMS = re.compile(
    r"(?<![\d.,])((?>\d+))\s*(?:kg|kgs|kilograms?|кг)\.?,?\s*(?:and\s+)?((?>\d{1,3}))\s*(?:g|gr|grams?|г)(?![^\W\d_])",
    re.IGNORECASE,
)
_QUANTITY_RE = re.compile(rf"(?P<n>{_NUMBER})\s*(?P<u>{_UNIT})?")
_TIMES_SIGN = re.compile(r"(\d\s*)([^\W\d_]{1,12}\.?|[\"'″]{1,2})?(\s*)[xX×✕✖*хХ]\s*(?=\d)")
_VOLUME_UNITS = frozenset(
    "l ml cl dl liter liters litre litres litro litros litri литр л мл 公升 毫升 升".split()
)
_RANGE_RE = re.compile(rf"{_NUMBER}\s*(?:{_UNIT})?\s*(?:-|–|—|~|to|bis|a|à)\s*{_NUMBER}")

#: Languages whose pages write decimal commas (the language part of an html lang / locale tag).
DECIMAL_COMMA_LANGUAGES = frozenset(
    "de fr es it pt nl pl cs sk sl hr sr bs ru uk be kk bg ro hu da sv nb nn no fi et lv lt tr el id vi".split()
)
# Country-code domains of decimal-comma countries (used when the page does not declare its language).
_DECIMAL_COMMA_TLDS = frozenset(
    "de at fr be es it pt br nl pl cz sk si hr rs ru ua by kz bg ro hu dk se no fi ee lv lt tr gr id vn ar cl co".split()
)


_DECIMAL_POINT_TLDS = frozenset("com uk us au ca nz ie in tw cn jp kr hk sg mx ch".split())
# Regions whose language elsewhere writes decimal commas but which write decimal points.
_DECIMAL_POINT_REGIONS = frozenset("mx us gt hn ni pa do pr sv cu ch li".split())


def decimal_comma_for(lang: str | None = None, url: str | None = None) -> bool | None:
    """True when a page in ``lang`` (or, failing that, on ``url``'s country domain) writes decimal commas;
    False for other known languages; None when neither says."""
    if lang:
        parts = re.split(r"[-_]", lang.strip().lower())
        if parts[0]:
            if len(parts) > 1 and parts[1] in _DECIMAL_POINT_REGIONS:
                return False  # es-MX, de-CH, ... write decimal points
            return parts[0] in DECIMAL_COMMA_LANGUAGES
    if url:
        m = re.match(r"[a-z][a-z0-9+.-]*://([^/:?#]+)", url.strip().lower())
        if m:
            tld = m.group(1).rsplit(".", 1)[-1]
            if tld in _DECIMAL_COMMA_TLDS:
                return True
            if tld in _DECIMAL_POINT_TLDS:
                return False
    return None


def clean_text(text: object) -> str:
    """Text with invisible marks removed, full-width forms folded (NFKC), spaces collapsed and every
    times sign between numbers written as `` x ``."""
    if text is None:
        return ""
    if not isinstance(text, str):
        text = str(text)
    text = text.translate(_INVISIBLE)
    if _HAS_VULGAR.search(text):
        text = _VULGAR_RE.sub(_vulgar, text)  # before NFKC, which would write "23½" as "231⁄2"
    text = unicodedata.normalize("NFKC", text).replace("\u2032\u2032", '"')  # NFKC writes ″ as ′′
    if "\\" in text or "\u201d" in text or "\u201c" in text:
        # an inch mark escaped inside embedded JSON (12\" x 8\") or written as a curly quote (40” x 28”)
        text = _QUOTED_INCH.sub('"', text.replace('\\"', '"'))
    if "/" in text or "\u2044" in text:
        text = _MIXED_FRACTION.sub(_mixed, text)
        text = _FRACTION.sub(_fraction, text)
    if "'" in text or "\u2019" in text:
        text = _APOSTROPHE_THOUSANDS.sub(lambda m: re.sub(r"['\u2019]", "", m.group(0)), text)
    if "'" in text or "\u2032" in text or "f" in text:
        text = _FEET_INCHES.sub(_feet_inches, text)
    if "\u05f4" in text or '"' in text:
        text = _HEBREW_UNITS.sub(
            lambda m: _HEBREW_UNIT_NAMES.get(m.group(1)[0] + m.group(1)[2], m.group(1)), text
        )
    text = _SPACES.sub(" ", text).strip()
    # Cyrillic х/Х and other times signs after a number (and maybe a unit or letter) and before a number.
    text = _TIMES_SIGN.sub(_times, text)
    if " by " in text:
        text = _BY.sub(r"\1 x ", text)  # "8 by 10 inches", "30 cm by 20 cm"
    return _SPACES.sub(" ", text).strip()


# Fractions as imperial measurements are written: "23½", "10 1/2 in", "10-1/2", "3/4 lb", "5' 3\"".
_VULGAR_VALUES = {
    "½": 1 / 2, "¼": 1 / 4, "¾": 3 / 4, "⅓": 1 / 3, "⅔": 2 / 3, "⅛": 1 / 8, "⅜": 3 / 8, "⅝": 5 / 8,
    "⅞": 7 / 8, "⅕": 1 / 5, "⅖": 2 / 5, "⅗": 3 / 5, "⅘": 4 / 5, "⅙": 1 / 6, "⅚": 5 / 6,
}  # fmt: skip
_HAS_VULGAR = re.compile(f"[{''.join(_VULGAR_VALUES)}]")
_VULGAR_RE = re.compile(rf"(?<![\d.,])(\d{{1,4}})?[ \u00a0-]?([{''.join(_VULGAR_VALUES)}])")
#: Denominators of the fractions shops write (halves to sixty-fourths of an inch, thirds); "4/5 stars"
#: or a date like "8/1" is not a measurement.
_DENOMINATORS = frozenset({2, 3, 4, 8, 16, 32, 64})
_MIXED_FRACTION = re.compile(r"(?<![\d.,/])(\d{1,4})(?: +|-)(\d{1,2}) ?[/\u2044] ?(\d{1,2})(?![\d/])")
# A lone fraction counts only before a unit (or at the end of a value): "3/4 lb", "3/4\" thick".
_FRACTION = re.compile(
    r"(?<![\d.,/])(\d{1,2}) ?[/\u2044] ?(\d{1,2})(?![\d/.,])(?= ?(?:[^\W\d_]|[\"'\u2032]|$))"
)
# Swiss and Liechtenstein thousands: "1'200 g", "CHF 1'249.00".
_APOSTROPHE_THOUSANDS = re.compile(r"(?<![\d'\u2019.,])\d{1,3}(?:['\u2019]\d{3})+(?![\d'\u2019])")
_FEET_INCHES = re.compile(
    r"(?<![\d.,])(\d{1,3}) ?(?:'(?!')|\u2032(?!\u2032)|ft\b\.?|feet\b|foot\b)[ -]?"
    r"(\d{1,2}(?:\.\d+)?) ?(?:''|\"|in\b\.?|inch(?:es)?\b)"
)


# A curly closing (or opening) double quote right after a number is an inch mark.
_QUOTED_INCH = re.compile(r"(?<=\d)\s?[\u201c\u201d]")

_BY = re.compile(r"(\d(?:\s?(?:''|[\"″]|[a-zA-Z]{1,6}\.?))?) by (?=\d)")


def _decimal(value: float) -> str:
    """A number written so that no decimal-mark rule misreads it (never exactly three decimals)."""
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    if "." in text and len(text.split(".")[1]) == 3:
        text += "0"
    return text


def _vulgar(m: re.Match) -> str:
    whole = int(m.group(1)) if m.group(1) else 0
    return _decimal(whole + _VULGAR_VALUES[m.group(2)])


def _mixed(m: re.Match) -> str:
    num, den = int(m.group(2)), int(m.group(3))
    if den not in _DENOMINATORS or not 0 < num < den:
        return m.group(0)
    return _decimal(int(m.group(1)) + num / den)


def _fraction(m: re.Match) -> str:
    num, den = int(m.group(1)), int(m.group(2))
    if den not in _DENOMINATORS or not 0 < num < den:
        return m.group(0)
    return _decimal(num / den)


def _feet_inches(m: re.Match) -> str:
    inches = float(m.group(2))
    if inches >= 12:
        return m.group(0)
    return _decimal(int(m.group(1)) * 12 + inches) + '"'


def _times(m: re.Match) -> str:
    between = m.group(2) or ""
    if between and len(between) > 1 and length_unit(between) is None:
        return m.group(0)  # "max 5": a word, not a unit or an L/W/H letter, before the sign
    return f"{m.group(1)}{between}{m.group(3)} x "


def parse_number(text: str, decimal_comma: bool | None = None) -> float | None:
    """The number written in ``text`` (one number, separators as described in the module doc), or None."""
    if not isinstance(text, str):
        return None
    s = text.strip().replace(" ", "")
    if s.startswith(".") and s[1:].isdigit():
        s = "0" + s  # ".5 Pounds"
    if not re.fullmatch(_NUMBER, s):
        return None
    commas, dots = s.count(","), s.count(".")
    if commas and dots:
        dec = "," if s.rfind(",") > s.rfind(".") else "."
        grp = "." if dec == "," else ","
        s = s.replace(grp, "")
        if s.count(dec) > 1:
            return None
        s = s.replace(dec, ".")
    elif commas:
        parts = s.split(",")
        if commas > 1:
            if not all(len(p) == 3 for p in parts[1:]):
                return None
            s = "".join(parts)
        elif len(parts[1]) == 3 and not decimal_comma and parts[0] not in ("0", ""):
            s = "".join(parts)
        else:
            s = ".".join(parts)
    elif dots > 1:
        parts = s.split(".")
        if not all(len(p) == 3 for p in parts[1:]):
            return None
        s = "".join(parts)
    elif dots == 1:
        whole, frac = s.split(".")
        if decimal_comma and len(frac) == 3 and whole not in ("0", ""):
            s = whole + frac
    try:
        value = float(s)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _unit_key(unit: str | None) -> str:
    if not unit:
        return ""
    u = unit.strip().lower()
    if u not in ("''", '"', "'", "″", "′"):
        u = u.rstrip(".")
    return u


def length_unit(unit: str | None) -> float | None:
    """Centimetres per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a length unit."""
    key = _unit_key(unit)
    return LENGTH_UNITS.get(key, LENGTH_UNITS.get(_strip_accents(key)))


def mass_unit(unit: str | None) -> float | None:
    """Grams per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a mass unit."""
    key = _unit_key(unit)
    return MASS_UNITS.get(key, MASS_UNITS.get(_strip_accents(key)))


def unit_hint(label: str) -> str | None:
    """A unit stated in a label: ``Výška [mm]``, ``Grubość (w mm)``, ``Габариты, см``, ``Weight (kg)``,
    ``Width in cm``. Returns the unit token or None."""
    text = clean_text(label[:MAX_TEXT]).lower()
    for pattern in (
        r"[\[(]\s*(?:w|in|en|em|in\s+)?\s*([^\W\d_]+\.?|''|\")\s*[\])]",
        r",\s*([^\W\d_]+)\s*:?\s*$",
        r"\b(?:in|en|em)\s+([^\W\d_]+)\s*:?\s*$",
    ):
        for m in re.finditer(pattern, text):
            unit = m.group(1)
            if length_unit(unit) is not None or mass_unit(unit) is not None:
                return unit
    return None


@dataclass(frozen=True)
class Dims:
    """Dimensions found in a text, in the order written, converted to cm (``ranged``: a value was a range)."""

    values_cm: tuple[float, ...]
    text: str
    #: What each value measures (:data:`kb.features.EXTENT_ROLES`), from axis letters or a diameter mark;
    #: "extent" where the text does not say.
    roles: tuple[str, ...] = ()

    def extents(self) -> tuple[tuple[str, float], ...]:
        """``(role, cm)`` per stated value."""
        roles = self.roles or ("extent",) * len(self.values_cm)
        return tuple(zip(roles, self.values_cm, strict=True))


#: Axis letters (en, de: B = Breite, T = Tiefe) and diameter marks, by role.
AXIS_LETTER_ROLES = {
    "L": "length", "W": "width", "B": "width", "H": "height", "D": "depth", "T": "depth",
    "Ø": "diameter", "⌀": "diameter",
}  # fmt: skip


_AXIS_WORD_ROLES = {
    "length": "length", "länge": "length", "longueur": "length", "largo": "length",
    "width": "width", "breite": "width", "largeur": "width", "ancho": "width",
    "height": "height", "höhe": "height", "hauteur": "height", "alto": "height", "altura": "height",
    "depth": "depth", "tiefe": "depth", "profondeur": "depth", "profundidad": "depth", "thickness": "thickness",
}  # fmt: skip
_CJK_AXIS_ROLES = {
    "長": "length", "长": "length", "長さ": "length", "寬": "width", "宽": "width", "幅": "width",
    "高": "height", "高さ": "height", "深": "depth", "奥行": "depth", "奥行き": "depth", "厚": "thickness",
}  # fmt: skip


def _letter_role(letter: str | None) -> str:
    """The role an axis letter (or CJK axis word) names; "extent" when none."""
    if not letter:
        return "extent"
    letter = letter.strip("()")
    if letter in _CJK_AXIS_ROLES:
        return _CJK_AXIS_ROLES[letter]
    if letter.lower() in _AXIS_WORD_ROLES:
        return _AXIS_WORD_ROLES[letter.lower()]
    if letter in ("Ø", "⌀"):
        return "diameter"
    return AXIS_LETTER_ROLES.get(letter.upper(), "extent")


def _find_unit(tokens: list[str | None], convert, default: str | None) -> list[float | None]:
    factors = [convert(u) if u else None for u in tokens]
    last = next((f for f in reversed(factors) if f is not None), None)
    if last is None and default:
        last = convert(default)
    return [f if f is not None else last for f in factors]


def parse_dims(text: str, default_unit: str | None = None, decimal_comma: bool | None = None) -> list[Dims]:
    """Every ``A x B [x C]`` group in ``text`` with a length unit (after each term, after the last term,
    or ``default_unit`` from the label), converted to cm. Groups without a length unit are skipped."""
    try:
        return _parse_dims(text, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001 - the contract is "never raises on any text"
        return []


_LETTERED = re.compile(
    rf"(?<![^\W_])(?P<axis>[HWDLBTØ⌀])\.?\s*[:=]?\s*(?P<n>{_NUMBER})"
    r"(?:\s*(?:(?P<u>mm|cm|m|inches|inch|in|ft)(?![^\W\d_])|(?P<q>''|\")))?"
)
_STANDALONE_X = re.compile(r"\bx\b")
_LETTERED_GAP = re.compile(r"\s*(?:[,;/]|and|x)?\s*")


def _lettered_dims(s: str, default_unit: str | None, decimal_comma: bool | None) -> Dims | None:
    """Argos / John Lewis style ``H21.6, W9.1, D1.5cm`` (axis letters, no times signs), or None."""
    tokens = list(_LETTERED.finditer(s))
    if len(tokens) < 2:
        return None
    run = [tokens[0]]
    for tok in tokens[1:]:
        if _LETTERED_GAP.fullmatch(s[run[-1].end() : tok.start()]) and tok["axis"] not in {
            t["axis"] for t in run
        }:
            run.append(tok)
            if len(run) == 3:
                break
        elif len(run) >= 2:
            break
        else:
            run = [tok]
    if len(run) < 2:
        return None
    units = [t["u"] or t["q"] for t in run]
    factors = _find_unit(units, length_unit, default_unit)
    values = [parse_number(t["n"], decimal_comma) for t in run]
    if any(f is None for f in factors) or any(v is None or v <= 0 for v in values):
        return None
    text = s[run[0].start() : run[-1].end()]
    cm = [round(v * f, 6) for v, f in zip(values, factors, strict=True)]
    return Dims(tuple(cm), text, tuple(_letter_role(t["axis"]) for t in run))


# "(L) 30 cm x (W) 20 cm", "30(W) x 20(D) x 10(H) mm": bracketed axis letters carry no value.
_BRACKETED_AXIS = re.compile(r"\s*\(\s*[LWHDBTlwhdbt]\s*\)")
# "30 x 20 x 10 (cm)": a unit in brackets after the last number.
_BRACKETED_UNIT = re.compile(r"(?<=\d)\s*\(\s*(mm|cm|m|in|inch|inches|ft|см|мм)\.?\s*\)")
# "Abmessungen (B/H/T): 30/20/10 cm": three numbers separated by slashes (fractions are already decimals).
_SLASHED = re.compile(rf"(?<![\d/])({_NUMBER})\s*/\s*({_NUMBER})\s*/\s*({_NUMBER})(?![\d/])")


def _parse_dims(text: str, default_unit: str | None, decimal_comma: bool | None) -> list[Dims]:
    s = clean_text(text[:MAX_TEXT])
    if "(" in s:
        s = _BRACKETED_UNIT.sub(r" \1", _BRACKETED_AXIS.sub("", s))
    if "/" in s:
        s = _SLASHED.sub(r"\1 x \2 x \3", s)
    if not _STANDALONE_X.search(s):
        lettered = _lettered_dims(s, default_unit, decimal_comma)
        if lettered is not None:
            return [lettered]
    diameters: set[str] = set()
    if _DIAMETER_PREFIX.search(s):  # "直径12cm × 高さ6.5cm", "Ø 12 x 6,5 cm": a round object, d x d x h
        diameters = {m.group("n") for m in _DIAMETER_PREFIX.finditer(s)}
        s = _DIAMETER_PREFIX.sub(lambda m: m.group("n"), s)
    prefixed: list[str] = []
    if _AXIS_PREFIX.search(s):
        prefixed = [p.group(0).strip(" .:=約约") for p in _AXIS_PREFIX.finditer(s)]
        s = clean_text(_AXIS_PREFIX.sub("", s))  # "H 30 cm x W 20 cm", "長37.5*寬26*高13.5cm"
    found: list[Dims] = []
    for m in _DIMS_RE.finditer(s):
        nums = [m.group("n1"), m.group("n2"), m.group("n3")]
        units = [m.group("u1"), m.group("u2"), m.group("u3")]
        n = 3 if nums[2] is not None else 2
        nums, units = nums[:n], units[:n]
        # A one-letter "unit" like the L/W/H suffix of "23L" is a letter, not a unit; a trailing unit
        # may follow a suffix letter ("30H centímetros"): look past it.
        letters = [m.group("l1"), m.group("l2"), None][:n]
        for i in range(n - 1):  # "23L x 13,8W x ...": a suffix letter read as a unit
            if letters[i] is None and units[i] and len(units[i]) == 1 and length_unit(units[i]) is None:
                letters[i] = units[i]
        if n == 3 and units[2] and len(units[2]) == 1 and length_unit(units[2]) is None:
            letters[2], units[2] = units[2], None
        tail = s[m.end() :]
        if n == 3 and letters[2] is None and (after := re.match(r"\s?([a-zA-Z])\b", tail)):
            letters[2] = after.group(1)  # 20"w x 4"d x 16"h
        if units[-1] is None or length_unit(units[-1]) is None:
            t = re.match(rf"\s*(?:\b[a-zA-Z]\b\s*)?({_UNIT})", tail)
            if t and length_unit(t.group(1)) is not None:
                units[-1] = t.group(1)
        clean_units = [u if u and length_unit(u) is not None else None for u in units]
        factors = _find_unit(clean_units, length_unit, default_unit)
        if any(f is None for f in factors):
            continue
        values = [parse_number(x, decimal_comma) for x in nums]
        if any(v is None or v <= 0 for v in values):
            continue
        cm = [round(v * f, 6) for v, f in zip(values, factors, strict=True)]
        plain = [i for i, x in enumerate(nums) if x not in diameters]
        if len(prefixed) == len(plain) and all(letter is None for letter in letters):
            for i, letter in zip(plain, prefixed, strict=True):  # "Ø 12 x H 20", "Diameter 30 x Height 15"
                letters[i] = letter
        roles = tuple(
            "diameter" if x in diameters else _letter_role(letter)
            for x, letter in zip(nums, letters, strict=True)
        )
        found.append(Dims(tuple(cm), m.group(0), roles))
    return found


def _parse_single(text: str, convert, default_unit: str | None, decimal_comma: bool | None) -> float | None:
    s = clean_text(text[:MAX_TEXT])
    if convert is mass_unit:
        m = _POUNDS_OUNCES.search(s)
        if m:
            return round(float(m.group(1)) * 453.59237 + float(m.group(2)) * 28.349523125, 6)
        m = _KILOS_GRAMS.search(s)
        if m:
            return round(float(m.group(1)) * 1000 + float(m.group(2)), 6)
    if _RANGE_RE.search(s):
        return None
    for m in _QUANTITY_RE.finditer(s):
        unit = m.group("u")
        factor = convert(unit) if unit else None
        if factor is None and unit and default_unit and len(unit.rstrip(".")) > 0:
            # a word after the number that is not our unit ("6 Liter"): only a label unit can save it
            if convert(default_unit) is None:
                continue
            other = length_unit(unit) or mass_unit(unit)
            if other is not None or _unit_key(unit) in _VOLUME_UNITS:
                continue
        if factor is None and default_unit:
            factor = convert(default_unit)
        if factor is None:
            continue
        number = m.group("n")
        if factor <= 1.0 and decimal_comma is not False and _DOT_GROUPED.fullmatch(number):
            # "1.200 g", "1.500 mm": a thousandth of a gram or millimetre is not how shops write sizes
            value = float(number.replace(".", ""))
        else:
            value = parse_number(number, decimal_comma)
        if value is None or value <= 0:
            continue
        return round(value * factor, 6)
    return None


def parse_length(
    text: str, default_unit: str | None = None, decimal_comma: bool | None = None
) -> float | None:
    """The first length in ``text`` in cm (``"67,7 cm"`` -> 67.7), or None; a range (``15.5 - 116.5"``) is
    not one length."""
    try:
        return _parse_single(text, length_unit, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001
        return None


def parse_mass(text: str, default_unit: str | None = None, decimal_comma: bool | None = None) -> float | None:
    """The first mass in ``text`` in grams (``"Gewicht 4,7 kg"`` -> 4700.0), or None; ranges are refused."""
    try:
        return _parse_single(text, mass_unit, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001
        return None


_RANGE_PARTS = re.compile(
    rf"(?P<a>{_NUMBER})\s*(?P<ua>{_UNIT})?\s*(?:-|–|—|~|to|bis|a|à)\s*(?P<b>{_NUMBER})\s*(?P<ub>{_UNIT})?"
)


def parse_length_range(
    text: str, default_unit: str | None = None, decimal_comma: bool | None = None
) -> tuple[float, float] | None:
    """A range written as ``15.5" - 116.5"`` or ``0.5 - 5 mm`` as (low, high) in the unit's catalog unit
    (cm for lengths; for a mass unit, grams), or None."""
    try:
        s = clean_text(text[:MAX_TEXT])
        m = _RANGE_PARTS.search(s)
        if not m:
            return None
        unit = m.group("ub") or m.group("ua") or default_unit
        factor = length_unit(unit) or mass_unit(unit) if unit else None
        if factor is None:
            return None
        a, b = parse_number(m.group("a"), decimal_comma), parse_number(m.group("b"), decimal_comma)
        if a is None or b is None or a <= 0 or b < a:
            return None
        return round(a * factor, 6), round(b * factor, 6)
    except Exception:  # noqa: BLE001
        return None


_THIRD_AXIS = re.compile(
    rf"(?P<q>{_NUMBER}\s*(?:''|[\"″]|[^\W\d_]+\.?))\s+(?:thick|deep|tall|high|in (?:height|depth|thickness)|"
    r"dick|tief|hoch|d'épaisseur|d'epaisseur|de profondeur|de haut|de grosor|de espesor|de alto|di spessore)\b",
    re.IGNORECASE,
)


def third_axis(text: str, decimal_comma: bool | None = None) -> float | None:
    """The single axis a sentence adds to a two-value size (``8" x 10" and is 3/4" thick`` -> 1.905), in
    cm, or None."""
    try:
        m = _THIRD_AXIS.search(clean_text(text[:MAX_TEXT]))
        return parse_length(m.group("q"), None, decimal_comma) if m else None
    except Exception:  # noqa: BLE001
        return None
