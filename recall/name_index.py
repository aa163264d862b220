"""Names in a description: which catalog objects it names, and how much that says.

:class:`NameIndex` holds the catalog's names and aliases as word n-grams and head nouns (tables built
column-wise by :mod:`recall.names`); :meth:`NameIndex.find` returns the :class:`NameEvidence` of a
text: the rows named by a whole name or alias and by a head noun only, each with the information of the
naming in nats (ln(N / m)). The hybrid ranking subtracts :meth:`NameEvidence.bonus` from a named row's
distance. Rules and weights: ``recall/RECALL.md``, "The hybrid".
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field

from kb.kinds import noun_in, singular, words_of
from recall.compounds import COMPOUND_CHECK_LIMIT, compound_agrees, modifier_noun
from recall.names import GENERIC_NOUNS, MIN_SUFFIX, name_words, rows_with_word
from recall.subject import (
    adjective_feature_words,
    counted_head,
    feature_words,
    is_participle,
    negated_spans,
    subject_phrase,
)
from recall.synonyms import SynonymPhrases

__all__ = ["HEAD_WEIGHT", "NAME_WEIGHT", "NameEvidence", "NameIndex"]

#: Hybrid: a name or alias in the text that names m of the catalog's N objects lowers each of their JP
#: distances by NAME_WEIGHT * ln(N / m) nats (multiplies the joint probability by (N / m)^NAME_WEIGHT);
#: a head noun only ("ball" -> every ball) by HEAD_WEIGHT * ln(N / m). Feature distance still ranks the
#: named candidates among themselves, and a named object whose features are far off can still lose.
NAME_WEIGHT = 0.6
HEAD_WEIGHT = 0.4

#: A name followed by one of these words only describes the object ("lemon-shaped", "pen-like").
#: ("die-cast": made in a die, not a die).
_AFTER_COMPARISON = frozenset(
    {"like", "shaped", "shape", "style", "type", "sized", "size", "looking", "cast"}
)
#: ... or preceded by these within two words ("like a pen", "the size of a tennis ball", "as big as").
_BEFORE_COMPARISON = frozenset({"like", "as", "than", "resemble", "resembling", "similar"})


def _comparison(words: list[str], start: int, end: int) -> bool:
    """Whether the name at words[start:end] is a comparison, not the object itself."""
    if end < len(words) and words[end] in _AFTER_COMPARISON:
        return True
    before = words[max(0, start - 3) : start]
    if any(w in _BEFORE_COMPARISON for w in before):
        return True
    return (
        len(before) >= 2 and before[-2:] in (["size", "of"], ["size", "a"]) or before[-3:-1] == ["size", "of"]
    )


#: A phrase after "with" says what an object has ("a garbage bin *with lid*", "a caddy *with a handle*",
#: "a mug with a handle"): its head nouns name parts and accessories, not the object described. It runs to
#: punctuation; a text that starts with it ("with a handle, 30 cm") has no other phrase to
#: name the object, so it keeps its heads.
_WITH_PHRASE = re.compile(r"(?<=\S)(\s+with\b[^,.;:()]*)", re.IGNORECASE)


def _without_with_phrases(text: str) -> str:
    """``text`` with the phrases after "with" (:data:`_WITH_PHRASE`) blanked, character for character."""
    return _WITH_PHRASE.sub(lambda m: " " * len(m.group()), text)


#: The words between a container and what it holds or is for: "a box *of* tissues", "a caddy *for* cleaning
#: supplies", "a brush *for* bottles" say the compounds "tissue box", "cleaning supplies caddy", "bottle brush".
_CONTENTS_WORDS = frozenset({"of", "for"})
#: How many words after "of" may hold the contents of "<head> of <contents>" (``NameIndex._contents_names``).
CONTENTS_WINDOW = 4


@dataclass(frozen=True)
class NameEvidence:
    """Catalog rows a description names and the information of the naming, in nats: a phrase that names
    m of the N catalog objects carries ln(N / m). ``exact``: by a whole name or alias (the longest
    matches); ``head``: by the head noun of a name or alias only ("a plastic ball" -> every ball,
    "spoon" -> teaspoon)."""

    exact: dict[int, float] = field(default_factory=dict)
    head: dict[int, float] = field(default_factory=dict)
    phrases: tuple[str, ...] = ()
    heads: tuple[str, ...] = ()
    #: The subject's head noun when the catalog does not know it (:meth:`NameIndex.unknown_noun`).
    unknown_noun: str | None = None
    #: The rows of the catalog head the described noun is a sort of (``DescribedNoun.sort_of``: "a
    #: hacksaw" -> every "saw"), with the information of that head: ranked as a head noun is, yet no name
    #: of the object (the verdict does not trust it as named).
    sorts: dict[int, float] = field(default_factory=dict)

    def rows(self) -> list[int]:
        return sorted(set(self.exact) | set(self.head) | set(self.sorts))

    def bonus(self, row: int) -> float:
        """Nats subtracted from the row's JP distance (see RECALL.md)."""
        named = max(NAME_WEIGHT * self.exact.get(row, 0.0), HEAD_WEIGHT * self.head.get(row, 0.0))
        return max(named, HEAD_WEIGHT * self.sorts.get(row, 0.0)) if self.sorts else named


class NameIndex:
    """Catalog names and aliases as word n-grams and head nouns, for finding the objects a description
    names."""

    #: Shortest head noun matched as the end of a compound ("spoon" in "teaspoon").
    MIN_SUFFIX = MIN_SUFFIX

    def __init__(
        self,
        names: Sequence[str],
        aliases: Sequence[Sequence[str]],
        materials: Sequence[str | None] | None = None,
        tables=None,
    ):
        from recall.lexicon import MATERIAL_WORDS
        from recall.name_tables import name_tables

        # built column-wise (recall.name_tables; or read back by recall.stored_index): phrases (words and core
        # of every name and alias) -> rows; generic names ("wood piece", "wooden block": only material
        # words and generic nouns) -> their material, describing any object of it (rows by material);
        # head nouns and their suffixes -> rows, and (head, row) -> the materials its names state
        # ("wood cylinder" -> wood; None: some name states none)
        if tables is None:
            tables = name_tables(names, aliases, materials, self.MIN_SUFFIX)
        # the catalog's phrases, answered also for their synonyms and closed-compound spellings
        self.phrases = SynonymPhrases(tables.phrases)
        self.generic = tables.generic
        self.by_material = tables.by_material
        self.heads = tables.heads
        self.head_materials = tables.head_materials
        # material words name what a thing is made of, not the thing ("made of glass")
        self.not_heads = frozenset(singular(w) for w in MATERIAL_WORDS if " " not in w)
        self.vocabulary = tables.vocabulary | frozenset(p[-1] for p in self.phrases.extra)  # synonyms' heads
        # one word more: a name said with a closed compound split ("toilet brush holder")
        self.longest = max(tables.longest + 1, self.phrases.longest)
        self.size = len(names)
        self._names, self._aliases = names, aliases  # names_of: compounds, contents

    def names_of(self, row: int) -> tuple[str, ...]:
        """The row's name and its aliases."""
        return (self._names[row], *self._aliases[row])

    def unknown_noun(self, text: str) -> str | None:
        """The head noun of the description's subject (:func:`subject_head`) when the catalog does not know
        it: in no name or alias, not a feature word of the parser's lexicon (materials, shapes, units,
        ...; a colour word counts only when the lexicon has it as a noun: "an orange", not "red, round,
        7.5 cm across"), not a generic noun (:data:`GENERIC_NOUNS`)."""
        phrase = subject_phrase(text)
        head = phrase[-1] if phrase else None
        if (
            len(phrase) > 1
            and phrase[-2] in self.heads
            and phrase[-2] not in GENERIC_NOUNS
            and phrase[-2] not in self.not_heads
        ):
            return None  # a compound on a known noun: "remote control" (tv remote), "bottle cap"
        if head is None or head in self.vocabulary or head in GENERIC_NOUNS or is_participle(head):
            return None
        if (head,) in self.phrases:  # a catalog name written as one word ("headband" for "head band")
            return None
        if head in feature_words() or _colour_only(head):
            return None
        return head

    def find(
        self, text: str, skip_spans: Sequence[tuple[int, int]] = (), material: str | None = None
    ) -> NameEvidence:
        """The rows named in ``text``.

        Characters in ``skip_spans`` (the parser's numeric evidence, so "seven and quarter centimeters"
        never names the US quarter) and in negated noun phrases ("not a mug": ``subject.negated_spans``)
        are ignored, and so are comparisons ("lemon-shaped", "like a pen",
        "the size of a tennis ball"). Exact matches inside a longer match are dropped, then the longest
        remaining phrases win. A head noun does not name an object whose names all state another
        material than the description's ``material`` ("a metal cylinder" is no "wood cylinder").
        """
        chars = list(text)
        for start, end in (*skip_spans, *negated_spans(text)):  # and "not a mug": no name
            for i in range(max(0, start), min(len(chars), end)):
                chars[i] = " "
        words = words_of("".join(chars))
        exact: dict[int, float] = {}
        head: dict[int, float] = {}
        phrases = self._whole_names(words, exact, head)
        phrases += [p for p in self._contents_names(words, exact) if p not in phrases]
        heads = self._head_nouns(words_of(_without_with_phrases("".join(chars))), material, head, counted_head(text))
        if not phrases and not heads:
            heads = self._name_words(list(subject_phrase(text)[-1:]), head)  # the subject's head only
        return NameEvidence(
            exact,
            head,
            tuple(dict.fromkeys(phrases)),
            tuple(dict.fromkeys(heads)),
            self.unknown_noun(text),
        )

    def _whole_names(self, words: list[str], exact: dict[int, float], head: dict[int, float]) -> list[str]:
        """Record in ``exact`` (``head`` for generic names) the rows the longest whole names or aliases in
        ``words`` name, with their information; returns those phrases (generic ones left out)."""
        found: list[tuple[int, int, tuple[str, ...]]] = []
        for n in range(min(self.longest, len(words)), 0, -1):
            for i in range(len(words) - n + 1):
                gram = tuple(words[i : i + n])
                if gram not in self.phrases or any(s <= i and i + n <= e for s, e, _ in found):
                    continue
                if _comparison(words, i, i + n):
                    continue
                found.append((i, i + n, gram))
        n = max(self.size, 1)
        phrases: list[str] = []
        if found:
            best = max(e - s for s, e, _ in found)
            for s, e, gram in found:
                if e - s == best and gram in self.generic:
                    # "a wood piece" names no one object: weak evidence for every object of its material
                    rows = self.phrases[gram] | self.by_material.get(self.generic[gram], set())
                    for row in rows:
                        head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
                elif e - s == best:
                    rows = self.phrases[gram]
                    for row in rows:
                        exact[row] = max(exact.get(row, 0.0), math.log(n / len(rows)))
                    phrases.append(" ".join(gram))
        return phrases

    def _contents_names(self, words: list[str], exact: dict[int, float]) -> list[str]:
        """Record in ``exact`` the rows of the catalog names "<contents> <head>" that the text says as
        "<head> of <contents>" ("squeeze bottle of mustard" -> "mustard bottle", "a can of Campbell's tomato
        soup" -> "tomato soup can"; "for" alike: :data:`_CONTENTS_WORDS`): one or two words of the
        :data:`CONTENTS_WINDOW` words after "of", then the word before it; returns the names found."""
        n = max(self.size, 1)
        found: list[str] = []
        for i, word in enumerate(words):
            if word not in _CONTENTS_WORDS or i == 0:
                continue
            window = words[i + 1 : i + 1 + CONTENTS_WINDOW]
            grams = [(*window[j : j + k], words[i - 1]) for k in (2, 1) for j in range(len(window) - k + 1)]
            for gram in grams:
                if gram in self.phrases and " ".join(gram) not in found:
                    rows = self.phrases[gram]
                    for row in rows:
                        exact[row] = max(exact.get(row, 0.0), math.log(n / len(rows)))
                    found.append(" ".join(gram))
        return found

    def _name_words(self, words: list[str], head: dict[int, float]) -> list[str]:
        """When no whole name or head noun is found: record in ``head`` the rows whose names have the
        subject's head noun (``words``) when only a catalog name knows it ("a wasserkocher", "a sartén":
        :func:`recall.names.name_words`); returns the words found."""
        n = max(self.size, 1)
        found: list[str] = []
        for word in name_words(words, self.vocabulary):
            rows = rows_with_word(self.phrases.base, word)
            for row in rows:
                head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
            if rows:
                found.append(word)
        return found

    def _head_nouns(
        self, words: list[str], material: str | None, head: dict[int, float], counted: str | None = None
    ) -> list[str]:
        """Record in ``head`` the rows a head noun in ``words`` names (not those whose names all state
        another material than ``material``, nor those that are another compound: "a wedding ring" is no
        "key ring", :mod:`recall.compounds`); returns the head nouns found. A material word is no head
        noun unless an article counts it as the subject (``counted``: "a glass")."""
        n = max(self.size, 1)
        heads: list[str] = []
        for i, word in enumerate(words):
            material_word = word in self.not_heads and word != counted
            if word in self.heads and not material_word and not _comparison(words, i, i + 1):
                if word in adjective_feature_words() and (word,) not in self.phrases:
                    continue  # a feature word ("light", "heavy") is no head noun ("tea light")
                rows = self._same_compound(words, i, self.heads[word])
                if not rows:
                    continue
                for row in rows:
                    implied = self.head_materials.get((word, row))
                    if material is not None and implied and material not in implied:
                        continue
                    head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
                heads.append(word)
        return heads

    def _same_compound(self, words: list[str], i: int, rows: set[int]) -> set[int]:
        """The rows the head ``words[i]`` names given the noun modifier before it (all of them without one,
        or above :data:`recall.compounds.COMPOUND_CHECK_LIMIT` rows)."""
        modifier = modifier_noun(words, i)
        if modifier is None or len(rows) > COMPOUND_CHECK_LIMIT:
            return rows
        return {r for r in rows if compound_agrees(modifier, words[i], self.names_of(r))}


def _colour_only(word: str) -> bool:
    """Whether ``word`` is a colour and nothing else: no lexicon noun ("red", "purple"; "orange", "plum"
    and "lime" are fruit). A subject of colour words alone is a list of adjectives, not an object."""
    from recall.lexicon import COLOUR_WORDS
    from recall.words import COLOURS

    return (word in COLOURS or word in COLOUR_WORDS) and noun_in([word]) is None
