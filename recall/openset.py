"""Open set by kinds: a description that names a household noun the catalog does not have.

The catalog's objects each get a kind (:func:`kb.kinds.kind_of_name`). A description whose subject
names a noun of the kinds lexicon (``kb/data/kind_nouns.csv``) that names no catalog object (no name,
alias or head noun of one, in the noun itself or in its English name) is **not in the catalog**: "An
orange of 7 cm diameter" (fruit), "a ceramic teapot" (jug). The recall still ranks the physically
closest objects (a physically similar object serves the grasp) and adds the closest objects of the same
kind (:meth:`KindIndex.rows_of_kind`: the noun's kind, else its nearest ancestor below the root that has
objects). Rules and figures: ``recall/RECALL.md``.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

from kb.kinds import ROOT, Noun, ancestors, kind_of_name, noun_in, words_of
from recall.subject import feature_words, is_adjective

__all__ = [
    "OPEN_SET_NAMED_THRESHOLD",
    "OPEN_SET_THRESHOLD",
    "OPEN_SET_UNKNOWN_NOUN_THRESHOLD",
    "DescribedNoun",
    "KindIndex",
    "described_noun",
    "foreign_modifier",
    "material_agrees",
    "material_of_word",
    "is_open_set",
    "unseen_noun",
]

#: Open set: the best match's closeness (mean relative error over the stated features, see
#: :func:`recall.metrics.relative_errors`) above this means "not a close match" ...
OPEN_SET_THRESHOLD = 0.30
#: ... above this when the description names the match by a whole name or alias (a name is evidence) ...
OPEN_SET_NAMED_THRESHOLD = 0.45
#: ... and above this when the subject of the description is a noun the catalog does not know ("an
#: orange", "a watermelon"): an unknown noun alone is not enough (synonyms), with a loose match it is.
OPEN_SET_UNKNOWN_NOUN_THRESHOLD = 0.15


@dataclass(frozen=True)
class DescribedNoun:
    """The lexicon noun a description's subject names, its kind, and whether the catalog has it."""

    noun: str
    kind: str
    english: str
    in_catalog: bool

    def to_dict(self) -> dict[str, object]:
        return {"noun": self.noun, "kind": self.kind, "english": self.english, "in_catalog": self.in_catalog}


class KindIndex:
    """The kind of every catalog row, and the rows of each kind. Lazy: a row's kind is worked out when
    first asked for (a match shown), the rows of each kind on the first "not in the catalog" answer, so
    building a recaller over a large catalog costs nothing here."""

    def __init__(self, names: Sequence[str], aliases: Sequence[Sequence[str]]):
        self._names = names
        self._aliases = aliases
        self._kinds: dict[int, str | None] = {}
        self._rows: dict[str, list[int]] | None = None

    def kind(self, row: int) -> str | None:
        if row not in self._kinds:
            self._kinds[row] = kind_of_name(self._names[row], self._aliases[row])
        return self._kinds[row]

    def rows_of_kind(self, kind: str) -> tuple[str | None, list[int]]:
        """The rows of ``kind`` or of its nearest ancestor that has rows (never the root): (kind used,
        rows); (None, []) when none."""
        if self._rows is None:
            rows: dict[str, list[int]] = {}
            for row in range(len(self._names)):
                own = self.kind(row)
                for k in ancestors(own) if own else ():
                    rows.setdefault(k, []).append(row)
            self._rows = rows
        for k in ancestors(kind):
            if k == ROOT:
                break
            if self._rows.get(k):
                return k, list(self._rows[k])
        return None, []


def described_noun(
    subject: Sequence[str],
    phrases,
    heads,
    vocabulary: frozenset[str],
    generic: frozenset[str],
    after_of: Sequence[str] = (),
) -> DescribedNoun | None:
    """The lexicon noun heading the subject phrase (``subject``: its words, singular), and whether the
    catalog knows it: the noun or its English name is a catalog name or alias (``phrases``: word tuples),
    or its head is a catalog head noun (``heads``). Generic nouns ("thing", "piece", "fruit", "toy") name
    a kind, not an object: None. ``after_of``: the phrase after "of" when the subject is a measure of
    something ("a bar of soap", "a pair of scissors"), used when the subject itself names no noun;
    ``vocabulary``: every word of the catalog's names and aliases."""
    noun: Noun | None = noun_in(list(subject))
    before = subject[-len(noun.words) - 1] if noun is not None and len(subject) > len(noun.words) else None
    if noun is not None and noun.words[-1] in generic and before is not None:
        # "a plush dinosaur toy": a generic noun after a noun the catalog does not know names a thing of
        # the generic noun's kind that the catalog does not have
        if before not in vocabulary and before not in generic and noun_like(before):
            return DescribedNoun(f"{before} {noun.text}", noun.kind, f"{before} {noun.english}", False)
    if (
        noun is not None and noun.words[-1] in SHAPE_NOUNS and noun.words[-1] not in heads
        and before is not None and (before in _material_words() or before in COLOURS)
    ):  # fmt: skip
        return None  # "a wood plate", "a white stick": a material or colour and a shape, no object's name
    if (noun is None or noun.words[-1] in generic) and after_of:
        noun = noun_in(list(after_of))
    if noun is None or noun.words[-1] in generic:
        return None
    english = tuple(words_of(noun.english))
    # known: a catalog name or alias, or a catalog head noun ("bottle": every bottle) whose modifiers are
    # all catalog words ("bottle cap"; but "bowling ball" is no catalog ball)
    known = any(
        words in phrases or (words and words[-1] in heads and all(w in vocabulary for w in words[:-1]))
        for words in (noun.words, english)
    )
    return DescribedNoun(noun.text, noun.kind, noun.english, known)


#: Words that hold the place of an object without naming one ("something", "a whatsit"): never an
#: unseen noun (the generic nouns of :data:`recall.names.GENERIC_NOUNS` never are either).
PLACEHOLDERS = frozenset(
    "something anything everything nothing thing stuff whatsit whatchamacallit thingy thingamajig thingamabob "
    "doohickey gizmo widget".split()
)
#: Nouns that name a part of a thing ("a steel *blade* with a handle", "a padded *headband* with two ear
#: cups"): a description can name an object by its part, so they are never an unseen noun ...
PART_NOUNS = frozenset(
    "blade handle head headband band strap lid tip base body shell casing housing grip cover top bottom "
    "edge face side end rim neck cap spout knob button wheel leg arm frame panel surface".split()
)
#: ... nor are the abbreviations of a listing's notes ("*dims* 8.5 x 3 in, wt 1.5 lbs").
NOTE_WORDS = frozenset("dim dims dimension measurement approx wt weight size spec specs pic photo".split())


def unseen_noun(unknown: str | None, subject: Sequence[str]) -> DescribedNoun | None:
    """The unseen-noun rule (RECALL.md, "Not in the catalog"): the subject's head ``unknown`` is a noun
    the catalog's names and aliases do not know (:meth:`recall.name_index.NameIndex.unknown_noun`: no
    catalog word, generic noun or feature word), the kinds lexicon does not list it either, and it is no
    placeholder ("something"), part of a thing ("blade", :data:`PART_NOUNS`), listing abbreviation
    ("dims"), shape noun ("wire *loops*", :data:`SHAPE_NOUNS`), colour or adjective-like word
    (:func:`noun_like`): the description names an object the catalog does not have, of unknown kind (the
    root). The noun reported is the head with the noun before it when there is one ("lint roller"; its
    ``english``, the search word of a store lookup, is the head alone). The recall uses it only when the
    description states a feature ("qwerty uiop" is nothing to recall). None otherwise (a lexicon noun is :func:`described_noun`'s to judge)."""
    if unknown is None or any(unknown in words for words in (PLACEHOLDERS, PART_NOUNS, NOTE_WORDS, SHAPE_NOUNS)):
        return None
    if noun_in([unknown]) is not None or not noun_like(unknown):
        return None
    before = subject[-2] if len(subject) > 1 and subject[-1] == unknown else None
    text = f"{before} {unknown}" if before and before not in PLACEHOLDERS and noun_like(before) else unknown
    return DescribedNoun(text, ROOT, unknown, False)


def is_open_set(closeness: float | None, named: bool, unknown_noun: str | None) -> bool:
    """The open-set rule (RECALL.md): the best match is not a close match when its closeness (mean
    relative error) exceeds :data:`OPEN_SET_THRESHOLD`, :data:`OPEN_SET_NAMED_THRESHOLD` when the text
    names it exactly, or :data:`OPEN_SET_UNKNOWN_NOUN_THRESHOLD` when the subject is an unknown noun."""
    if closeness is None:
        return False
    if named:
        return closeness > OPEN_SET_NAMED_THRESHOLD
    if unknown_noun is not None:
        return closeness > OPEN_SET_UNKNOWN_NOUN_THRESHOLD
    return closeness > OPEN_SET_THRESHOLD


#: Nouns that also name a shape ("a wood *plate*", "a white *stick*"): after a material or colour word,
#: and when no catalog object has them as head noun, they describe a piece of that shape, not an object.
SHAPE_NOUNS = frozenset(
    "plate board bar stick tube ring panel tile plank rod strip slab sheet disc disk loop coil spiral hoop "
    "cone pyramid triangle oval".split()
)
#: Colour words, which never name an object as modifiers ("a white stick").
COLOURS = frozenset(
    "white black grey gray silver gold golden red green blue yellow orange pink purple brown beige tan "
    "clear transparent dark light bright pale navy cream ivory".split()
)


@functools.cache
def _material_words() -> frozenset[str]:
    from recall.lexicon import MATERIAL_WORDS

    return frozenset(w for w in MATERIAL_WORDS if " " not in w)


def material_of_word(word: str) -> str | None:
    """The catalog material a single word states ("wooden" -> wood), or None."""
    from recall.lexicon import MATERIAL_WORDS

    return MATERIAL_WORDS.get(word)


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


def foreign_modifier(subject: Sequence[str], object_words: frozenset[str]) -> str | None:
    """The noun before the subject's head when the head names the matched object but that noun is in
    none of its names ("a ceramic *salad* plate" -> dinner plate, "a *garlic* bulb" -> light bulb, "a
    glass *measuring* cup" -> coffee mug): the name says less than it seems, so the open-set rule does
    not trust it (RECALL.md). None otherwise."""
    if len(subject) < 2 or subject[-1] not in object_words:
        return None
    word = subject[-2]
    return word if word not in object_words and noun_like(word) else None


def material_agrees(subject: Sequence[str], material: str | None) -> bool:
    """Whether no material word before the subject's head contradicts the named match's ``material``
    (an unknown one agrees): a name is trusted as evidence only then ("a wooden spoon" named "spoon" is
    no steel spoon)."""
    stated = {material_of_word(w) for w in subject[:-1]} - {None}
    return material is None or not stated or material in stated
