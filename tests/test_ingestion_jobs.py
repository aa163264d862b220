"""Ingestion jobs started by the service: where their logs go, and that the service's own temporary log
folder is removed when it shuts down (a folder it was given is kept)."""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from kb.service.http import create_app
from kb.service.http.jobs import IngestionJobs

TOKEN = "jobs-token"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
#: Stands in for `objrecall`: prints its arguments ("ingest --sources ... --db ...") and exits.
FAKE_OBJRECALL = [sys.executable, "-c", "import sys; print('fake', *sys.argv[1:])"]


def _wait(job, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while job.returncode is None:
        assert time.monotonic() < deadline, "the job did not finish"
        time.sleep(0.02)


def test_the_default_log_folder_is_made_on_the_first_job_and_removed_on_close():
    jobs = IngestionJobs()
    assert jobs.log_dir is None  # nothing made before a job starts
    job = jobs.start([*FAKE_OBJRECALL, "ingest"])
    _wait(job)
    folder = jobs.log_dir
    assert folder is not None and folder.is_dir()
    assert folder.parent == Path(tempfile.gettempdir()) and folder.name.startswith("objrecall-ingest-logs-")
    assert "fake ingest" in job.to_dict()["log_tail"]
    jobs.close()
    assert not folder.exists()
    jobs.close()  # twice is harmless


def test_a_given_log_folder_is_used_and_kept(tmp_path):
    jobs = IngestionJobs(tmp_path / "logs")
    _wait(jobs.start([*FAKE_OBJRECALL, "ingest"]))
    jobs.close()
    (log,) = (tmp_path / "logs").iterdir()
    assert "fake ingest" in log.read_text()


def test_close_stops_a_running_job_first():
    jobs = IngestionJobs()
    job = jobs.start([sys.executable, "-c", "import time; time.sleep(60)"])
    folder = jobs.log_dir
    jobs.close()
    assert job.process is not None and job.process.poll() is not None
    assert folder is not None and not folder.exists()


def _app(tmp_path, **kwargs):
    sources = tmp_path / "sources.toml"
    sources.write_text("")
    return create_app(
        tmp_path / "catalog.duckdb", token=TOKEN, sources=sources, ingest_command=FAKE_OBJRECALL, **kwargs
    )


def _run_one_job(client) -> Path:
    started = client.post("/ingestion/runs", headers=AUTH)
    assert started.status_code == 202, started.text
    job = client.app.state.jobs.get(started.json()["id"])  # type: ignore[attr-defined]
    _wait(job)
    assert client.get(started.json()["status_url"]).json()["status"] == "succeeded"
    assert job.log_path is not None
    return job.log_path


def _client(app) -> TestClient:
    return TestClient(app, base_url="http://127.0.0.1")


@pytest.fixture(autouse=True)
def _no_configured_log_dir(monkeypatch):
    monkeypatch.delenv("OBJRECALL_INGEST_LOG_DIR", raising=False)


def test_the_service_removes_its_temporary_log_folder_on_shutdown(tmp_path):
    app = _app(tmp_path)
    with _client(app) as client:
        log = _run_one_job(client)
        assert log.exists() and "fake ingest --sources" in log.read_text()
    assert not log.parent.exists()


@pytest.mark.parametrize("how", ["argument", "environment"])
def test_the_service_keeps_logs_in_the_configured_folder(tmp_path, monkeypatch, how):
    folder = tmp_path / "ingest-logs"
    if how == "environment":
        monkeypatch.setenv("OBJRECALL_INGEST_LOG_DIR", str(folder))
        app = _app(tmp_path)
    else:
        app = _app(tmp_path, ingest_log_dir=folder)
    with _client(app) as client:
        log = _run_one_job(client)
    assert log.parent == folder and log.exists()
