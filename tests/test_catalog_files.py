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
    else:  # a real catalog cut short, or with a header block zeroed (its checksum fails)
        good = tmp_path / "good.duckdb"
        assert runner.invoke(app, ["init", "--seed", "--db", str(good)]).exit_code == 0
        shutil.copy(good, path)
        with open(path, "r+b") as f:
            if kind == "truncated":
                f.truncate(100_000)  # past the header, short of the blocks it lists
            else:
                f.seek(4096)
                f.write(bytes(8192))  # DuckDB: "Corrupt database file: computed checksum ... does not match"
    return path


#: Each kind of damage and the reason its message gives (DuckDB's words), for every command.
REASONS = {"text": "not a valid DuckDB database", "random": "not a valid DuckDB database",
           "truncated": "", "checksum": "Corrupt database file: computed checksum"}  # fmt: skip


@pytest.mark.parametrize("kind", list(REASONS))
def test_every_command_names_a_damaged_file_and_why(tmp_path, kind) -> None:
    path = _damaged(tmp_path, kind)
    before = path.read_bytes()
    for args in (["init"], *READERS):
        res = runner.invoke(app, [*args, "--db", str(path)])
        assert res.exit_code == 1, (args, res.output)
        line = res.stderr.strip()
        assert line.count("\n") == 0 and path.name in line, (args, line)
        assert "sqlalche" not in line and "(_duckdb" not in line and "Background on this error" not in line
        named = f"{path}: not a usable objrecall catalog: " if args[0] != "sql" else f"{path.name}: not a usable"
        assert named in line and REASONS[kind] in line.split("catalog: ", 1)[-1], (args, line)  # the SQL worker
        assert line.split("catalog: ", 1)[-1].strip(), (args, line)  # masks the folder; a reason, not only the file
    assert path.read_bytes() == before  # nothing written


def test_a_duckdb_file_without_the_catalogs_tables_is_named_with_the_reason(tmp_path) -> None:
    import duckdb

    other = tmp_path / "other.duckdb"
    duckdb.connect(str(other)).execute("CREATE TABLE t (x INT)").close()
    for args in (["recall", "a mug"], ["catalog", "list"], ["catalog", "show", "mug"]):
        res = runner.invoke(app, [*args, "--db", str(other)])
        assert res.exit_code == 1, res.output
        assert res.stderr.strip().startswith(f"Error: {other}: not a usable objrecall catalog: Catalog Error: Table"), (
            args, res.stderr)


def test_one_unwrapping_serves_migrations_and_reasons(tmp_path) -> None:
    """kb.connections.innermost_error follows every wrapper (SQLAlchemy's ``orig``, ``raise ... from``) to the
    driver's error; the migration (init) and the reason both use it, so a damaged file under Alembic's and
    SQLAlchemy's wrappers is CatalogUnreadable with DuckDB's reason, never a failed migration."""
    import duckdb

    from kb.connections import database_reason, innermost_error, is_unreadable_file
    from kb.errors import MigrationError
    from kb.migrate import upgrade

    driver = duckdb.IOException("IO Error: damaged")
    wrapped = RuntimeError("(sqlalchemy) wrapper")
    wrapped.orig = driver
    try:
        try:
            raise wrapped
        except RuntimeError as inner:
            raise MigrationError("migration failed") from inner
    except MigrationError as outer:
        assert innermost_error(outer) is driver and is_unreadable_file(outer)  # two levels down
        assert database_reason(outer) == "IO Error: damaged"
    assert not is_unreadable_file(duckdb.IOException('Could not set lock on file "x": Conflicting lock'))
    for kind in ("text", "checksum"):
        with pytest.raises(CatalogUnreadable, match=REASONS[kind]):
            upgrade(_damaged(tmp_path, kind))


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
