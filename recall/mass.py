"""Resolving the mass: which stated quantity is the object's mass (rules in ``recall/PARSER.md``, "Mass").

The first quantity with a mass unit; else contents (a volume in a sentence with a contents word, at
:data:`recall.lexicon.CONTENTS_DENSITY_G_PER_ML`), which is a lower bound: the container adds its own.
A mass owned by another object ("my 2 kg dumbbell") counts only when no other mass is stated. A value
outside the catalog's limits (:func:`recall.reading.limit_refusal`) is refused, with its reason.
"""

from __future__ import annotations

from recall import lexicon as lx
from recall.reading import Reading, Stated, limit_refusal

__all__ = ["resolve_mass"]


def resolve_mass(reading: Reading) -> Stated | None:
    """The stated mass in grams, or None."""
    masses = reading.masses or [(q, False) for q in reading.other_masses]
    for q, in_contents in masses:
        assert q.unit is not None
        grams = q.value * q.unit.factor
        reason = limit_refusal("mass_g", grams)
        if reason is not None:
            reading.refuse(q.start, q.end, f"{grams:.10g} g: {reason}")
            continue
        qualifier = "at_least" if in_contents and q.qualifier != "range" else q.qualifier
        f = q.unit.factor
        low = grams if qualifier == "at_least" else (None if q.low is None else q.low * f)
        high = None if q.high is None or qualifier == "at_least" else q.high * f
        return Stated(grams, low, high, qualifier, q.start, q.end)
    for q in reading.contents:
        assert q.unit is not None
        grams = q.value * q.unit.factor * lx.CONTENTS_DENSITY_G_PER_ML
        reason = limit_refusal("mass_g", grams)
        if reason is not None:
            reading.refuse(q.start, q.end, f"{grams:.10g} g of contents: {reason}")
            continue
        return Stated(grams, grams, None, "at_least", q.start, q.end)
    return None
