"""A minus sign written before a stated value (``Weight: -600 g``, ``-27 x 27 x 2 cm``, ``27 x -27``).

A size or a mass is never negative, so a page stating one is wrong, and its value must be refused with
its reason rather than read without the sign. The readers (:mod:`scrapers.sizes`,
:mod:`scrapers.quantities`) return such a value negative, and the catalog limits
(:func:`scrapers.normalize.check_dims`, :func:`~scrapers.normalize.check_mass`) refuse it.

A ``-`` is a minus sign when it is glued to the digits after it (``-600``) and stands at the start of
the value or after a label, a colon, an equals sign, an opening bracket or a times sign. It is a dash,
not a sign, in a range (``10 -20 cm``, ``10 cm -20 cm``: a number or a unit before it) and as a bullet
(``- 600 g``: a space after it).
"""

from __future__ import annotations

from kb.measures.units import length_unit, mass_unit

__all__ = ["MINUS_SIGNS", "minus_before"]

#: The hyphen-minus and the minus sign (U+2212); an en or em dash is a range or a pause.
MINUS_SIGNS = frozenset("-\u2212")
_BEFORE_SIGN = frozenset(":=([")


def minus_before(text: str, index: int) -> bool:
    """True when the number starting at ``text[index]`` is written with a minus sign (module doc)."""
    if index <= 0 or index > len(text) or text[index - 1] not in MINUS_SIGNS:
        return False
    before = text[: index - 1]
    if not before or before[-1] in _BEFORE_SIGN:
        return True
    if not before[-1].isspace():
        return False  # "10-20", "AB-12": a range or a code
    words = before.split()
    if not words:
        return True
    prev = words[-1].rstrip(".,;")
    if not prev:
        return True
    if prev[-1].isdigit() or prev[-1] in "\"'\u2032\u2033":
        return False  # "10 -20 cm", '10" -20"': a range
    unit = prev.lstrip("0123456789.,")
    return length_unit(unit) is None and mass_unit(unit) is None  # "10 cm -20 cm": a range
