"""Words the open-set verdict (:mod:`recall.openset`) and the contents rule (:mod:`recall.contents`) both
read: size and colour words, the materials a single word states, the head noun of a phrase. Here so that
neither imports the other (tests/test_layering.py: no import circles)."""

from __future__ import annotations

import functools
from collections.abc import Sequence

__all__ = ["COLOURS", "SIZE_WORDS", "head_noun", "material_of_word", "material_words"]

#: Size and degree words, which qualify a name ("*small* clamp", "*extra* large clamp") and never make a
#: compound.
SIZE_WORDS = frozenset(
    "small big large little tiny mini medium extra huge giant jumbo xl xxl short long tall thin thick wide "
    "narrow heavy light biggest smallest largest".split()
)
#: Colour words, which never name an object as modifiers ("a white stick").
COLOURS = frozenset(
    "white black grey gray silver gold golden red green blue yellow orange pink purple brown beige tan "
    "clear transparent dark light bright pale navy cream ivory".split()
)


def head_noun(words: Sequence[str]) -> str | None:
    """The head noun of a phrase as the catalog's names have it: the word before "of" ("*bunch* of keys",
    "*bottle* of water"), else the last word; None for no words."""
    words = list(words)
    if "of" in words[1:]:
        return words[words.index("of", 1) - 1]
    return words[-1] if words else None


@functools.cache
def material_words() -> frozenset[str]:
    """The single-word materials of the lexicon (:data:`recall.lexicon.MATERIAL_WORDS`)."""
    from recall.lexicon import MATERIAL_WORDS

    return frozenset(w for w in MATERIAL_WORDS if " " not in w)


def material_of_word(word: str) -> str | None:
    """The catalog material a single word states ("wooden" -> wood), or None."""
    from recall.lexicon import MATERIAL_WORDS

    return MATERIAL_WORDS.get(word)
