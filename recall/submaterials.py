"""Finer materials than the catalog's categories, read from object names: "ceramic" is no "wax".

The catalog's material category ``other`` lumps ceramic, stone, wax, leather, foam, soap and chalk, so a
stated "ceramic" matches a wax candle as well as a ceramic mug. Many catalog names say the finer
material ("ceramic mug", "wax candle", "leather wallet", "clay brick"). When a description states one of
these materials, a catalog object filed under ``other`` whose names say *another* of them pays a category
mismatch (``2 ln 2``, :data:`recall.metrics.MISMATCH_TERM`), as the category would if it were finer;
an object whose names say none pays nothing (unknown is not evidence). Objects of the other categories
already pay the mismatch of their category. Measured in ``recall/RECALL.md``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from kb.kinds import words_of
from recall.metrics import MISMATCH_TERM
from recall.vague import SoftEvidence

__all__ = ["SUBMATERIALS", "SubmaterialIndex", "submaterial_of", "with_submaterial"]

#: Finer material -> the words that state it (all filed under the catalog's ``other``).
SUBMATERIALS: dict[str, frozenset[str]] = {
    "ceramic": frozenset({"ceramic", "ceramics", "porcelain", "stoneware", "earthenware", "terracotta", "clay"}),
    "stone": frozenset({"stone", "marble", "granite", "concrete", "rock", "pebble"}),
    "wax": frozenset({"wax", "candle", "paraffin"}),
    "leather": frozenset({"leather", "leathery"}),
    "foam": frozenset({"foam", "sponge"}),
    "soap": frozenset({"soap"}),
    "chalk": frozenset({"chalk"}),
}
_WORD_TO_SUB = {w: sub for sub, words in SUBMATERIALS.items() for w in words}


def submaterial_of(words: Sequence[str]) -> str | None:
    """The finer material the first word of ``words`` that states one names, or None."""
    for w in words:
        if w in _WORD_TO_SUB:
            return _WORD_TO_SUB[w]
    return None


class SubmaterialIndex:
    """The finer material of each catalog row filed under ``other`` (from its names and aliases), worked
    out on first use."""

    def __init__(self, names: Sequence[str], aliases: Sequence[Sequence[str]], is_other: np.ndarray):
        self._names, self._aliases, self._is_other = names, aliases, np.asarray(is_other, dtype=bool)
        self._codes: np.ndarray | None = None

    def _rows(self) -> np.ndarray:
        if self._codes is None:
            order = list(SUBMATERIALS)
            codes = np.full(len(self._names), -1, dtype=np.int8)
            for row in np.flatnonzero(self._is_other).tolist():
                words = [w for name in (self._names[row], *self._aliases[row]) for w in words_of(name)]
                sub = submaterial_of(words)
                codes[row] = order.index(sub) if sub is not None else -1
            self._codes = codes
        return self._codes

    def penalty(self, stated_words: str) -> tuple[str, np.ndarray] | None:
        """("ceramic -> not wax, stone, ...", per-row penalty) for the material text a description states
        (the parser's evidence words), or None when it states no finer material."""
        sub = submaterial_of(words_of(stated_words))
        if sub is None:
            return None
        codes = self._rows()
        own = list(SUBMATERIALS).index(sub)
        penalty = np.where((codes >= 0) & (codes != own), MISMATCH_TERM, 0.0)
        return f"{sub} (finer material, from names)", penalty


def with_submaterial(soft: SoftEvidence | None, sub: tuple[str, np.ndarray] | None) -> SoftEvidence | None:
    """The vague words' soft evidence plus the finer-material evidence of :meth:`SubmaterialIndex.penalty`."""
    if sub is None:
        return soft
    word, penalty = sub
    if soft is None:
        return SoftEvidence((word,), penalty)
    return dataclasses.replace(soft, words=(*soft.words, word), penalty=soft.penalty + penalty)
