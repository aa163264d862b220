"""Vague words as soft evidence: "small", "tiny", "big", "heavy", "light", "weighs almost nothing".

A vague size or weight word states no value, but it does rule out part of the catalog: "something small
and round" is no basketball. Each word is a soft range on the catalog's *own* distribution (quantiles of
the largest extent ``a_cm`` or of ``mass_g`` over the catalog's known values):

=================================================== ========= ============================
words                                               feature   an object is fine when
=================================================== ========= ============================
tiny, minuscule                                     a_cm      a <= 10th percentile
small, little, mini, smallish                       a_cm      a <= 33rd percentile
big, large, bigger                                  a_cm      a >= 67th percentile
huge, giant, enormous                               a_cm      a >= 90th percentile
very light, weighs almost nothing, weighs nothing,  mass_g    m <= 10th percentile
featherweight, feather light
light, lightweight (the parser's mass hint)         mass_g    m <= 33rd percentile
heavy, hefty (the parser's mass hint)               mass_g    m >= 67th percentile
very heavy                                          mass_g    m >= 90th percentile
=================================================== ========= ============================

An object outside its range costs ``VAGUE_WEIGHT · min(1, |ln x − ln q| / ln 2)`` nats (a factor 2
past the quantile costs the whole weight); an unknown value costs half. ``VAGUE_WEIGHT`` = 1.0 nat is
less than one categorical mismatch (2 ln 2 = 1.39): a vague word never outweighs a stated feature. A
word is ignored when the description states the feature itself (a size word when any extent is given,
a weight word when a mass is given).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from kb.features import NUMERIC_FEATURES

__all__ = ["VAGUE_WEIGHT", "SoftEvidence", "soft_evidence"]

#: The most one vague word adds to an object's ranking score, nats (< a category mismatch, 1.39).
VAGUE_WEIGHT = 1.0

#: (pattern, feature, quantile, side): side -1 = the value should be at most the quantile, +1 at least.
_RULES: tuple[tuple[str, str, float, int], ...] = (
    (r"\b(tiny|minuscule|teeny)\b", "a_cm", 0.10, -1),
    (r"\b(small|smallish|little|mini)\b", "a_cm", 0.33, -1),
    (r"\b(big|large|bigger|largish)\b", "a_cm", 0.67, +1),
    (r"\b(huge|giant|enormous|massive)\b", "a_cm", 0.90, +1),
    (r"\b(very|super|extremely) light\b|\bweighs? (almost |next to |practically )?nothing\b"
     r"|\bfeather ?(weight|light)\b", "mass_g", 0.10, -1),
    (r"\b(very|super|extremely) heavy\b", "mass_g", 0.90, +1),
)
_HINTS = {"light": ("mass_g", 0.33, -1), "heavy": ("mass_g", 0.67, +1)}
#: Words that make a size word something else ("a little over 5 cm", "small amount of", "smaller than").
_NOT_SIZE = re.compile(r"\b(a little|little bit|small amount|small part|little one)\b")


@dataclass(frozen=True)
class SoftEvidence:
    """The vague words found (``words``: "small -> a_cm <= 9.8"), and each catalog row's penalty, nats."""

    words: tuple[str, ...]
    penalty: np.ndarray
    #: (feature, limit, side) of each word used: side -1 = at most the limit, +1 = at least.
    limits: tuple[tuple[str, float, int], ...] = ()
    #: Relative errors (0 match, 0.5 half, 1 mismatch) per row of stated categories scored here instead
    #: of by the metric (:mod:`recall.alternatives`): they count in the closeness as stated features.
    errors: tuple[tuple[str, np.ndarray], ...] = ()

    def errors_of(self, row: int) -> dict[str, float]:
        """The relative errors of ``row`` for the categories scored here (see ``errors``)."""
        return {feature: float(err[row]) for feature, err in self.errors}

    def to_dict(self) -> dict[str, object]:
        return {"words": list(self.words), "max_penalty": VAGUE_WEIGHT}


def soft_evidence(
    text: str, stated: Mapping[str, object], mass_hint: str | None, columns: Sequence[np.ndarray]
) -> SoftEvidence | None:
    """The soft evidence of ``text`` over the catalog's numeric ``columns`` (one array per feature of
    :data:`kb.features.NUMERIC_FEATURES`, NaN unknown), or None when there is none. ``stated``: the
    features the description states; ``mass_hint``: the parser's "light"/"heavy"."""
    low = _NOT_SIZE.sub(" ", text.lower())
    found: list[tuple[str, str, float, int]] = []
    for pattern, feature, q, side in _RULES:
        m = re.search(pattern, low)
        if m and not any(f == feature for _, f, _, _ in found):
            found.append((m.group(0), feature, q, side))
    if mass_hint in _HINTS and not any(f == "mass_g" for _, f, _, _ in found):
        found.append((mass_hint, *_HINTS[mass_hint]))
    dims_stated = any(f in stated for f in ("a_cm", "b_cm", "c_cm"))
    found = [
        r for r in found if not (r[1] == "a_cm" and dims_stated) and not (r[1] == "mass_g" and "mass_g" in stated)
    ]
    if not found:
        return None
    penalty = np.zeros(len(columns[0]))
    words = []
    limits = []
    for word, feature, q, side in found:
        col = np.asarray(columns[NUMERIC_FEATURES.index(feature)], dtype=np.float64)
        known = np.isfinite(col) & (col > 0)
        if not known.any():
            continue
        limit = float(np.quantile(col[known], q))
        excess = np.zeros_like(col)
        excess[known] = np.maximum(0.0, side * (math.log(limit) - np.log(col[known])))
        part = VAGUE_WEIGHT * np.minimum(1.0, excess / math.log(2.0))
        part[~known] = VAGUE_WEIGHT / 2
        penalty += part
        unit = "cm" if feature == "a_cm" else "g"
        words.append(f"{word} -> {feature} {'<=' if side < 0 else '>='} {limit:.3g} {unit}")
        limits.append((feature, limit, side))
    return SoftEvidence(tuple(words), penalty, tuple(limits)) if words else None
