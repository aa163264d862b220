"""Numbers as storefront pages write them: digits with decimal commas or points and thousands separators.

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

__all__ = ["DECIMAL_COMMA_LANGUAGES", "NUMBER_PATTERN", "decimal_comma_for", "format_decimal", "parse_number"]

#: One number in digits (atomic: no backtracking), or a leading-dot decimal like ".5" after a space, an
#: opening bracket or a colon.
NUMBER_PATTERN = r"(?:(?<![\d.,])(?>\d+(?:[.,]\d+)*)|(?<![^\s(:])(?>\.\d+))"
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
    """A number written so that no decimal-mark rule misreads it (never exactly three decimals)."""
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    if "." in text and len(text.split(".")[1]) == 3:
        text += "0"
    return text


def parse_number(text: str, decimal_comma: bool | None = None) -> float | None:
    """The number written in ``text`` (one number, separators as described in the module doc), or None."""
    if not isinstance(text, str):
        return None
    s = text.strip().replace(" ", "")
    if s.startswith(".") and s[1:].isdigit():
        s = "0" + s  # ".5 Pounds"
    if not re.fullmatch(NUMBER_PATTERN, s):
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
