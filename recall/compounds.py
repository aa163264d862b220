"""Compound nouns: whether the head noun of a description names a catalog object whose names are compounds.

A head noun in a description names every catalog object with that head ("a steel bottle" -> every bottle;
``recall/RECALL.md``, "The hybrid"). A compound is another matter: its modifier says which sort of the head
it is. When the description's head comes after a *noun modifier* ("a **wedding** ring") and every name of
an object with that head is a compound on another noun ("**key** ring", "**tea**spoon"), the description
names another sort of thing: a wedding ring is no key ring, and the head alone is no name match. Modifier
and head must both agree: the description's modifier is a word of one of the object's names ("a water
bottle" and "bottle of water"), the prefix of a compound word ("a tea spoon", "teaspoon"), or the object
has a name with that head and no noun modifier before it or after its "of" ("plastic mug", "ball"), which
any sort of the head names.

Without a tagger a noun modifier is a word of three letters or more before the head that is no function
word or word of the parser's lexicon (materials, units, numbers, hedges, ...), no generic noun ("toy",
"piece"), colour or adjective by its ending (:func:`recall.openset.noun_like`).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence

__all__ = ["COMPOUND_CHECK_LIMIT", "compound_agrees", "modifier_noun"]

#: A head noun naming more catalog objects than this is not checked object by object (a million-row
#: catalog's "ball"): such a head carries little information (ln N/m) anyway.
COMPOUND_CHECK_LIMIT = 2_000


def modifier_noun(words: Sequence[str], i: int) -> str | None:
    """The noun modifier of the head noun ``words[i]`` ("wedding" in "a wedding ring"), or None."""
    from recall.names import GENERIC_NOUNS
    from recall.openset import noun_like

    if i < 1:
        return None
    word = words[i - 1]
    if word in GENERIC_NOUNS or word in _function_words() or word.isdigit():
        return None
    return word if noun_like(word) else None


def compound_agrees(modifier: str, head: str, phrases: Sequence[str]) -> bool:
    """Whether a description's ``modifier`` + ``head`` ("wedding ring") can name an object whose names and
    aliases are ``phrases``: the modifier is a word of one of them, or the prefix of a compound word on the
    head ("tea" + "spoon"), or a name has the head with no noun modifier (module docstring)."""
    for phrase in phrases:
        words, word, plain = _name_parts(phrase)
        if modifier in words:
            return True
        if not word:
            continue
        if word == head and plain:
            return True
        if word != head and word.endswith(head) and word[: -len(head)] == modifier:
            return True
    return False


@functools.lru_cache(maxsize=1 << 14)
def _name_parts(phrase: str) -> tuple[frozenset[str], str, bool]:
    """What :func:`compound_agrees` reads of a name or alias, the same at every query (so cached: up to
    COMPOUND_CHECK_LIMIT rows' names are read per head noun, ~10 µs a name): its words, its head word in
    :func:`recall.names.name_core` (the word before "of", else the last; "" without one) and whether its
    other words, also after "of" ("bottle of *water*"), only qualify the head (a material, colour or
    adjective: "*plastic* mug"; :func:`recall.catalog_kinds.is_qualifier`)."""
    from kb.kinds import words_of
    from recall.catalog_kinds import is_qualifier
    from recall.names import name_core

    core = name_core(phrase)
    if not core:
        return frozenset(words_of(phrase)), "", False
    at = core.index("of", 1) - 1 if "of" in core[1:] else len(core) - 1
    others = core[:at] + core[at + 2 :]
    return frozenset(words_of(phrase)), core[at], all(is_qualifier(w) for w in others)


@functools.cache
def _function_words() -> frozenset[str]:
    """Words that are no noun modifier: the parser's lexicon (function words, features, units, numbers) and
    the words that end or are skipped in a subject phrase (pronouns, determiners, "old", "new")."""
    from recall.names import _tagged_words
    from recall.subject import _PHRASE_ENDS, _PHRASE_SKIP

    return _tagged_words() | _PHRASE_ENDS | _PHRASE_SKIP
