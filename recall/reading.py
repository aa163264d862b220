"""What the parser reads from one description before resolving it: the records the stages pass on.

:class:`recall.quantities.QuantityReader` fills a :class:`Reading` (quantities, dimension statements,
masses, contents, category words, refused values); :mod:`recall.dimensions`, :mod:`recall.mass` and
:mod:`recall.categories` resolve it into :class:`Stated` values and category words;
:func:`limit_refusal` is the catalog's rule for a value in catalog units.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kb.errors import InvalidFeature
from kb.features import validate_features
from kb.measures.units import Unit
from recall.tokens import Token

__all__ = [
    "MIN_STATED",
    "NEGATED_REASON",
    "DimStatement",
    "Quantity",
    "Reading",
    "Relation",
    "Stated",
    "limit_refusal",
]

#: The smallest value stated (cm or g): the parser's evidence has 4 decimals.
MIN_STATED = 0.0001
#: The reason a negated value is refused ("not 10 cm": not stated; :meth:`Reading.refuse`).
NEGATED_REASON = "negated: the description says it is not this value"


@dataclass(slots=True)
class Quantity:
    value: float
    low: float | None
    high: float | None
    qualifier: str
    unit: Unit | None
    start: int
    end: int
    pos: int  # token index in the text (for unit inheritance)


@dataclass
class DimStatement:
    role: str
    quantities: list[Quantity]
    start: int
    end: int


@dataclass
class Relation:
    """An extent stated relative to another ("twice as long as it is wide"): ``role`` is ``factor``
    times ``ref`` (None: the extent stated last before it, as in "6 cm wide and three times as long")."""

    role: str
    factor: float
    ref: str | None
    start: int
    end: int


@dataclass
class Reading:
    """Everything read from the chunks, in text order, before the features are resolved."""

    dims: list[DimStatement] = field(default_factory=list)
    multis: list[DimStatement] = field(default_factory=list)
    sizes: list[DimStatement] = field(default_factory=list)
    masses: list[tuple[Quantity, bool]] = field(default_factory=list)  # (quantity, is contents)
    other_masses: list[Quantity] = field(default_factory=list)  # "my 2 kg dumbbell": used only alone
    contents: list[Quantity] = field(default_factory=list)
    length_units: list[tuple[int, Unit]] = field(default_factory=list)  # (token index, unit)
    categories: dict[str, list[tuple[int, int, str, Token]]] = field(default_factory=dict)
    mass_hints: list[str] = field(default_factory=list)
    cue_words: set[str] = field(default_factory=set)
    in_dim_chunk: set[int] = field(default_factory=set)
    relations: list[Relation] = field(default_factory=list)
    refused: dict[tuple[int, int], str] = field(default_factory=dict)  # (start, end) -> reason

    def refuse(self, start: int, end: int, reason: str) -> None:
        """Record a stated value that is not used, with the reason (the first reason given for a span)."""
        self.refused.setdefault((start, end), reason)


@dataclass
class Stated:
    """A resolved value in catalog units (cm, g), its bounds and qualifier, and its character span."""

    value: float
    low: float | None
    high: float | None
    qualifier: str
    start: int
    end: int


def limit_refusal(feature: str, value: float) -> str | None:
    """Why ``value`` (catalog units) cannot be ``feature``: :mod:`kb.features`' rule (more than zero,
    finite, at most MAX_DIM_CM / MAX_MASS_G, the limit itself accepted), or under :data:`MIN_STATED`, the
    parser's precision (its values are rounded to 4 decimals); None when it can."""
    try:
        validate_features({feature: value})
    except InvalidFeature as err:
        return err.reason
    if value < MIN_STATED:
        return f"too small to state (under {MIN_STATED:g})"
    return None
