"""Crash safety and the CLI: a real `objrecall ingest` subprocess, killed (SIGKILL) at several moments,
leaves the catalog as it was before the run or as it is after it, never in between."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import duckdb
import pytest

import kb
from kb.catalog import KnowledgeBase
from scrapers.demo_store import DemoStore
from scrapers.ingest import PAUSE_ENV

SEED_CSV = Path(kb.__file__).parent / "data" / "seed_catalog.csv"

pytestmark = [
    pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="needs POSIX signals"),
    pytest.mark.slow,
]

SOURCES = """
[defaults]
delay_s = 0
read_timeout_s = 1.0
max_retries = 1
backoff_s = 0
max_bytes = 2_000_000

[[stores]]
name = "demo"
base_url = "http://127.0.0.1:8765"
sitemaps = ["{base_url}/sitemap.xml"]
include = ["^/(p|dp|ikea|shop)/"]
exclude = ["slow", "flaky", "huge"]  # they test timeouts and retries (test_fetcher.py), not crash safety
"""


def snapshot(path: Path) -> tuple:
    """The catalog's content, without timestamps and run ids (which differ between equal runs)."""
    con = duckdb.connect(str(path), read_only=True)
    try:
        objects = con.execute(
            "SELECT name, a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity, source, gtin, "
            "canonical_url FROM objects ORDER BY name"
        ).fetchall()
        observations = con.execute(
            "SELECT o.name, feature, value_num, value_text, role, b.source, adapter FROM observations b "
            "JOIN objects o ON o.id = b.object_id ORDER BY ALL"
        ).fetchall()
        counts = con.execute(
            "SELECT (SELECT count(*) FROM ingestion_runs), (SELECT count(*) FROM pages), "
            "(SELECT count(*) FROM page_events)"
        ).fetchone()
    finally:
        con.close()
    return objects, observations, counts


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None, slow_s=2.5) as s:
        yield s


@pytest.fixture(scope="module")
def setup(store, tmp_path_factory):
    """A seeded catalog (before), the sources file, and the state after one complete CLI run (after)."""
    root = tmp_path_factory.mktemp("crash")
    before_db = root / "before.duckdb"
    KnowledgeBase.open(before_db).import_csv(SEED_CSV)
    sources = root / "sources.toml"
    sources.write_text(SOURCES)
    after_db = root / "after.duckdb"
    shutil.copy(before_db, after_db)
    started = time.monotonic()
    done = _ingest(after_db, sources, store)
    out, err = done.communicate(timeout=120)
    duration = time.monotonic() - started
    assert done.returncode == 0, err
    report = json.loads(out)
    assert report["new"] > 10 and report["run_id"] == 1
    return before_db, sources, snapshot(before_db), snapshot(after_db), duration, report


def _env(extra: dict[str, str] | None = None) -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env.update(extra or {})
    return env


def _ingest(db: Path, sources: Path, store: DemoStore, env: dict[str, str] | None = None) -> subprocess.Popen:
    exe = shutil.which("objrecall", path=_env()["PATH"])
    cmd = [exe] if exe else [sys.executable, "-m", "kb.service.cli"]
    return subprocess.Popen(
        [*cmd, "ingest", "--sources", str(sources), "--db", str(db), "--base-url", store.base_url, "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=_env(env),
    )


def test_cli_reports_the_run_as_json(setup):
    *_, report = setup
    assert report["status"] == "ok" and report["rejected_reasons"]["http_500"] == 1
    assert report["rejected_reasons"]["absurd_value"] == 1
    assert report["fetched"] > 0 and report["pages_per_s"] > 0


@pytest.mark.parametrize("fraction", [0.3, 0.7, 0.95])
def test_kill_at_any_moment_leaves_before_or_after(setup, store, tmp_path, fraction):
    before_db, sources, before, after, duration, _ = setup
    db = tmp_path / "killed.duckdb"
    shutil.copy(before_db, db)
    proc = _ingest(db, sources, store)
    time.sleep(duration * fraction)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    state = snapshot(db)
    assert state == before or state == after


def test_kill_inside_the_open_write_transaction_leaves_before_then_a_rerun_completes(setup, store, tmp_path):
    before_db, sources, before, after, *_ = setup
    db = tmp_path / "killed-in-tx.duckdb"
    shutil.copy(before_db, db)
    proc = _ingest(db, sources, store, env={PAUSE_ENV: "60"})
    deadline = time.monotonic() + 120
    line = ""
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        if "write transaction open" in line or not line:
            break
    assert "write transaction open" in line  # every row is written, only COMMIT is missing
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert snapshot(db) == before
    rerun = _ingest(db, sources, store)
    _, err = rerun.communicate(timeout=120)
    assert rerun.returncode == 0, err
    assert snapshot(db) == after


def test_bad_sources_file_is_one_clear_error(tmp_path, store):
    bad = tmp_path / "bad.toml"
    bad.write_text("[[stores]]\nname = 'x'\n")
    proc = _ingest(tmp_path / "x.duckdb", bad, store)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 1
    assert err.strip().splitlines()[-1].startswith("Error: ") and "missing base_url" in err
    assert "Traceback" not in err


@pytest.mark.parametrize("moment", ["crawling", "write transaction open"])
def test_ctrl_c_leaves_before_or_after_and_exits_130(setup, store, tmp_path, moment):
    """SIGINT (Ctrl-C) while crawling the slow loopback store, or with the write transaction open: the
    catalog is as before or as after the run (INGESTION.md: a run commits once), no traceback, and the
    exit code 130 (typer's for Ctrl-C). The run prints no line saying it was interrupted (left: report)."""
    before_db, sources, before, after, duration, _ = setup
    db = tmp_path / "interrupted.duckdb"
    shutil.copy(before_db, db)
    if moment == "crawling":
        seen = len(store.log)
        proc = _ingest(db, sources, store)
        deadline = time.monotonic() + 60  # crawling: the store has served this run's robots.txt and a page
        while len(store.log) < seen + 2 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.01)
        time.sleep(duration * 0.1)
    else:
        proc = _ingest(db, sources, store, env={PAUSE_ENV: "60"})
        while "write transaction open" not in (line := proc.stderr.readline()) and line:
            pass
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "Traceback" not in err, err
    state = snapshot(db)
    assert state == before or state == after
    if moment != "crawling":
        assert state == before  # the COMMIT never ran


def test_a_ctrl_c_python_drops_is_still_seen_and_the_handler_is_restored():
    """A KeyboardInterrupt swallowed on its way (as Python does inside a garbage-collector callback) still
    leaves its record, so `ingest` exits as interrupted; the previous SIGINT handler is back afterwards."""
    import os

    from kb.service.cli.ingest import interrupts_seen

    before = signal.getsignal(signal.SIGINT)
    with interrupts_seen() as seen:
        assert seen == []
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1)
        except KeyboardInterrupt:
            pass  # dropped, as in a GC callback
    assert seen == [signal.SIGINT]
    assert signal.getsignal(signal.SIGINT) is before
