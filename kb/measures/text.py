"""Page text made readable for the number and unit rules: invisible marks removed, full-width forms
folded, fractions and feet+inches written as decimals, every times sign between numbers written ``x``.

Handles what real pages do: invisible marks (U+200E, U+200F, zero-width spaces, NBSP), full-width
characters (``：``, ``１``), the times signs ``x``, ``×``, ``*``, ``✕`` and Cyrillic ``х``, inch marks
``"``, ``''``, ``″``, curly ``”`` and JSON-escaped ``\\"``, fractions (``23½``, ``10 1/2``, ``10-1/2``,
``3/4 lb``), feet and inches (``5' 3"``), Swiss thousands (``1'200``), Hebrew unit abbreviations (``ס"מ``)
and "8 by 10".
"""

from __future__ import annotations

import re
import unicodedata

from kb.measures.aliases import PARSER_LANGUAGES
from kb.measures.numbers import VULGAR_FRACTIONS as _VULGAR_VALUES
from kb.measures.numbers import format_decimal
from kb.measures.units import (
    aliases_of,
    combine,
    length_unit,
    lookup,
    symbol,
    unit_table,
    unit_words,
    words_pattern,
)
from kb.measures.words import FRACTION_WORDS, MAGNITUDE_WORDS, NUMBER_WORDS, number_value

__all__ = ["MAX_TEXT", "clean_text"]

#: Only the first this many characters of a value are read (values are short; this bounds the work).
MAX_TEXT = 2000

# Invisible formatting characters pages sprinkle into values (LRM/RLM, embeddings, isolates, zero widths).
_INVISIBLE = dict.fromkeys(
    map(
        ord,
        "\u200b\u200c\u200d\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\ufeff\u00ad",
    ),
    None,
)
# Hebrew unit abbreviations are written with a gershayim (or a plain double quote) inside: ס"מ = cm.
_HEBREW_UNITS = re.compile(
    r"(?<![\u0590-\u05ff])("
    + "|".join(w.replace('"', '[\"\u05f4]') for w in unit_words() if '"' in w and w != '"')
    + r")(?![\u0590-\u05ff])"
)
_TIMES_SIGN = re.compile(
    r"(\d\s*)([\"'″]{1,2}\s*[A-Za-z]\b\.?|[^\W\d_]{1,12}\.?|[\"'″]{1,2})?(\s*)[xX×✕✖*хХ]\s*(?=\d)"
)  # "30 x 20", "30cm × 20", "43'' H X 27'' W": after a number, its unit or inch mark (and an axis letter)
#: Thousands grouped with spaces before a mass or length unit, as French, Nordic, Slavic and Swiss stores
#: write them (``4 000 kg``, ``1 250 g``; NFKC has already written the narrow no-break space as a space).
_SPACED_THOUSANDS = re.compile(
    r"(?<![\d.,] )(?<![\d.,])\d{1,3}(?: \d{3})+(?:[.,]\d+)?(?=\s?(?:kg|g|mm|cm|m|lb|lbs|t)\b)"
)
_SPACES = re.compile(r"[\s\u00a0\u2000-\u200a\u202f\u205f\u3000]+")


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
    words = set(_LETTERS.findall(text.lower()))  # one pass: the word rules below run only when they can match
    if not _NUMBER_WORD_SET.isdisjoint(words):
        text = _SPELLED.sub(_spelled, text)  # "twelve inches", "two and a half pounds"
    if "\\" in text or "\u201d" in text or "\u201c" in text:
        # an inch mark escaped inside embedded JSON (12\" x 8\") or written as a curly quote (40” x 28”)
        text = _QUOTED_INCH.sub('"', text.replace('\\"', '"'))
    if "/" in text or "\u2044" in text:
        text = _MIXED_FRACTION.sub(_mixed, text)
        text = _FRACTION.sub(_fraction, text)
    if "'" in text or "\u2019" in text:
        text = _APOSTROPHE_THOUSANDS.sub(lambda m: re.sub(r"['\u2019]", "", m.group(0)), text)
    if "'" in text or "\u2032" in text or not _FOOT_WORDS.isdisjoint(words):
        text = _FEET_INCHES.sub(_feet_inches, text)
    if "\u05f4" in text or '"' in text:
        text = _HEBREW_UNITS.sub(_hebrew_unit, text)
    text = _SPACES.sub(" ", text).strip()
    if " " in text:
        text = _SPACED_THOUSANDS.sub(lambda m: m.group(0).replace(" ", ""), text)  # "Vekt: 4 000 kg"
    # Cyrillic х/Х and other times signs after a number (and maybe a unit or letter) and before a number.
    text = _TIMES_SIGN.sub(_times, text)
    if " by " in text:
        text = _BY.sub(r"\1 x ", text)  # "8 by 10 inches", "30 cm by 20 cm"
    return _SPACES.sub(" ", text).strip()


# Fractions as imperial measurements are written: "23½", "10 1/2 in", "10-1/2", "3/4 lb", "5' 3\"".
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
_FOOT_WORDS = frozenset(words_pattern("foot").replace("\\", "").split("|"))
_FEET_INCHES = re.compile(
    rf"(?<![\d.,])(\d{{1,3}}) ?(?:'(?!')|\u2032(?!\u2032)|(?i:{words_pattern('foot')})\b\.?)[ -]?"
    rf"(\d{{1,2}}(?:\.\d+)?) ?(?:''|\"|(?i:{words_pattern('inch')})\b\.?)"
)


# A curly closing (or opening) double quote right after a number is an inch mark.
_QUOTED_INCH = re.compile(r"(?<=\d)\s?[\u201c\u201d]")

_BY = re.compile(r"(\d(?:\s?(?:''|[\"″]|[a-zA-Z]{1,6}\.?))?) by (?=\d)")


# English number words right before an English length or mass unit of two letters or more ("in" and
# one-letter symbols are too often words: "one in ten", "two m...").
_NUMBER_WORD = "|".join(sorted({*NUMBER_WORDS, *MAGNITUDE_WORDS, *FRACTION_WORDS}, key=lambda w: (-len(w), w)))
_SPELLED_UNIT = "|".join(
    re.escape(w)
    for w in sorted({*aliases_of("length", PARSER_LANGUAGES), *aliases_of("mass", PARSER_LANGUAGES)}, key=lambda w: (-len(w), w))
    if len(w) > 1 and w != "in" and w.isalpha()
)
_NUMBER_WORD_SET = frozenset(_NUMBER_WORD.split("|"))
_LETTERS = re.compile(r"[^\W\d_]+")
_SPELLED = re.compile(
    rf"(?i)(?<![\w-])((?:an?\s+)?(?:{_NUMBER_WORD})(?:(?:\s+|-)(?:(?:and|an?)\s+)*(?:{_NUMBER_WORD}))*)"
    rf"\s*-?\s*({_SPELLED_UNIT})(?![^\W\d_])"
)


def _spelled(m: re.Match) -> str:
    value = number_value(re.split(r"[\s-]+", m.group(1).lower()))
    return m.group(0) if value is None or value <= 0 else f"{format_decimal(value)} {m.group(2)}"


def _vulgar(m: re.Match) -> str:
    whole = int(m.group(1)) if m.group(1) else 0
    return format_decimal(whole + _VULGAR_VALUES[m.group(2)])


def _mixed(m: re.Match) -> str:
    num, den = int(m.group(2)), int(m.group(3))
    if den not in _DENOMINATORS or not 0 < num < den:
        return m.group(0)
    return format_decimal(int(m.group(1)) + num / den)


def _fraction(m: re.Match) -> str:
    num, den = int(m.group(1)), int(m.group(2))
    if den not in _DENOMINATORS or not 0 < num < den:
        return m.group(0)
    return format_decimal(num / den)


def _feet_inches(m: re.Match) -> str:
    table = unit_table()
    feet = combine(int(m.group(1)), table["ft"], float(m.group(2)), table["in"])
    if isinstance(feet, str):
        return m.group(0)  # "5' 12\"" is not one length
    return format_decimal(feet * 12) + '"'


def _hebrew_unit(m: re.Match) -> str:
    unit = lookup(m.group(1).replace("\u05f4", '"'))
    return symbol(unit) if unit is not None else m.group(0)


def _times(m: re.Match) -> str:
    between = m.group(2) or ""
    mark = re.match(r"[\"'″]{1,2}", between)  # an inch mark, maybe with an axis letter ("'' H")
    if between and len(between) > 1 and mark is None and length_unit(between) is None:
        return m.group(0)  # "max 5": a word, not a unit or an L/W/H letter, before the sign
    return f"{m.group(1)}{between}{m.group(3)} x "
