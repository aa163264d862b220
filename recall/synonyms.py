"""Synonyms of catalog names: other words for the same kind of household object.

``kb/data/synonyms.csv`` (``gloss,nouns``) holds synsets of everyday household nouns, written from general
knowledge (WordNet-style: "trash can; garbage can; wastebasket; dustbin", "allen wrench; allen key; hex
key"), one synset a row, its nouns separated by ";". A catalog that calls an object by one noun of a
synset is named by every other noun of it: :class:`SynonymPhrases` answers the name index's phrase look-ups
(word tuples -> rows) with the catalog's own phrases first, then a synonym of one of them, then the same
words written as one closed compound or split in two ("head band" / "headband", "toilet brushholder" /
"toilet brush holder"). A synset never names two different objects of one catalog (a test checks the
three catalogs of the tests: the seed catalog, YCB, Yale); where it would, the look-up names none.
Rules and figures: ``recall/RECALL.md`` ("Synonyms").
"""

from __future__ import annotations

import csv
import functools
from collections.abc import Iterator, Mapping
from pathlib import Path

from kb.errors import RecallError
from kb.kinds import words_of

__all__ = ["MIN_PART", "SynonymPhrases", "synsets"]

_PATH = Path(__file__).resolve().parent.parent / "kb" / "data" / "synonyms.csv"
#: The shortest part of a closed compound split in two ("head|band", "brush|holder"; not "a|mat").
MIN_PART = 3


@functools.cache
def synsets() -> tuple[frozenset[tuple[str, ...]], ...]:
    """The synsets of ``kb/data/synonyms.csv``, each the word tuples of its nouns (:func:`kb.kinds.words_of`:
    singular, hyphens split). A row with fewer than two distinct nouns is refused."""
    out = []
    with _PATH.open(encoding="utf-8", newline="") as fh:
        for n, row in enumerate(csv.DictReader(fh), 2):
            nouns = frozenset(tuple(words_of(x)) for x in (row["nouns"] or "").split(";") if words_of(x))
            if len(nouns) < 2:
                raise RecallError(f"{_PATH.name} row {n}: a synset needs two nouns or more")
            out.append(nouns)
    return tuple(out)


class SynonymPhrases(Mapping):
    """The catalog's phrases (``base``: word tuples -> rows, any of the name index's tables) and their
    synonyms: a synonym maps to the rows of the catalog phrases of its synset, when those are one set of
    rows (a synset that names two different objects of the catalog names none of them)."""

    def __init__(self, base):
        self.base = base
        self.extra: dict[tuple[str, ...], frozenset[int]] = {}
        for synset in synsets():
            named = {frozenset(base[p]) for p in synset if p in base}
            if len(named) != 1:
                continue
            rows = next(iter(named))
            for phrase in synset:
                if phrase not in base:
                    self.extra[phrase] = rows
        self.longest = max((len(p) for p in self.extra), default=0)

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
        return isinstance(words, tuple) and self._key(words) is not None

    def __getitem__(self, words):
        key = self._key(words) if isinstance(words, tuple) else None
        if key is None:
            raise KeyError(words)
        return self.base[key] if key in self.base else set(self.extra[key])

    def get(self, words, default=None):
        return self[words] if words in self else default

    def __iter__(self) -> Iterator:
        return iter(self.base)

    def __len__(self) -> int:
        return len(self.base)
