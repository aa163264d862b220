"""Category words that allow more than one class: ambiguous shape words, mixed materials, finish words.

The paper's JP charges a category mismatch ``2 ln 2`` and a match 0, so a word must name one class. Two
kinds of words do not (hybrid only; the paper's JP, features only, keeps the stated class as it is):

* **Ambiguous shape words.** People call a padlock a "metal block", a coin a "flat disc", a dowel a
  "wooden cylinder" or a "stick", while the catalog files objects by geometry (``compact``, ``thin``,
  ``long``, ``prism``). A word of :data:`SHAPE_ALTERNATIVES` names other classes that the word's own
  development uses often meant (together at least 20 % of 4 or more uses, counted in ``recall/RECALL.md``): an
  object of that class pays half a mismatch (``ln 2``, as an unknown category) instead of a whole one.
  Unambiguous words ("ball", "cube", "bottle": 94–100 % one class) keep the whole mismatch, and the
  geometry of three stated extents still replaces the word (:mod:`recall.geometry`).
* **Mixed materials.** "Plastic and metal", "glass and metal", "steel and wood": the parser keeps one
  material, and the object filed under the other paid a whole mismatch. Two material words joined by
  and / & / or / "/" make either material a match.
* **Finish words.** A metal whose name is also a colour and a plated or painted finish
  (:data:`FINISH_WORDS`: "a *copper* lamp shade" of polycarbonate with a metalised copper finish, a
  *chrome* lamp or tap of chromed plastic, a *silver* laptop or phone of plastic, *bronze*- and
  *brass*-effect fittings) may say the look, not the material: when every material word of the text is
  one, the metal is a match and any other material half a mismatch (as an unknown material).

Either way the stated category leaves the JP query and becomes soft evidence over every row (shown in
the vague column): 0 for an allowed class, ``ln 2`` for a shape's second class or an unknown value,
``2 ln 2`` otherwise: the same numbers as the JP terms, so nothing else moves.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Sequence

import numpy as np

from kb.features import CATEGORICAL_FEATURES, CATEGORIES
from recall.lexicon import MATERIAL_WORDS, SHAPE_WORDS
from recall.metrics import LN2, MISMATCH_TERM, FeatureQuery
from recall.vague import SoftEvidence

__all__ = [
    "FINISH_WORDS", "SHAPE_ALTERNATIVES", "Alternatives", "alternatives", "finish_word", "mixed_materials",
    "with_alternatives",
]  # fmt: skip

#: Shape word -> the other classes it often means (development counts in RECALL.md, "Words that allow
#: two classes"); the first class is the lexicon's (:data:`recall.lexicon.SHAPE_WORDS`).
SHAPE_ALTERNATIVES: dict[str, tuple[str, ...]] = {
    "block": ("compact",), "brick": ("compact",), "flat": ("compact",), "round": ("compact", "prism"),
    "cylinder": ("long",), "cylindrical": ("long",), "tube": ("long",),
    "stick": ("prism",), "disc": ("thin",),
}  # fmt: skip
#: The cost of a shape word's second class: half a mismatch (an unknown category's term).
SECOND_CLASS_TERM = LN2
#: Material words that are also the names of a colour and of a finish over another material.
FINISH_WORDS = frozenset({"copper", "brass", "bronze", "chrome", "silver"})

_MATERIAL = "|".join(sorted((re.escape(w) for w in MATERIAL_WORDS if " " not in w), key=len, reverse=True))
_MIXED = re.compile(rf"\b({_MATERIAL})\s*(?:and/or|and|&|or|/)\s*({_MATERIAL})\b")


@dataclasses.dataclass(frozen=True)
class Alternatives:
    """The categories read as alternatives: feature -> (classes at 0, classes at ``ln 2``), and the words."""

    allowed: dict[str, tuple[frozenset[str], frozenset[str]]]
    words: tuple[str, ...]

    def variants(self, query: FeatureQuery) -> tuple[FeatureQuery, ...]:
        """``query`` with each combination of the allowed classes stated. The soft score of a row is the
        JP distance of the variant of its own class (plus ln 2 for a shape's second class), and never more
        than that of any variant, so the rows ranking first under the soft score are among the union of
        each variant's first rows: the engine searches those (pruned) instead of scanning the catalog."""
        rest = tuple((f, v) for f, v in query.categorical if f not in self.allowed)
        combos: list[tuple[tuple[str, str], ...]] = [()]
        for feature, (full, half) in self.allowed.items():
            combos = [(*c, (feature, v)) for c in combos for v in sorted(full | half)]
        return tuple(FeatureQuery(query.numeric, (*rest, *c)) for c in combos)

    def terms(self, cat_cols: Sequence[np.ndarray]) -> dict[str, np.ndarray]:
        """Each feature's soft term per catalog row, nats (the category codes of ``cat_cols``, -1 unknown)."""
        out = {}
        for feature, (full, half) in self.allowed.items():
            codes = np.asarray(cat_cols[CATEGORICAL_FEATURES.index(feature)])
            names = CATEGORIES[feature]
            term = np.full(len(codes), MISMATCH_TERM)
            term[np.isin(codes, [names.index(v) for v in half])] = SECOND_CLASS_TERM
            term[np.isin(codes, [names.index(v) for v in full])] = 0.0
            term[codes < 0] = LN2
            out[feature] = term
        return out


def finish_word(parsed) -> str | None:
    """The finish word (:data:`FINISH_WORDS`) the material of ``parsed`` (a parser result) is stated by,
    when every material word of its text is one ("a copper lamp shade"; not "chrome steel"), else None."""
    evidence = parsed.features.get("material")
    word = (evidence.words or "").lower() if evidence is not None else ""
    if word not in FINISH_WORDS:
        return None
    said = [w for w in re.findall(r"[^\W_]+(?:-[^\W_]+)*", parsed.text.lower()) if w in MATERIAL_WORDS]
    return word if all(w in FINISH_WORDS for w in said) else None


def mixed_materials(text: str) -> frozenset[str] | None:
    """The two material classes of "plastic and metal" (two different classes), else None."""
    for m in _MIXED.finditer(text.lower()):
        pair = frozenset((MATERIAL_WORDS[m.group(1)], MATERIAL_WORDS[m.group(2)]))
        if len(pair) == 2:
            return pair
    return None


def alternatives(query: FeatureQuery, parsed) -> Alternatives | None:
    """The stated categories of ``query`` that the words of ``parsed`` (a parser result) allow more than
    one class for, or None. A shape word allows its second class only while the query still has the
    word's own class and fewer than three extents are stated (three: :mod:`recall.geometry` decides)."""
    values = query.values()
    allowed: dict[str, tuple[frozenset[str], frozenset[str]]] = {}
    words: list[str] = []
    shape_ev = parsed.features.get("shape")
    word = (shape_ev.words or "").lower() if shape_ev is not None else ""
    second = SHAPE_ALTERNATIVES.get(word)
    extents = all(f in values for f in ("a_cm", "b_cm", "c_cm"))  # then the geometry decides
    if second is not None and not extents and values.get("shape") == SHAPE_WORDS[word][0]:
        allowed["shape"] = (frozenset({values["shape"]}), frozenset(second))
        words.append(f"{word} -> shape {values['shape']} (or {'/'.join(second)}, half a mismatch)")
    mixed = mixed_materials(parsed.text)
    finish = finish_word(parsed)
    if "material" in values and mixed is not None and values["material"] in mixed:
        allowed["material"] = (mixed, frozenset())
        words.append(f"{' and '.join(sorted(mixed))} -> material either")
    elif "material" in values and finish is not None:
        stated = values["material"]
        allowed["material"] = (frozenset({stated}), frozenset(CATEGORIES["material"]) - {stated})
        words.append(f"{finish} -> material {stated} (or a {finish} finish: another material half a mismatch)")
    return Alternatives(allowed, tuple(words)) if allowed else None


def with_alternatives(
    query: FeatureQuery, soft: SoftEvidence | None, alt: Alternatives | None, cat_cols: Sequence[np.ndarray]
) -> tuple[FeatureQuery, SoftEvidence | None]:
    """``query`` without the categories of ``alt``, and ``soft`` with their terms added."""
    if alt is None:
        return query, soft
    cats = tuple((f, v) for f, v in query.categorical if f not in alt.allowed)
    query = dataclasses.replace(query, categorical=cats)
    variants = alt.variants(query)
    terms = alt.terms(cat_cols)
    penalty = np.sum(list(terms.values()), axis=0)
    # relative errors as recall.metrics.relative_errors counts categories: 0 / 0.5 / 1
    errors = tuple((f, t / MISMATCH_TERM) for f, t in terms.items())
    if soft is None:
        return query, SoftEvidence(alt.words, penalty, errors=errors, scan=False, variants=variants)
    return query, dataclasses.replace(
        soft, words=(*soft.words, *alt.words), penalty=soft.penalty + penalty, errors=(*soft.errors, *errors)
    )
