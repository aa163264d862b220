"""Stage 1 of the description parser (the paper's Fig. 2): text to tokens with character spans.

``nltk.tokenize.RegexpTokenizer`` over :data:`TOKEN_PATTERN` (numbers in digits, unicode fractions,
words with inner hyphens or apostrophes, ``"`` ``'`` ``×`` and punctuation; anything else is skipped).
A hyphenated word the lexicon does not know is split ("5-cm-long", "non-fragile"), except number
compounds ("twenty-one"); ``−`` (the minus sign) is a token for the tagger's sign rule; multi-word expressions of :data:`recall.lexicon.MULTIWORD` ("more than",
"on each side", "fl oz") are merged into one token, longest first.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

from kb.measures.numbers import DIGITS_PATTERN, fold_width
from recall import lexicon as lx
from recall.toolkit import RegexpTokenizer

__all__ = ["FRACTION_CHARS", "TOKEN_PATTERN", "Token", "Tokenizer"]

FRACTION_CHARS = "".join(lx.UNICODE_FRACTIONS)
#: Tokens: numbers in digits, unicode fractions, words (with inner apostrophes and hyphens), unit
#: symbols and the punctuation the grammar uses. Unmatched characters are skipped. No nested quantifiers.
TOKEN_PATTERN = (
    DIGITS_PATTERN
    + r"|[" + FRACTION_CHARS + r"]"
    + r"|[^\W\d_]+(?:['’-][^\W\d_]+)*"
    + r"|''|[\"”″'′’]"
    + r"|\+/-|\+-|±"
    + r"|[×~≈*=:;,.!?()&–—−-]"
)  # fmt: skip


@dataclass(slots=True)
class Token:
    """One token: its surface text, its lower-case lookup form, its span and (after tagging) its tag."""

    word: str  # surface text
    low: str  # lower-case lookup form (merged words joined by one space)
    start: int
    end: int
    tag: str = "W"
    negative: bool = False  # a number with a minus sign before it ("-10 kg", "minus 5 cm")


class _RegexpTokenizer(RegexpTokenizer):
    """nltk's RegexpTokenizer over the fixed :data:`TOKEN_PATTERN`, compiled with the standard ``re``
    engine. nltk routes a *caller-supplied* pattern through ``nltk.redos`` (the ``regex`` engine with a
    wall-clock timeout on every call), which costs more than the matching itself; our pattern is a
    constant without nested quantifiers, and the hostile-input tests (100 KB digit-comma, hyphen and
    quote chains) show it stays linear."""

    def _check_regexp(self) -> None:
        if self._regexp is None:
            self._regexp = re.compile(self._pattern, self._flags)


class Tokenizer:
    """Text to :class:`Token` s. ``known`` is the tagger's lexicon: a hyphenated word in it stays whole."""

    def __init__(self, known: Mapping[str, str]) -> None:
        self._regexp = _RegexpTokenizer(TOKEN_PATTERN)
        self._known = known
        mwe: dict[tuple[str, ...], str] = {}
        for phrase in lx.MULTIWORD:
            mwe[tuple(phrase.split())] = phrase
        self._mwe = mwe
        self._mwe_first = {k[0] for k in mwe}
        self._mwe_max = max((len(k) for k in mwe), default=1)

    def tokens(self, text: str) -> list[Token]:
        """The tokens of ``text``, hyphenated words split and multi-word expressions merged."""
        raw: list[Token] = []
        known = self._known
        for start, end in self._regexp.span_tokenize(text):
            word = text[start:end]
            low = fold_width(word).lower()  # "１５ｃｍ": the unit table's "cm"
            if "’" in low:
                low = low.replace("’", "'")
            if (
                "-" in low
                and len(low) > 1
                and low not in known
                and low not in lx.TOLERANCE_WORDS
                and _split_hyphen(low, glued=bool(raw) and raw[-1].end == start)
            ):
                # "5-cm-long" parts, "non-fragile" -> non fragile; number compounds stay whole
                offset = start
                for part in word.split("-"):
                    if part:
                        raw.append(Token(part, part.lower(), offset, offset + len(part)))
                    offset += len(part) + 1
                continue
            raw.append(Token(word, low, start, end))
        if self._mwe_first.isdisjoint(t.low for t in raw):
            return raw
        return self._merge(raw, text)

    def _merge(self, raw: list[Token], text: str) -> list[Token]:
        """Merge multi-word expressions, longest first."""
        out: list[Token] = []
        i = 0
        n = len(raw)
        while i < n:
            tok = raw[i]
            if tok.low in self._mwe_first:
                for size in range(min(self._mwe_max, n - i), 1, -1):
                    key = tuple(t.low for t in raw[i : i + size])
                    phrase = self._mwe.get(key)
                    if phrase is not None:
                        last = raw[i + size - 1]
                        out.append(Token(text[tok.start : last.end], phrase, tok.start, last.end))
                        i += size
                        break
                else:
                    out.append(tok)
                    i += 1
            else:
                out.append(tok)
                i += 1
        return out


def _split_hyphen(low: str, glued: bool = False) -> bool:
    """Whether a hyphenated word is split (``glued``: right after the token before it, as "300g-ish")."""
    parts = low.split("-")
    if len(parts) == 2 and parts[0] in lx.NUMBER_WORDS and parts[1] in lx.NUMBER_WORDS:
        return False  # "twenty-one"
    if len(parts[0]) == 1 and not glued and not any(p in lx.DIMENSION_WORDS for p in parts[1:]):
        return False  # "t-shirt", "l-shaped", "x-ray": one word (no tonne, litre or "x"); "5 m-long" splits
    return True
