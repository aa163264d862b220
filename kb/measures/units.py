"""The unit words storefront pages write, converted to catalog units (cm, g).

Lower-case keys, accents kept (a lookup strips them too): unit words in many languages, symbols, inch and
foot marks, and the UN/CEFACT codes used by schema.org (CMT MMT MTR INH FOT GRM KGM LBR ONZ).
"""

from __future__ import annotations

import unicodedata

__all__ = ["LENGTH_UNITS", "MASS_UNITS", "UNIT_PATTERN", "VOLUME_WORDS", "length_unit", "mass_unit", "strip_accents"]

#: Length units -> centimetres per unit. Keys are lower case, accents kept (matching strips them too).
LENGTH_UNITS: dict[str, float] = {}
#: Mass units -> grams per unit.
MASS_UNITS: dict[str, float] = {}


def _add(table: dict[str, float], factor: float, *names: str) -> None:
    for name in names:
        table[name] = factor
        table[strip_accents(name)] = factor


def strip_accents(text: str) -> str:
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

#: A unit token after a number: a word (any script), a CJK unit character, an inch or foot mark; "lb." ends
#: with a dot.
UNIT_PATTERN = r"(?:''|[\"″′']|(?![xX]\b)[^\W\d_]+\.?)"
#: Volume words: a number before one is a capacity, never a length or mass.
VOLUME_WORDS = frozenset(
    "l ml cl dl liter liters litre litres litro litros litri литр л мл 公升 毫升 升".split()
)


def unit_key(unit: str | None) -> str:
    """The lookup key of a unit token: lower case, without a trailing dot (marks kept as they are)."""
    if not unit:
        return ""
    u = unit.strip().lower()
    if u not in ("''", '"', "'", "″", "′"):
        u = u.rstrip(".")
    return u


def length_unit(unit: str | None) -> float | None:
    """Centimetres per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a length unit."""
    key = unit_key(unit)
    return LENGTH_UNITS.get(key, LENGTH_UNITS.get(strip_accents(key)))


def mass_unit(unit: str | None) -> float | None:
    """Grams per ``unit`` (a unit word, symbol or UN/CEFACT code), or None if not a mass unit."""
    key = unit_key(unit)
    return MASS_UNITS.get(key, MASS_UNITS.get(strip_accents(key)))
