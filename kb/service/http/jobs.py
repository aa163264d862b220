"""Ingestion jobs the service starts (``POST /ingestion/runs``): one ``objrecall ingest`` child process at a
time, its log kept for status queries."""

from __future__ import annotations

import secrets
import shutil
import subprocess
import sys
import threading
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

    def __init__(self, log_dir: Path):
        self.log_dir = log_dir
        self.jobs: dict[str, IngestionJob] = {}
        self._lock = threading.Lock()

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
            self.log_dir.mkdir(parents=True, exist_ok=True)
            log_path = self.log_dir / f"ingest-{job_id}.log"
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
