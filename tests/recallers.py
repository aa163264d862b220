"""Recallers over the catalogs the recall tests share, each built once per test run (a Recaller is
read-only after it is built, so one instance serves every test module)."""

from __future__ import annotations

import functools
from pathlib import Path

from recall.engine import Recaller

REPO = Path(__file__).resolve().parents[1]
SEED_CSV = REPO / "kb" / "data" / "seed_catalog.csv"
CATALOG2_CSV = REPO / "tests" / "data" / "catalog2" / "catalog.csv"


@functools.cache
def seed() -> Recaller:
    """The seed catalog's recaller."""
    return Recaller.from_csv(SEED_CSV)


@functools.cache
def catalog2() -> Recaller:
    """The second catalog's (tests/data/catalog2) recaller."""
    return Recaller.from_csv(CATALOG2_CSV)


#: The header of a catalog CSV with aliases and a source (``Recaller.from_csv`` reads it).
CATALOG_HEADER = "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity,aliases,source".split(",")


def from_sizes(path: Path, rows) -> Recaller:
    """A recaller over a small catalog written here to ``path``: ``rows`` of (name, a_cm, b_cm, c_cm,
    mass_g), every other feature unknown, source "written here"."""
    import csv

    with path.open("w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(CATALOG_HEADER)
        for name, a, b, c, g in rows:
            w.writerow([name, a, b, c, g, "", "", "", "", "", "", "written here"])
    return Recaller.from_csv(path)
