"""An ingestion run that read nothing because of failures (every store down) is ``failed`` and
``objrecall ingest`` exits 3, so a nightly job detects the outage (a blind test found it exiting 0 as
ok_with_errors with 0 pages fetched); a run that read some pages despite failures stays ok_with_errors."""

from __future__ import annotations

import json
import socket
from datetime import UTC, datetime
from pathlib import Path

import duckdb
from hostile_store import HostileStore
from typer.testing import CliRunner

from kb.service.cli import app
from scrapers.ingest import EXIT_CODES, run_status
from scrapers.outcomes import IngestionReport

runner = CliRunner()
EVENT = [("http://127.0.0.1:1/sitemap.xml", "discover", "connection_failed")]


def _report(**counts) -> IngestionReport:
    return IngestionReport(run_id=None, status="ok", sources="s", started_at=datetime.now(UTC), **counts)


def test_nothing_read_because_of_failures_is_failed() -> None:
    assert run_status(_report(), EVENT) == "failed"
    assert run_status(_report(pages=3, rejected=3), []) == "failed"  # every page's fetch failed


def test_one_page_read_or_confirmed_unchanged_despite_failures_is_ok_with_errors() -> None:
    assert run_status(_report(fetched=1), EVENT) == "ok_with_errors"
    assert run_status(_report(not_modified=1), EVENT) == "ok_with_errors"


def test_no_failure_is_ok_even_with_nothing_to_read() -> None:
    assert run_status(_report(), []) == "ok" and run_status(_report(fetched=2), []) == "ok"


def test_only_a_failed_run_exits_non_zero() -> None:
    assert EXIT_CODES == {"ok": 0, "ok_with_errors": 0, "failed": 3}


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _sources(tmp_path: Path, base_url: str) -> Path:
    path = tmp_path / "stores.toml"
    path.write_text(
        "[defaults]\ndelay_s = 0\nread_timeout_s = 2.0\nconnect_timeout_s = 1\nmax_retries = 0\n"
        f'[[stores]]\nname = "shop"\nbase_url = "{base_url}"\nsitemaps = ["{{base_url}}/sitemap.xml"]\n'
    )
    return path


def _ingest(tmp_path: Path, base_url: str):
    db = tmp_path / "catalog.duckdb"
    result = runner.invoke(
        app, ["ingest", "--sources", str(_sources(tmp_path, base_url)), "--db", str(db), "--json"]
    )
    with duckdb.connect(str(db), read_only=True) as con:
        (status,) = con.execute("SELECT status FROM ingestion_runs").fetchone()
    return result, status


def test_an_unreachable_store_fails_the_run_with_exit_code_3(tmp_path: Path) -> None:
    result, status = _ingest(tmp_path, f"http://127.0.0.1:{_closed_port()}")
    assert result.exit_code == 3 and status == "failed"
    report = json.loads(result.stdout)
    assert report["status"] == "failed" and report["fetched"] == 0 and report["errors"]


def test_a_reachable_store_exits_0(tmp_path: Path) -> None:
    with HostileStore() as store:
        result, status = _ingest(tmp_path, store.base_url)
    assert result.exit_code == 0 and status == "ok"
