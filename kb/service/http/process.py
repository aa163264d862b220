"""Running the service in a child process on loopback (tests, benchmarks, demos)."""

from __future__ import annotations

import socket
import subprocess
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from kb.service.http.jobs import objrecall_command

__all__ = ["free_port", "serve_subprocess", "stop_process"]


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port free on ``host`` right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((host, 0))
        return s.getsockname()[1]


@contextmanager
def serve_subprocess(
    db: str | Path,
    *,
    port: int | None = None,
    env: dict[str, str] | None = None,
    extra_args: list[str] | None = None,
    startup_timeout: float = 60.0,
) -> Iterator[str]:
    """Run ``objrecall serve --db DB`` on 127.0.0.1 in a child process and yield its base URL once
    ``/health`` answers (for tests, benchmarks and demos); the child is stopped on exit."""
    import httpx

    port = port or free_port()
    command = [*objrecall_command(), "serve", "--host", "127.0.0.1", "--port", str(port), "--db", str(db)]
    log = tempfile.TemporaryFile()
    proc = subprocess.Popen(
        [*command, *(extra_args or [])],
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
        stdin=subprocess.DEVNULL,
    )
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + startup_timeout
        while True:
            if proc.poll() is not None:
                log.seek(0)
                raise RuntimeError(
                    f"objrecall serve exited with {proc.returncode}: {log.read().decode()[-2000:]}"
                )
            try:
                if httpx.get(f"{base}/health", timeout=1.0).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if time.monotonic() > deadline:
                raise RuntimeError(f"objrecall serve did not answer on {base} within {startup_timeout:g} s")
            time.sleep(0.1)
        yield base
    finally:
        stop_process(proc)
        log.close()


def stop_process(proc: subprocess.Popen, timeout: float = 10.0) -> None:
    """Ask a child process to stop (SIGTERM), and kill it if it has not within ``timeout`` seconds."""
    proc.terminate()
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
