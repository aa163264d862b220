"""The SQL sandbox's error text (kb/sandbox.py, ``objrecall sql``, ``POST /sql``): limits refused in the
names the caller used (``--max-rows``, ``--timeout``; ``max_rows``, ``timeout_s``), a refused statement named
by the word the user wrote (INSTALL, not DuckDB's type LOAD), and a write hidden in a SELECT refused in
the sandbox's own words, never DuckDB's text."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.errors import QueryFailed, QueryRefused
from kb.sandbox import MAX_ROWS, MAX_TIMEOUT_S
from kb.service.cli import app
from kb.service.http import create_app

LOCAL = {"raise_server_exceptions": False, "base_url": "http://127.0.0.1"}

#: Writes inside a SELECT: DuckDB types each statement SELECT, and its read-only connection stops it.
HIDDEN_WRITES = [
    ("with x as (delete from objects returning *) select * from x", "DELETE"),
    ("with x as (insert into objects (name) values ('evil') returning *) select * from x", "INSERT"),
    ("with x as (update objects set name = 'evil' returning name) select * from x", "UPDATE"),
    # the first write word outside string literals and quoted names: DELETE, not the literal 'update'
    (
        'with "update" as (delete from objects where name = \'update\' returning *) select count(*) from "update"',
        "DELETE",
    ),
]
#: Statements whose DuckDB type is not the word the user wrote.
NAMED_BY_THEIR_WORD = [
    ("install httpfs", "INSTALL"),
    ("FORCE INSTALL httpfs", "FORCE INSTALL"),
    ("/* a comment */ -- and another\n  Install httpfs", "INSTALL"),
    ("LOAD httpfs", "LOAD"),
    ("RESET memory_limit", "RESET"),
    ("TRUNCATE objects", "TRUNCATE"),
    ("UPDATE EXTENSIONS", "UPDATE EXTENSIONS"),
]


def _cli(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


@pytest.fixture(scope="module")
def db(tmp_path_factory):
    from kb.service.bootstrap import seed_catalog_path

    path = tmp_path_factory.mktemp("sqlerr") / "sandboxed-file.duckdb"  # its name must not leak
    KnowledgeBase.open(path).import_csv(seed_catalog_path())
    return path


@pytest.mark.parametrize(("query", "word"), NAMED_BY_THEIR_WORD)
def test_a_refused_statement_is_named_by_the_users_word(db, query, word):
    with pytest.raises(QueryRefused) as err:
        KnowledgeBase.open(db, read_only=True).sql(query)
    assert f"refused: {word} statements are not allowed" in str(err.value)
    assert "LOAD statements" not in str(err.value) or word == "LOAD"


def test_a_write_inside_a_with_is_not_named_with_but_by_its_type(db):
    with pytest.raises(QueryRefused, match="refused: INSERT statements are not allowed"):
        KnowledgeBase.open(db, read_only=True).sql(
            "with x as (select 1) insert into objects (name) select 'e'"
        )


@pytest.mark.parametrize(("query", "word"), HIDDEN_WRITES)
def test_a_write_hidden_in_a_select_gets_the_sandboxs_own_refusal(db, query, word):
    kb = KnowledgeBase.open(db, read_only=True)
    before = kb.count_objects()
    with pytest.raises(QueryRefused) as err:
        kb.sql(query)
    message = str(err.value)
    assert (
        message
        == f"refused: the query writes ({word} inside the query); the catalog is read-only (SELECT only)"
    )
    assert "Cannot execute" not in message and db.stem not in message  # DuckDB's text named the file
    assert kb.count_objects() == before


def test_the_library_names_its_parameters_and_never_leaks_a_type_error(db):
    kb = KnowledgeBase.open(db, read_only=True)
    for kwargs, words in [
        ({"max_rows": 10**20}, f"max_rows must be from 1 to {MAX_ROWS:,}"),
        ({"max_rows": MAX_ROWS + 1}, "max_rows must be from 1"),
        ({"max_rows": 0}, "max_rows must be from 1"),
        ({"timeout_s": -1}, "timeout_s must be more than 0"),
        ({"timeout_s": MAX_TIMEOUT_S * 2}, "timeout_s must be more than 0"),
    ]:
        with pytest.raises(QueryFailed, match=words):
            kb.sql("select 1", **kwargs)
    assert kb.sql("select 1 as one", max_rows=MAX_ROWS).rows == [(1,)]  # the limit itself is accepted


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (
            ["--max-rows", "99999999999999999999"],
            "--max-rows must be from 1 to 100,000,000, got 99999999999999999999",
        ),
        (["--max-rows", "0"], "--max-rows must be from 1"),
        (["--max-rows", str(MAX_ROWS + 1)], "--max-rows must be from 1"),
        (["--timeout", "-1"], "--timeout must be more than 0 and at most 86400 seconds, got -1"),
        (["--timeout", "0"], "--timeout must be more than 0"),
        (["--timeout", "nan"], "--timeout must be more than 0"),
        (["--timeout", str(MAX_TIMEOUT_S + 1)], "--timeout must be more than 0"),
    ],
)
def test_the_cli_names_its_options(db, args, words):
    res = _cli("sql", "select 1", "--db", db, *args)
    assert res.exit_code == 1, res.output
    assert words in res.output
    assert "TypeError" not in res.output and "timeout_s" not in res.output and "max_rows" not in res.output


def test_the_cli_accepts_the_limits_themselves(db):
    res = _cli(
        "sql", "select 1 as one", "--db", db, "--max-rows", MAX_ROWS, "--timeout", MAX_TIMEOUT_S, "--json"
    )
    assert res.exit_code == 0, res.output


def test_http_names_the_json_fields_and_refuses_like_the_library(db):
    client = TestClient(create_app(db, token=""), **LOCAL)
    for body, field in [({"max_rows": 99999999999999999999}, "max_rows"), ({"timeout_s": -1}, "timeout_s")]:
        r = client.post("/sql", json={"query": "select 1", **body})
        assert r.status_code == 422 and r.json()["detail"].startswith(field), r.text
    r = client.post("/sql", json={"query": "install httpfs"})
    assert r.status_code == 400 and "INSTALL statements are not allowed" in r.json()["detail"], r.text
    r = client.post("/sql", json={"query": HIDDEN_WRITES[0][0]})
    assert r.status_code == 400 and r.json()["detail"].startswith("refused: the query writes (DELETE"), r.text
