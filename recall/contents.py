"""Contents of a container: "a box of Cheerios" where the catalog holds its boxes only by other contents.

A catalog that names every object of a container noun by what it holds ("cracker box", "sugar box",
"mustard bottle", "roll of tape") and none by the container alone or with qualifiers ("box", "small
bottle") has no "box" in general: a container of contents none of those names has ("a box of
*Cheerios*", "a roll of *toilet paper*") is another object, not in the catalog, as another sort of a
catalog head is where the catalog names that head's objects by their sorts (:func:`recall.openset.
sort_of_catalog_object`). Contents a name of that container has ("a box of *tissues*" -> "tissue box",
"a bottle of *dish* soap" -> "dish washing soap bottle") stay in the catalog; a catalog with a plain object
of the container ("small bottle") holds any bottle, the features decide. Rule and figures: RECALL.md,
"Contents of a container".
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from kb.kinds import words_of
from recall.lexicon import CONTAINER_NOUNS
from recall.words import COLOURS, SIZE_WORDS, head_noun, material_of_word

__all__ = ["foreign_contents"]


def _material_adjective(word: str) -> bool:
    """A material named as such ("plastic", "glass") or by its adjective ("wooden", "metallic"); not a
    material word that is a thing's name too ("tissue" -> paper: a "tissue box" holds tissues)."""
    material = material_of_word(word)
    return material is not None and (material == word or word.endswith(("en", "ic")))


def _lexicon_names_it(after_of: Sequence[str], container: str, phrases) -> bool:
    """Whether "<contents> <container>" is a catalog name (or a synonym of one, ``phrases``) or a lexicon
    noun that is one or has one as its English name ("a box of cornflakes": the lexicon's "cornflakes box",
    English "cereal box"), or the contents are a lexicon noun whose English name is a catalog name on the
    container ("a can of spam": English "potted meat can")."""
    from kb.kinds import noun_in

    if (*after_of, container) in phrases:
        return True
    contents = noun_in(list(after_of))
    english = tuple(words_of(contents.english or "")) if contents is not None else ()
    if english[-1:] == (container,) and english in phrases:
        return True
    for words in ([*after_of, container], [*after_of[:-1], f"{after_of[-1]}s", container]):
        noun = noun_in(words)
        if noun is not None and noun.words[-1] == container:
            if tuple(noun.words) in phrases or tuple(words_of(noun.english or "")) in phrases:
                return True
    return False


def foreign_contents(text: str, subject: Sequence[str], after_of: Sequence[str], names) -> str | None:
    """The object "<contents> <container>" the text describes when the catalog holds that container only
    by other contents (module docstring): ``subject`` the subject phrase's words (its last the container,
    one of :data:`recall.lexicon.CONTAINER_NOUNS`), ``after_of`` the phrase after its "of" (the contents),
    ``names`` the catalog's :class:`recall.name_index.NameIndex`. None otherwise (also when the contents
    are no word at all, or a container noun the catalog's names do not head)."""
    if not subject or not after_of or subject[-1] not in CONTAINER_NOUNS:
        return None
    container = subject[-1]
    if not re.search(rf"\b{re.escape(container)}s?\s+of\b", text.lower()):
        return None
    rows = names.heads.get(container)
    if not rows:
        return None
    held: set[str] = set()
    for row in rows:
        for phrase in names.names_of(row):
            words = words_of(phrase)
            if head_noun(words) != container:
                continue
            if all(w in SIZE_WORDS or w in COLOURS or _material_adjective(w) for w in words[:-1]):
                return None  # "small bottle", "bottle": the catalog holds a bottle of anything
            held.update(w for w in words if w != container)
    if any(w in held for w in after_of) or _lexicon_names_it(after_of, container, names.phrases):
        return None
    return f"{' '.join(after_of)} {container}"
