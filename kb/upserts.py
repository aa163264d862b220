"""Writing objects into the catalog: set-based upserts that keep every changed value as an observation.

:class:`kb.catalog.KnowledgeBase` calls :func:`upsert_records` in its own short transaction; the ingestion
job calls it (and :func:`bulk_execute`) inside the one write transaction of a run.
"""

from __future__ import annotations

import contextlib
import hashlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

import duckdb

from kb.csvio import SkippedRow
from kb.errors import InvalidFeature
from kb.features import DIMENSIONS, FEATURES, NUMERIC_FEATURES, ObjectRecord, sort_dims
from kb.plausibility import check_plausible

__all__ = ["ARROW_TYPES", "OBJECT_COLUMNS", "ImportReport", "bulk_execute", "features_hash", "upsert_records"]

#: The ``objects`` columns read back into records, in this order.
OBJECT_COLUMNS = ("id", "name", *FEATURES, "source")


@dataclass
class ImportReport:
    """What an import did: objects created, updated, unchanged, and rows skipped (with reasons)."""

    source: str
    new: list[str] = field(default_factory=list)
    updated: list[str] = field(default_factory=list)
    unchanged: int = 0
    skipped: list[SkippedRow] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {
            "source": self.source,
            "new": len(self.new),
            "updated": len(self.updated),
            "unchanged": self.unchanged,
            "skipped": [{"row": s.row, "column": s.column, "reason": s.reason} for s in self.skipped],
        }


def features_hash(record: ObjectRecord) -> str:
    """A short stable hash of an object's feature values (changes when any catalog value changes)."""
    text = "|".join(f"{f}={getattr(record, f)!r}" for f in FEATURES)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def upsert_records(
    con: duckdb.DuckDBPyConnection,
    records: Sequence[ObjectRecord],
    report: ImportReport,
    *,
    source: str,
    adapter: str,
    run_id: int | None,
) -> None:
    """Insert new objects and update changed ones by name inside the caller's transaction on ``con``, set-based.

    Known values replace stored ones, unknown (None) ones leave them; every new or changed value becomes an
    observation (role ``product``) with ``source`` and ``adapter``; new aliases are added unless another
    object already has that name or alias. ``report`` is filled in.
    """
    existing = {
        row[1]: dict(zip(OBJECT_COLUMNS, row, strict=True))
        for row in con.execute(f"SELECT {', '.join(OBJECT_COLUMNS)} FROM objects").fetchall()
    }
    taken_aliases = {a for (a,) in con.execute("SELECT alias FROM object_aliases").fetchall()}
    now = datetime.now(UTC).replace(tzinfo=None)
    inserts, updates, observations, alias_rows = [], [], [], []
    for rec in records:
        known = rec.known_features()
        old = existing.get(rec.name)
        if old is None:
            _check_merged(rec.name, rec.features())
            inserts.append([rec.name, *(getattr(rec, f) for f in FEATURES), rec.source, now, now])
            changed = known
            report.new.append(rec.name)
        else:
            changed = {f: v for f, v in known.items() if old[f] != v}
            new_source = rec.source if rec.source and rec.source != old["source"] else None
            if changed or new_source:
                merged = {f: (changed[f] if f in changed else old[f]) for f in FEATURES}
                _check_merged(rec.name, merged)
                updates.append([*(merged[f] for f in FEATURES), new_source or old["source"], now, rec.name])
                report.updated.append(rec.name)
            else:
                report.unchanged += 1
        for feat, value in changed.items():
            numeric = feat in NUMERIC_FEATURES
            observations.append(
                [rec.name, feat, value if numeric else None, None if numeric else value, "product",
                 rec.source or source, adapter, now, str(value), run_id]
            )
        for alias in rec.aliases:
            if alias not in taken_aliases and alias not in existing and alias != rec.name:
                taken_aliases.add(alias)
                alias_rows.append([alias, rec.name])
    _write_rows(con, inserts, updates, observations, alias_rows)


def _check_merged(name: str, merged: Mapping[str, Any]) -> None:
    """An object's values are checked together as they will be stored (:mod:`kb.plausibility`): a partial
    update with the stored values it keeps (400 kg given alone is fine, not on a stored 1 cm cube), a new
    record even when it was built without ``ObjectRecord.create``."""
    values = dict(merged)
    values.update(zip(DIMENSIONS, sort_dims(*(merged[d] for d in DIMENSIONS)), strict=True))
    try:
        check_plausible(values)
    except InvalidFeature as err:
        stored = ", ".join(f"{f}={values[f]:g}" for f in NUMERIC_FEATURES if values[f] is not None)
        raise InvalidFeature(err.field, err.value, f"{err.reason}; with {name!r}'s values ({stored})") from None


def _write_rows(con: duckdb.DuckDBPyConnection, inserts, updates, observations, alias_rows) -> None:
    """The upsert's four set-based statements: new objects, changed objects, observations, aliases."""
    bulk_execute(con, "new_objects", ["name", *FEATURES, "source", "created_at", "updated_at"], inserts,
          f"INSERT INTO objects (name, {', '.join(FEATURES)}, source, created_at, updated_at) "
          f"SELECT name, {', '.join(FEATURES)}, source, created_at, updated_at FROM new_objects")
    sets = ", ".join(f"{f} = u.{f}" for f in FEATURES)
    bulk_execute(con, "changed_objects", [*FEATURES, "source", "updated_at", "name"], updates,
          f"UPDATE objects SET {sets}, source = u.source, updated_at = u.updated_at "
          "FROM changed_objects u WHERE objects.name = u.name")
    obs_cols = ["name", "feature", "value_num", "value_text", "role", "source", "adapter", "fetched_at",
                "raw_text", "run_id"]
    bulk_execute(con, "new_observations", obs_cols, observations,
          "INSERT INTO observations (object_id, feature, value_num, value_text, role, source, adapter, "
          "fetched_at, raw_text, run_id) SELECT o.id, i.feature, i.value_num, i.value_text, i.role, i.source, "
          "i.adapter, i.fetched_at, i.raw_text, i.run_id FROM new_observations i JOIN objects o ON o.name = i.name")
    bulk_execute(con, "new_aliases", ["alias", "name"], alias_rows,
          "INSERT INTO object_aliases (alias, object_id) SELECT a.alias, o.id FROM new_aliases a "
          "JOIN objects o ON o.name = a.name")


#: Arrow types of catalog columns for :func:`bulk_execute` (other columns are strings).
ARROW_TYPES: dict[str, str] = {
    "id": "int64",
    "object_id": "int64",
    "run_id": "int64",
    "status": "int32",
    "value_num": "float64",
    **{f: "float64" for f in NUMERIC_FEATURES},
    "created_at": "timestamp",
    "updated_at": "timestamp",
    "fetched_at": "timestamp",
    "occurred_at": "timestamp",
}


def bulk_execute(
    con: duckdb.DuckDBPyConnection,
    view: str,
    columns: Sequence[str],
    rows: Sequence[Sequence[Any]] | Sequence[Mapping[str, Any]],
    sql: str,
) -> None:
    """Run ``sql`` once over ``rows`` exposed as the relation ``view`` (an Arrow table): one set-based
    statement per batch, not one statement per row. Rows are sequences in ``columns`` order or mappings
    (a missing key is NULL); column types come from :data:`ARROW_TYPES`."""
    if not rows:
        return
    import pyarrow as pa

    by_name = isinstance(rows[0], Mapping)
    arrays, fields = [], []
    for i, c in enumerate(columns):
        kind = ARROW_TYPES.get(c, "string")
        typ = pa.timestamp("us") if kind == "timestamp" else getattr(pa, kind)()
        values = [r.get(c) for r in rows] if by_name else [r[i] for r in rows]
        arrays.append(pa.array(values, type=typ))
        fields.append(pa.field(c, typ))
    con.register(view, pa.Table.from_arrays(arrays, schema=pa.schema(fields)))
    try:
        con.execute(sql)
    except BaseException:
        # inside a failed transaction the unregister fails too ("Current transaction is aborted"): the
        # statement's own error is the one to raise
        with contextlib.suppress(Exception):
            con.unregister(view)
        raise
    con.unregister(view)
