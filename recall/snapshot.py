"""A NumPy column snapshot of the catalog: what the recall engine searches.

A :class:`CatalogSnapshot` holds the object names and aliases, one float32 column per numeric feature
(NaN = unknown) and one int8 column of codes per categorical feature (-1 = unknown; codes follow the order
of ``kb.features`` tuples). That is the only copy of the values: 4 × 4 + 5 × 1 = 21 B per object. The
(n, 4) / (n, 5) matrices (:attr:`num`, :attr:`cat`) and the paper's one-hot matrix (:attr:`matrix`) are
derived on demand; :meth:`num_rows` / :meth:`cat_rows` give a few rows. float32 keeps 24 bits: a catalog
value is stored to 6e-8 of itself (1.2e-6 cm at 20 cm), and read back as the shortest decimal that rounds
to it (15.4 stays 15.4).

The snapshot knows nothing of search: the indexes over it are built by :mod:`recall.search`.
:func:`load_snapshot` reads a knowledge base once (columns straight from DuckDB, no per-object Python)
and caches the snapshot; it is rebuilt only when the database changed (the catalog's version when
``kb.catalog`` provides one, else the file's mtime and size).
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import CatalogMissing, RecallError
from kb.features import (
    CATEGORICAL_FEATURES,
    CATEGORIES,
    MAX_DIM_CM,
    MAX_MASS_G,
    NUMERIC_FEATURES,
    VECTOR_COLUMNS,
    ObjectRecord,
)
from recall.metrics import CATEGORY_CODES, log_units

__all__ = ["CatalogSnapshot", "load_snapshot", "read_columns", "records_from_csv"]


def _stored(x: float) -> float:
    """A float32 catalog value as the shortest decimal that rounds to it (what the catalog held)."""
    return float(str(np.float32(x)))


class CatalogSnapshot:
    """Column arrays of a catalog: :attr:`num_cols` (4 float32), :attr:`cat_cols` (5 int8).

    Built from ``num`` (n, 4) and ``cat`` (n, 5) arrays (copied once into the columns) or, without a
    copy, by :meth:`from_columns`. Identity is the object (no value equality)."""

    def __init__(
        self,
        names: Sequence[str],
        aliases: Sequence[tuple[str, ...]],
        num: np.ndarray,
        cat: np.ndarray,
        version: Any = None,
    ) -> None:
        num, cat = np.asarray(num), np.asarray(cat)
        n = len(names)
        if num.shape != (n, len(NUMERIC_FEATURES)) or cat.shape != (n, len(CATEGORICAL_FEATURES)):
            raise RecallError("snapshot arrays do not match the number of names")
        self._init(
            names,
            aliases,
            [np.ascontiguousarray(num[:, j], dtype=np.float32) for j in range(num.shape[1])],
            [np.ascontiguousarray(cat[:, j], dtype=np.int8) for j in range(cat.shape[1])],
            version,
        )

    def _init(self, names, aliases, num_cols, cat_cols, version) -> None:
        n = len(names)
        if len(num_cols) != len(NUMERIC_FEATURES) or len(cat_cols) != len(CATEGORICAL_FEATURES):
            raise RecallError("snapshot columns do not match the catalog's features")
        if any(len(c) != n for c in (*num_cols, *cat_cols)):
            raise RecallError("snapshot arrays do not match the number of names")
        self.names = names
        self.aliases = aliases
        self.num_cols: list[np.ndarray] = list(num_cols)
        self.cat_cols: list[np.ndarray] = list(cat_cols)
        self.version = version

    @classmethod
    def from_columns(
        cls,
        names: Sequence[str],
        aliases: Sequence[tuple[str, ...]],
        num_cols: Sequence[np.ndarray],
        cat_cols: Sequence[np.ndarray],
        version: Any = None,
    ) -> CatalogSnapshot:
        """A snapshot over existing float32 / int8 columns (no copy when they already are)."""
        snap = cls.__new__(cls)
        snap._init(
            names,
            aliases,
            [np.ascontiguousarray(c, dtype=np.float32) for c in num_cols],
            [np.ascontiguousarray(c, dtype=np.int8) for c in cat_cols],
            version,
        )
        return snap

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
            version=version,
        )

    # -- derived views (copies: for a few rows, tests and tools, not per query over the catalog)
    def num_rows(self, rows) -> np.ndarray:
        """(len(rows), 4) float64 numeric values of ``rows`` (an index array or an int)."""
        return np.stack([c[rows] for c in self.num_cols], axis=-1).astype(np.float64)

    def cat_rows(self, rows) -> np.ndarray:
        """(len(rows), 5) int8 category codes of ``rows``."""
        return np.stack([c[rows] for c in self.cat_cols], axis=-1)

    @property
    def num(self) -> np.ndarray:
        """(n, 4) float64 copy of the numeric columns."""
        return self.num_rows(slice(None))

    @property
    def cat(self) -> np.ndarray:
        """(n, 5) int8 copy of the category codes."""
        return self.cat_rows(slice(None))

    @cached_property
    def matrix(self) -> np.ndarray:
        """The paper's encoding: (n, len(VECTOR_COLUMNS)) float64, numeric then one-hot, NaN = unknown
        (kept once built: the baselines and the k-d tree use it)."""
        n = len(self)
        out = np.full((n, len(VECTOR_COLUMNS)), np.nan)
        out[:, : len(NUMERIC_FEATURES)] = self.num
        col = len(NUMERIC_FEATURES)
        for feat, codes in zip(CATEGORICAL_FEATURES, self.cat_cols, strict=True):
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
        """The same catalog with the numeric columns in log units (``recall.metrics.log_units``, float32):
        what the ``jplog`` metric searches. Shares the names and the category columns (16 B per object)."""
        return CatalogSnapshot.from_columns(
            self.names,
            self.aliases,
            [log_units(c.astype(np.float64)).astype(np.float32) for c in self.num_cols],
            self.cat_cols,
            version=self.version,
        )

    def record(self, i: int) -> ObjectRecord:
        """Object ``i`` rebuilt from the columns (features, name, aliases; not its source)."""
        values: dict[str, Any] = {}
        for feat, col in zip(NUMERIC_FEATURES, self.num_cols, strict=True):
            x = col[i]
            values[feat] = None if np.isnan(x) else _stored(x)
        for feat, col in zip(CATEGORICAL_FEATURES, self.cat_cols, strict=True):
            c = int(col[i])
            values[feat] = None if c < 0 else CATEGORIES[feat][c]
        return ObjectRecord(name=self.names[i], aliases=tuple(self.aliases[i]), **values)

    @property
    def nbytes(self) -> int:
        """Bytes of the feature columns (without names, aliases and any index)."""
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


def _read_db(path: Path, version: Any) -> CatalogSnapshot:
    """The catalog's columns (:func:`read_columns`) over one read-only connection."""
    from kb.catalog import KnowledgeBase

    with KnowledgeBase.open(path, read_only=True).connect() as con:
        return read_columns(con, version)


def read_columns(con, version: Any = None) -> CatalogSnapshot:
    """The catalog's columns read by DuckDB into NumPy over the connection ``con`` (objects ordered by
    name, as ``list_objects``; a category value outside the vocabulary reads as unknown)."""
    codes = ", ".join(
        f"coalesce(list_position([{', '.join(repr(v) for v in CATEGORIES[f])}], {f}), 0) - 1 AS {f}"
        for f in CATEGORICAL_FEATURES
    )
    numbers = ", ".join(f"coalesce({f}, 'NaN'::DOUBLE) AS {f}" for f in NUMERIC_FEATURES)
    cols = con.execute(f"SELECT name, {numbers}, {codes} FROM objects ORDER BY name").fetchnumpy()
    named = con.execute(
        "SELECT r.i, list(a.alias ORDER BY a.alias) FROM object_aliases a JOIN "
        "(SELECT id, row_number() OVER (ORDER BY name) - 1 AS i FROM objects) r ON r.id = a.object_id "
        "GROUP BY r.i"
    ).fetchall()
    names = cols["name"].tolist()
    aliases: list[tuple[str, ...]] = [()] * len(names)
    for i, alias in named:
        aliases[i] = tuple(alias)
    return CatalogSnapshot.from_columns(
        names,
        aliases,
        [np.asarray(cols[f], dtype=np.float32) for f in NUMERIC_FEATURES],
        [np.asarray(cols[f], dtype=np.int8) for f in CATEGORICAL_FEATURES],
        version=version,
    )


def load_snapshot(db: str | Path) -> CatalogSnapshot:
    """The snapshot of the knowledge base at ``db`` (a DuckDB file; a ``.csv`` path reads a catalog CSV),
    cached until the database changes."""
    path = Path(db)
    if not path.exists():
        raise CatalogMissing(path)
    key = str(path.resolve())
    version = _db_version(path)
    with _LOCK:
        cached = _CACHE.get(key)
        if cached is not None and cached.version == version:
            return cached
    if path.suffix.lower() == ".csv":
        snap = CatalogSnapshot.from_records(records_from_csv(path), version=version)
    else:
        snap = _read_db(path, version)
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
    num, cat = snap.num_rows(i), snap.cat_rows(i)
    known = [f for j, f in enumerate(NUMERIC_FEATURES) if not np.isnan(num[j])]
    known += [f for j, f in enumerate(CATEGORICAL_FEATURES) if cat[j] >= 0]
    if features is not None:  # a fixed description pattern (those of its features the object has)
        chosen = [f for f in features if f in known]
    else:
        count = int(rng.integers(min_features, max_features + 1))
        chosen = rng.choice(known, size=min(count, len(known)), replace=False) if known else []
    values: dict[str, Any] = {}
    qualifiers: dict[str, str] = {}
    for feat in chosen:
        if feat in NUMERIC_FEATURES:
            x = float(num[NUMERIC_FEATURES.index(feat)])
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
            code = int(cat[CATEGORICAL_FEATURES.index(feat)])
            values[feat] = words[code] if rng.random() < 0.9 else words[int(rng.integers(len(words)))]
    return i, FeatureQuery.from_values(values, qualifiers)
