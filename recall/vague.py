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
very light, weighs almost nothing, weighs nothing,  mass_g    m <= 33rd percentile of the
featherweight, feather light                                  objects of its size (*)
light, lightweight (the parser's mass hint)         mass_g    the same (*)
heavy, hefty (the parser's mass hint)               mass_g    m >= 67th percentile
very heavy                                          mass_g    m >= 90th percentile
=================================================== ========= ============================

(*) Light words are relative to size: a person holding a 19 cm plastic banana of 66 g calls it "very
light" (40th percentile of the whole catalog, 22nd among the objects of its size). The quantile is taken
over the catalog objects whose largest extent is within a factor 1.5 of the row's own (at least 10 of
them, else the whole catalog's). The development sets' "very light" and "weighs almost nothing" objects
sit at the 0–31st percentile of their size (11 of 12; of the whole catalog at the 1st–40th), and their
"light" ones at the 16th–20th: the sets do not tell "very light" from "light" apart, so both use the
33rd. Heavy words stay on the whole catalog.

An object outside its range costs ``VAGUE_WEIGHT · min(1, |ln x − ln q| / ln 2)`` nats (a factor 2
past the quantile costs the whole weight); an unknown value costs half. ``VAGUE_WEIGHT`` = 1.0 nat is
less than one categorical mismatch (2 ln 2 = 1.39): a vague word never outweighs a stated feature. A
word is ignored when the description states the feature itself (a size word when any extent is given,
a weight word when a mass is given).
"""

from __future__ import annotations

import math
import re
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from kb.features import NUMERIC_FEATURES

__all__ = ["VAGUE_WEIGHT", "SoftEvidence", "soft_evidence"]

#: The most one vague word adds to an object's ranking score, nats (< a category mismatch, 1.39).
VAGUE_WEIGHT = 1.0

#: Light words are judged against the objects of a row's own size (:func:`_limits_for_size`): a 66 g plastic
#: banana is "very light" for 19 cm, a 30 g die would not be. Measured in RECALL.md.
SIZE_RELATIVE_MASS = True
#: Quantiles of the light words among the objects of a size (very light: the development sets' "very
#: light" / "weighs almost nothing" objects sit at the 0-31st such percentile, 11 of 12).
VERY_LIGHT_Q = 0.33
LIGHT_Q = 0.33
#: Objects whose largest extent is within this factor of a row's are "of its size" (:func:`_limits_for_size`).
SIZE_FACTOR = 1.5
#: Fewer objects of a size than this: the whole catalog's quantile.
MIN_OF_SIZE = 10

#: (pattern, feature, quantile, side): side -1 = the value should be at most the quantile, +1 at least.
_RULES: tuple[tuple[str, str, float, int], ...] = (
    (r"\b(tiny|minuscule|teeny)\b", "a_cm", 0.10, -1),
    (r"\b(small|smallish|little|mini)\b", "a_cm", 0.33, -1),
    (r"\b(big|large|bigger|largish)\b", "a_cm", 0.67, +1),
    (r"\b(huge|giant|enormous|massive)\b", "a_cm", 0.90, +1),
    (
        r"\b(very|super|extremely) light\b|\bweighs? (almost |next to |practically )?nothing\b"
        r"|\bfeather ?(weight|light)\b",
        "mass_g",
        VERY_LIGHT_Q,
        -1,
    ),
    (r"\b(very|super|extremely) heavy\b", "mass_g", 0.90, +1),
)
_HINTS = {"light": ("mass_g", LIGHT_Q, -1), "heavy": ("mass_g", 0.67, +1)}
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
    #: Whether the ranking must score every row (vague words can reorder the whole catalog). False for
    #: category alternatives only (:mod:`recall.alternatives`): then the union of the pruned top-k of
    #: each of ``variants`` (the query with each allowed class stated) holds the answer.
    scan: bool = True
    variants: tuple = ()

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
        r
        for r in found
        if not (r[1] == "a_cm" and dims_stated) and not (r[1] == "mass_g" and "mass_g" in stated)
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
        row_limits = np.full(len(col), limit)
        if feature == "mass_g" and side < 0 and SIZE_RELATIVE_MASS:
            row_limits = _cached_limits(columns, q, limit)
        excess = np.zeros_like(col)
        excess[known] = np.maximum(0.0, side * (np.log(row_limits[known]) - np.log(col[known])))
        part = VAGUE_WEIGHT * np.minimum(1.0, excess / math.log(2.0))
        part[~known] = VAGUE_WEIGHT / 2
        penalty += part
        unit = "cm" if feature == "a_cm" else "g"
        bound = f"{'<=' if side < 0 else '>='} {limit:.3g} {unit}"
        if feature == "mass_g" and side < 0 and SIZE_RELATIVE_MASS:
            bound = (
                f"in the lightest {round(100 * q)} % of objects of its size (<= {limit:.3g} {unit} overall)"
            )
        words.append(f"{word} -> {feature} {bound}")
        limits.append((feature, limit, side))
    return SoftEvidence(tuple(words), penalty, tuple(limits)) if words else None


#: The per-row limits of the last few catalogs (their columns, kept by weak reference, and q): the same
#: snapshot's columns give the same limits, so a catalog of a million rows bins them once, not per query.
_LIMITS_CACHE: dict[tuple[int, int, float], tuple[weakref.ref, weakref.ref, np.ndarray]] = {}


def _cached_limits(columns: Sequence[np.ndarray], q: float, overall: float) -> np.ndarray:
    """:func:`_limits_for_size` of ``columns`` (a_cm first, mass_g last), cached per column objects."""
    a_col, m_col = columns[0], columns[NUMERIC_FEATURES.index("mass_g")]
    key = (id(a_col), id(m_col), q)
    hit = _LIMITS_CACHE.get(key)
    if hit is not None and hit[0]() is a_col and hit[1]() is m_col:
        return hit[2]
    out = _limits_for_size(
        np.asarray(m_col, dtype=np.float64), np.asarray(a_col, dtype=np.float64), q, overall
    )
    try:
        refs = (weakref.ref(a_col), weakref.ref(m_col))
    except TypeError:  # a plain list: not cached
        return out
    if len(_LIMITS_CACHE) >= 8:
        _LIMITS_CACHE.clear()
    _LIMITS_CACHE[key] = (*refs, out)
    return out


def _limits_for_size(mass: np.ndarray, a: np.ndarray, q: float, overall: float) -> np.ndarray:
    """The ``q`` quantile of the mass of the catalog objects of each row's size (largest extent within a
    factor :data:`SIZE_FACTOR`), per row; ``overall`` where the row's size is unknown or fewer than
    :data:`MIN_OF_SIZE` objects have it. Binned in log size (bins of a quarter of the factor's log, the
    window ±4 bins), so it costs one sort per bin, not per row."""
    out = np.full(len(mass), overall)
    ok = np.isfinite(mass) & (mass > 0) & np.isfinite(a) & (a > 0)
    if not ok.any():
        return out
    width = math.log(SIZE_FACTOR) / 4
    bins = np.floor(np.log(a[ok]) / width).astype(np.int64)
    lo = int(bins.min())
    counts = np.bincount(bins - lo)
    order = np.argsort(bins, kind="stable")
    m_sorted = mass[ok][order]
    starts = np.concatenate(([0], np.cumsum(counts)))
    per_bin = np.full(len(counts), overall)
    for b in range(len(counts)):
        if counts[b] == 0:
            continue
        window = m_sorted[starts[max(0, b - 4)] : starts[min(len(counts), b + 5)]]
        if len(window) >= MIN_OF_SIZE:
            per_bin[b] = float(np.quantile(window, q))
    row_bins = np.floor(np.log(np.where(np.isfinite(a) & (a > 0), a, 1.0)) / width).astype(np.int64) - lo
    inside = np.isfinite(a) & (a > 0) & (row_bins >= 0) & (row_bins < len(counts))
    out[inside] = per_bin[row_bins[inside]]
    return out
