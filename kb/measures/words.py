"""Numbers written in English words, as people describe objects: ``fifteen``, ``twenty one``,
``fifteen and half``, ``one and a half``, ``seven and quarter``, ``three quarters``, ``a dozen``,
``a couple``, ``a hundred and fifty``, and digits among them (``7 1/4``, ``7 and 1/2``). Number-word
libraries read "fifteen and half" as 15; this small grammar does not.

:func:`number_value` reads a token list (lower case; the parser's NUM chunk) and returns its value, or
``None`` when the words are not one well-formed number ("three four", "half twenty").
:func:`parse_number_words` does the same for a string. Digit tokens are read by
:func:`kb.measures.numbers.digits_value`.

Grammar (informal)::

    number   := [a] whole [and [a] fraction] | [a] whole fraction | [a|one] fraction [a]
    whole    := DIGITS | words
    words    := [unit|teen|tens [unit]] [hundred [and] rest] | ... thousand ... | [unit] dozen | couple
    fraction := half | quarter(s) | third(s) | unit fraction ("three quarters") | 1/4 | ¼
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from kb.measures.numbers import DIGITS_PATTERN, VULGAR_FRACTIONS, digits_value

__all__ = [
    "COUNT_WORDS",
    "FRACTION_WORDS",
    "MAGNITUDE_WORDS",
    "NUMBER_WORDS",
    "count_words",
    "is_number_token",
    "number_value",
    "parse_number_words",
]

#: Number words and their values (tag NW). "couple" is 2 ("a couple of centimeters"), "dozen" 12.
NUMBER_WORDS: dict[str, int] = {
    "zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
    "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13, "fourteen": 14, "fifteen": 15,
    "sixteen": 16, "seventeen": 17, "eighteen": 18, "nineteen": 19, "twenty": 20, "thirty": 30,
    "forty": 40, "fourty": 40, "fifty": 50, "sixty": 60, "seventy": 70, "eighty": 80, "ninety": 90,
    "dozen": 12, "couple": 2,
}  # fmt: skip
#: Magnitude words (tag NMAG): they multiply what precedes them ("two hundred", "a thousand").
MAGNITUDE_WORDS: dict[str, int] = {"hundred": 100, "thousand": 1000, "million": 10**6, "billion": 10**9}
#: Fraction words (tag FRC): "half", "a quarter", "three quarters", "seven and quarter".
FRACTION_WORDS: dict[str, float] = {
    "half": 0.5, "halves": 0.5, "quarter": 0.25, "quarters": 0.25, "third": 1 / 3, "thirds": 1 / 3,
    "fifth": 0.2, "fifths": 0.2, "sixth": 1 / 6, "sixths": 1 / 6, "eighth": 0.125, "eighths": 0.125,
    "tenth": 0.1, "tenths": 0.1, "sixteenth": 0.0625, "sixteenths": 0.0625,
}  # fmt: skip

#: Counts of items written as words ("a set of four", "vier Stück", "lot de trois"), by language: the store
#: languages whose set wording :mod:`scrapers.sets` reads. English is :data:`NUMBER_WORDS` from two up
#: ("couple" aside: "a couple pack" is no count); the others are the small counts stores write in words.
#: The description parser reads English only (``NUMBER_WORDS``).
COUNT_WORDS: dict[str, dict[str, int]] = {
    "en": {w: v for w, v in NUMBER_WORDS.items() if v >= 2 and w != "couple"},
    "de": {"zwei": 2, "drei": 3, "vier": 4, "fünf": 5, "sechs": 6, "sieben": 7, "acht": 8, "neun": 9,
           "zehn": 10, "zwölf": 12},
    "fr": {"deux": 2, "trois": 3, "quatre": 4, "cinq": 5, "six": 6, "sept": 7, "huit": 8, "dix": 10,
           "douze": 12},  # not "neuf": in a product name it is "new" more often than nine
    "es": {"dos": 2, "tres": 3, "cuatro": 4, "cinco": 5, "seis": 6, "siete": 7, "ocho": 8, "nueve": 9,
           "diez": 10, "doce": 12},
    "it": {"due": 2, "tre": 3, "quattro": 4, "cinque": 5, "sei": 6, "sette": 7, "otto": 8, "nove": 9,
           "dieci": 10, "dodici": 12},
}  # fmt: skip


def count_words() -> dict[str, int]:
    """Every count word of :data:`COUNT_WORDS`, any language, with its value (a word two languages share
    has one value: French and English "six")."""
    merged: dict[str, int] = {}
    for table in COUNT_WORDS.values():
        for word, value in table.items():
            if merged.setdefault(word, value) != value:
                raise ValueError(f"count word {word!r} has two values")
    return merged


_HYPHEN_WORDS = re.compile(r"[a-z]+(?:-[a-z]+)+")
_ARTICLES = frozenset({"a", "an"})
_SIMPLE_FRACTION = re.compile(r"(\d+)/(\d+)")


def _is_fraction_token(token: str) -> bool:
    return token in FRACTION_WORDS or token in VULGAR_FRACTIONS or _SIMPLE_FRACTION.fullmatch(token) is not None


def is_number_token(token: str) -> bool:
    """True for any token that can be part of a number (not counting "a", "and")."""
    token = token.lower()
    return (
        token in NUMBER_WORDS
        or token in MAGNITUDE_WORDS
        or token in FRACTION_WORDS
        or digits_value(token) is not None
        or _compound_word(token) is not None
    )


def _compound_word(token: str) -> int | None:
    """``twenty-one`` -> 21 (a tens word, a hyphen and a unit word)."""
    if not _HYPHEN_WORDS.fullmatch(token):
        return None
    parts = token.split("-")
    if len(parts) != 2:
        return None
    tens, unit = NUMBER_WORDS.get(parts[0]), NUMBER_WORDS.get(parts[1])
    if tens is None or unit is None or tens < 20 or tens % 10 or not 1 <= unit <= 9:
        return None
    return tens + unit


class _Whole:
    """Accumulates the whole part of a number written in words and/or digits, refusing ill-formed runs."""

    def __init__(self) -> None:
        self.total = 0.0  # completed thousands
        self.group: float | None = None  # the part under a thousand being built
        self.last = ""  # kind of the last piece: digits, unit, teen, tens, hundred, thousand, scale, dozen
        self.seen = False

    def add(self, kind: str, value: float) -> bool:
        g, last = self.group, self.last
        if kind == "digits":
            if last in ("digits", "unit", "teen", "tens", "dozen"):
                return False
            self.group = (g or 0) + value
        elif kind == "unit":  # 1..9
            if last in ("tens", "hundred", "", "thousand", "scale"):
                self.group = (g or 0) + value
            else:
                return False
        elif kind in ("teen", "tens"):  # 10..19, 20..90
            if last in ("", "hundred", "thousand", "scale"):
                self.group = (g or 0) + value
            else:
                return False
        elif kind == "hundred":
            if last in ("hundred", "dozen"):
                return False
            self.group = (g if g is not None else 1) * 100
        elif kind == "thousand":
            if last == "thousand":
                return False
            self.total += (g if g is not None else 1) * 1000
            self.group = None
        elif kind == "scale":  # "a million", "two million three hundred thousand", "three thousand million"
            if last in ("scale", "dozen"):
                return False
            base = self.total + (g or 0)
            self.total = (base if base else 1) * value
            self.group = None
        elif kind == "dozen":  # "a dozen", "two dozen"
            if last in ("dozen", "hundred", "thousand", "scale"):
                return False
            self.group = (g if g is not None else 1) * value
        self.last = kind
        self.seen = True
        return True

    @property
    def value(self) -> float:
        return self.total + (self.group or 0)


def _word_kind(word: str) -> tuple[str, float] | None:
    if word in MAGNITUDE_WORDS:
        value = float(MAGNITUDE_WORDS[word])
        return ("hundred" if value == 100 else "thousand" if value == 1000 else "scale"), value
    if word == "dozen":
        return "dozen", 12.0
    if word == "couple":
        return "unit", 2.0
    value = NUMBER_WORDS.get(word)
    if value is None:
        compound = _compound_word(word)
        return ("teen", float(compound)) if compound is not None else None  # "twenty-one" acts like 21
    if value < 10:
        return "unit", float(value)
    if value < 20:
        return "teen", float(value)
    return "tens", float(value)


def number_value(tokens: Sequence[str]) -> float | None:
    """Value of the number written by ``tokens`` (lower-case words of one NUM chunk), or None.

    >>> number_value(["fifteen", "and", "half"])
    15.5
    >>> number_value(["one", "and", "a", "half"])
    1.5
    >>> number_value(["7", "1/4"])
    7.25
    """
    toks = [t.lower() for t in tokens if t]
    while toks and toks[-1] in ("a", "an", "of"):  # "half a (liter)", "a couple of (cm)"
        toks.pop()
    if not toks:
        return None
    return _NumberReading(toks).value()


class _NumberReading:
    """Reading one number's tokens left to right: a whole part (:class:`_Whole`), then at most one
    fraction, joined by "and" ("fifteen and half", "one and a half", "two and three quarters")."""

    def __init__(self, toks: list[str]) -> None:
        self.toks = toks
        self.whole = _Whole()
        self.fraction = 0.0
        self.numerator: float | None = None  # a small number word before a fraction word ("three quarters")
        self.after_and = False
        self.had_fraction = False

    def value(self) -> float | None:
        """The number, or None when the tokens are not one well-formed number."""
        toks = self.toks
        for i in range(1 if toks[0] in _ARTICLES else 0, len(toks)):
            tok = toks[i]
            nxt = toks[i + 1] if i + 1 < len(toks) else ""
            if tok in _ARTICLES:
                # only "and a half", "and a quarter", "one and a half": the article of a fraction
                ok = self.after_and and _is_fraction_token(nxt)
            elif tok == "and":
                ok = self._and()
            elif _is_fraction_token(tok):
                ok = self._fraction(tok)
            else:
                ok = self._word(tok, nxt)
            if not ok:
                return None
        if self.after_and and not self.had_fraction:
            return None
        if not self.whole.seen and not self.had_fraction:
            return None
        return self.whole.value + self.fraction

    def _and(self) -> bool:
        if self.after_and or not self.whole.seen or self.had_fraction:
            return False
        self.after_and = True
        return True

    def _fraction(self, tok: str) -> bool:
        if self.had_fraction and self.numerator is None:
            return False
        f = FRACTION_WORDS.get(tok)
        if f is None:
            f = digits_value(tok)
            if f is None or self.numerator is not None:  # "three 1/4" is not a number
                return False
        part = (self.numerator if self.numerator is not None else 1.0) * f
        if self.numerator is not None and not self.after_and:
            # "three quarters": the numerator was counted in the whole part: take it back
            self.whole = _Whole()
        self.fraction += part
        self.numerator = None
        self.had_fraction = True
        return True

    def _word(self, tok: str, nxt: str) -> bool:
        """A number word or digits: part of the whole, or the numerator of the fraction that follows."""
        if self.had_fraction:
            return False  # nothing follows the fraction ("half twenty")
        kind_value = _word_kind(tok)
        if kind_value is None:
            value = digits_value(tok)
            if value is None:
                return False
            kind_value = ("digits", value)
        kind, value = kind_value
        whole = self.whole
        if self.after_and:
            # after "and": a fraction's numerator ("and three quarters") or the rest after a hundred
            if kind == "unit" and _is_fraction_token(nxt) and nxt in FRACTION_WORDS:
                self.numerator = value
                return True
            if whole.last in ("hundred", "thousand") and kind in ("unit", "teen", "tens"):
                if not whole.add(kind, value):
                    return False
                self.after_and = False
                return True
            return False
        if kind == "unit" and nxt in FRACTION_WORDS and not whole.seen:
            self.numerator = value  # "three quarters", "one half"
            whole.add(kind, value)
            return True
        return whole.add(kind, value)


_SPLIT = re.compile(DIGITS_PATTERN + r"|[^\W\d_]+(?:-[^\W\d_]+)*|[" + "".join(VULGAR_FRACTIONS) + "]")


def parse_number_words(text: str) -> float | None:
    """Value of ``text`` when all of it is one number ("twenty one and a half", "7½", "1,5"), else None."""
    if not isinstance(text, str):
        return None
    return number_value([t.lower() for t in _SPLIT.findall(text)])
