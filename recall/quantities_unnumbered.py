"""Amounts stated without a number: refused with the reason, never dropped silently.

* **Not a number**: "NaN cm", "inf kg", "infinity grams" (a word a float parser takes for a number,
  before a unit word): reason :data:`NONFINITE_REASON`, as "1e999 g" is refused as not finite.
* **A vague count**: "a few kilograms", "several inches long", "many grams", "some kilos" (a
  :data:`VAGUE_WORDS` word right before a unit word), and "a few hundred grams", "several thousand
  grams" (right before a number that opens with a scale word, which would otherwise be read as one
  hundred, one thousand): reason :data:`VAGUE_REASON`. "some 20 cm" is a hedge (about 20 cm), not this.

A unit word here is one of the description unit table's words of two letters or more that is not also
a common English word ("in": "a few in the box").
"""

from __future__ import annotations

from collections.abc import Mapping

from kb.measures.units import Unit
from recall.quantities_joins import SCALE_WORDS
from recall.reading import Reading
from recall.tokens import Token

__all__ = ["NONFINITE_REASON", "NONFINITE_WORDS", "VAGUE_REASON", "VAGUE_WORDS", "read_unnumbered", "vague_before"]

#: Words that parse as a float but are no size or mass.
NONFINITE_WORDS = frozenset({"nan", "inf", "infinity", "infinite"})
#: Counts that state no number ("a few", "several").
VAGUE_WORDS = frozenset({"few", "several", "many", "some"})
NONFINITE_REASON = "not a number: a size or a mass is a finite number"
VAGUE_REASON = "vague: no number is stated"
#: Unit words that are also common words, never taken as a unit here.
_COMMON_WORDS = frozenset({"in", "an", "at", "to", "is"})


def _is_unit(tok: Token, units: Mapping[str, Unit]) -> bool:
    low = tok.low
    return len(low) >= 2 and low.isalpha() and low not in _COMMON_WORDS and low in units


def _start(segment: list[Token], i: int) -> int:
    """The character start of the amount whose word is at ``i``: with its article ("a few")."""
    return segment[i - 1].start if i > 0 and segment[i - 1].low in ("a", "an") else segment[i].start


def vague_before(segment: list[Token], k: int, words: list[str]) -> int | None:
    """The character start of a vague count right before the number at ``k`` whose words are ``words``
    when that number opens with a scale word ("a few hundred"), else None."""
    if k == 0 or segment[k - 1].low not in VAGUE_WORDS or not words or words[0] not in SCALE_WORDS:
        return None
    return _start(segment, k - 1)


def read_unnumbered(segment: list[Token], base: int, reading: Reading, units: Mapping[str, Unit]) -> None:
    """Refuse each non-finite or vague word right before a unit word in one sentence (``base``: the index
    of its first token); a dimension word after the unit ("NaN cm long") is then no shape word."""
    for i, (tok, unit) in enumerate(zip(segment, segment[1:], strict=False)):
        if tok.low in NONFINITE_WORDS:
            reason = NONFINITE_REASON
        elif tok.low in VAGUE_WORDS:
            reason = VAGUE_REASON
        else:
            continue
        if not _is_unit(unit, units) or unit.tag not in ("W", "HA"):
            continue  # a unit the tagger read belongs to a quantity that is read
        reading.refuse(_start(segment, i), unit.end, reason)
        last = i + 2 if i + 2 < len(segment) and segment[i + 2].tag == "DIM" else i + 1
        reading.in_dim_chunk.update(range(base + i, base + last + 1))
