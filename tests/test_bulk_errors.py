"""A set-based statement that fails inside a write transaction raises its own error, not the "Current
transaction is aborted" of the cleanup after it (a blind tester read only the latter from `objrecall
ingest`). A real DuckDB file."""

from __future__ import annotations

import duckdb
import pytest

from kb.upserts import bulk_execute


def test_the_statements_own_error_is_raised(tmp_path):
    con = duckdb.connect(str(tmp_path / "t.duckdb"))
    con.execute("CREATE TABLE t (url VARCHAR PRIMARY KEY)")
    con.execute("INSERT INTO t VALUES ('a')")
    con.begin()
    with pytest.raises(duckdb.ConstraintException, match="Duplicate key"):
        bulk_execute(con, "v", ["url"], [{"url": "a"}], "INSERT INTO t SELECT url FROM v")
    con.close()  # the ingestion's write closes its connection after a failed transaction
    with duckdb.connect(str(tmp_path / "t.duckdb")) as again:
        assert again.execute("SELECT url FROM t").fetchall() == [("a",)]
