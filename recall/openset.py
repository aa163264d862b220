"""Open set by kinds: a description that names a household noun the catalog does not have.

The catalog's objects each get a kind (:func:`kb.kinds.kind_of_name`). A description whose subject
names a noun of the kinds lexicon (``kb/data/kind_nouns.csv``) that names no catalog object (no name,
alias or head noun of one, in the noun itself or in its English name) is **not in the catalog**: "An
orange of 7 cm diameter" (fruit), "a ceramic teapot" (jug). The recall still ranks the physically
closest objects (a physically similar object serves the grasp) and adds the closest objects of the same
kind (:meth:`recall.catalog_kinds.KindIndex.rows_of_kind`: the noun's kind, else its nearest ancestor
below the root that has objects). Rules and figures: ``recall/RECALL.md``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from kb.kinds import ROOT, Noun, kinds, noun_in, words_of
from recall.catalog_kinds import KindIndex, is_qualifier, kind_mate, names_sort_of, sort_of_catalog_object
from recall.fit import DISAGREE_FACTOR, THRESHOLDS, Trust, disagreeing_features, judge
from recall.reading import NEGATED_REASON
from recall.subject import feature_words, is_participle
from recall.unheld import PLACEHOLDERS, noun_like, unheld_pair
from recall.words import COLOURS, SIZE_WORDS, material_of_word, material_words

__all__ = [
    "OPEN_SET_NAMED_THRESHOLD",
    "OPEN_SET_THRESHOLD",
    "OPEN_SET_UNKNOWN_NOUN_THRESHOLD",
    "DISAGREE_FACTOR",
    "DescribedNoun",
    "bare_part",
    "compound_head",
    "describe",
    "disagreeing_features",
    "foreign_head",
    "described_noun",
    "foreign_modifier",
    "material_agrees",
    "material_of_word",
    "nothing_compared",
    "is_open_set",
    "SIZE_WORDS",
    "trust_of",
    "synonym_rows",
    "unseen_noun",
]

#: The open-set thresholds, one rule with the store lookup's fit (:mod:`recall.fit`, :data:`THRESHOLDS`):
#: the best match's closeness above this means "not a close match" ...
OPEN_SET_THRESHOLD = THRESHOLDS[Trust.PLAIN]
#: ... above this when the description names the match by a whole name or alias (a name is evidence) ...
OPEN_SET_NAMED_THRESHOLD = THRESHOLDS[Trust.NAMED]
#: ... and above this when the subject of the description is a noun the catalog does not know.
OPEN_SET_UNKNOWN_NOUN_THRESHOLD = THRESHOLDS[Trust.DOUBTED]


def nothing_compared(refused: Sequence, numeric_stated: bool) -> tuple[str, ...]:
    """The words of the values the parser refused (``refused``: ``ParsedDescription.refused``)
    when no numeric value is left to compare (``numeric_stated`` False): the description stated a size or
    mass, and nothing of it can be compared ("a ball 10 m wide"), so no match is a close one. A negated value
    ("a mug, not 10 cm") was not stated: it does not count. Empty otherwise."""
    if numeric_stated:
        return ()
    return tuple(r.words for r in refused if r.reason != NEGATED_REASON)


@dataclass(frozen=True)
class DescribedNoun:
    """The lexicon noun a description's subject names, its kind, and whether the catalog has it."""

    noun: str
    kind: str
    english: str
    in_catalog: bool
    #: The catalog head noun the noun names a sort of (:func:`sort_of_catalog_object`), when that alone
    #: puts it in the catalog: the described object is then in the catalog only as an object of that head.
    sort_of: str | None = None

    def to_dict(self) -> dict[str, object]:
        return {
            "noun": self.noun, "kind": self.kind, "english": self.english, "in_catalog": self.in_catalog,
            "sort_of": self.sort_of,
        }  # fmt: skip


def described_noun(
    subject: Sequence[str],
    phrases,
    heads,
    vocabulary: frozenset[str],
    generic: frozenset[str],
    after_of: Sequence[str] = (),
    kinds_of: KindIndex | None = None,
) -> DescribedNoun | None:
    """The lexicon noun heading the subject phrase (``subject``: its words, singular), and whether the
    catalog knows it: the noun or its English name is a catalog name or alias (``phrases``: word tuples),
    or its head is a catalog head noun (``heads``). Generic nouns ("thing", "piece", "fruit", "toy") name
    a kind, not an object: None. ``after_of``: the phrase after "of" when the subject is a measure of
    something ("a bar of soap", "a pair of scissors"), used when the subject itself names no noun;
    ``vocabulary``: every word of the catalog's names and aliases; ``kinds_of``: the catalog's kinds, for
    the hypernym and compound rules (:func:`_names_catalog_object`; without it a kind's name is a
    hypernym whenever it is no catalog head, and a compound never agrees by kind)."""
    noun: Noun | None = noun_in(list(subject))
    before = subject[-len(noun.words) - 1] if noun is not None and len(subject) > len(noun.words) else None
    pair = (before, *noun.words) if noun is not None and before is not None else subject[-2:]
    if (noun is None or len(noun.words) == 1) and unheld_pair(pair, vocabulary, phrases, generic):
        # "a plush dinosaur toy", "an RF development kit": a generic noun after a noun the catalog does not
        # know names a thing of the generic noun's kind (a lexicon noun's, else none) it does not have
        if noun is None:
            return DescribedNoun(" ".join(pair), ROOT, " ".join(pair), False)
        return DescribedNoun(f"{before} {noun.text}", noun.kind, f"{before} {noun.english}", False)
    if (
        noun is not None and noun.words[-1] in SHAPE_NOUNS and noun.words[-1] not in heads
        and before is not None and (before in material_words() or before in COLOURS)
    ):  # fmt: skip
        return None  # "a wood plate", "a white stick": a material or colour and a shape, no object's name
    if (noun is None or _generic(noun, generic) or _hypernym(noun, kinds_of, heads)) and after_of and not (
        subject and subject[-1] in PART_NOUNS and subject[-1] in heads
    ):  # "the handle of a C-clamp": a part the catalog holds objects of; the whole says only whose it is
        noun = noun_in(list(after_of)) or noun
    if noun is None or _generic(noun, generic):
        return None  # a generic noun ("thing", "toy") names a kind; a compound on one ("glue stick") an object
    if _hypernym(noun, kinds_of, heads):
        return None
    english = tuple(words_of(noun.english))
    known = _names_catalog_object(noun.words, phrases, heads) or (
        noun.english != noun.text and bool(english)
        and (_names_catalog_object(english, phrases, heads) or names_sort_of(noun, english, heads, kinds_of))
    )  # a synonym names a sort of its English name's head noun ("puzzle cube" -> rubik's cube: a cube)
    base = None if known else sort_of_catalog_object(noun, heads, kinds_of) or kind_mate(noun, subject, kinds_of)
    return DescribedNoun(noun.text, noun.kind, noun.english, known or base is not None, base)


def _generic(noun: Noun, generic: frozenset[str]) -> bool:
    return len(noun.words) == 1 and noun.words[0] in generic


def _hypernym(noun: Noun, kinds_of: KindIndex | None, heads=()) -> bool:
    """Whether the noun is a kind's own name ("a cup", "a jar", "a battery") and the catalog has objects
    of that kind: it names any of them (a mug is a cup), not a missing object. Where the catalog has
    none of the kind, it names an object the catalog does not have. A kind name that is a catalog head
    noun needs no look at the kinds (which works out every row's kind once: seconds on a large catalog)."""
    if noun.text not in kinds() or noun.text == ROOT:
        return False
    return noun.text in heads or kinds_of is None or kinds_of.has_kind(noun.kind)


def _names_catalog_object(words: tuple[str, ...], phrases, heads) -> bool:
    """Whether a lexicon noun's words (or its English name's) name a catalog object: a catalog name or
    alias; a single word that is a catalog head noun ("bottle": every bottle); or a catalog head noun after
    material or colour words only ("metal cap"). A compound the lexicon lists ("egg cup", "watering can",
    "toilet brush", "bowling ball") names another object than the catalog's cups, cans, brushes and balls,
    even when its modifier is a catalog word ("egg"): the lexicon lists it because it is one. A compound
    that is a sort of the catalog's objects has its catalog word as its English name ("bottle cap" ->
    cap, "frypan" -> frying pan)."""
    if not words:
        return False
    if words in phrases:
        return True
    if words[-1] not in heads:
        return False
    return all(is_qualifier(w) for w in words[:-1])


#: Nouns that name a part of a thing ("a steel *blade* with a handle", "a padded *headband* with two ear
#: cups"): a description can name an object by its part, so they are never an unseen noun ...
PART_NOUNS = frozenset(
    "blade handle head headband band strap lid tip base body shell casing housing grip cover top bottom "
    "edge face side end rim neck cap spout knob button wheel leg arm frame panel surface".split()
)
#: Solid shapes a list of features can start with ("hollow *cylinder*, 60 cm long"): with
#: :data:`SHAPE_NOUNS`, a shape, not an object's name, when no article introduces them.
SOLID_NOUNS = frozenset("cylinder sphere cube cuboid prism dome wedge".split())


def bare_part(text: str, subject: Sequence[str]) -> bool:
    """Whether the subject's head is a part of a thing (:data:`PART_NOUNS`, a screen too) or a shape
    (:data:`SHAPE_NOUNS`, :data:`SOLID_NOUNS`) that no determiner introduces (:func:`recall.subject.
    introduced`): "glass screen, 170 grams, thin", "C-shaped steel frame, 250 g", "hollow cylinder, 60 cm
    long" list what the object has or looks like; "a frame", "the screen" name the thing itself."""
    from recall.subject import introduced

    head = subject[-1] if subject else None
    if head is None or head not in PART_NOUNS | SHAPE_NOUNS | SOLID_NOUNS | {"screen"}:
        return False
    return not introduced(text, head)


#: ... nor are the abbreviations of a listing's notes ("*dims* 8.5 x 3 in, wt 1.5 lbs").
NOTE_WORDS = frozenset("dim dims dimension measurement approx wt weight size spec specs pic photo".split())


def unseen_noun(unknown: str | None, subject: Sequence[str], plural: bool = False) -> DescribedNoun | None:
    """The unseen-noun rule (RECALL.md, "Not in the catalog"): the subject's head ``unknown`` is a noun
    the catalog's names and aliases do not know (:meth:`recall.name_index.NameIndex.unknown_noun`: no
    catalog word, generic noun or feature word), the kinds lexicon does not list it either, and it is no
    placeholder ("something"), part of a thing ("blade", :data:`PART_NOUNS`), listing abbreviation
    ("dims"), shape noun ("wire *loops*", :data:`SHAPE_NOUNS`), colour or adjective-like word
    (:func:`noun_like`; a word said in the plural, ``plural``, is a noun whatever its ending): the description names an object the catalog does not have, of unknown kind (the
    root). The noun reported is the head with the noun before it when there is one ("lint roller"; its
    ``english``, the search word of a store lookup, is the head alone). The recall uses it only when the
    description states a feature ("qwerty uiop" is nothing to recall). None otherwise (a lexicon noun is :func:`described_noun`'s to judge)."""
    if unknown is None or any(unknown in words for words in (PLACEHOLDERS, PART_NOUNS, NOTE_WORDS, SHAPE_NOUNS)):
        return None
    if noun_in([unknown]) is not None or not (noun_like(unknown) or (plural and _plural_noun(unknown))):
        return None  # ``plural``: said in the plural ("binoculars"), a noun whatever its ending
    before = subject[-2] if len(subject) > 1 and subject[-1] == unknown else None
    text = f"{before} {unknown}" if before and before not in PLACEHOLDERS and noun_like(before) else unknown
    return DescribedNoun(text, ROOT, unknown, False)


def counted_material(text: str, vocabulary: frozenset[str]) -> str | None:
    """A material word that an indefinite article counts as the subject ("*a walnut*, in the shell", "*a
    cork*": :func:`recall.subject.counted_head`) and that no catalog name and no lexicon noun has: it
    names a thing the catalog does not have, as "a glass" names a drinking glass where the catalog has
    one (RECALL.md, "Compounds"). None otherwise."""
    from recall.subject import counted_head

    word = counted_head(text)
    if word is None or word not in material_words() or word in vocabulary or noun_in([word]) is not None:
        return None
    return word


def names_inside(noun: DescribedNoun | None, phrases: Sequence[str]) -> bool:
    """Whether every catalog name the text names (``phrases``) is only a part of the described noun's
    words ("egg" in "egg cup", "lemon" in "lemon squeezer", the alias "bulb" in "garlic bulb"): the
    noun, a compound the catalog does not have, says what the text describes, not the name inside it.
    False when it names none."""
    if noun is None or not phrases:
        return False
    words = tuple(noun.noun.split())
    return all(_proper_part(tuple(words_of(p)), words) for p in phrases)


def _proper_part(part: tuple[str, ...], words: tuple[str, ...]) -> bool:
    n = len(part)
    return 0 < n < len(words) and any(words[i : i + n] == part for i in range(len(words) - n + 1))


def synonym_rows(noun: DescribedNoun | None, phrases) -> set[int]:
    """The catalog rows a lexicon synonym names by its English word ("cellphone" -> the smartphone,
    "frypan" -> the frying pan): the rows of that whole catalog name or alias; empty for a noun that is
    not in the catalog, that has no other English word, or none that is a catalog name."""
    if noun is None or not noun.in_catalog or noun.english == noun.noun:
        return set()
    words = tuple(words_of(noun.english))
    return set(phrases.get(words, ()) or ())


def compound_head(subject: Sequence[str], vocabulary: frozenset[str]) -> str | None:
    """The head of a compound whose modifier is a catalog noun and whose head is no catalog word at all
    ("a bottle *warmer*", "a key *holder*", "a back *scratcher*"): a candidate for the unseen-noun rule
    (:func:`unseen_noun` then applies its exclusions), which :meth:`recall.name_index.NameIndex.unknown_noun`
    does not give for a compound on a catalog head noun (there "remote control" must stay the tv remote:
    "control" is a catalog word, so it is none here either). None otherwise."""
    return foreign_head(subject, vocabulary) if len(subject) >= 2 else None


def foreign_head(words: Sequence[str], vocabulary: frozenset[str]) -> str | None:
    """The last of ``words`` when it is no catalog word, generic noun, feature word or participle: the
    head of a phrase the catalog's names do not know (also the phrase after "a pair of")."""
    from recall.names import GENERIC_NOUNS

    head = words[-1] if words else None
    if head is None or head in vocabulary or head in GENERIC_NOUNS:
        return None
    if head in feature_words() or is_participle(head):
        return None
    return head


def is_open_set(closeness: float | None, named: bool, unknown_noun: str | None) -> bool:
    """The open-set rule on the closeness alone (RECALL.md): the best match is not a close match when its
    closeness (mean relative error) exceeds :data:`OPEN_SET_THRESHOLD`, :data:`OPEN_SET_NAMED_THRESHOLD` when
    the text names it exactly, or :data:`OPEN_SET_UNKNOWN_NOUN_THRESHOLD` when the subject is an unknown noun
    (:func:`recall.fit.judge` with that trust)."""
    if closeness is None:
        return False
    return not judge(closeness, {}, trust_of(named, unknown_noun)).close


def trust_of(named: bool, doubt: str | None) -> Trust:
    """What the words say about the best match: named by the text (and not contradicted), doubted (an
    unknown subject noun or a foreign modifier, ``doubt``), or neither."""
    if named:
        return Trust.NAMED
    return Trust.DOUBTED if doubt is not None else Trust.PLAIN


#: Nouns that also name a shape ("a wood *plate*", "a white *stick*"): after a material or colour word,
#: and when no catalog object has them as head noun, they describe a piece of that shape, not an object.
SHAPE_NOUNS = frozenset(
    "plate board bar stick tube ring panel tile plank rod strip slab sheet disc disk loop coil spiral hoop "
    "cone pyramid triangle oval".split()
)



def _plural_noun(word: str) -> bool:
    from recall.lexicon import COLOUR_WORDS

    return len(word) >= 3 and word.isalpha() and word not in COLOURS and word not in COLOUR_WORDS and (
        word not in feature_words()
    )


def foreign_modifier(subject: Sequence[str], object_words: frozenset[str]) -> str | None:
    """The noun before the subject's head when the head names the matched object but that noun is in
    none of its names ("a ceramic *salad* plate" -> dinner plate, "a *garlic* bulb" -> light bulb, "a
    glass *measuring* cup" -> coffee mug): the name says less than it seems, so the open-set rule does
    not trust it (RECALL.md). None otherwise."""
    if len(subject) < 2 or subject[-1] not in object_words:
        return None
    word = subject[-2]
    # a gerund says what the object is for ("a *baking* potato", "a *mixing* bowl"), not another object
    return word if word not in object_words and noun_like(word) and not word.endswith("ing") else None


def material_agrees(subject: Sequence[str], material: str | None) -> bool:
    """Whether no material word before the subject's head contradicts the named match's ``material``
    (an unknown one agrees): a name is trusted as evidence only then ("a wooden spoon" named "spoon" is
    no steel spoon)."""
    stated = {material_of_word(w) for w in subject[:-1]} - {None}
    return material is None or not stated or material in stated


def describe(text: str, names, kinds_of: KindIndex) -> DescribedNoun | None:
    """The noun a description names and whether the catalog has it (``names``: the catalog's
    :class:`recall.name_index.NameIndex`): the lexicon noun of its subject phrase
    (:func:`recall.subject.noun_phrase`, or the phrase after "of" when the subject is a measure of
    something: "a bar of soap"; :func:`described_noun`), else an unseen noun (:func:`unseen_noun`: the
    subject's unknown head, an unknown head after a catalog noun, or after "a pair of"), a word one typing
    slip from a catalog or lexicon word read as that word (:mod:`recall.typos`)."""
    import re

    from recall.contents import foreign_contents
    from recall.names import GENERIC_NOUNS
    from recall.subject import counted_parts, introduced, noun_phrase, said_in_plural, subject_phrase
    from recall.typos import corrected

    subject = noun_phrase(text)
    if counted_parts(text, subject):
        return None  # "tiny, two screw caps, 8 g": the parts the object has, not its name
    after_of: tuple[str, ...] = ()
    if subject:  # "a bar of soap", "a pair of scissors": the noun after "of"
        m = re.search(rf"\b{re.escape(subject[-1])}s?\s+of\s+(.*)", text.lower())
        after_of = subject_phrase(m.group(1)) if m else ()
    held_elsewhere = foreign_contents(text, subject, after_of, names)
    if held_elsewhere is not None:  # "a box of Cheerios" where the catalog's boxes hold other things
        container = noun_in([subject[-1]])
        return DescribedNoun(held_elsewhere, container.kind if container else ROOT, subject[-1], False)
    args = (names.phrases, names.heads, names.vocabulary, GENERIC_NOUNS, after_of, kinds_of)
    noun = described_noun(subject, *args)
    if noun is not None and not noun.in_catalog and bare_part(text, subject):
        return None  # "glass screen, 170 grams, thin": a list of features names a part or a shape
    if noun is not None or any(w in names.vocabulary for w in after_of):
        return noun  # "a pint of milk": a measure of something the catalog knows is no unseen object
    head = names.unknown_noun(text) or compound_head(subject, names.vocabulary)
    thing = counted_material(text, names.vocabulary)
    if head is None and thing is not None:
        return DescribedNoun(thing, ROOT, thing, False)  # "a walnut, 3.5 cm": a thing, not its material
    if head is None and after_of and subject[-1] in GENERIC_NOUNS:  # "a pair of bifocals"
        subject, head = after_of, foreign_head(after_of, names.vocabulary)
    bare = head is not None and not introduced(text, head)
    if head is not None and subject and subject[-1] == head:
        fixed = corrected(head, names.heads)
        noun = described_noun((*subject[:-1], fixed), *args) if fixed is not None else None
        if noun is not None and (noun.in_catalog or not bare):
            return noun  # "a screwdiver": the catalog's screwdriver, or a lexicon noun, misspelt
    if bare:  # a bare phrase in a list of features ("spring-loaded jaws", "five fingers"): doubt, no verdict
        return None
    return unseen_noun(head, subject, plural=head is not None and said_in_plural(head, text))
