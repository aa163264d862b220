"""`objrecall recall --lookup`, `POST /recall/lookup` and the web page's "look it up" box, against the demo
store over real HTTP on 127.0.0.1 and a real DuckDB catalog."""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import httpx
import pytest
from conftest import SEED_CSV
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.service.cli import app as cli_app
from kb.service.http import create_app, serve_subprocess
from scrapers.demo_store import DemoStore

TEAPOT = "A glazed ceramic teapot about 22 cm wide and 14 cm tall, it weighs around 900 grams."
TEAPOT_NAME = "glazed ceramic teapot 1.2 l"
TOKEN = "lookup-test-token"
runner = CliRunner()


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None) as s:
        yield s


@pytest.fixture
def sources_file(tmp_path, store) -> Path:
    path = tmp_path / "stores.toml"
    path.write_text(
        f'[defaults]\ndelay_s = 0\n[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\n'
        'search = "{base_url}/search?q={query}"\n'
    )
    return path


@pytest.fixture
def db(tmp_path) -> Path:
    path = tmp_path / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(SEED_CSV)
    return path


def cli(*args):
    return runner.invoke(cli_app, [str(a) for a in args])


def test_cli_lookup_json_finds_the_teapot(db, sources_file):
    res = cli("recall", TEAPOT, "--lookup", "--sources", sources_file, "--db", db, "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["looked_up"] and out["found"] and out["result"]["matches"][0]["name"] == TEAPOT_NAME
    assert out["stores"]["new_objects"] == [TEAPOT_NAME] and out["before"]["match"] != TEAPOT_NAME


def test_cli_lookup_says_what_it_did(db, sources_file):
    res = cli("recall", "a purple velvet hippo 40 cm long", "--lookup", "--sources", sources_file, "--db", db)
    assert res.exit_code == 0, res.output
    said = " ".join(res.stdout.split())  # rich wraps long lines
    assert "no close match in the catalog, and none found in the stores" in said and "store demo: no_results" in said
    res = cli("recall", TEAPOT, "--lookup", "--sources", sources_file, "--db", db)
    said = " ".join(res.stdout.split())
    assert "added from 1 of 1 store(s)" in said and "-> added" in said


def test_cli_base_url_override_and_env_sources(db, sources_file, store, monkeypatch):
    monkeypatch.setenv("OBJRECALL_SOURCES", str(sources_file))
    res = cli("recall", TEAPOT, "--lookup", "--db", db, "--json")
    assert json.loads(res.stdout)["found"]
    res = cli("recall", TEAPOT, "--force-lookup", "--base-url", "http://127.0.0.1:9", "--db", db, "--json",
              "--budget", "2")  # fmt: skip
    out = json.loads(res.stdout)
    assert out["looked_up"] and out["why"] == "forced" and not out["found"]
    assert "no store answered" in out["message"]


def test_cli_refuses_absurd_budgets(db, sources_file):
    res = cli("recall", TEAPOT, "--lookup", "--sources", sources_file, "--db", db, "--budget", "0")
    assert res.exit_code == 1 and "time budget" in res.output


def test_http_lookup_needs_the_token_and_finds_the_teapot(db, sources_file):
    client = TestClient(create_app(db, token=TOKEN, sources=sources_file), raise_server_exceptions=False, base_url="http://127.0.0.1")
    assert client.post("/recall/lookup", json={"text": TEAPOT}).status_code == 401
    res = client.post("/recall/lookup", json={"text": TEAPOT}, headers={"Authorization": f"Bearer {TOKEN}"})
    assert res.status_code == 200, res.text
    body = res.json()
    assert body["found"] and body["result"]["matches"][0]["name"] == TEAPOT_NAME
    # the plain recall sees it now
    assert client.post("/recall", json={"text": TEAPOT}).json()["matches"][0]["name"] == TEAPOT_NAME
    bad = client.post("/recall/lookup", json={"text": TEAPOT, "budget_s": 0}, headers={"Authorization": f"Bearer {TOKEN}"})
    assert bad.status_code == 422


def test_http_lookup_without_sources_says_so(db):
    client = TestClient(create_app(db, token=TOKEN, sources=None), raise_server_exceptions=False, base_url="http://127.0.0.1")
    res = client.post("/recall/lookup", json={"text": TEAPOT}, headers={"Authorization": f"Bearer {TOKEN}"})
    assert res.status_code >= 400 and "no sources file" in res.json()["detail"]


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (apt-get install chromium)")
def test_web_page_looks_it_up(db, sources_file):
    from test_webpage import browser_at

    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
           "OBJRECALL_API_TOKEN": TOKEN}  # fmt: skip
    env.pop("OBJRECALL_API_TOKEN_FILE", None)
    args = ["--log-level", "warning", "--sources", str(sources_file)]
    with serve_subprocess(db, env=env, extra_args=args) as base:
        httpx.post(f"{base}/recall", json={"text": "warm up: a mug"}, timeout=120)
        with browser_at(f"{base}/") as tools:
            tools.eval(
                f"document.getElementById('q').value = {json.dumps(TEAPOT)};"
                "document.getElementById('lookup').checked = true;"
                f"document.getElementById('token').value = {json.dumps(TOKEN)};"
                "document.getElementById('recall-button').click()"
            )
            top = tools.wait_for("(document.getElementById('top-match') || {}).textContent")
            assert top == TEAPOT_NAME
            summary = tools.eval("document.getElementById('lookup-summary').textContent")
            assert summary.startswith("Lookup: added from 1 of 1 store(s)")


def test_cli_lookup_of_a_file_gives_one_json_line_per_description(db, sources_file, tmp_path):
    csv_file = tmp_path / "d.csv"
    csv_file.write_text(f'description\n"{TEAPOT}"\n"a tennis ball, 6.7 cm across, 58 g"\n')
    res = cli("recall", "--file", csv_file, "--lookup", "--sources", sources_file, "--db", db, "--json")
    assert res.exit_code == 0, res.output
    first, second = (json.loads(line) for line in res.stdout.splitlines())
    assert first["looked_up"] and first["found"] and first["result"]["matches"][0]["name"] == TEAPOT_NAME
    assert not second["looked_up"] and second["result"]["matches"][0]["name"] == "tennis ball"
