"""The knowledge base: a DuckDB catalog file and its Python API.

One writer at a time
--------------------
DuckDB lets one process open a database file for writing, and while it does no other process can open the
file at all, not even read-only. So :class:`KnowledgeBase` never keeps a connection open between calls:

* every call opens a connection, does its work and closes it (:meth:`KnowledgeBase.connect`);
* opening retries with a short backoff while another process holds the file, for up to ``busy_timeout``
  seconds (default 30 s), then raises :class:`~kb.errors.DatabaseBusy`;
* writers (CSV import, the nightly ingestion, grasp results) prepare everything first and hold the write
  connection only for one short transaction;
* readers use a *sandboxed* read-only connection (no file or network access, no extensions, a memory cap);
  user SQL runs on the same settings with the configuration locked, in a worker process of its own;
* inside one process a reader/writer lock keeps read and write connections from overlapping (DuckDB refuses
  two connections with different settings on one file in one process).

So a reader waits at most one write transaction, and a writer waits at most for the readers' short calls.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import duckdb

from kb.connections import CATALOG_READ_CONFIG, SANDBOX_CONFIG, open_connection, retry_while_locked
from kb.csvio import read_catalog_csv, write_catalog_csv
from kb.errors import CatalogMissing, DatabaseError, FolderMissing, ObjectNotFound, QueryFailed
from kb.features import CATEGORICAL_FEATURES, FEATURES, ObjectRecord, normalize_name
from kb.locks import lock_for
from kb.sandbox import run_user_sql
from kb.sql_policy import ALLOWED_STATEMENTS
from kb.upserts import ARROW_TYPES, OBJECT_COLUMNS, ImportReport, bulk_execute, features_hash, upsert_records
from kb.versions import CatalogVersion, catalog_version

__all__ = [
    "ALLOWED_STATEMENTS",
    "ARROW_TYPES",
    "DEFAULT_BUSY_TIMEOUT",
    "ImportReport",
    "KnowledgeBase",
    "QueryResult",
    "SANDBOX_CONFIG",
    "bulk_execute",
    "features_hash",
]

DEFAULT_BUSY_TIMEOUT = 30.0
DEFAULT_MAX_ROWS = 10_000
DEFAULT_SQL_TIMEOUT = 10.0
#: What :meth:`Catalog.sql` can return: a QueryResult, a pyarrow Table or a pandas DataFrame.
SQL_OUTPUTS = ("rows", "arrow", "pandas")


@dataclass
class QueryResult:
    """Rows of a user query; ``truncated`` is True when more than ``max_rows`` rows were available."""

    columns: list[str]
    rows: list[tuple]
    truncated: bool = False

    def to_dicts(self) -> list[dict[str, Any]]:
        return [dict(zip(self.columns, row, strict=True)) for row in self.rows]

    def to_dict(self) -> dict[str, Any]:
        return {"columns": self.columns, "rows": [list(r) for r in self.rows], "truncated": self.truncated}


class KnowledgeBase:
    """The object catalog in one DuckDB file. Open it with :meth:`open`."""

    def __init__(self, path: Path, *, read_only: bool = False, busy_timeout: float = DEFAULT_BUSY_TIMEOUT):
        self.path = Path(path)
        self.read_only = read_only
        self.busy_timeout = busy_timeout
        self._lock = lock_for(self.path)

    # ------------------------------------------------------------------ opening
    @classmethod
    def open(
        cls,
        path: str | Path,
        *,
        read_only: bool = False,
        busy_timeout: float = DEFAULT_BUSY_TIMEOUT,
        upgrade: bool = True,
    ) -> KnowledgeBase:
        """Open the catalog at ``path``.

        A writer (``read_only=False``) creates the file if needed and upgrades it to the schema head
        (``upgrade=False`` skips that). A reader requires an existing file and never writes to it.
        """
        path = Path(path)
        kb = cls(path, read_only=read_only, busy_timeout=busy_timeout)
        if read_only:
            if not path.exists():
                raise CatalogMissing(path)
        elif upgrade:
            kb.upgrade()
        return kb

    def upgrade(self, revision: str = "head") -> None:
        """Create or upgrade the schema to ``revision`` (Alembic), waiting while another process writes."""
        if self.read_only:
            raise DatabaseError(f"{self.path}: opened read-only; cannot migrate")
        from kb import migrate  # Alembic and SQLAlchemy load only when a writer migrates

        if not self.path.parent.is_dir():
            raise FolderMissing(self.path, self.path.parent)  # a typo in --db: no folders made silently
        with self._lock.write():
            self._retry(lambda: migrate.upgrade(self.path, revision))

    def schema_revision(self) -> str | None:
        from kb import migrate

        with self._lock.read():
            return self._retry(lambda: migrate.current_revision(self.path))

    def _retry(self, fn):
        return retry_while_locked(fn, path=self.path, busy_timeout=self.busy_timeout)

    @contextmanager
    def connect(self, *, write: bool = False) -> Iterator[duckdb.DuckDBPyConnection]:
        """A short-lived connection: sandboxed read-only by default, read-write with ``write=True``.

        Keep the ``with`` block short: while it is open, other processes cannot write (reader) or cannot
        open the file at all (writer). Retries while another process holds the file.
        """
        if write and self.read_only:
            raise DatabaseError(f"{self.path}: opened read-only; cannot write")
        if not write and not self.path.exists():
            raise CatalogMissing(self.path)
        lock = self._lock.write() if write else self._lock.read()
        with lock:
            if write:
                con = self._retry(lambda: open_connection(self.path, read_only=False))
            else:
                con = self._retry(lambda: open_connection(self.path, read_only=True, config=CATALOG_READ_CONFIG))
            try:
                yield con
            finally:
                con.close()

    # ------------------------------------------------------------------ reading objects
    def _rows_to_records(self, con: duckdb.DuckDBPyConnection, rows: Sequence[tuple]) -> list[ObjectRecord]:
        ids = [r[0] for r in rows]
        aliases: dict[int, list[str]] = {}
        if ids:
            for alias, oid in con.execute(
                "SELECT alias, object_id FROM object_aliases WHERE list_contains(?, object_id) ORDER BY alias",
                [ids],
            ).fetchall():
                aliases.setdefault(oid, []).append(alias)
        out = []
        for row in rows:
            values = dict(zip(OBJECT_COLUMNS, row, strict=True))
            out.append(
                ObjectRecord(
                    name=values["name"],
                    aliases=tuple(aliases.get(values["id"], ())),
                    source=values["source"],
                    **{f: values[f] for f in FEATURES},
                )
            )
        return out

    def list_objects(self, *, limit: int | None = None, offset: int = 0) -> list[ObjectRecord]:
        """Objects ordered by name, with their aliases."""
        sql = f"SELECT {', '.join(OBJECT_COLUMNS)} FROM objects ORDER BY name"
        params: list[Any] = []
        if limit is not None:
            sql += " LIMIT ? OFFSET ?"
            params = [int(limit), int(offset)]
        with self.connect() as con:
            return self._rows_to_records(con, con.execute(sql, params).fetchall())

    def count_objects(self) -> int:
        with self.connect() as con:
            return int(con.execute("SELECT count(*) FROM objects").fetchone()[0])

    def get_object(self, name: str) -> ObjectRecord:
        """The object with this name or alias (case and spacing do not matter)."""
        key = normalize_name(name)
        with self.connect() as con:
            rows = con.execute(
                f"SELECT {', '.join(OBJECT_COLUMNS)} FROM objects WHERE name = ? "
                "OR id = (SELECT object_id FROM object_aliases WHERE alias = ?) ORDER BY name = ? DESC LIMIT 1",
                [key, key, key],
            ).fetchall()
            if not rows:
                raise ObjectNotFound(name, self._close_names(con, key))
            return self._rows_to_records(con, rows)[0]

    @staticmethod
    def _close_names(con: duckdb.DuckDBPyConnection, key: str, n: int = 3) -> tuple[str, ...]:
        """Object names whose name or an alias is close to ``key`` (difflib), for "did you mean"."""
        import difflib

        pairs = con.execute(
            "SELECT name, name FROM objects UNION ALL "
            "SELECT a.alias, o.name FROM object_aliases a JOIN objects o ON o.id = a.object_id"
        ).fetchall()
        spelled = {}
        for spelling, name in pairs:
            spelled.setdefault(spelling, name)
        close = difflib.get_close_matches(key, list(spelled), n=n * 2, cutoff=0.75)
        return tuple(dict.fromkeys(spelled[c] for c in close))[:n]

    def provenance(self, name: str) -> list[dict[str, Any]]:
        """Every observed value of the object's features, newest first, with source and raw text."""
        obj = self.get_object(name)
        with self.connect() as con:
            cur = con.execute(
                "SELECT feature, value_num, value_text, role, source, adapter, fetched_at, raw_text, run_id "
                "FROM observations WHERE object_id = (SELECT id FROM objects WHERE name = ?) "
                "ORDER BY fetched_at DESC, id DESC",
                [obj.name],
            )
            cols = [d[0] for d in cur.description]
            return [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]

    def catalog_version(self) -> CatalogVersion:
        """(object count, largest id, latest update, alias count, alias checksum, value checksum): changes
        whenever an object, one of its values or an alias changes, whether or not ``updated_at`` moved
        (:mod:`kb.versions`)."""
        with self.connect() as con:
            return catalog_version(con)

    def summary(self) -> dict[str, Any]:
        """Counts for a quick look: objects, per category value, observations, runs, grasp trials."""
        with self.connect() as con:
            out: dict[str, Any] = {"objects": con.execute("SELECT count(*) FROM objects").fetchone()[0]}
            for feat in CATEGORICAL_FEATURES:
                rows = con.execute(
                    f"SELECT coalesce({feat}, 'unknown'), count(*) FROM objects GROUP BY 1 ORDER BY 2 DESC, 1"
                ).fetchall()
                out[feat] = dict(rows)
            for table in ("observations", "ingestion_runs", "grasp_validations"):
                out[table] = con.execute(f"SELECT count(*) FROM {table}").fetchone()[0]
        return out

    # ------------------------------------------------------------------ writing objects
    def import_csv(self, path: str | Path, *, skip_invalid: bool = False) -> ImportReport:
        """Import a canonical CSV in one transaction (upsert by name).

        A file with any bad row imports nothing and raises :class:`~kb.errors.CatalogImportError` naming
        row, column and reason, unless ``skip_invalid``, which imports the valid rows and lists the rest in
        the report. Blank cells leave the stored value as it is; re-importing a file changes nothing.
        """
        result = read_catalog_csv(path, skip_invalid=skip_invalid)
        report = self.upsert(result.records, source=f"csv:{Path(path).name}", adapter="csv")
        report.skipped = result.skipped
        return report

    def upsert(
        self,
        records: Iterable[ObjectRecord],
        *,
        source: str,
        adapter: str,
        run_id: int | None = None,
        con: duckdb.DuckDBPyConnection | None = None,
    ) -> ImportReport:
        """Insert new objects and update changed ones by name, in one transaction.

        Known values in a record replace stored ones; unknown (None) values leave them. Every new or
        changed value is kept in ``observations`` with ``source`` and ``adapter``. New aliases are added
        (an alias that is another object's name or alias is ignored). Pass ``con`` to join a transaction
        the caller already holds.
        """
        records = list(records)
        report = ImportReport(source=source)
        if con is None:
            with self.connect(write=True) as own:
                own.begin()
                try:
                    upsert_records(own, records, report, source=source, adapter=adapter, run_id=run_id)
                    own.commit()
                except BaseException:
                    own.rollback()
                    raise
        else:
            upsert_records(con, records, report, source=source, adapter=adapter, run_id=run_id)
        return report

    def delete_object(self, name: str) -> None:
        obj = self.get_object(name)
        with self.connect(write=True) as con:
            con.begin()
            oid = con.execute("SELECT id FROM objects WHERE name = ?", [obj.name]).fetchone()[0]
            con.execute("DELETE FROM object_aliases WHERE object_id = ?", [oid])
            con.execute("DELETE FROM observations WHERE object_id = ?", [oid])
            con.execute("DELETE FROM objects WHERE id = ?", [oid])
            con.commit()

    def export_csv(self, path: str | Path | None = None) -> str:
        """The whole catalog as canonical CSV (with aliases and source); written to ``path`` if given."""
        return write_catalog_csv(self.list_objects(), path)

    # ------------------------------------------------------------------ user SQL
    def sql(
        self,
        query: str,
        params: Sequence[Any] | None = None,
        *,
        max_rows: int = DEFAULT_MAX_ROWS,
        timeout_s: float = DEFAULT_SQL_TIMEOUT,
        output: Literal["rows", "arrow", "pandas"] = "rows",
    ) -> Any:
        """Run one read-only statement in the SQL sandbox (:mod:`kb.sandbox`: a separate worker process
        with a hard memory cap) and return its rows.

        Only SELECT (and EXPLAIN of a SELECT) statements run; any other statement type, file or network
        access and the functions that reveal server paths raise :class:`~kb.errors.QueryRefused`, as does a
        query needing more memory than the sandbox allows. At most ``max_rows`` rows come back
        (``truncated`` says when more were there); a statement running longer than ``timeout_s`` is
        stopped (:class:`~kb.errors.QueryTimeout`). Repeated column names come back renamed
        (``a``, ``a (2)``). ``output="arrow"`` / ``"pandas"`` return a pyarrow Table /
        pandas DataFrame instead of a :class:`QueryResult`.
        """
        if not isinstance(query, str) or not query.strip():
            raise QueryFailed("empty query")
        if output not in SQL_OUTPUTS:
            raise QueryFailed(f"unknown output {output!r}; expected one of {', '.join(map(repr, SQL_OUTPUTS))}")
        if not self.path.exists():
            raise CatalogMissing(self.path)
        with self._lock.read():  # in-process writers wait for the worker, as for any reader
            answer = run_user_sql(
                self.path, query, params, max_rows=max_rows, timeout_s=timeout_s, busy_timeout=self.busy_timeout
            )
        result = QueryResult(columns=answer.columns, rows=answer.rows, truncated=answer.truncated)
        columns = result.columns
        if output == "rows":
            return result
        import pyarrow as pa

        table = pa.Table.from_pylist(result.to_dicts()) if result.rows else pa.table({c: [] for c in columns})
        return table if output == "arrow" else table.to_pandas()

    # ------------------------------------------------------------------ grasp validations
    def record_grasp_results(self, rows: Iterable[dict[str, Any]]) -> int:
        """Store grasp trial results (dicts keyed by ``grasp_validations`` columns) in one transaction;
        a row whose (object, grasp type, seed, hand version, features hash) is stored already is replaced."""
        rows = list(rows)
        if not rows:
            return 0
        cols = [
            "object_name", "object_id", "features_hash", "grasp_type", "family", "rank", "success", "outcome",
            "reason", "slip_cm", "rotation_deg", "grip_force_n", "max_contact_force_n", "seed", "simulator",
            "hand_version", "planner_version", "details",
        ]
        values = [[r.get(c) for c in cols] for r in rows]
        for v in values:
            v[2] = v[2] or ""
            v[13] = v[13] or 0
            v[15] = v[15] or ""
        with self.connect(write=True) as con:
            con.begin()
            con.executemany(
                "DELETE FROM grasp_validations WHERE object_name = ? AND grasp_type = ? AND seed = ? "
                "AND hand_version = ? AND features_hash = ?",
                [[v[0], v[3], v[13], v[15], v[2]] for v in values],
            )
            con.executemany(
                f"INSERT INTO grasp_validations ({', '.join(cols)}) VALUES ({', '.join(['?'] * len(cols))})", values
            )
            con.commit()
        return len(values)

    def grasp_results(self, object_name: str | None = None) -> list[dict[str, Any]]:
        sql = "SELECT * FROM grasp_validations"
        params: list[Any] = []
        if object_name is not None:
            sql += " WHERE object_name = ?"
            params.append(normalize_name(object_name))
        sql += " ORDER BY object_name, rank, grasp_type, seed"
        with self.connect() as con:
            cur = con.execute(sql, params)
            cols = [d[0] for d in cur.description]
            return [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]

    def ingestion_runs(self, limit: int = 20) -> list[dict[str, Any]]:
        with self.connect() as con:
            cur = con.execute("SELECT * FROM ingestion_runs ORDER BY id DESC LIMIT ?", [limit])
            cols = [d[0] for d in cur.description]
            return [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]
