"""Numbers written in digits, as pages and descriptions write them: decimal commas or points, thousands
separators, fractions (``3/4``, ``½``), scientific notation and powers (:func:`digits_value`).

The decimal mark is decided by a locale rule passed in (``decimal_comma``: True for a page in a
decimal-comma language, False for one that writes decimal points, None when unknown, as for the
parser's English descriptions), one rule for everyone:

A comma followed by other than exactly three digits is a decimal comma (``4,7``); with both ``.`` and
``,`` the last one is the decimal mark; ``1,643,215`` is grouped. A single comma followed by exactly three
digits (``61,800``) is ambiguous: it is read as a decimal comma when the page's language writes decimal
commas (``decimal_comma=True``, see :func:`decimal_comma_for`), else as a thousands separator. A single
dot followed by exactly three digits (``1.200``) is read as a thousands separator only in a decimal-comma
language and when the integer part is not 0.
"""

from __future__ import annotations

import math
import re

__all__ = [
    "DECIMAL_COMMA_LANGUAGES",
    "DIGITS_PATTERN",
    "NUMBER_PATTERN",
    "VULGAR_FRACTIONS",
    "decimal_comma_for",
    "digits_value",
    "fold_width",
    "format_decimal",
    "parse_number",
]

#: Not a number of its own: digits that are part of scientific notation ("1e308", "2.5E+1": the mantissa or
#: the exponent). A page never writes a size in exponents, so such digits are not read at all (reading "308"
#: out of "1e308" and "1" out of "2.5e1" was the old fault). A minus sign is not part of the number: the
#: page readers decide whether a "-" before it is a sign, a dash or a bullet (``scrapers/signs.py``).
_NOT_ALONE = r"(?<!\d[eE])(?<!\d[eE][+-])"
_NO_EXPONENT = r"(?![.,]?\d*[eE][+-]?\d)"
#: One number in digits (atomic: no backtracking), or a leading-dot decimal like ".5" after a space, an
#: opening bracket or a colon; never digits of a number in scientific notation (:data:`_NOT_ALONE`).
NUMBER_PATTERN = (
    rf"(?:(?<![\d.,]){_NOT_ALONE}(?>\d+(?:[.,]\d+)*){_NO_EXPONENT}|(?<![^\s(:])(?>\.\d+){_NO_EXPONENT})"
)
#: Regular expression for one number written with digits; the parser's tokenizer uses it as is. It
#: stays linear on long digit-comma chains ("1,234,567,..."): a thousands group only needs no digit
#: after it, so a failed match backs off one group and succeeds.
DIGITS_PATTERN = (
    r"\d+(?:\.\d+)?(?:[eE]|\*\*|\^)[+-]?\d+"  # scientific notation and powers: 1.5e2, 10**3, 10^3
    r"|\d+/\d+|\d{1,3}(?:,\d{3})+(?:\.\d+)?(?!\d)"
    r"|\d{1,3}(?:\.\d{3})+,\d+(?!\d)|\d{1,3}(?:\.\d{3}){2,}(?!\d)"  # 1.250,5 and 1.000.000
    r"|\d+[.,]\d+|\d+|\.\d+"
)
#: Unicode vulgar fractions, alone ("½") or after digits ("7½").
VULGAR_FRACTIONS: dict[str, float] = {
    "½": 1 / 2, "⅓": 1 / 3, "⅔": 2 / 3, "¼": 1 / 4, "¾": 3 / 4, "⅕": 1 / 5, "⅖": 2 / 5, "⅗": 3 / 5,
    "⅘": 4 / 5, "⅙": 1 / 6, "⅚": 5 / 6, "⅛": 1 / 8, "⅜": 3 / 8, "⅝": 5 / 8, "⅞": 7 / 8,
}  # fmt: skip
_FRACTION = re.compile(r"(\d+)/(\d+)")
_SCIENTIFIC = re.compile(r"\d+(?:\.\d+)?[eE][+-]?\d+")
_POWER = re.compile(r"(\d+(?:\.\d+)?)(?:\*\*|\^)([+-]?\d+)")
#: A number grouped by dots ("1.200"), read as thousands for a gram or a millimetre.
DOT_GROUPED = re.compile(r"\d{1,3}(?:\.\d{3})+")

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


def format_decimal(value: float) -> str:
    """A number written so that no decimal-mark rule misreads it (never exactly three decimals), to 6
    decimals (a sixty-fourth of an inch is 0.015625)."""
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    if "." in text and len(text.split(".")[1]) == 3:
        text += "0"
    return text


_FULL_WIDTH = {c: c - 0xFEE0 for c in range(0xFF01, 0xFF5F)}


def fold_width(text: str) -> str:
    """Full-width forms (``１５ｃｍ``) as ASCII (``15cm``), one character for one: positions are kept."""
    return text if text.isascii() else text.translate(_FULL_WIDTH)


def parse_number(text: str, decimal_comma: bool | None = None) -> float | None:
    """The number written in ``text`` (one number, separators as described in the module doc), or None
    (also for a number too large for a float)."""
    if not isinstance(text, str):
        return None
    s = text.strip().replace(" ", "")
    if s.startswith(".") and s[1:].isdigit():
        s = "0" + s  # ".5 Pounds"
    plain = _plain(s, decimal_comma)
    if plain is None:
        return None
    value = float(plain)
    return value if math.isfinite(value) else None


def _plain(s: str, decimal_comma: bool | None) -> str | None:
    """``s`` (one number in digits, no spaces) with its grouping removed and a decimal point, or None."""
    if not re.fullmatch(NUMBER_PATTERN, s):
        return None
    commas, dots = s.count(","), s.count(".")
    if commas and dots:
        dec = "," if s.rfind(",") > s.rfind(".") else "."
        grp = "." if dec == "," else ","
        s = s.replace(grp, "")
        if s.count(dec) > 1:
            return None
        return s.replace(dec, ".")
    if commas:
        parts = s.split(",")
        if commas > 1:
            return "".join(parts) if all(len(p) == 3 for p in parts[1:]) else None
        if len(parts[1]) == 3 and not decimal_comma and parts[0] not in ("0", ""):
            return "".join(parts)
        return ".".join(parts)
    if dots > 1:
        parts = s.split(".")
        return "".join(parts) if all(len(p) == 3 for p in parts[1:]) else None
    if dots == 1:
        whole, frac = s.split(".")
        if decimal_comma and len(frac) == 3 and whole not in ("0", ""):
            return whole + frac
    return s


def digits_value(token: str, decimal_comma: bool | None = None) -> float | None:
    """Value of one token written in digits (``15``, ``7.5``, ``7,5``, ``1,000``, ``3/4``, ``½``, ``1.5e2``,
    ``10**3``, ``10^3``): separators by :func:`parse_number`'s rule. A value too large for a float is
    ``inf`` (for the caller to refuse), never another number ("1e308" is not 308)."""
    if token in VULGAR_FRACTIONS:
        return VULGAR_FRACTIONS[token]
    if _SCIENTIFIC.fullmatch(token):
        return float(token)  # "1e400" is inf
    m = _POWER.fullmatch(token)
    if m:
        try:
            return float(m.group(1)) ** float(m.group(2))  # a 5,000-digit exponent is inf, not an error
        except OverflowError:
            return math.inf
    m = _FRACTION.fullmatch(token)
    if m:
        den = int(m.group(2))
        return int(m.group(1)) / den if den else None
    plain = _plain(token, decimal_comma)
    return float(plain) if plain is not None else None  # "9" * 400 is inf
