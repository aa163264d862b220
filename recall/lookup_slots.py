"""Which size slots a description's extents may take when it states fewer than three (the lookup's fit).

The parser files the extents a description states largest first into ``a_cm >= b_cm >= c_cm``, and a lone
extent by its word: "120 cm wide" alone is the middle extent (``b_cm``: a width is usually under a length).
Stated alone, a width does not say there is a longer extent: "a curved gaming monitor, about 120 cm wide"
is 119.5 x 52.9 x 28.4 cm, its width the largest; "a rabbit hutch 97 cm high" may be as high as it is
long or lower. Against a product page that states every extent, the fit compares each stated extent with
the slots its word allows (:data:`ROLE_SLOTS`), as it compares a page's fewer than three extents with each
slot they can take (:func:`recall.lookup.placements`), and takes the placement that fits best:

- a length or an overall extent is the largest (``a``), as the parser reads it;
- a width is the largest or the middle one (a monitor, a shelf: wider than tall or deep);
- a height is any (a tall bottle's largest, a tray's smallest);
- a depth or a thickness is the middle or the smallest one (a drawer deeper than tall; a board);
- an extent without such a word ("31 x 12 cm", "45 cm across", "a side") stays where the parser put it.

The stated extents keep their order (a larger stated value never takes a smaller slot than a smaller one),
and three stated extents are compared as they are. The recall itself (:mod:`recall.engine`) reads the
parse unchanged; only the lookup's judgement of a product tries the placements.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import replace
from typing import Any

from recall.lexicon import DIMENSION_WORDS

__all__ = ["ROLE_SLOTS", "SLOTS", "extent_role", "stated_placements"]

SLOTS = ("a_cm", "b_cm", "c_cm")
#: The slots an extent stated by a word of this role may take (module docstring).
ROLE_SLOTS: dict[str, tuple[str, ...]] = {
    "length": ("a_cm",),
    "overall": ("a_cm",),
    "width": ("a_cm", "b_cm"),
    "height": ("a_cm", "b_cm", "c_cm"),
    "depth": ("b_cm", "c_cm"),
    "thickness": ("b_cm", "c_cm"),
}
_WORDS = sorted(DIMENSION_WORDS, key=len, reverse=True)
_ROLE_WORD = re.compile(r"\b(" + "|".join(re.escape(w) for w in _WORDS) + r")\b")


def extent_role(words: str) -> str | None:
    """The role of the last dimension word of an extent's words ("about 120 cm wide" -> "width"), or None."""
    found = _ROLE_WORD.findall((words or "").lower())
    return DIMENSION_WORDS[found[-1]] if found else None


def stated_placements(parsed: Any) -> list[Any]:
    """``parsed`` (a parser result) with its stated extents (fewer than three) in each combination of the
    slots their words allow, in order, the parse itself first; ``[parsed]`` when it states none or three."""
    stated = [(slot, parsed.features[slot]) for slot in SLOTS if slot in parsed.features]
    if not stated or len(stated) >= 3:
        return [parsed]
    choices = []
    for slot, ev in stated:
        allowed = ROLE_SLOTS.get(extent_role(ev.words) or "", ())
        choices.append(tuple(dict.fromkeys((slot, *allowed))))
    out = [parsed]
    for slots in itertools.product(*choices):
        if len(set(slots)) < len(slots) or tuple(slots) == tuple(s for s, _ in stated):
            continue
        values = [float(ev.value) for _, ev in stated]
        order = sorted(range(len(slots)), key=lambda i: SLOTS.index(slots[i]))
        if any(values[i] < values[j] for i, j in itertools.pairwise(order)):
            continue  # a larger stated value in a smaller slot
        features = {f: ev for f, ev in parsed.features.items() if f not in SLOTS}
        for (_, ev), slot in zip(stated, slots, strict=True):
            features[slot] = replace(ev, feature=slot)
        out.append(replace(parsed, features=features))
    return out
