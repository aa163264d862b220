"""Values a spec sheet writes with no unit anywhere (not in the value, its label, a heading or the locale):
lengths read in millimetres when centimetres would be absurd, and then that sheet's weights in kilograms
(``scrapers/EXTRACTION.md``, "No unit")."""

from __future__ import annotations

import re
from dataclasses import replace

from kb.features import MAX_DIM_CM
from scrapers.quantities import clean_text, parse_number
from scrapers.spec_pairs import LENGTH_KINDS, Pair

__all__ = ["UNITLESS_LETTERED", "unitless_millimetres"]

#: Numbers only, maybe with axis letters in brackets (``5.20(w) x 8.00(h) x 0.40(d)``, ``923 x 253 x 659.4``,
#: ``19.4``): the unit must come from the label, a heading above it or the page's locale.
UNITLESS_LETTERED = re.compile(r"(?:[\d\s.,x×*/-]|\((?:[whdlWHDL])\))+")


_FIGURE = re.compile(r"\d+(?:[.,]\d+)*")


def _after_colon(value: str) -> str:
    """A value's figures after a sub-label (``Set Size(WXDXH) with Stand: 923 x 253 x 659.4``)."""
    return clean_text(value.rsplit(": ", 1)[-1])


def unitless_millimetres(pairs: list[Pair], decimal_comma: bool | None) -> list[Pair]:
    """``pairs`` with the product's lengths written with no unit anywhere read in millimetres when the
    largest of them, read in centimetres, is over the :data:`kb.features.MAX_DIM_CM` limit and in
    millimetres within it (Play.com's ``923 x 253 x 659.4``, a German shop's ``Breite: 540,00`` for a 54 cm
    monitor: spec sheets that drop the unit are written in mm), and its weights written with no unit in
    kilograms (Play.com's ``Set Weight with Stand: 19.4``, the German shop's ``Gewicht: 5,00`` beside its
    ``5 kg``). A largest figure within the limit leaves them unread (``no unit stated``): nothing says
    which unit."""
    bare = [p for p in pairs if p.info.unit is None and p.info.kind in LENGTH_KINDS and p.info.role == "product"
            and not p.package and not p.info.package and UNITLESS_LETTERED.fullmatch(_after_colon(p.value))]  # fmt: skip
    figures = [n for p in bare for f in _FIGURE.findall(_after_colon(p.value))
               if (n := parse_number(f, decimal_comma)) is not None]  # fmt: skip
    if not figures or not MAX_DIM_CM < max(figures) <= 10 * MAX_DIM_CM:
        return pairs
    said = f"no unit stated; read as millimetres ({max(figures):g} cm would be over the {MAX_DIM_CM:g} cm limit)"
    kg = "no unit stated; read as kilograms, beside lengths read as millimetres (a metric spec sheet)"
    units = {id(p): ("mm", said) for p in bare}
    units.update({id(p): ("kg", kg) for p in pairs if p.info.unit is None and p.info.kind == "weight"
                  and p.info.role == "product" and not p.package and not p.info.package
                  and UNITLESS_LETTERED.fullmatch(_after_colon(p.value))})  # fmt: skip
    return [replace(p, info=replace(p.info, unit=units[id(p)][0]), unit_context=units[id(p)][1])
            if id(p) in units else p for p in pairs]  # fmt: skip
