"""A value a page states twice: once in a sentence, once under a label that says whose it is.

A description's sentence ("Pendant measures 5/16 x 3/4") names no field, so the free-text reader takes it
for the product's; the same page's spec list says "Pendant measures: 0.3125" x 0.75"", a part's label.
The labelled statement says whose the value is: a sentence's candidate that agrees with a part's, a
variant's or a capacity's value stated under a label is that thing's, not the product's.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

_WORD = re.compile(r"[^\W\d_]{3,}")

#: Adapters that read sentences, not labelled fields.
SENTENCE_SOURCES = frozenset({"free_text"})
#: Whose labelled values decide a sentence's (the product's box and the parcel do not: a sentence stating
#: the box's size beside the product's label is not evidence either way).
OTHER_THINGS = ("component", "variant", "capacity")


def restated_elsewhere(
    valid: Sequence[Any], observations: Sequence[Any], feature: str, agree: Callable[[Any, Any], bool],
) -> list[tuple[Any, Any]]:
    """(sentence candidate, the labelled observation of another thing it agrees with) for every product
    candidate of ``feature`` read from a sentence whose value a labelled field gives to a part, a variant
    or a capacity. A "part" named by a word of the product's name is the product itself ("This vase
    weighs approximately: 1.2 kg" on the vase's page), never evidence."""
    name_words = {w for o in observations if o.feature == "name" for w in _WORD.findall(str(o.value).lower())}
    others = [o for o in observations if o.feature == feature and o.role in OTHER_THINGS
              and o.source not in SENTENCE_SOURCES
              and not (set(_WORD.findall((o.part or "").lower())) & name_words)]  # fmt: skip
    out = []
    for cand in valid:
        if cand.source not in SENTENCE_SOURCES:
            continue
        hit = next((o for o in others if _agrees(cand.value, o.value, feature, agree)), None)
        if hit is not None:
            out.append((cand, hit))
    return out


def _agrees(a: Any, b: Any, feature: str, agree: Callable[[Any, Any], bool]) -> bool:
    if feature == "dims":
        a, b = tuple(a), tuple(b)
        return len(a) == len(b) and agree(a, b)
    return agree(a, b)
