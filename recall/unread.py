"""Values the parser could not read: a number followed by a word it knows no meaning of ("a 40 blorps
mug", "60 watt"). Such a value is never dropped silently: it is listed with the refused values
(``ParsedDescription.refused``, reason :data:`UNREAD_REASON`), and the recall lowers its confidence
(:data:`recall.confidence.REFUSED_CONFIDENCE_CAP`).

The rule: a number written in digits, then (glued or after a space) a word of two letters or more that
the parser's lexicon does not tag (no unit, dimension, shape, material, hedge ... word), that is no
ordinal or decade suffix ("2nd", "1920s") and no noun of the kinds lexicon ("3 spoons", "a 2 pack"). The
recall engine then keeps only the words its catalog's names do not hold (:func:`unknown_to_catalog`: "2 AA
batteries" is the catalog's "aa battery"). See ``recall/RECALL.md``, "Values not read".
"""

from __future__ import annotations

import dataclasses
import functools
import re
from collections.abc import Iterable
from typing import Any

from recall.reading import Reading
from recall.tokens import Token

__all__ = ["UNREAD_REASON", "read_unread", "unknown_to_catalog"]

#: The reason of a value not read (the unit word is the refused words' last).
UNREAD_REASON = "not read: no size or mass unit the parser knows"
_SUFFIXES = frozenset({"st", "nd", "rd", "th", "s", "ish"})


@functools.cache
def _kinds_noun(word: str) -> bool:
    from kb.kinds import noun_in, words_of

    return noun_in(words_of(word)) is not None


def read_unread(tokens: list[Token], reading: Reading) -> None:
    """Record in ``reading.refused`` each number in digits followed by a word the parser does not read
    (the module's rule), unless that span is already refused."""
    for num, word in zip(tokens, tokens[1:], strict=False):
        if num.tag != "CD" or not num.word[-1:].isdigit() or word.tag != "W":
            continue
        low = word.low
        if len(low) < 2 or not low.isalpha() or low in _SUFFIXES or _kinds_noun(low):
            continue
        if any(a <= num.start and word.end <= b for a, b in reading.refused):
            continue
        reading.refuse(num.start, word.end, UNREAD_REASON)


def _unit_word(words: str) -> str:
    found = re.search(r"[^\W\d_]+$", words)
    return found.group(0).lower() if found else ""


def unknown_to_catalog(parsed: Any, catalog_words: Iterable[str] | frozenset[str]) -> Any:
    """``parsed`` (a ``ParsedDescription``) without the values not read whose word a catalog name holds
    ("2 AA batteries": the catalog's "aa battery"; "9 volt" of a "9 volt battery")."""
    words = catalog_words if isinstance(catalog_words, frozenset) else frozenset(catalog_words)
    kept = tuple(r for r in parsed.refused if r.reason != UNREAD_REASON or _unit_word(r.words) not in words)
    return parsed if len(kept) == len(parsed.refused) else dataclasses.replace(parsed, refused=kept)
