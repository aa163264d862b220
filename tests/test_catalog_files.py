"""A catalog file that is missing, damaged or no DuckDB database, and a --db in a folder that does not exist:
one message per case, naming the file and the reason, for every command and for the service (robustness
review, findings 3 and 5). Files written here."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.catalog_check import CatalogWatch, check_catalog
from kb.errors import CatalogMissing, CatalogUnreadable, FolderMissing
from kb.service.cli import app
from kb.service.http import create_app

runner = CliRunner()
READERS = (["recall", "a mug"], ["catalog", "list"], ["catalog", "show", "mug"], ["catalog", "summary"],
           ["sql", "select 1"], ["grasp", "validate", "mug"], ["catalog", "export", "-"])  # fmt: skip


def _damaged(tmp_path, kind: str):
    path = tmp_path / f"{kind}.duckdb"
    if kind == "text":
        path.write_text("name,a_cm\nmug,10\n")
    elif kind == "random":
        path.write_bytes(bytes(range(256)) * 80)
    else:  # a real catalog cut short
        good = tmp_path / "good.duckdb"
        assert runner.invoke(app, ["init", "--seed", "--db", str(good)]).exit_code == 0
        shutil.copy(good, path)
        with open(path, "r+b") as f:
            f.truncate(100_000)  # past the header, short of the blocks it lists
    return path


@pytest.mark.parametrize("kind", ["text", "random", "truncated"])
def test_every_command_names_a_damaged_file_and_why(tmp_path, kind) -> None:
    path = _damaged(tmp_path, kind)
    before = path.read_bytes()
    for args in (["init"], *READERS):
        res = runner.invoke(app, [*args, "--db", str(path)])
        assert res.exit_code == 1, (args, res.output)
        line = res.stderr.strip()
        assert line.count("\n") == 0 and path.name in line, (args, line)
        assert "sqlalche" not in line and "(_duckdb" not in line and "Background on this error" not in line
        if args[0] != "sql":  # the SQL worker masks the folder
            assert f"{path}: not a usable objrecall catalog" in line, (args, line)
    assert path.read_bytes() == before  # nothing written


def test_a_missing_catalog_is_one_message_for_every_command(tmp_path) -> None:
    path = tmp_path / "absent.duckdb"
    expected = str(CatalogMissing(path))
    for args in READERS:
        res = runner.invoke(app, [*args, "--db", str(path)])
        assert res.exit_code == 1 and res.stderr.strip() == f"Error: {expected}", (args, res.stderr)
    assert not path.exists()


def test_init_refuses_a_missing_folder_and_creates_nothing(tmp_path) -> None:
    path = tmp_path / "typo" / "dir" / "x.duckdb"
    res = runner.invoke(app, ["init", "--db", str(path)])
    assert res.exit_code == 1 and str(tmp_path / "typo" / "dir") in res.stderr and "does not exist" in res.stderr
    assert not (tmp_path / "typo").exists()
    with pytest.raises(FolderMissing):
        KnowledgeBase.open(path)
    (tmp_path / "typo" / "dir").mkdir(parents=True)  # the folder exists: the file is created
    assert runner.invoke(app, ["init", "--db", str(path)]).exit_code == 0 and path.exists()


def test_the_default_data_folder_is_still_made_on_first_use(tmp_path, monkeypatch) -> None:
    monkeypatch.delenv("OBJRECALL_DB", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    assert runner.invoke(app, ["init"]).exit_code == 0
    assert (tmp_path / "data" / "objrecall" / "catalog.duckdb").exists()


def test_check_catalog_and_the_watch(tmp_path) -> None:
    with pytest.raises(CatalogMissing):
        check_catalog(tmp_path / "none.duckdb")
    bad = _damaged(tmp_path, "random")
    with pytest.raises(CatalogUnreadable, match="not a valid DuckDB database"):
        check_catalog(bad)
    import duckdb

    other = tmp_path / "other.duckdb"  # a DuckDB file, but no catalog
    duckdb.connect(str(other)).close()
    with pytest.raises(CatalogUnreadable, match="objects"):
        check_catalog(other)
    watch = CatalogWatch(tmp_path / "later.duckdb")
    assert watch.state().state == "missing"
    assert runner.invoke(app, ["init", "--seed", "--db", str(tmp_path / "later.duckdb")]).exit_code == 0
    assert watch.state().state == "ok"  # the file changed: checked again


def test_serve_refuses_to_start_on_a_damaged_catalog(tmp_path, cli_env) -> None:
    path = _damaged(tmp_path, "random")
    proc = subprocess.run([sys.executable, "-m", "kb.service.cli", "serve", "--db", str(path), "--port", "1"],
                          capture_output=True, text=True, env=cli_env, timeout=120)  # fmt: skip
    assert proc.returncode == 1 and proc.stdout == ""
    assert proc.stderr.startswith(f"Error: {path}: not a usable objrecall catalog") and proc.stderr.count("\n") == 1


def test_health_reports_the_catalog_state(tmp_path) -> None:
    path = tmp_path / "c.duckdb"
    assert runner.invoke(app, ["init", "--seed", "--db", str(path)]).exit_code == 0
    client = TestClient(create_app(path, token=""), raise_server_exceptions=False, base_url="http://127.0.0.1")
    assert client.get("/health").json()["catalog_state"] == "ok"
    path.write_bytes(bytes(range(256)) * 80)  # damaged while serving
    health = client.get("/health")
    assert health.status_code == 200 and health.json()["status"] == "degraded"
    assert health.json()["catalog_state"] == "unreadable" and str(path) in health.json()["catalog_error"]
    res = client.post("/recall", json={"text": "a mug"})
    assert res.status_code == 503 and "not a usable objrecall catalog" in res.json()["detail"], res.text
