"""The catalog's kinds and the sorts of its objects: which kind each catalog object is, which objects are
of a kind (:class:`KindIndex`), and whether a lexicon noun the catalog's names do not hold names a sort
of an object it holds under a plain name (:func:`sort_of_catalog_object`, :func:`kind_mate`). The
open-set verdict (:mod:`recall.openset`) asks these; rules and figures: ``recall/RECALL.md``, "Sorts of
a catalog object".
"""

from __future__ import annotations

from collections.abc import Sequence

from kb.kinds import ROOT, Noun, ancestors, kind_of_name, kinds, noun_in, words_of
from recall.unheld import noun_like
from recall.words import COLOURS, SIZE_WORDS, head_noun, material_words

__all__ = [
    "KIND_SCAN_LIMIT",
    "KindIndex",
    "is_qualifier",
    "kind_mate",
    "names_sort_of",
    "plain_name",
    "sort_of_catalog_object",
]

#: Catalogs larger than this are not scanned for their kinds just to tell a kind name's hypernym
#: (:meth:`KindIndex.has_kind`).
KIND_SCAN_LIMIT = 20_000


class KindIndex:
    """The kind of every catalog row, and the rows of each kind. Lazy: a row's kind is worked out when
    first asked for (a match shown), the rows of each kind on the first "not in the catalog" answer, so
    building a recaller over a large catalog costs nothing here."""

    def __init__(self, names: Sequence[str], aliases: Sequence[Sequence[str]]):
        self._names = names
        self._aliases = aliases
        self._kinds: dict[int, str | None] = {}
        self._rows: dict[str, list[int]] | None = None
        self._heads: dict[str, frozenset[str]] | None = None
        self._english: dict[str, str] | None = None
        self._words: dict[str, frozenset[str]] | None = None
        self._kind_named: frozenset[str] | None = None

    def kind(self, row: int) -> str | None:
        if row not in self._kinds:
            self._kinds[row] = kind_of_name(self._names[row], self._aliases[row])
        return self._kinds[row]

    def _rows_by_kind(self) -> dict[str, list[int]]:
        if self._rows is None:
            rows: dict[str, list[int]] = {}
            for row in range(len(self._names)):
                own = self.kind(row)
                for k in ancestors(own) if own else ():
                    rows.setdefault(k, []).append(row)
            self._rows = rows
        return self._rows

    def plain_head_kinds(self) -> dict[str, frozenset[str]]:
        """The kinds of the catalog objects with a plain name (:func:`plain_name`), by its head noun, for
        the heads no catalog object names a sort of ("ball" when there is a "soccer ball": none)."""
        if self._heads is None:
            out: dict[str, set[str]] = {}
            sorts: set[str] = set()
            bare: set[str] = set()
            for row in range(len(self._names)):
                own = self.kind(row)
                words = words_of(self._names[row])
                if own and plain_name(words):
                    out.setdefault(words[-1], set()).add(own)
                    if len(words) == 1:
                        bare.add(words[0])
                elif words:
                    sorts.add(words[-1])
            # an object named by the head alone ("cord" beside "power cord") is the catalog's generic one
            self._heads = {h: frozenset(k) for h, k in out.items() if h not in sorts or h in bare}
        return self._heads

    def kind_named(self) -> frozenset[str]:
        """The kinds (``kb/data/kinds.csv``) that a catalog object is called by alone: the Yale objects
        "furniture", "game", "cup", "tube" stand for any thing of their kind."""
        if self._kind_named is None:
            every = kinds()
            self._kind_named = frozenset(
                w[0] for w in (words_of(n) for n in self._names) if len(w) == 1 and w[0] in every
            )
        return self._kind_named

    def words_by_head(self) -> dict[str, frozenset[str]]:
        """The words before the head noun in the catalog's names, by head ("box" -> {"sugar", "cracker",
        ...}); empty on a catalog larger than :data:`KIND_SCAN_LIMIT`."""
        if self._words is None:
            out: dict[str, set[str]] = {}
            if len(self._names) <= KIND_SCAN_LIMIT:
                for name in self._names:
                    words = words_of(name)
                    head = head_noun(words)
                    if len(words) > 1:  # "roll of tape": the head "roll", its words "of" and "tape"
                        out.setdefault(head, set()).update(w for w in words if w != head)
            self._words = {h: frozenset(w) for h, w in out.items()}
        return self._words

    def english_names(self) -> dict[str, str]:
        """The English names of the lexicon nouns heading the catalog objects' names and aliases, each with
        the head noun of that name ("frying pan" -> "skillet")."""
        if self._english is None:
            out: dict[str, str] = {}
            for row in range(len(self._names)):
                for phrase in (self._names[row], *self._aliases[row]):
                    words = words_of(phrase)
                    noun = noun_in(words)
                    if noun is not None and noun.english:
                        out.setdefault(noun.english, words[-1])
            self._english = out
        return self._english

    def has_kind(self, kind: str) -> bool:
        """Whether some catalog object is of ``kind`` or of a kind below it. On a catalog of more than
        :data:`KIND_SCAN_LIMIT` objects, whose kinds are not yet worked out, assumed so (working out every
        row's kind costs ~30 s at a million rows; a large catalog has most kinds)."""
        if self._rows is None and len(self._names) > KIND_SCAN_LIMIT:
            return True
        return bool(self._rows_by_kind().get(kind))

    def rows_of_kind(self, kind: str) -> tuple[str | None, list[int]]:
        """The rows of ``kind`` or of its nearest ancestor that has rows (never the root): (kind used,
        rows); (None, []) when none."""
        self._rows_by_kind()
        for k in ancestors(kind):
            if k == ROOT:
                break
            if self._rows.get(k):
                return k, list(self._rows[k])
        return None, []


def names_sort_of(noun: Noun, english: Sequence[str], heads, kinds_of: KindIndex | None) -> bool:
    """Whether a lexicon synonym is a sort of the catalog's objects of its English name's head noun: that
    head is a catalog head, and either the synonym is itself a word of that head ("puzzle *cube*" ->
    "rubik's cube", "squeeze *bottle*") or the catalog has a plain object of it
    (:meth:`KindIndex.plain_head_kinds`). A synonym of another head ("cola" -> "soda *can*", the seed
    catalog's) names that sort only: a catalog that names its cans by other sorts ("chips can", "tomato
    soup can") does not have it."""
    head = head_noun(english)
    if head is None or head not in heads:
        return False
    return noun.words[-1] == head or kinds_of is None or head in kinds_of.plain_head_kinds()


def kind_mate(noun: Noun, subject: Sequence[str], kinds_of: KindIndex | None) -> str | None:
    """Whether a lexicon noun is a sort of the catalog objects named by its kind's name, with the same
    modifier ("the yellow *sugar carton*": a carton is a box, and the catalog has a "sugar box"): the
    kind's name (a carton's "box"), when it is the head noun of a catalog name that has the word before
    the noun in the subject. Without that modifier ("a carton", "a cereal carton") it names another
    object. Not worked out on catalogs larger than :data:`KIND_SCAN_LIMIT`. Returns the head, or None."""
    if kinds_of is None or len(noun.words) != 1 or len(subject) < 2 or subject[-1] != noun.words[0]:
        return None
    words = kinds_of.words_by_head()
    return noun.kind if subject[-2] in words.get(noun.kind, ()) else None


def sort_of_catalog_object(noun: Noun, heads, kinds_of: KindIndex | None) -> str | None:
    """Whether a lexicon noun the catalog's names do not hold names a sort of an object the catalog holds
    under a plain name (RECALL.md, "Sorts of a catalog object"): a compound or closed compound on the head
    noun of a catalog object named by that noun alone or with qualifiers only (:func:`plain_name`: "timer",
    "small clamp", "spoon") and of the noun's own kind ("kitchen timer", "spring clamp", "tablespoon"), or
    a noun whose English name is a catalog object's ("frying pan" -> the skillet). Where the catalog names
    its objects of that head by their sorts ("soccer ball", "tennis ball"), another sort ("volleyball") is
    another object; a compound of another kind ("egg cup": tableware) is never one. The features still
    decide whether the object is the one described (:func:`recall.fit.judge`, not named), and the engine
    holds it in the catalog only when its best match has that head. Returns the catalog head, or None."""
    if kinds_of is None:
        return None
    english = kinds_of.english_names()
    if english.get(noun.english, noun.words[-1]) != noun.words[-1]:
        return english[noun.english]  # "frying pan": the catalog's "skillet", whose English name it is
    head = noun.words[-1]
    plain = kinds_of.plain_head_kinds()
    bases = [h for h in plain if h != head and len(h) >= 3 and head.endswith(h)]
    if head in plain and len(noun.words) > 1:
        bases.append(head)
    if noun.kind != head and noun.kind in kinds_of.kind_named():
        return noun.kind  # "a side table" where the catalog has an object called "furniture", its kind
    return next((h for h in bases if noun.kind in plain[h]), None)


def plain_name(words: Sequence[str]) -> bool:
    """Whether a name is its head noun alone or after qualifiers only (materials, colours, adjectives:
    "timer", "small clamp", "adjustable wrench"), no noun or gerund naming a sort ("soccer ball",
    "frying pan", "sugar box")."""
    return bool(words) and all(is_qualifier(w) and not w.endswith("ing") for w in words[:-1])


def is_qualifier(word: str) -> bool:
    """Whether a word before a catalog head noun only qualifies it: a material (also a word of a
    multi-word one: "*cast* iron", "*stainless* steel") or colour, or a feature word or adjective that is
    no lexicon noun ("heavy", "non-stick", "pre-seasoned"). A noun ("*egg* cup", "*bottle* warmer") makes
    a compound: another object."""
    if word in material_words() or word in COLOURS or word in SIZE_WORDS:
        return True
    return noun_in([word]) is None and not noun_like(word)
