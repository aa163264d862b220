"""A NumPy column snapshot of the catalog: what the recall engine searches.

A :class:`CatalogSnapshot` holds the object names and aliases, the numeric features as float64 columns
(NaN = unknown) and the categorical features as int8 codes (-1 = unknown; codes follow the order of
``kb.features`` tuples). The paper's one-hot matrix over ``VECTOR_COLUMNS`` is derived on demand.

:func:`load_snapshot` reads a knowledge base once and caches the snapshot; it is rebuilt only when the
database changed (the catalog's version when ``kb.catalog`` provides one, else the file's mtime and size).
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import (
    CATEGORICAL_FEATURES,
    MAX_DIM_CM,
    MAX_MASS_G,
    NUMERIC_FEATURES,
    VECTOR_COLUMNS,
    ObjectRecord,
)
from recall.metrics import CATEGORY_CODES

__all__ = ["CatalogSnapshot", "load_snapshot", "records_from_csv"]


@dataclass(eq=False)
class CatalogSnapshot:
    """Column arrays of a catalog. ``num`` is (n, 4) float64 C-contiguous by column (see :attr:`num_cols`),
    ``cat`` (n, 5) int8."""

    names: list[str]
    aliases: list[tuple[str, ...]]
    num: np.ndarray
    cat: np.ndarray
    records: list[ObjectRecord] | None = field(default=None, repr=False)
    version: Any = None

    def __post_init__(self) -> None:
        n = len(self.names)
        if self.num.shape != (n, len(NUMERIC_FEATURES)) or self.cat.shape != (n, len(CATEGORICAL_FEATURES)):
            raise RecallError("snapshot arrays do not match the number of names")
        # Contiguous per-column copies: gathers on one column touch one array.
        self.num_cols = [
            np.ascontiguousarray(self.num[:, j], dtype=np.float64) for j in range(self.num.shape[1])
        ]
        self.cat_cols = [
            np.ascontiguousarray(self.cat[:, j], dtype=np.int8) for j in range(self.cat.shape[1])
        ]

    def __len__(self) -> int:
        return len(self.names)

    @classmethod
    def from_records(cls, records: Sequence[ObjectRecord], version: Any = None) -> CatalogSnapshot:
        n = len(records)
        num = np.full((n, len(NUMERIC_FEATURES)), np.nan)
        cat = np.full((n, len(CATEGORICAL_FEATURES)), -1, dtype=np.int8)
        for i, rec in enumerate(records):
            for j, feat in enumerate(NUMERIC_FEATURES):
                value = getattr(rec, feat)
                if value is not None:
                    num[i, j] = float(value)
            for j, feat in enumerate(CATEGORICAL_FEATURES):
                value = getattr(rec, feat)
                if value is not None:
                    cat[i, j] = CATEGORY_CODES[feat][value]
        return cls(
            names=[r.name for r in records],
            aliases=[tuple(r.aliases) for r in records],
            num=num,
            cat=cat,
            records=list(records),
            version=version,
        )

    @cached_property
    def matrix(self) -> np.ndarray:
        """The paper's encoding: (n, len(VECTOR_COLUMNS)) float64, numeric then one-hot, NaN = unknown."""
        n = len(self)
        out = np.full((n, len(VECTOR_COLUMNS)), np.nan)
        out[:, : len(NUMERIC_FEATURES)] = self.num
        col = len(NUMERIC_FEATURES)
        for j, feat in enumerate(CATEGORICAL_FEATURES):
            codes = self.cat[:, j]
            width = len(CATEGORY_CODES[feat])
            known = codes >= 0
            block = np.full((n, width), np.nan)
            block[known] = 0.0
            block[np.flatnonzero(known), codes[known]] = 1.0
            out[:, col : col + width] = block
            col += width
        return out

    @cached_property
    def log_scaled(self) -> CatalogSnapshot:
        """The same catalog with the numeric columns in log units (``recall.metrics.log_units``): what the
        ``jplog`` metric searches, with its own pruned index."""
        from recall.metrics import log_units

        return CatalogSnapshot(
            names=self.names,
            aliases=self.aliases,
            num=log_units(self.num),
            cat=self.cat,
            records=self.records,
            version=self.version,
        )

    @cached_property
    def index(self):  # -> recall.search.JPIndex
        """The pruned-search index (sorted columns, rows per category), built on first use."""
        from recall.search import JPIndex

        return JPIndex(self)

    def record(self, i: int) -> ObjectRecord:
        if self.records is not None:
            return self.records[i]
        values: dict[str, Any] = {}
        for j, feat in enumerate(NUMERIC_FEATURES):
            x = self.num[i, j]
            values[feat] = None if np.isnan(x) else float(x)
        for j, feat in enumerate(CATEGORICAL_FEATURES):
            c = int(self.cat[i, j])
            values[feat] = None if c < 0 else list(CATEGORY_CODES[feat])[c]
        return ObjectRecord(name=self.names[i], aliases=self.aliases[i], **values)

    @property
    def nbytes(self) -> int:
        """Bytes of the feature arrays (without names and the search index)."""
        return int(sum(a.nbytes for a in self.num_cols) + sum(a.nbytes for a in self.cat_cols))


def records_from_csv(path: str | Path) -> list[ObjectRecord]:
    """Records of a canonical catalog CSV (invalid rows refused, see ``kb.csvio``)."""
    from kb.csvio import read_catalog_csv

    return read_catalog_csv(path).records


_CACHE: dict[str, CatalogSnapshot] = {}
_LOCK = threading.Lock()


def _db_version(path: Path) -> Any:
    """What tells a changed catalog: the knowledge base's ``catalog_version()`` (object count, largest id,
    latest update), else the file's mtime and size."""
    st = path.stat()
    if path.suffix.lower() != ".csv":
        try:
            from kb.catalog import KnowledgeBase

            return ("catalog", KnowledgeBase.open(path, read_only=True).catalog_version())
        except Exception:  # noqa: BLE001 - an older file or a busy database: fall back to the file's stat
            pass
    return ("stat", st.st_mtime_ns, st.st_size)


def load_snapshot(db: str | Path) -> CatalogSnapshot:
    """The snapshot of the knowledge base at ``db`` (a DuckDB file; a ``.csv`` path reads a catalog CSV),
    cached until the database changes."""
    path = Path(db)
    if not path.exists():
        raise RecallError(f"{path}: no catalog here (run `objrecall init` and import a catalog first)")
    key = str(path.resolve())
    version = _db_version(path)
    with _LOCK:
        cached = _CACHE.get(key)
        if cached is not None and cached.version == version:
            return cached
    if path.suffix.lower() == ".csv":
        records = records_from_csv(path)
    else:
        from kb.catalog import KnowledgeBase

        records = KnowledgeBase.open(path, read_only=True).list_objects()
    snap = CatalogSnapshot.from_records(records, version=version)
    with _LOCK:
        _CACHE[key] = snap
    return snap


#: Rough bulk densities (g/cm³ of the bounding box, before the fill factor) per material, for synthetic data.
_SYNTHETIC_DENSITY = {
    "fabric": 0.25,
    "glass": 2.5,
    "metal": 4.0,
    "paper": 0.5,
    "plastic": 0.9,
    "rubber": 1.1,
    "wood": 0.6,
    "other": 1.5,
}


def synthetic_snapshot(n: int, rng: np.random.Generator, unknown_rate: float = 0.03) -> CatalogSnapshot:
    """A realistic random catalog of ``n`` objects (for benchmarks and tests).

    Largest extent log-normal around 12 cm, the others a random fraction of it; category frequencies
    skewed (Zipf-like); mass = density(material) × box volume × a fill factor, so mass follows size; a
    few values unknown (``unknown_rate``), as in scraped rows.
    """
    a = np.clip(rng.lognormal(np.log(12.0), 0.8, n), 0.5, 300.0)
    b = a * rng.beta(4.0, 2.0, n)
    c = b * rng.beta(2.0, 2.5, n)
    dims = np.round(np.maximum(np.stack([a, b, c], axis=1), 0.1), 1)
    cat = np.empty((n, len(CATEGORICAL_FEATURES)), dtype=np.int8)
    for j, feat in enumerate(CATEGORICAL_FEATURES):
        width = len(CATEGORY_CODES[feat])
        p = 1.0 / np.arange(1, width + 1) ** 1.2
        perm = rng.permutation(width)
        cat[:, j] = perm[rng.choice(width, size=n, p=p / p.sum())]
    materials = list(CATEGORY_CODES["material"])
    density = np.array([_SYNTHETIC_DENSITY[m] for m in materials])[
        cat[:, CATEGORICAL_FEATURES.index("material")]
    ]
    fill = rng.uniform(0.05, 1.0, n)
    mass = np.round(np.clip(density * dims.prod(axis=1) * fill, 1.0, 400_000.0))
    num = np.concatenate([dims, mass[:, None]], axis=1)
    num[rng.random(num.shape) < unknown_rate] = np.nan
    cat[rng.random(cat.shape) < unknown_rate] = -1
    names = [f"object {i}" for i in range(n)]
    return CatalogSnapshot(names=names, aliases=[()] * n, num=num, cat=cat)


def synthetic_description(
    snap: CatalogSnapshot,
    rng: np.random.Generator,
    min_features: int = 2,
    max_features: int = 8,
    features: Sequence[str] | None = None,
):
    """A random human-like description (as a :class:`~recall.metrics.FeatureQuery`) of a random object of
    ``snap``: 2 to 8 of its known features (or those of ``features``), dimensions off by ~10 % and rounded to 0.5 cm, mass off by ~20 %
    and rounded to two significant digits, a wrong category now and then, an "at least"/"at most" sometimes.
    Returns (row, query)."""
    from recall.metrics import FeatureQuery

    i = int(rng.integers(len(snap)))
    known = [f for j, f in enumerate(NUMERIC_FEATURES) if not np.isnan(snap.num[i, j])]
    known += [f for j, f in enumerate(CATEGORICAL_FEATURES) if snap.cat[i, j] >= 0]
    if features is not None:  # a fixed description pattern (those of its features the object has)
        chosen = [f for f in features if f in known]
    else:
        count = int(rng.integers(min_features, max_features + 1))
        chosen = rng.choice(known, size=min(count, len(known)), replace=False) if known else []
    values: dict[str, Any] = {}
    qualifiers: dict[str, str] = {}
    for feat in chosen:
        if feat in NUMERIC_FEATURES:
            x = float(snap.num[i, NUMERIC_FEATURES.index(feat)])
            if feat == "mass_g":
                y = x * rng.lognormal(0.0, 0.2)
                digits = max(0, 1 - int(np.floor(np.log10(max(y, 1e-9)))))
                y = round(y, digits)
            else:
                y = round(x * rng.lognormal(0.0, 0.1) * 2) / 2
            values[feat] = min(
                max(y, 0.5 if feat != "mass_g" else 1.0), MAX_MASS_G if feat == "mass_g" else MAX_DIM_CM
            )
            roll = rng.random()
            if roll < 0.05:
                qualifiers[feat] = "at_least"
            elif roll < 0.1:
                qualifiers[feat] = "at_most"
        else:
            words = list(CATEGORY_CODES[feat])
            code = int(snap.cat[i, CATEGORICAL_FEATURES.index(feat)])
            values[feat] = words[code] if rng.random() < 0.9 else words[int(rng.integers(len(words)))]
    return i, FeatureQuery.from_values(values, qualifiers)
