"""One description length limit (recall.descriptions.MAX_DESCRIPTION_CHARS), held by the recall API and so by
every face with the same one-line error: the Python API (parse, Recaller.recall_text), the CLI (recall,
parse, grasp plan) and the HTTP service (/parse, /recall, /grasp/plan). Texts written here."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from kb.errors import DescriptionError
from kb.service.cli import app
from kb.service.http import create_app
from kb.service.http.settings import MAX_TEXT_CHARS
from recall.descriptions import MAX_DESCRIPTION_CHARS
from recall.engine import Recaller
from recall.parser import parse

LIMIT = MAX_DESCRIPTION_CHARS
AT = ("a red mug " * (LIMIT // 10 + 1))[:LIMIT]
PAST = AT + "x"
MESSAGE = f"description too long: {LIMIT + 1:,} characters (at most {LIMIT:,})"


@pytest.fixture(scope="module")
def db(tmp_path_factory):
    path = tmp_path_factory.mktemp("limit") / "seed.duckdb"
    assert CliRunner().invoke(app, ["init", "--seed", "--db", str(path)]).exit_code == 0
    return path


def test_the_limit_is_one_constant() -> None:
    assert LIMIT == MAX_TEXT_CHARS == 5_000 and len(AT) == LIMIT


def test_python_api_reads_the_limit_and_refuses_one_more(db) -> None:
    assert parse(AT).values()  # at the limit: parsed
    recaller = Recaller.from_db(db)
    assert recaller.recall_text(AT).matches
    for call in (parse, recaller.recall_text):
        with pytest.raises(DescriptionError) as err:
            call(PAST)
        assert str(err.value) == MESSAGE


@pytest.mark.parametrize("command", [["recall"], ["parse"], ["grasp", "plan"]])
def test_cli_gives_the_same_one_line_error(db, command) -> None:
    res = CliRunner().invoke(app, [*command, PAST, "--db", str(db)] if command != ["parse"] else ["parse", PAST])
    assert res.exit_code == 1, res.output
    assert MESSAGE in res.output and len(res.output.strip().splitlines()) == 1
    ok = CliRunner().invoke(app, [*command, AT, "--db", str(db)] if command != ["parse"] else ["parse", AT])
    assert ok.exit_code == 0, ok.output


@pytest.mark.parametrize("path", ["/parse", "/recall", "/grasp/plan"])
def test_http_gives_the_same_error(db, path) -> None:
    client = TestClient(create_app(db, token=""), raise_server_exceptions=False, base_url="http://127.0.0.1")
    res = client.post(path, json={"text": PAST})
    assert res.status_code == 400 and res.json()["detail"] == MESSAGE, res.text
    assert client.post(path, json={"text": AT}).status_code == 200
