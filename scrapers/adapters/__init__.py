"""Extractors ("adapters"): each reads one kind of product data from a :class:`~scrapers.page.Page`.

An adapter is a function ``(page) -> list[Observation]`` registered with :func:`adapter` and a priority
number; :data:`ADAPTERS` is kept in priority order (structured data first, free text last). Adding a store format is
one small module here that registers one function, imported in :mod:`scrapers.extract`.

An adapter never raises on a bad page: it returns what it found (maybe nothing) and reports doubts in
``Observation.note`` or as ``feature="warning"`` observations. :func:`scrapers.extract.extract_page` runs
every adapter and fuses their observations (see ``scrapers/EXTRACTION.md``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["ADAPTERS", "Adapter", "Observation", "adapter"]

#: Features an observation can carry.
OBSERVED = ("name", "gtin", "canonical_url", "dims", "mass", "material", "shape", "warning")


@dataclass
class Observation:
    """One value a page states.

    feature: one of :data:`OBSERVED`; value: dims as a tuple of cm (in the page's order), mass in g,
    words for the rest. package: a package or shipping value. rank: how direct the statement is within
    its adapter (0 explicit structured field, 1 labelled spec row, 2 weaker: a range bound, a title).
    order: position on the page. group: observations of one package share a group. raw: the page text
    the value came from. note: a doubt, reported as a warning when this value is used. roles: for dims,
    what each value measures (:data:`kb.features.EXTENT_ROLES`, parallel to ``value``; empty = unnamed
    extents). The catalog axes are filled from them by :func:`kb.features.axes_from_extents`.
    """

    feature: str
    value: Any
    package: bool = False
    rank: int = 1
    order: int = 0
    group: int | None = None
    raw: str = ""
    note: str | None = None
    source: str = ""
    roles: tuple[str, ...] = ()
    #: Whose value it is: "product" (package values have ``package``), "shipping" (a shipment's: gross, the
    #: parcel), or "component" / "capacity" (a part's extent, a capacity or rating: proposed so the chooser
    #: can list it, never chosen), or "name" (a quantity written only in the product's name: used when no
    #: other product value of that feature is stated), or "content" (a size row's net content, ``Size: 275g``:
    #: used beside a "name" mass, never alone).
    role: str = "product"
    #: For a component's value, the part it names (``cable``), else None.
    part: str | None = None
    #: Read in a site-wide block (the store's header, footer, navigation, an aside: ``Line.site_wide``).
    site_wide: bool = False
    #: Stated only in a ``<meta>`` field the page never shows (Open Graph's ``product:weight``, a microdata
    #: ``<meta itemprop="weight">``): the weight a shop system computes postage from, the product's only
    #: when a shown statement agrees (``scrapers.choice``, feature ``main``).
    hidden: bool = False

    @property
    def off_main(self) -> bool:
        """Not read in the page's main, shown content: a site-wide block or a hidden meta field."""
        return self.site_wide or self.hidden

    def extents(self) -> tuple[tuple[str, float], ...]:
        """``(role, cm)`` per stated extent of a dims observation."""
        roles = self.roles if len(self.roles) == len(self.value) else ("extent",) * len(self.value)
        return tuple(zip(roles, self.value, strict=True))


@dataclass(frozen=True)
class Adapter:
    name: str
    func: Callable[..., list[Observation]]
    priority: int
    description: str = ""
    #: A fallback runs only while the product's dimensions or mass are still unknown (it is slow or weak).
    fallback: bool = False


#: Registered adapters, in priority order.
ADAPTERS: list[Adapter] = []


def adapter(
    name: str, priority: int, *, fallback: bool = False
) -> Callable[[Callable[..., list[Observation]]], Callable[..., list[Observation]]]:
    """Register ``func`` as the adapter ``name``; a lower ``priority`` number is tried and trusted first.
    A ``fallback`` adapter is skipped once higher-priority adapters found both dimensions and mass."""

    def register(func: Callable[..., list[Observation]]) -> Callable[..., list[Observation]]:
        if any(a.name == name for a in ADAPTERS):
            raise ValueError(f"adapter {name!r} registered twice")
        doc = (func.__doc__ or "").strip().splitlines()
        ADAPTERS.append(Adapter(name, func, priority, doc[0] if doc else "", fallback))
        ADAPTERS.sort(key=lambda a: a.priority)
        return func

    return register
