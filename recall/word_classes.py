"""Word classes without a tagger: the parser-lexicon words that state a feature rather than name an object,
and adjectives and participles by their endings.

:func:`feature_words` and :func:`adjective_feature_words` let the name index and the open set tell a noun
from a feature word; :func:`is_participle` and :func:`is_adjective` are heuristics on endings, used only as
evidence (``recall/RECALL.md``, "Unknown subject noun"). Split from :mod:`recall.subject` (no behaviour
change).
"""

from __future__ import annotations

import functools
import re

from kb.kinds import words_of

__all__ = ["adjective_feature_words", "feature_words", "is_adjective", "is_participle"]


@functools.cache
def feature_words() -> frozenset[str]:
    """Single words of the parser's lexicon that state a feature, a unit, a number or a hedge. Colour
    words and the object nouns among the shape words ("orange", "candle", "vase") are left out: as the
    head of the subject they name the object; of the shape words only adjectives ("round", "cylindrical",
    "ball-shaped") are kept."""
    from recall import lexicon as lx

    words: set[str] = set()
    tables = (
        lx.MATERIAL_WORDS, lx.RIGIDITY_WORDS, lx.TEXTURE_WORDS, lx.FRAGILITY_WORDS, lx.MASS_HINT_WORDS,
        lx.DIMENSION_WORDS, lx.NUMBER_WORDS, lx.MAGNITUDE_WORDS, lx.FRACTION_WORDS, lx.HEDGES,
        lx.LENGTH_UNITS, lx.MASS_UNITS, lx.VOLUME_UNITS, lx.MEDIUM_WORDS, lx.DIMENSION_NOUNS, lx.FILL_WORDS,
        lx.CAPACITY_WORDS, lx.NEGATIONS,
    )  # fmt: skip
    for table in tables:
        for phrase in table:
            words.update(words_of(phrase))
    shape_words = set(lx.SHAPE_WORDS) | lx.SPHERE_WORDS | lx.CUBE_WORDS | lx.FLAT_WORDS | lx.ROUND_WORDS
    for word in shape_words | lx.CYLINDER_WORDS | lx.DISC_WORDS:
        if _ADJECTIVE.search(word) or word in _SHAPE_ADJECTIVES:
            words.update(words_of(word))
    return frozenset(words)


@functools.cache
def adjective_feature_words() -> frozenset[str]:
    """Single words that state a mass hint, texture, rigidity or fragility ("light", "soft"): adjectives,
    never a head noun, although a catalog name may end in one ("tea light")."""
    from recall import lexicon as lx

    tables = (lx.MASS_HINT_WORDS, lx.TEXTURE_WORDS, lx.RIGIDITY_WORDS, lx.FRAGILITY_WORDS)
    return frozenset(w for table in tables for w in table if " " not in w)


#: Adjective endings; "-y" only after a consonant ("squishy", "fuzzy"), not in "key", "tray", "trolley".
_ADJECTIVE = re.compile(r"(al|ic|ed|[^aeiou]y|ish|ar|shaped|like)$")


_SHAPE_ADJECTIVES = frozenset(
    {"flat", "round", "long", "thin", "slim", "slender", "compact", "oval", "squat", "floppy"}
)


#: Participles and adjectives that end a phrase ("full", "filled", "folded", "useful"): never a head.
_PARTICIPLE = re.compile(r"^(full|play|fake|toy)$|..(ed|ful|ous|able|ible)$")


def is_participle(word: str) -> bool:
    """Whether ``word`` is a participle or adjective that never heads a subject ("full", "filled")."""
    return _PARTICIPLE.search(word) is not None


def is_adjective(word: str) -> bool:
    """Whether ``word`` looks like an adjective or participle by its ending or is a shape adjective
    ("metallic", "round", "folded"); a heuristic without a tagger (nouns such as "garlic" match too:
    callers check the noun lexicon first)."""
    return bool(_ADJECTIVE.search(word)) or word in _SHAPE_ADJECTIVES or is_participle(word)
