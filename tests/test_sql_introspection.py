"""What SQL users do first, on a real DuckDB catalog file through the sandbox (kb/sql_policy.py, kb/sandbox.py):
the read-only catalog introspection runs (DESCRIBE, SHOW TABLES, duckdb_tables(), information_schema,
pragma_table_info), while every PRAGMA that names the server's file or changes a setting stays refused;
every file or URL read is refused in the sandbox's own words ("reading files is not allowed"), naming the
file, whichever DuckDB error stopped it (a permission error, or "a table that does not exist" for a quoted
path DuckDB has no reader for); and DuckDB's "Did you mean" hint reaches the user."""

from __future__ import annotations

import hashlib

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.errors import QueryFailed, QueryRefused
from kb.service.cli import app
from kb.service.http import create_app

#: Catalog introspection: each runs and its rows name the objects table or one of its columns.
INTROSPECTION = [
    "select * from pragma_table_info('objects')",
    "PRAGMA table_info('objects')",
    "pragma table_info('objects');",
    "PRAGMA show_tables",
    "PRAGMA show_tables_expanded",
    "select * from pragma_show('objects')",
    "select table_name from duckdb_tables()",
    "select column_name from duckdb_columns() where table_name = 'objects'",
    "select table_name from information_schema.tables",
    "select column_name from information_schema.columns where table_name = 'objects'",
    "DESCRIBE objects",
    "SHOW TABLES",
    "SHOW objects",
    "SUMMARIZE objects",
]
#: PRAGMAs that are no catalog introspection: they name the server's file, its settings or machine, or
#: change a setting. Each stays refused (the neighbours of the allowed ones above).
STILL_REFUSED = [
    "PRAGMA database_list",
    "select * from pragma_database_list",
    "select * from pragma_database_size()",
    "select * from pragma_platform()",
    "select * from pragma_version()",
    "select * from pragma_storage_info('objects')",
    "PRAGMA enable_profiling",
    "PRAGMA memory_limit = '1GB'",
    "PRAGMA threads = 8",
    "PRAGMA table_info('objects') ; PRAGMA database_list",
]
#: File and URL reads of every form, and the path each refusal names.
FILE_READS = [
    ("select * from '/etc/passwd'", "/etc/passwd"),  # DuckDB: "Catalog Error: Table ... does not exist"
    ('select * from "/etc/passwd"', "/etc/passwd"),
    ("select o.name from objects o join '/etc/hosts' h on true", "/etc/hosts"),
    ("describe '/etc/passwd'", "/etc/passwd"),
    ("select * from pragma_table_info('/etc/passwd')", "/etc/passwd"),
    ("select * from read_csv('/etc/passwd')", "/etc/passwd"),  # DuckDB: "Permission Error"
    ("select * from read_text('/etc/passwd')", "/etc/passwd"),
    ("select * from read_json('/etc/x.json')", "/etc/x.json"),
    ("select * from read_parquet('https://example.com/y.parquet')", "https://example.com/y.parquet"),
    ("select * from glob('/etc/*')", "/etc/*"),
    ("select * from '~/x.csv'", "~/x.csv"),
    ("select * from 's3://bucket/x.parquet'", "s3://bucket/x.parquet"),
    ("ATTACH '/tmp/other.duckdb' AS other", "/tmp/other.duckdb"),
    ("COPY objects FROM '/etc/passwd'", "/etc/passwd"),
    ("IMPORT DATABASE '/tmp/export'", "/tmp/export"),
]


@pytest.fixture(scope="module")
def db(tmp_path_factory):
    from kb.service.bootstrap import seed_catalog_path

    path = tmp_path_factory.mktemp("introspect") / "introspected.duckdb"
    KnowledgeBase.open(path).import_csv(seed_catalog_path())
    return path


@pytest.mark.parametrize("query", INTROSPECTION)
def test_catalog_introspection_runs(db, query):
    before = hashlib.sha256(db.read_bytes()).hexdigest()
    result = KnowledgeBase.open(db, read_only=True).sql(query)
    cells = {str(v) for row in result.rows for v in row}
    assert cells & {"objects", "name", "mass_g"}, (query, result.rows[:3])
    assert hashlib.sha256(db.read_bytes()).hexdigest() == before


@pytest.mark.parametrize("query", STILL_REFUSED)
def test_pragmas_beyond_introspection_stay_refused(db, query):
    with pytest.raises(QueryRefused) as err:
        KnowledgeBase.open(db, read_only=True).sql(query)
    assert str(db.parent) not in str(err.value)


def test_a_refused_pragma_names_the_ones_that_run(db):
    with pytest.raises(QueryRefused, match=r"only the PRAGMAs that describe the catalog's tables run \(table_info"):
        KnowledgeBase.open(db, read_only=True).sql("PRAGMA database_list")


@pytest.mark.parametrize(("query", "path"), FILE_READS)
def test_every_file_read_gets_the_sandboxs_message_naming_it(db, query, path):
    with pytest.raises(QueryRefused) as err:
        KnowledgeBase.open(db, read_only=True).sql(query)
    message = str(err.value)
    assert "reading files is not allowed" in message and repr(path) in message, message
    assert "Catalog Error" not in message and "Permission Error" not in message, message


@pytest.mark.parametrize(
    "query", ["COPY objects TO '/tmp/leak.csv'", "COPY (select * from objects) TO '/tmp/leak.csv'",
              "EXPORT DATABASE '/tmp/export'"],
)
def test_a_file_write_is_named_as_one(db, query):
    with pytest.raises(QueryRefused, match=r"writing files is not allowed \('/tmp/"):
        KnowledgeBase.open(db, read_only=True).sql(query)


def test_an_extensions_function_is_refused_naming_it(db):
    with pytest.raises(QueryRefused, match=r"sqlite_scan\(\) is in DuckDB's sqlite_scanner extension"):
        KnowledgeBase.open(db, read_only=True).sql("select * from sqlite_scan('/tmp/x.db', 't')")


def test_a_misspelled_table_is_a_query_error_with_duckdbs_hint_not_a_file(db):
    """The boundary of the path rule: a missing table whose name is no path ('objcts', even quoted) is
    DuckDB's catalog error, with its hint; one with a path character or a file extension is a file."""
    kb = KnowledgeBase.open(db, read_only=True)
    for query in ("select * from objcts", "select * from 'objcts'"):
        with pytest.raises(QueryFailed, match=r'does not exist! \(Did you mean "objects"\?\)') as err:
            kb.sql(query)
        assert not isinstance(err.value, QueryRefused)
    for query in ("select * from 'objcts.csv'", "select * from 'a/objcts'"):
        with pytest.raises(QueryRefused, match="reading files is not allowed"):
            kb.sql(query)
    with pytest.raises(QueryFailed, match=r'Candidate bindings: "name"'):
        kb.sql("select nme from objects")


def test_the_cli_and_http_faces_say_the_same(db):
    runner = CliRunner()
    ok = runner.invoke(app, ["sql", "select name from pragma_table_info('objects')", "--db", str(db), "--json"])
    assert ok.exit_code == 0 and '"name": "mass_g"' in ok.output, ok.output
    bad = runner.invoke(app, ["sql", "select * from '/etc/passwd'", "--db", str(db)])
    assert bad.exit_code == 1 and "reading files is not allowed ('/etc/passwd')" in bad.output, bad.output
    client = TestClient(create_app(db, token=""), raise_server_exceptions=False, base_url="http://127.0.0.1")
    r = client.post("/sql", json={"query": "SHOW TABLES"})
    rows = r.json()["rows"] if r.status_code == 200 else []
    assert any("objects" in (row.values() if isinstance(row, dict) else row) for row in rows), r.text
    r = client.post("/sql", json={"query": "select * from '/etc/passwd'"})
    assert r.status_code == 400 and "reading files is not allowed ('/etc/passwd')" in r.json()["detail"], r.text
