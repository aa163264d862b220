"""Saved product pages with their true values (``labels.jsonl``), and the rule that judges an extraction.

The folder is ``$OBJRECALL_STOREFRONT_PAGES`` or ``../shared/storefront-pages`` beside the repository;
each line of its ``labels.jsonl`` names a ``file`` and gives ``dims_cm`` (largest first), ``mass_g`` and
package values (null when the page states none).

A page counts as right (:func:`judge`) when every non-null true value is matched within
:data:`TOLERANCE` (each true dimension by a different extracted one) and every null true value is either
null in the record or accompanied by a warning.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from scrapers.records import ProductRecord

__all__ = [
    "BLIND_FRACTION",
    "ENV_PAGES",
    "TOLERANCE",
    "LabelledPage",
    "Verdict",
    "blind_split",
    "default_pages_dir",
    "judge",
    "load_labels",
    "within",
]

ENV_PAGES = "OBJRECALL_STOREFRONT_PAGES"
TOLERANCE = 0.01
#: Share of each folder's pages held back as the blind split (see :func:`blind_split`).
BLIND_FRACTION = 0.25


def default_pages_dir() -> Path:
    env = os.environ.get(ENV_PAGES)
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "shared" / "storefront-pages"


@dataclass(frozen=True)
class LabelledPage:
    path: Path
    url: str
    truth: dict[str, Any]


def load_labels(folder: Path | None = None) -> list[LabelledPage]:
    """The labelled pages of ``folder`` (default :func:`default_pages_dir`); [] when it is absent."""
    folder = Path(folder) if folder is not None else default_pages_dir()
    labels = folder / "labels.jsonl"
    if not labels.is_file():
        return []
    pages = []
    for line in labels.read_text(encoding="utf-8").splitlines():
        if line.strip():
            truth = json.loads(line)
            pages.append(LabelledPage(folder / truth["file"], truth.get("url") or "", truth))
    return pages


def blind_split(pages: list[LabelledPage]) -> tuple[list[LabelledPage], list[LabelledPage]]:
    """(dev, blind): the rule fixed before any page was read closely. Sort a folder's pages by the sha1 of
    the file name; the first ``ceil(BLIND_FRACTION * n)`` are blind, the rest are development pages."""
    ranked = sorted(pages, key=lambda p: hashlib.sha1(p.truth["file"].encode()).hexdigest())
    n_blind = math.ceil(BLIND_FRACTION * len(ranked))
    blind = {p.truth["file"] for p in ranked[:n_blind]}
    return [p for p in pages if p.truth["file"] not in blind], [p for p in pages if p.truth["file"] in blind]


def within(a: float, b: float, tolerance: float) -> bool:
    """Whether ``a`` and ``b`` differ by at most ``tolerance`` of the larger."""
    return abs(a - b) <= tolerance * max(abs(a), abs(b))


def dims_within(got, want, tolerance: float) -> bool:
    """Every true dimension matched by a different extracted one within ``tolerance``."""
    if got is None or len(got) < len(want):
        return False
    remaining = list(got)
    for w in sorted(want, reverse=True):
        hit = next((i for i, g in enumerate(remaining) if within(g, w, tolerance)), None)
        if hit is None:
            return False
        remaining.pop(hit)
    return True


@dataclass
class Verdict:
    right: bool
    problems: list[str] = field(default_factory=list)


def _close(a: float, b: float) -> bool:
    return within(a, b, TOLERANCE)


def _dims_match(got, want) -> bool:
    """Every true dimension is matched by a different extracted one (an extra extracted value, e.g. a
    diameter counted as both width and depth, is allowed)."""
    return dims_within(got, want, TOLERANCE)


def judge(record: ProductRecord, truth: dict[str, Any]) -> Verdict:
    """Whether ``record`` gets the product's own dimensions and mass right (see the module doc)."""
    problems = []
    want_dims, want_mass = truth.get("dims_cm"), truth.get("mass_g")
    if want_dims is not None and not _dims_match(record.dims_cm, want_dims):
        problems.append(f"dims {record.dims_cm} != {want_dims}")
    if want_dims is None and record.dims_cm is not None and not record.warnings:
        problems.append(f"dims {record.dims_cm} where the page states none")
    if want_mass is not None and (record.mass_g is None or not _close(record.mass_g, want_mass)):
        problems.append(f"mass {record.mass_g} != {want_mass}")
    if want_mass is None and record.mass_g is not None and not record.warnings:
        problems.append(f"mass {record.mass_g} where the page states none")
    return Verdict(not problems, problems)


def package_matches(record: ProductRecord, truth: dict[str, Any]) -> bool:
    """Whether the package values match the labelled ones (a single package may be labelled unlisted), and
    the shipping values too (``shipping_dims_cm``/``shipping_mass_g``: none stated when absent)."""
    return _listed_match(
        record.package_dims_cm, record.package_mass_g, truth.get("package_dims_cm"), truth.get("package_mass_g")
    ) and _listed_match(
        record.shipping_dims_cm, record.shipping_mass_g, truth.get("shipping_dims_cm"), truth.get("shipping_mass_g")
    )


def _listed_match(got_dims, got_mass, want_dims, want_mass) -> bool:
    if want_dims and not isinstance(want_dims[0], list):
        want_dims = [want_dims]
    if want_mass is not None and not isinstance(want_mass, list):
        want_mass = [want_mass]
    if not want_dims:
        dims_ok = not got_dims
    else:
        dims_ok = len(got_dims) == len(want_dims) and all(
            _dims_match(g, w) for g, w in zip(got_dims, want_dims, strict=True)
        )
    if not want_mass:
        mass_ok = not got_mass
    else:
        mass_ok = len(got_mass) == len(want_mass) and all(
            _close(g, w) for g, w in zip(got_mass, want_mass, strict=True)
        )
    return dims_ok and mass_ok
