"""A described noun no catalog row holds: a generic noun after a noun the catalog's names never use.

A generic noun ("toy", "kit", "set", "gadget": :data:`recall.names.GENERIC_NOUNS`) names a kind, not an
object, so alone it says nothing about which catalog object is meant ("a plastic toy", "a set"). After a
noun that no catalog name or alias has, two sorts of generic noun make an object of the pair, and no
catalog row holds it: the described object is not in the catalog, and the store lookup is asked for it
(issue 22):

* a generic noun the kinds lexicon lists ("a plush *dinosaur* toy", "a *mailing* tube": the lexicon's
  kind of the noun);
* a collection made for a purpose (:data:`COLLECTIONS`: "an RF *development* kit", "a *chess* set"), whose
  compounds the kinds lexicon lists as objects (first aid kit, sewing kit, test kit, tea set, train set,
  socket set, paint set, ...), where it lists none on the category words ("gadget", "device",
  "accessory", "appliance", "equipment", "item", "product"): "a heavy metal *office* gadget" (a
  stapler) is still a gadget of the office, the features decide which.

The open-set verdict (:func:`recall.openset.described_noun`) and so the lookup
(:func:`recall.lookup.lookup_reason`, which reads the verdict's ``not_in_catalog``) read this one function.
Not such a pair (None): a generic noun a catalog object is called by alone ("tube": "a mailing tube" is
a sort of it); a word before it that the catalog's names use ("a *tennis* kit" where the catalog has
tennis balls), that is itself generic ("a *tool* set", "a *food* container"), a placeholder, or no noun (a
material, colour, size word or adjective by its ending: :func:`noun_like`).
"""

from __future__ import annotations

from collections.abc import Sequence

from kb.kinds import noun_in
from recall.subject import feature_words, is_adjective
from recall.words import COLOURS

__all__ = ["COLLECTIONS", "PLACEHOLDERS", "noun_like", "unheld_pair"]

#: Words that hold the place of an object without naming one ("something", "a whatsit"): never an
#: unseen noun (the generic nouns of :data:`recall.names.GENERIC_NOUNS` never are either).
PLACEHOLDERS = frozenset(
    "something anything everything nothing thing stuff whatsit whatchamacallit thingy thingamajig thingamabob "
    "doohickey gizmo widget".split()
)

#: Generic nouns outside the kinds lexicon that name a collection made for a purpose: after a noun, an
#: object (module docstring).
COLLECTIONS = frozenset({"kit", "set"})


def unheld_pair(subject: Sequence[str], vocabulary: frozenset[str], phrases, generic: frozenset[str]) -> str | None:
    """The modifier and generic head ("development kit") when the subject phrase (``subject``: its words,
    singular) ends in a generic noun (``generic``) of the kinds lexicon or of :data:`COLLECTIONS` after a
    noun that no catalog name or alias holds (``vocabulary``: every word of them; ``phrases``: their word
    tuples), as the module docstring says; None otherwise."""
    if len(subject) < 2:
        return None
    before, head = subject[-2], subject[-1]
    if head not in generic or (head,) in phrases or (head not in COLLECTIONS and noun_in([head]) is None):
        return None
    if before in vocabulary or before in generic or before in PLACEHOLDERS or not noun_like(before):
        return None
    return f"{before} {head}"


def noun_like(word: str) -> bool:
    """Whether a word of a subject phrase can be a noun modifier ("salad" in "salad plate", "garlic",
    "dinosaur"): a lexicon noun, or a word of three letters or more that is no feature word (material,
    texture, unit, number, colour, ...) and does not look like an adjective."""
    from recall.lexicon import COLOUR_WORDS

    if word in COLOURS or word in COLOUR_WORDS or word in feature_words():
        return False
    if noun_in([word]) is not None:
        return True
    return len(word) >= 3 and word.isalpha() and not is_adjective(word)
