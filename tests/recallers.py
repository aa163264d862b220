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
