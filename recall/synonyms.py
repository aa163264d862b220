"""Synonyms of catalog names: other words for the same kind of household object.

``kb/data/synonyms.csv`` (``gloss,nouns``) holds synsets of everyday household nouns, written from general
knowledge (WordNet-style: "trash can; garbage can; wastebasket; dustbin", "allen wrench; allen key; hex
key"), one synset a row, its nouns separated by ";". A catalog that calls an object by one noun of a
synset is named by every other noun of it: :class:`SynonymPhrases` answers the name index's phrase look-ups
(word tuples -> rows) with the catalog's own phrases first, then a synonym of one of them, then the same
words written as one closed compound or split in two ("head band" / "headband", "toilet brushholder" /
"toilet brush holder"). A synset never names two different objects of one catalog (a test checks the
three catalogs of the tests: the seed catalog, YCB, Yale); where it would, the look-up names none. A
two-word compound the table does not hold, "<modifier> <head>", is read in the sense of its head that the
modifier picks (:func:`senses`, :meth:`SynonymPhrases.sense_rows`): "a kitchen flipper" is the spatula's.
Rules and figures: ``recall/RECALL.md`` ("Synonyms").
"""

from __future__ import annotations

import csv
import functools
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from kb.errors import RecallError
from kb.kinds import kinds, nouns, words_of
from recall.words import COLOURS, SIZE_WORDS, head_noun, material_words

__all__ = ["MIN_PART", "Sense", "SynonymPhrases", "senses", "synsets"]

_PATH = Path(__file__).resolve().parent.parent / "kb" / "data" / "synonyms.csv"
#: The shortest part of a closed compound split in two ("head|band", "brush|holder"; not "a|mat").
MIN_PART = 3


@functools.cache
def _rows() -> tuple[tuple[str, frozenset[tuple[str, ...]]], ...]:
    """The rows of ``kb/data/synonyms.csv``: each gloss and the word tuples of its nouns."""
    out = []
    with _PATH.open(encoding="utf-8", newline="") as fh:
        for n, row in enumerate(csv.DictReader(fh), 2):
            members = frozenset(tuple(words_of(x)) for x in (row["nouns"] or "").split(";") if words_of(x))
            if len(members) < 2:
                raise RecallError(f"{_PATH.name} row {n}: a synset needs two nouns or more")
            out.append((row["gloss"] or "", members))
    return tuple(out)


def synsets() -> tuple[frozenset[tuple[str, ...]], ...]:
    """The synsets of ``kb/data/synonyms.csv``, each the word tuples of its nouns (:func:`kb.kinds.words_of`:
    singular, hyphens split). A row with fewer than two distinct nouns is refused."""
    return tuple(members for _, members in _rows())


#: Words of a gloss or a kind's description that tell no sense from another.
_FUNCTION_WORDS = frozenset("a an the of for with and or to in on at by under one other".split())


@dataclass(frozen=True)
class Sense:
    """One sense of a head noun: a synset of ``synonyms.csv`` with a noun on that head (``synset``: its
    index in :func:`synsets`), or the kinds lexicon's noun of that one word (``synset`` None); ``words``:
    the words that say it, less the head and function words (the synset's nouns and the gloss's modifiers
    of their heads, :func:`_gloss_modifiers`; the lexicon noun's English name, kind and kind description)."""

    synset: int | None
    words: frozenset[str]


def _words(texts, head: str) -> frozenset[str]:
    return frozenset(w for t in texts for w in words_of(t)) - _FUNCTION_WORDS - {head}


def _gloss_modifiers(i: int) -> str:
    """The words of synset ``i``'s gloss that modify one of its nouns' heads there ("*kitchen* turner" of
    "a kitchen turner with a flat blade"); the gloss's other words say what else it has or is for ("flat"
    blade, "socket" screws), not which sort of the head it is."""
    gloss, members = _rows()[i]
    heads = {head_noun(m) for m in members}
    words = words_of(gloss)
    return " ".join(w for w, nxt in zip(words, words[1:], strict=False) if nxt in heads and w not in heads)


@functools.cache
def senses() -> dict[str, tuple[Sense, ...]]:
    """Head noun -> its senses (:class:`Sense`), for the heads with two or more: each synset with a noun
    on that head (:func:`recall.words.head_noun`: "*flipper*" of "egg flipper"), and the lexicon's noun
    of that one word unless it or its English name is a noun of one of those synsets (then it is that
    synset's sense: "turner" -> spatula). "flipper": the spatula's synset ("egg flipper", "pancake
    flipper", gloss "a kitchen turner ...") and the lexicon's swim fin (sports equipment)."""
    by_head: dict[str, list[int]] = {}
    for i, (_, members) in enumerate(_rows()):
        for head in dict.fromkeys(head_noun(m) for m in members):
            by_head.setdefault(head, []).append(i)
    table, kind_table = nouns(), kinds()
    out: dict[str, tuple[Sense, ...]] = {}
    for head, found in by_head.items():
        out_senses = [
            Sense(i, _words([_gloss_modifiers(i), *(" ".join(m) for m in _rows()[i][1])], head))
            for i in found
        ]
        noun = table.get((head,))
        if noun is not None and not any(
            (head,) in _rows()[i][1] or tuple(words_of(noun.english)) in _rows()[i][1] for i in found
        ):
            kind = kind_table.get(noun.kind)
            out_senses.append(
                Sense(None, _words([noun.english, noun.kind, kind.description if kind else ""], head))
            )
        if len(out_senses) > 1:
            out[head] = tuple(out_senses)
    return out


def _says_no_sense(word: str) -> bool:
    """A modifier that states a feature (a material, colour or size: "a plastic flipper") is no sense's."""
    return word in _FUNCTION_WORDS or word in COLOURS or word in SIZE_WORDS or word in material_words()


class SynonymPhrases(Mapping):
    """The catalog's phrases (``base``: word tuples -> rows, any of the name index's tables) and their
    synonyms: a synonym maps to the rows of the catalog phrases of its synset, when those are one set of
    rows (a synset that names two different objects of the catalog names none of them)."""

    def __init__(self, base):
        self.base = base
        self.extra: dict[tuple[str, ...], frozenset[int]] = {}
        #: The rows each synset names (by its index in :func:`synsets`), for the synsets that name one object.
        self.synset_rows: dict[int, frozenset[int]] = {}
        for i, synset in enumerate(synsets()):
            named = {frozenset(base[p]) for p in synset if p in base}
            if len(named) != 1:
                continue
            rows = self.synset_rows[i] = next(iter(named))
            for phrase in synset:
                if phrase not in base:
                    self.extra[phrase] = rows
        self.longest = max((len(p) for p in self.extra), default=0)

    def sense_rows(self, words: tuple[str, ...]) -> frozenset[int] | None:
        """The rows a two-word compound the table does not hold names by its head's sense that the
        modifier picks: of the head's :func:`senses`, the one sense whose words have the modifier, when
        that is a synset naming a catalog object ("kitchen flipper": "kitchen" is in the spatula synset's
        gloss, not in the swim fin's words). A modifier in no sense's words, in two senses' words, or
        stating a feature (:func:`_says_no_sense`) leaves the head's default reading: None."""
        if len(words) != 2 or _says_no_sense(words[0]):
            return None
        picked = [s for s in senses().get(words[1], ()) if words[0] in s.words]
        if len(picked) != 1 or picked[0].synset is None:
            return None
        return self.synset_rows.get(picked[0].synset)

    def _key(self, words: tuple[str, ...]) -> tuple[str, ...] | None:
        """The catalog phrase (or synonym) ``words`` stands for: itself, or the same words with two
        neighbours joined ("tooth brush" -> "toothbrush") or one word split in two parts of
        :data:`MIN_PART` letters or more ("headband" -> "head band")."""
        if words in self.base or words in self.extra:
            return words
        for i in range(len(words) - 1):
            joined = (*words[:i], words[i] + words[i + 1], *words[i + 2 :])
            if joined in self.base:
                return joined
        for i, word in enumerate(words):
            for cut in range(MIN_PART, len(word) - MIN_PART + 1):
                split = (*words[:i], word[:cut], word[cut:], *words[i + 1 :])
                if split in self.base:
                    return split
        return None

    def __contains__(self, words) -> bool:
        return isinstance(words, tuple) and (
            self._key(words) is not None or self.sense_rows(words) is not None
        )

    def __getitem__(self, words):
        key = self._key(words) if isinstance(words, tuple) else None
        if key is None:
            rows = self.sense_rows(words) if isinstance(words, tuple) else None
            if rows is None:
                raise KeyError(words)
            return set(rows)
        return self.base[key] if key in self.base else set(self.extra[key])

    def get(self, words, default=None):
        return self[words] if words in self else default

    def __iter__(self) -> Iterator:
        return iter(self.base)

    def __len__(self) -> int:
        return len(self.base)
