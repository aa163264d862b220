"""Negated noun phrases: the words of "not a mug", "without a lid", "neither a mug nor a cup".

The parser's negation scope for values (``recall/PARSER.md``, "Negated values") applied to nouns: the words
of a negated noun phrase name no object (:func:`negated_words`, :func:`negated_spans`); the subject of a
description is never one (:mod:`recall.subject`). Split from :mod:`recall.subject` (no behaviour change).
"""

from __future__ import annotations

import functools
import re

__all__ = ["negated_spans", "negated_words"]


def negated_words(words: list[str]) -> set[int]:
    """The indices of the words of a negated noun phrase in ``words`` (lower case, apostrophes dropped,
    punctuation as its own words): the parser's negation scope for values (``recall/PARSER.md``,
    "Negated values") applied to nouns. After a value negation (``lexicon.VALUE_NEGATIONS``; not "non",
    "hardly") and at most two gap words ("is", "really", ...), an article starts the phrase ("not *a mug*",
    "isn't really *the cup*"; not "not heavy"), and ``lexicon.NOUN_NEGATIONS`` start it right after them
    ("no *handle*", "without *a lid*", "neither *a mug* nor *a cup*"); it runs to a comma or other
    punctuation, "and", "but", a number or the next negation."""
    negated: set[int] = set()
    i = 0
    while i < len(words):
        start = _negated_start(words, i)
        i += 1
        if start is None:
            continue
        i = start
        while i < len(words) and words[i] not in _NEGATED_PHRASE_ENDS and words[i] not in _negations():
            if not words[i].isalpha():
                break
            negated.add(i)
            i += 1
    return negated


def negated_spans(text: str) -> list[tuple[int, int]]:
    """The character spans of the words of ``text`` in a negated noun phrase (:func:`negated_words`):
    they name no object ("not a mug, a glass")."""
    tokens = list(_TOKEN.finditer(text))
    words = [m.group().lower().replace("'", "").replace("\u2019", "") for m in tokens]
    return [tokens[i].span() for i in sorted(negated_words(words))]


_TOKEN = re.compile(r"[^\W_]+(?:['\u2019][^\W_]+)*|[^\w\s]")


#: What ends a negated noun phrase (besides punctuation, numbers and another negation).
_NEGATED_PHRASE_ENDS = frozenset({"and", "but", "&", "instead", "rather"})


def _negated_start(words: list[str], i: int) -> int | None:
    """The index where the noun phrase negated by ``words[i]`` starts, or None (see :func:`negated_words`)."""
    from recall import lexicon as lx

    word = words[i]
    if word not in _phrase_negations():
        return None
    if word in lx.NOUN_NEGATIONS:
        j = i + 1
        return j + 1 if j < len(words) and words[j] in lx.ARTICLES else j
    for j in range(i + 1, min(len(words), i + 4)):
        if words[j] in lx.ARTICLES:
            return j + 1
        if not (words[j] in lx.NEGATION_GAP_WORDS or words[j] in _GAP_WORDS):
            return None
    return None


#: Linking words that may stand between a negation and its article ("is not really a mug": the parser's
#: BE words and gap words).
_GAP_WORDS = frozenset({"is", "are", "was", "be", "really", "actually", "quite", "even", "exactly", "just"})


@functools.cache
def _negations() -> frozenset[str]:
    """The negation words, apostrophes dropped ("isnt", "doesnt")."""
    from recall import lexicon as lx

    return frozenset(w.replace("'", "") for w in lx.NEGATIONS)


@functools.cache
def _phrase_negations() -> frozenset[str]:
    """The negations that can negate a noun phrase (:func:`negated_words`), apostrophes dropped: the
    value negations (``lexicon.VALUE_NEGATIONS``) but "non" ("non-stick")."""
    from recall import lexicon as lx

    return frozenset(w.replace("'", "") for w in lx.VALUE_NEGATIONS - {"non"})


@functools.cache
def _phrase_negation() -> re.Pattern[str]:
    """A word of :func:`_phrase_negations` in a sentence (lower case, apostrophes dropped)."""
    return re.compile(rf"\b(?:{'|'.join(sorted(_phrase_negations()))})\b")
