"""Executing an ingestion run's write set: stages 5-7 in **one** short write transaction.

:func:`write` opens the catalog for writing, registers the run, reads what it must match against (objects,
aliases, the matched objects' observations), then applies the plan :mod:`scrapers.write_set` computes:
new objects, updated objects, aliases, observations, ``pages`` rows and ``page_events``, each one
set-based statement over an Arrow batch (no row-by-row round trips), and commits. Any failure rolls the
whole run back, so a crash or a kill leaves the catalog as it was before the run or as it is after it.
"""

from __future__ import annotations

import json
import os
import sys
import time
from datetime import datetime
from typing import TYPE_CHECKING, Any

from kb.catalog import bulk_execute
from kb.features import FEATURES
from scrapers import write_set as plan

if TYPE_CHECKING:
    from scrapers.outcomes import IngestionReport, PageOutcome

__all__ = ["PAUSE_ENV", "write"]

#: Testing hook: seconds to sleep inside the write transaction, after every statement and before COMMIT,
#: so a test can kill the process while the transaction is open (see tests/test_ingest_crash.py).
PAUSE_ENV = "OBJRECALL_INGEST_PAUSE_BEFORE_COMMIT"

_OBJECT_COLS = ["id", "name", *FEATURES, "source", "gtin", "canonical_url", "updated_at"]
_NEW_COLS = ["name", *FEATURES, "source", "gtin", "canonical_url", "created_at", "updated_at"]
_UPDATE_COLS = ["id", *FEATURES, "gtin", "canonical_url", "updated_at"]
_OBS_COLS = [
    "object_id", "feature", "value_num", "value_text", "role", "source", "adapter", "fetched_at", "raw_text",
    "run_id",
]  # fmt: skip


def _warm_up_arrow() -> None:
    """Register one Arrow table on a throwaway in-memory database: DuckDB and pyarrow import what they need
    for that (pandas and friends, seconds on a cold, busy machine) now, not while we hold the write lock."""
    import duckdb
    import pyarrow as pa

    con = duckdb.connect()
    try:
        con.register("warm_up", pa.table({"x": [1]}))
        con.execute("SELECT count(*) FROM warm_up").fetchone()
    finally:
        con.close()


def write(
    kb, outcomes: list[PageOutcome], report: IngestionReport, events: list[tuple[str, str, str]], now: datetime
) -> None:
    """Write the run (see the module doc); fills ``report``'s run id, counts and ``write_s``."""
    groups = plan.group_pages([p for p in outcomes if p.outcome == "extracted"])
    pause = float(os.environ.get(PAUSE_ENV, "0") or 0)
    _warm_up_arrow()
    with kb.connect(write=True) as con:
        t0 = time.monotonic()
        con.begin()
        try:
            run_id = con.execute(
                "INSERT INTO ingestion_runs (started_at, status, sources) VALUES (?, 'running', ?) RETURNING id",
                [plan.naive(report.started_at), report.sources],
            ).fetchone()[0]
            report.run_id = run_id
            index = _read_index(con)
            matched, fresh = plan.match_groups(groups, index)
            object_of_page: dict[str, int] = {}
            obs_rows = _insert_new(con, fresh, report, object_of_page, now)
            obs_rows += _update_matched(con, matched, index, report, object_of_page, run_id, now)
            _insert_aliases(con, fresh, matched, index, object_of_page, report, events)
            _insert_observations(con, obs_rows, run_id, now)
            report.observations_added = len(obs_rows)
            _write_pages(con, outcomes, object_of_page, run_id, now)
            bulk_execute(
                con,
                "ingest_events",
                ["run_id", "url", "stage", "reason", "occurred_at"],
                plan.event_rows(outcomes, events, run_id, now),
                "INSERT INTO page_events (run_id, url, stage, reason, occurred_at) "
                "SELECT run_id, url, stage, reason, occurred_at FROM ingest_events",
            )
            _finish_run(con, report, run_id, now, t0)
            if pause > 0:
                print("ingest: write transaction open, pausing before commit", file=sys.stderr, flush=True)
                time.sleep(pause)
            con.commit()
        except BaseException:
            con.rollback()
            raise
        report.write_s = time.monotonic() - t0


def _read_index(con) -> plan.CatalogIndex:
    objects = {
        row[0]: dict(zip(_OBJECT_COLS, row, strict=True))
        for row in con.execute(f"SELECT {', '.join(_OBJECT_COLS)} FROM objects").fetchall()
    }
    aliases = con.execute("SELECT alias, object_id FROM object_aliases").fetchall()
    return plan.CatalogIndex.build(objects, aliases)


def _insert_new(con, fresh, report, object_of_page: dict[str, int], now) -> list[dict[str, Any]]:
    """Insert the new objects; returns their observation rows (with object ids)."""
    planned = [plan.plan_new(group, report.warnings, now) for group in fresh]
    bulk_execute(
        con,
        "ingest_new_objects",
        _NEW_COLS,
        [row for row, _ in planned],
        f"INSERT INTO objects ({', '.join(_NEW_COLS)}) SELECT {', '.join(_NEW_COLS)} FROM ingest_new_objects",
    )
    names = [row["name"] for row, _ in planned]
    ids = dict(con.execute("SELECT name, id FROM objects WHERE list_contains(?, name)", [names]).fetchall()) if names else {}
    obs_rows: list[dict[str, Any]] = []
    for group, (row, rows) in zip(fresh, planned, strict=True):
        oid = ids[row["name"]]
        for p in group:
            object_of_page[p.url] = oid
        obs_rows.extend({**r, "object_id": oid} for r in rows)
        report.new_objects.append(row["name"])
    report.new = len(report.new_objects)
    return obs_rows


def _history(con, object_ids: list[int]) -> dict[int, list[dict[str, Any]]]:
    """Existing observations of the matched objects, for idempotency and fusion."""
    out: dict[int, list[dict[str, Any]]] = {}
    if not object_ids:
        return out
    cur = con.execute(
        "SELECT id, object_id, feature, value_num, value_text, role, source, adapter, fetched_at, "
        "run_id FROM observations WHERE list_contains(?, object_id)",
        [object_ids],
    )
    cols = [d[0] for d in cur.description]
    for row in cur.fetchall():
        rec = dict(zip(cols, row, strict=True))
        out.setdefault(rec["object_id"], []).append(rec)
    return out


def _update_matched(con, matched, index, report, object_of_page, run_id, now) -> list[dict[str, Any]]:
    """Update the matched objects whose pages say something new; returns the observation rows to add."""
    history = _history(con, list(matched))
    updates, obs_rows = [], []
    for oid, group in matched.items():
        for p in group:
            object_of_page[p.url] = oid
        update, added = plan.plan_update(index.objects[oid], group, history.get(oid, []), run_id, report.warnings, now)
        if update is None:
            report.unchanged += 1
            continue
        updates.append(update)
        obs_rows.extend({**r, "object_id": oid} for r in added)
        report.updated_objects.append(index.objects[oid]["name"])
    sets = ", ".join(f"{c} = u.{c}" for c in _UPDATE_COLS[1:])
    bulk_execute(
        con,
        "ingest_updates",
        _UPDATE_COLS,
        updates,
        f"UPDATE objects SET {sets} FROM ingest_updates u WHERE objects.id = u.id",
    )
    report.updated = len(report.updated_objects)
    return obs_rows


def _insert_aliases(con, fresh, matched, index, object_of_page, report, events) -> None:
    """Other names a product goes by (a second store's title matched by URL or GTIN) become aliases, and
    so does the English name of a title in another language (:func:`kb.kinds.assign_kind`: "caffettiera
    moka ..." -> "moka pot"; else of the page's JSON-LD categories or breadcrumbs), recorded as a ``naming`` page event with where it came from."""
    from kb.kinds import assign_kind

    alias_rows = []
    new_ids = {g[0].clean.name: object_of_page[g[0].url] for g in fresh}
    taken = set(index.by_name) | set(new_ids)
    owners = [(new_ids[g[0].clean.name], g) for g in fresh] + list(matched.items())
    for oid, group in owners:
        for p in group:
            for alias in (p.clean.name, *p.clean.aliases):  # a record's own aliases: a lookup's search words
                if alias not in taken:
                    taken.add(alias)
                    alias_rows.append({"alias": alias, "object_id": oid})
            trail = p.record
            named = assign_kind(
                p.clean.name,
                breadcrumbs=trail.breadcrumbs if trail is not None else (),
                categories=trail.categories if trail is not None else (),
            )
            if named is not None and named.english and named.english not in taken:
                taken.add(named.english)
                alias_rows.append({"alias": named.english, "object_id": oid})
                reason = f"kind {named.kind}; English alias {named.english!r} from the {named.provenance}"
                events.append((p.url, "naming", reason))
    bulk_execute(
        con,
        "ingest_aliases",
        ["alias", "object_id"],
        alias_rows,
        "INSERT INTO object_aliases (alias, object_id) SELECT alias, object_id FROM ingest_aliases",
    )
    report.aliases_added = len(alias_rows)


def _insert_observations(con, obs_rows: list[dict[str, Any]], run_id: int, now) -> None:
    for r in obs_rows:
        r["run_id"] = run_id
        r["fetched_at"] = plan.naive(r["fetched_at"]) or now
    bulk_execute(
        con,
        "ingest_observations",
        _OBS_COLS,
        obs_rows,
        f"INSERT INTO observations ({', '.join(_OBS_COLS)}) SELECT {', '.join(_OBS_COLS)} FROM ingest_observations",
    )


def _write_pages(con, outcomes, object_of_page, run_id: int, now) -> None:
    """Pages: validators for next time (not-modified pages keep their object and hash; pages that could
    not be fetched keep everything but their error)."""
    not_modified, unfetched, others = plan.page_rows(outcomes, object_of_page, run_id, now)
    bulk_execute(
        con,
        "ingest_seen",
        ["url", "status", "fetched_at", "run_id", "etag", "last_modified"],
        not_modified,
        "UPDATE pages SET status = s.status, fetched_at = s.fetched_at, run_id = s.run_id, "
        "etag = coalesce(s.etag, pages.etag), last_modified = coalesce(s.last_modified, pages.last_modified) "
        "FROM ingest_seen s WHERE pages.url = s.url",
    )
    bulk_execute(
        con,
        "ingest_unfetched",
        ["url", "fetched_at", "run_id", "error"],
        unfetched,
        "UPDATE pages SET fetched_at = s.fetched_at, run_id = s.run_id, error = s.error "
        "FROM ingest_unfetched s WHERE pages.url = s.url",
    )
    known = {r[0] for r in con.execute("SELECT url FROM pages").fetchall()} if unfetched else set()
    others = others + [r for r in unfetched if r["url"] not in known]  # never seen before: a new row
    page_cols = list(others[0]) if others else []
    bulk_execute(con, "ingest_pages", ["url"], others, "DELETE FROM pages WHERE url IN (SELECT url FROM ingest_pages)")
    bulk_execute(
        con,
        "ingest_pages",
        page_cols,
        others,
        f"INSERT INTO pages ({', '.join(page_cols)}) SELECT {', '.join(page_cols)} FROM ingest_pages",
    )


def _finish_run(con, report, run_id: int, now, t0: float) -> None:
    report.finished_at = now
    report.duration_s += time.monotonic() - t0
    con.execute(
        "UPDATE ingestion_runs SET finished_at = ?, status = ?, fetched = ?, not_modified = ?, "
        "extracted = ?, rejected = ?, new = ?, updated = ?, rejected_reasons = ?, errors = ?, "
        "duration_s = ? WHERE id = ?",
        [
            plan.naive(now),
            report.status,
            report.fetched,
            report.not_modified,
            report.extracted,
            report.rejected,
            report.new,
            report.updated,
            json.dumps(report.rejected_reasons, sort_keys=True),
            json.dumps(report.errors[:100]),
            report.duration_s,
            run_id,
        ],
    )
