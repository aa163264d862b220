"""Descriptions in other languages: the household words of a French, German, Spanish, Italian or Dutch
description read as the English words the parser and the catalog's names know.

``kb/data/translations.csv`` (``word,language,english``; written here from general knowledge) holds the
common household kind nouns ("tasse" -> cup, "Schüssel" -> bowl), the material, texture, rigidity and
fragility words ("céramique" -> ceramic, "weich" -> soft), the size and dimension words ("haut" -> tall,
"Durchmesser" -> diameter) and the function words of a description ("une", "aus", "con") of five languages.
:func:`english_reading` replaces them in the text (longest phrase first: "brosse à dents" -> toothbrush),
case and accents ignored. A word that is also an English word the parser or the kinds lexicon knows
("large", "die", "of", "pen") is read as the other language's only when the description is in that
language: two or more of its words are no English word (French "large" is wide, Dutch "of" is or). Rules
and figures: ``recall/RECALL.md`` ("Descriptions in other languages").
"""

from __future__ import annotations

import csv
import functools
import re
import unicodedata
from collections.abc import Set as AbstractSet
from dataclasses import dataclass
from pathlib import Path

from kb.errors import RecallError

__all__ = ["LANGUAGES", "EnglishReading", "english_reading", "english_words", "table"]

_PATH = Path(__file__).resolve().parent.parent / "kb" / "data" / "translations.csv"
#: The languages of the table, in the order a tie between two is broken.
LANGUAGES: tuple[str, ...] = ("fr", "de", "es", "it", "nl")
#: Letters of any script, an apostrophe or hyphen inside ("serre-joint"); digits are no word.
_WORD = re.compile(r"[^\W\d_]+(?:-[^\W\d_]+)*")
#: The evidence a description is in a language: this many of its words are that language's and no English.
MIN_EVIDENCE = 2
#: English function words a description uses, that no table of the parser lists.
_ENGLISH_FUNCTION = frozenset(
    "a an the of in on at to by for from with without and or but is are was it its this that my our your "
    "one two three four five six seven eight nine ten made about some very weigh weighs weighing".split()
)


def fold(word: str) -> str:
    """Lower case, accents dropped ("Schüssel" -> "schussel", "céramique" -> "ceramique")."""
    w = unicodedata.normalize("NFKD", word.lower().replace("’", "'"))
    return "".join(c for c in w if not unicodedata.combining(c)).replace("ß", "ss")


@functools.cache
def table() -> dict[str, dict[tuple[str, ...], str]]:
    """Language -> folded word tuple -> English, from ``kb/data/translations.csv``; a language not in
    :data:`LANGUAGES` or a row without a word or English is refused."""
    out: dict[str, dict[tuple[str, ...], str]] = {lang: {} for lang in LANGUAGES}
    with _PATH.open(encoding="utf-8", newline="") as fh:
        for n, row in enumerate(csv.DictReader(fh), 2):
            word, lang, english = (row.get(k) or "" for k in ("word", "language", "english"))
            if lang not in out or not word.strip() or not english.strip():
                raise RecallError(f"{_PATH.name} row {n}: needs a word, a language of {LANGUAGES} and English")
            out[lang][tuple(fold(w) for w in _WORD.findall(word))] = english.strip()
    return out


@functools.cache
def english_words() -> frozenset[str]:
    """The English words the recall reads (folded): the parser's lexicon, the kinds lexicon's English
    nouns, the synonyms' nouns, colours and size words, and common function words."""
    from kb.kinds import nouns
    from recall.lexicon import tag_model
    from recall.synonyms import synsets
    from recall.words import COLOURS, SIZE_WORDS

    words = set(_ENGLISH_FUNCTION) | set(COLOURS) | set(SIZE_WORDS)
    words |= {w for key in tag_model() for w in key.split()}
    words |= {w for n in nouns().values() if n.lang == "en" for w in n.words}
    words |= {w for s in synsets() for noun in s for w in noun}
    return frozenset(fold(w) for w in words)


@dataclass(frozen=True)
class EnglishReading:
    """A description as the recall reads it: ``text`` with the translated words in English, the
    ``language`` it was read in (None: English, nothing translated) and the words translated."""

    text: str
    language: str | None = None
    translated: tuple[tuple[str, str], ...] = ()


def _spans(text: str) -> list[tuple[int, int, str]]:
    return [(m.start(), m.end(), fold(m.group())) for m in _WORD.finditer(text)]


def _matches(spans, lang: str, english: frozenset[str]) -> list[tuple[int, int, str, bool]]:
    """The phrases of ``lang``'s table in the text, longest first, left to right: (first word, past the
    last, English, whether a word of it is no English word)."""
    words = table()[lang]
    longest = max((len(k) for k in words), default=1)
    out, i = [], 0
    while i < len(spans):
        for n in range(min(longest, len(spans) - i), 0, -1):
            key = tuple(s[2] for s in spans[i : i + n])
            if key in words:
                foreign = any(w not in english for w in key) and sum(map(len, key)) > 1  # "y", "e", "o": no evidence
                out.append((i, i + n, words[key], foreign))
                i += n
                break
        else:
            i += 1
    return out


def english_reading(text: str, keep: AbstractSet[str] = frozenset()) -> EnglishReading:
    """The English reading of ``text`` (module docstring): the language with the most words of its table
    that are no English words (at least one; ties: :data:`LANGUAGES` order); its words that are no English
    word translated, and with :data:`MIN_EVIDENCE` of them its words that are English too; a dimension
    word after "of" ("9 cm de haut" -> "9 cm tall") loses the "of"; a phrase ``keep`` holds (the catalog's own,
    lowercase name words) stays as written. English text comes back unchanged."""
    spans = _spans(text)
    if not spans:
        return EnglishReading(text)
    english = english_words()
    found = {lang: _matches(spans, lang, english) for lang in LANGUAGES}
    evidence = {lang: sum(m[3] for m in found[lang]) for lang in LANGUAGES}
    lang = max(LANGUAGES, key=lambda x: evidence[x])  # max keeps the first of a tie
    if evidence[lang] == 0:
        return EnglishReading(text)
    whole = evidence[lang] >= MIN_EVIDENCE
    pieces, pos, done = [], 0, []
    for i, j, eng, foreign in found[lang]:
        if not (foreign or whole):
            continue
        start, end = spans[i][0], spans[j - 1][1]
        if text[start:end].lower() in keep:  # a word of the catalog's own names is the catalog's word
            continue
        pieces += [text[pos:start], eng]
        done.append((text[start:end], eng))
        pos = end
    pieces.append(text[pos:])
    out = re.sub(r"\bof\s+(tall|long|wide|thick|deep|diameter)\b", r"\1", "".join(pieces))
    return EnglishReading(out, lang, tuple(done))
