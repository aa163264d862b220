"""Ingestion jobs the service starts (``POST /ingestion/runs``): one ``objrecall ingest`` child process at a
time, its log kept for status queries.

Where the logs go: a folder the service is given (``objrecall serve --ingest-log-dir``,
``$OBJRECALL_INGEST_LOG_DIR``), kept after the service stops; or, by default, a private temporary folder
(``objrecall-ingest-logs-*``) made when the first job starts and removed when the service shuts down
(:meth:`IngestionJobs.close`, or when the jobs object is collected or the interpreter exits).
"""

from __future__ import annotations

import secrets
import shutil
import subprocess
import sys
import tempfile
import threading
import weakref
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from kb.errors import IngestionBusy, JobNotFound

__all__ = ["IngestionJob", "IngestionJobs", "objrecall_command"]


def objrecall_command() -> list[str]:
    """How to run ``objrecall`` from here: the console script beside this interpreter, else ``-m kb.service.cli``."""
    script = Path(sys.executable).parent / "objrecall"
    if script.exists():
        return [str(script)]
    found = shutil.which("objrecall")
    return [found] if found else [sys.executable, "-m", "kb.service.cli"]


@dataclass
class IngestionJob:
    """An ``objrecall ingest`` child process started by ``POST /ingestion/runs``."""

    id: str
    command: list[str]
    started_at: str
    process: subprocess.Popen | None = None
    log_path: Path | None = None
    returncode: int | None = None
    finished_at: str | None = None

    @property
    def status(self) -> str:
        if self.returncode is None:
            return "running"
        return "succeeded" if self.returncode == 0 else "failed"

    def to_dict(self) -> dict[str, Any]:
        log = ""
        if self.log_path is not None and self.log_path.exists():
            log = self.log_path.read_text(encoding="utf-8", errors="replace")[-4000:]
        return {
            "id": self.id,
            "status": self.status,
            "command": self.command,
            "started_at": self.started_at,
            "finished_at": self.finished_at,
            "returncode": self.returncode,
            "log_tail": log,
        }


class IngestionJobs:
    """At most one ingestion child process at a time; finished jobs are kept for status queries."""

    def __init__(self, log_dir: Path | None = None):
        """``log_dir``: where the logs go, kept; None: a temporary folder removed by :meth:`close`."""
        self.log_dir = log_dir
        self.jobs: dict[str, IngestionJob] = {}
        self._lock = threading.Lock()
        self._cleanup: weakref.finalize | None = None

    def _logs(self) -> Path:
        """The log folder, made on first use (a private temporary one when none was given)."""
        if self.log_dir is None:
            self.log_dir = Path(tempfile.mkdtemp(prefix="objrecall-ingest-logs-"))
            self._cleanup = weakref.finalize(self, shutil.rmtree, self.log_dir, True)
        self.log_dir.mkdir(parents=True, exist_ok=True)
        return self.log_dir

    def close(self, timeout: float = 10.0) -> None:
        """Stop a running job (its one write transaction rolls back if open), and remove the temporary log
        folder, if this object made one (a folder given to it is kept)."""
        job = self.running()
        if job is not None and job.process is not None:
            job.process.terminate()
            try:
                job.process.wait(timeout)
            except subprocess.TimeoutExpired:
                job.process.kill()
                job.process.wait()
        if self._cleanup is not None:
            self._cleanup()

    def running(self) -> IngestionJob | None:
        return next((j for j in self.jobs.values() if j.returncode is None), None)

    def start(self, command: list[str]) -> IngestionJob:
        with self._lock:
            busy = self.running()
            if busy is not None:
                raise IngestionBusy(
                    f"ingestion job {busy.id} is still running; try again when it has finished"
                )
            job_id = secrets.token_hex(6)
            log_path = self._logs() / f"ingest-{job_id}.log"
            job = IngestionJob(id=job_id, command=command, started_at=_now(), log_path=log_path)
            with log_path.open("wb") as log:
                job.process = subprocess.Popen(
                    command, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL
                )
            self.jobs[job_id] = job
        threading.Thread(target=self._reap, args=(job,), daemon=True).start()
        return job

    def _reap(self, job: IngestionJob) -> None:
        assert job.process is not None
        rc = job.process.wait()
        job.finished_at = _now()
        job.returncode = rc

    def get(self, job_id: str) -> IngestionJob:
        job = self.jobs.get(job_id)
        if job is None:
            raise JobNotFound(f"no ingestion job {job_id!r} started by this service")
        return job


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")
