"""The record an extractor returns for one product page (plain dataclass, no I/O)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

__all__ = ["ProductRecord"]


@dataclass
class ProductRecord:
    """What one page says about one product, normalised to catalog units.

    dims_cm: the product's own dimensions, largest first (1 to 3 values), or None: only the axes the page
    states, filled from ``dims`` by :func:`kb.features.axes_from_extents` (a diameter of a round object
    fills two; nothing is invented).
    dims: the extents the page states, each ``{"role": ..., "cm": ...}`` (roles in
    :data:`kb.features.EXTENT_ROLES`; "extent" where the page does not name the axis), largest first.
    mass_g: the product's own mass, or None.
    package_dims_cm / package_mass_g: the product in its own box, one entry per package, kept apart.
    shipping_dims_cm / shipping_mass_g: the shipment's values (gross, the parcel sent), kept apart.
    set_count / set_mass_g: when the page sells a set (a pack of 12 bowls, a pair of curtains), its count
    and the set's mass (``mass_g`` is then None unless the page states one item's).
    refused: feature -> the reason every product value of that feature was refused (an absurd value and
    nothing else), so that ingestion rejects the page; a refused value that lost to a valid one is not here.
    material / shape: catalog words (kb.features) or None; shape may be inferred from dims (documented).
    adapter: the extractor that produced the values ("jsonld", "microdata", "shopify", "woocommerce",
    "spec_table", ...). raw: feature -> the page text each value came from (provenance).
    warnings: disagreements and doubts (e.g. two sources on the page disagree on the weight).
    """

    name: str | None
    url: str
    canonical_url: str | None = None
    gtin: str | None = None
    dims_cm: tuple[float, ...] | None = None
    dims: list[dict[str, Any]] = field(default_factory=list)
    mass_g: float | None = None
    package_dims_cm: list[tuple[float, ...]] = field(default_factory=list)
    package_mass_g: list[float] = field(default_factory=list)
    shipping_dims_cm: list[tuple[float, ...]] = field(default_factory=list)
    shipping_mass_g: list[float] = field(default_factory=list)
    set_count: int | None = None
    set_mass_g: float | None = None
    material: str | None = None
    shape: str | None = None
    adapter: str | None = None
    warnings: list[str] = field(default_factory=list)
    raw: dict[str, str] = field(default_factory=dict)
    refused: dict[str, str] = field(default_factory=dict)
    #: The page's category trail (:mod:`scrapers.trail`): breadcrumbs and JSON-LD ``category`` texts,
    #: which name the object's kind when its title does not (``kb.kinds.assign_kind``).
    breadcrumbs: tuple[str, ...] = ()
    categories: tuple[str, ...] = ()
    #: Every dims and mass value the adapters proposed, with its role, adapter, rank, page text and what
    #: the chooser decided about it (``objrecall extract --json --explain``).
    candidates: list[dict[str, Any]] = field(default_factory=list, repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["dims_cm"] = list(self.dims_cm) if self.dims_cm is not None else None
        d["package_dims_cm"] = [list(p) for p in self.package_dims_cm]
        d["shipping_dims_cm"] = [list(p) for p in self.shipping_dims_cm]
        return d
