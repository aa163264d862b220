"""Words no table reads: a description most of whose content words the recall does not know is no close match.

A description in a language the tables do not hold ("uma caneca de cerâmica"), or mostly in words of none
of them, gives the parser and the names next to nothing: whatever it ranks first is the nearest object to
a stray number. The rule (issue 23): the **content words** of the text as read (:mod:`recall.translations`
applied; words of three letters or more, not digits) that no table reads (the parser's lexicon, the kinds
lexicon's nouns in every language, the synonyms, the translations, the catalog's own words, colours, size
words, generic nouns, common English function words; a plural, "-ing", "-ed" or "-ly" form of a word read
counts as read) are listed as **not read** when there are :data:`MIN_UNREAD` or more and they are more than
half of the content words; the result then says them, is never a close match and has confidence at most
:data:`UNREAD_CONFIDENCE`. Rules and figures: ``recall/RECALL.md`` ("Descriptions in other languages").
"""

from __future__ import annotations

import functools
import re

from kb.kinds import nouns, singular
from recall.translations import english_words, fold, table

__all__ = ["MIN_UNREAD", "UNREAD_CONFIDENCE", "content_words", "not_read", "unread_words"]

#: Fewest words not read for the rule to apply: two are an English sparse description's adjectives the
#: tables do not hold ("upright, noisy, about 7 kg"; "spring-loaded jaws"), not another language.
MIN_UNREAD = 3
#: The confidence of a result whose words were mostly not read: at most this.
UNREAD_CONFIDENCE = 0.2
_WORD = re.compile(r"[^\W\d_]+(?:-[^\W\d_]+)*")
_ENDINGS = ("ing", "ed", "ly", "es", "s", "er", "est")


@functools.cache
def _known() -> frozenset[str]:
    """Every word a table reads (folded), but the catalog's."""
    from recall.names import GENERIC_NOUNS
    from recall.subject import feature_words

    words = set(english_words()) | set(GENERIC_NOUNS) | set(feature_words())
    words |= {w for key in nouns() for w in key}
    words |= {w for lang in table().values() for key in lang for w in key}
    return frozenset(fold(w) for w in words)


def content_words(text: str) -> list[str]:
    """The words of ``text`` of three letters or more (folded), hyphenated ones split."""
    return [w for m in _WORD.finditer(text) for w in fold(m.group()).split("-") if len(w) >= 3]


def _read(word: str, vocabulary: frozenset[str]) -> bool:
    known = _known()
    if word in known or word in vocabulary or singular(word) in known or singular(word) in vocabulary:
        return True
    return any(word.endswith(e) and len(word) - len(e) >= 3 and word[: -len(e)] in known for e in _ENDINGS)


def unread_words(text: str, vocabulary: frozenset[str] = frozenset()) -> tuple[str, ...]:
    """The content words of ``text`` no table reads (module docstring; ``vocabulary``: the catalog's
    words), when they are at least :data:`MIN_UNREAD` and more than half of the content words; () else."""
    words = content_words(text)
    unread = [w for w in words if not _read(w, vocabulary)]
    if len(unread) < MIN_UNREAD or 2 * len(unread) <= len(words):
        return ()
    return tuple(dict.fromkeys(unread))


def not_read(result, unread: tuple[str, ...]):
    """``result`` (a :class:`recall.results.RecallResult`) when most of its description's content words
    were read by no table (``unread``): no close match, whatever was ranked (the reason names the words),
    its confidence at most :data:`UNREAD_CONFIDENCE`."""
    from recall.fit import Fit

    words = ", ".join(repr(w) for w in unread)
    score = max(result.fit.score if result.fit is not None else 0.0, 2.0)
    result.unread, result.open_set = unread, bool(result.matches)
    result.fit = Fit(False, score, f"most words not read: {words}")
    result.confidence = min(result.confidence, UNREAD_CONFIDENCE)
    return result
