"""Plausibility of a whole object: the size, mass and density a household object can have.

:func:`kb.features.validate_features` checks each value on its own (positive, finite, at most 5 m and
500 kg); this module checks the values of one object together, and is called wherever a catalog record
is made or changed: :meth:`kb.features.ObjectRecord.create` (so the CSV import, ``PUT /objects`` and the
ingestion's fused values), ``with_features``, and :mod:`kb.upserts` (a partial update merged with the stored
values, and records built without ``create``). The parser does not call it: a description's single values
keep their own, looser, rule (``recall/reading.py``), and the object a description asks a grasp for is not
stored (``create(..., plausible=False)``). The simulator names an object MuJoCo cannot build (an old row)
in its own words (``sim/world.py``).

The limits and their basis (catalog units, cm and g):

================== =========== ===========================================================================
limit              value       basis
================== =========== ===========================================================================
smallest extent    0.001 cm    10 µm: cling film (about 10 µm) and kitchen foil (16 µm) are the thinnest
                               household things; the thinnest seed object is a sheet of paper (0.01 cm)
largest extent     >= 0.1 cm   1 mm: a seed bead or a watch screw; the seed's smallest object is a die
                               (1.6 cm)
mass               >= 0.01 g   10 mg: a staple weighs about 30 mg; the seed's lightest is a paper clip
                               (0.5 g)
density (mass      <= 45       an object fits inside its box a x b x c, so mass / (a b c) cannot exceed
over a b c)        g/cm³       the density of its material; osmium (22.6 g/cm³) is the densest element;
                               twice that absorbs rounded stated extents. Seed: at most 5.95 (a coin)
density            >= 5e-5     a twenty-fourth of air's 0.0012 g/cm³, for hollow and open shapes: an
                   g/cm³       inflated 30 cm party balloon (3 g) is 1.1e-4, an open umbrella (100 x 100
                               x 60 cm, 400 g) 6.7e-5. Seed: at least 0.013 (a plastic cup)
================== =========== ===========================================================================

**Unknown extents.** Sizes may be partial (only the largest extent, or two): an unknown extent is at most
the next known one (``b <= a``, ``c <= b``) and at least the smallest extent, so a density limit refuses
only what no value of the unknown extents could make plausible: 400 kg with ``a = 1 cm`` and ``b``, ``c``
unknown is refused (at least 400 000 g/cm³), 40 g with ``a = 1 cm`` is not. Without a known extent
or mass there is no density to check.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kb.errors import InvalidFeature

__all__ = [
    "MAX_DENSITY_G_CM3",
    "MIN_DENSITY_G_CM3",
    "MIN_EXTENT_CM",
    "MIN_LARGEST_EXTENT_CM",
    "MIN_MASS_G",
    "check_plausible",
]

MIN_EXTENT_CM = 0.001
MIN_LARGEST_EXTENT_CM = 0.1
MIN_MASS_G = 0.01
MAX_DENSITY_G_CM3 = 45.0
MIN_DENSITY_G_CM3 = 5e-5

_DIMS = ("a_cm", "b_cm", "c_cm")


def _box_volumes(dims: list[float | None]) -> tuple[float, float, str] | None:
    """(largest, smallest) box volume the known extents allow, and the box as text; None when none known."""
    if dims[0] is None:
        return None
    largest, smallest, last = 1.0, 1.0, dims[0]
    for d in dims:
        last = d if d is not None else last
        largest *= last
        smallest *= d if d is not None else MIN_EXTENT_CM
    box = " x ".join(f"{d:g}" if d is not None else "?" for d in dims)
    return largest, smallest, f"{box} cm box"


def _check_sizes(dims: list[float | None], mass: float | None) -> None:
    if dims[0] is not None and dims[0] < MIN_LARGEST_EXTENT_CM:
        raise InvalidFeature(
            "a_cm",
            dims[0],
            f"too small for a household object (its largest extent under {MIN_LARGEST_EXTENT_CM:g} cm)",
        )
    for name, d in zip(_DIMS, dims, strict=True):
        if d is not None and d < MIN_EXTENT_CM:
            raise InvalidFeature(
                name, d, f"too thin for any household object (under {MIN_EXTENT_CM:g} cm, 10 µm)"
            )
    if mass is not None and mass < MIN_MASS_G:
        raise InvalidFeature("mass_g", mass, f"too light for a household object (under {MIN_MASS_G:g} g)")


def _number(x: float) -> str:
    return f"{x:,.0f}" if x >= 1000 else f"{x:.3g}"


def check_plausible(values: Mapping[str, Any]) -> None:
    """Raise :class:`InvalidFeature` (naming the value and the limit) when the numeric features in
    ``values`` (catalog units, validated, dims sorted a >= b >= c, None = unknown) cannot be one
    household object; see the module's table."""
    dims = [values.get(d) for d in _DIMS]
    mass = values.get("mass_g")
    _check_sizes(dims, mass)
    boxes = _box_volumes(dims)
    if mass is None or boxes is None:
        return
    largest, smallest, box = boxes
    if mass / largest > MAX_DENSITY_G_CM3:
        at_least = "" if smallest == largest else "at least "
        raise InvalidFeature(
            "mass_g", mass, f"denser than any material: {mass:g} g in a {box} is {at_least}{_number(mass / largest)} g/cm³ "
            f"(at most {MAX_DENSITY_G_CM3:g} g/cm³ over the box volume a x b x c)",
        )  # fmt: skip
    if mass / smallest < MIN_DENSITY_G_CM3:
        at_most = "" if smallest == largest else "at most "
        raise InvalidFeature(
            "mass_g", mass, f"too light for its size: {mass:g} g in a {box} is {at_most}{_number(mass / smallest)} g/cm³ "
            f"(at least {MIN_DENSITY_G_CM3:g} g/cm³ over the box volume a x b x c)",
        )  # fmt: skip
