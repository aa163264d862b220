"""Typing slips in a described noun: a word one edit (a letter dropped, added, changed or two swapped)
from a head noun of the catalog's names or a noun of the kinds lexicon ("screwdiver", "calculater", "nutcraker") is
read as that word, so that a misspelt catalog noun is not an unseen object. Only words of
:data:`MIN_LENGTH` letters or more: a short word is one edit from too many others ("mug", "jug"). The
edits of a word are generated and looked up (about 50 per letter), so the cost does not grow with the
catalog."""

from __future__ import annotations

import functools
import string

__all__ = ["MIN_LENGTH", "corrected", "edits"]

#: Shortest word a typing slip is corrected in.
MIN_LENGTH = 6


def edits(word: str) -> set[str]:
    """Every word one edit from ``word`` (Norvig's edits1)."""
    splits = [(word[:i], word[i:]) for i in range(len(word) + 1)]
    deletes = {a + b[1:] for a, b in splits if b}
    swaps = {a + b[1] + b[0] + b[2:] for a, b in splits if len(b) > 1}
    replaces = {a + c + b[1:] for a, b in splits if b for c in string.ascii_lowercase}
    inserts = {a + c + b for a, b in splits for c in string.ascii_lowercase}
    return (deletes | swaps | replaces | inserts) - {word}


@functools.cache
def _lexicon_words() -> frozenset[str]:
    from kb.kinds import nouns

    return frozenset(k[0] for k in nouns() if len(k) == 1)


def corrected(word: str, vocabulary) -> str | None:
    """The word of ``vocabulary`` (the catalog's head nouns: anything with ``in``), else the lexicon noun,
    one edit from ``word``, when exactly one such word of :data:`MIN_LENGTH` letters or more is found;
    None otherwise (no slip, or an ambiguous one)."""
    if len(word) < MIN_LENGTH or not word.isalpha():
        return None
    near = edits(word)
    for words in (vocabulary, _lexicon_words()):
        found = sorted(w for w in near if w in words and len(w) >= MIN_LENGTH)
        if len(found) == 1:
            return found[0]
        if found:
            return None
    return None
