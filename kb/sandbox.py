"""The SQL sandbox: user SQL runs in a separate, hard-limited worker process.

DuckDB's own limits do not bound every query: ``memory_limit`` does not cover one huge list or string
(``SELECT len(range(0, 3000000000))`` grew a process to 24 GB) and its interrupt is not checked inside
one scalar function call (``repeat('x', 2000000000)`` ran on for seconds after it). So user SQL never runs
in the caller's process. A small pool of worker processes (``python -m kb.sandbox``) runs it:

* each worker's address space is capped with ``RLIMIT_AS`` (:data:`WORKER_MEMORY_BYTES`), so an allocation
  past it fails at once inside DuckDB and the query is refused ("needs more memory than ...");
* DuckDB runs with one thread, ``max_memory`` under that cap and no temporary files, on a read-only
  connection with no file or network access and its configuration locked (:data:`USER_SQL_CONFIG`);
* the caller waits at most ``timeout_s`` (plus a short grace for DuckDB's own interrupt): past that the
  worker is killed, so no query outlives its caller's deadline, and a new worker starts on the next call;
* only plain reads run: an allow-list of statement types (SELECT, and EXPLAIN of a SELECT); any other
  type, including one this DuckDB version cannot name (``UPDATE EXTENSIONS``), is refused; so are the
  table functions that reveal the server's files (:data:`kb.sql_policy.HIDDEN_FUNCTIONS`), while the
  read-only catalog introspection (``DESCRIBE``, ``SHOW TABLES``, ``duckdb_tables()``, ``information_schema``,
  ``pragma_table_info``) runs; a file or URL read is refused as "reading files is not allowed", naming it;
* a refused statement is named by the word the user wrote (INSTALL, RESET, TRUNCATE, where DuckDB's types
  say LOAD, SET, DELETE), and a write inside a SELECT (``WITH x AS (DELETE ... RETURNING *) SELECT ...``),
  which the read-only connection stops before it runs, is refused in the sandbox's words (DuckDB's name the
  database file); ``max_rows`` is at most :data:`MAX_ROWS`;
* result columns with the same name are renamed visibly (``a``, ``a (2)``), never merged.

The worker (``kb.sandbox._worker_main``) speaks length-prefixed pickle frames on its stdin/stdout with its parent only.
"""

from __future__ import annotations

import atexit
import os
import pickle
import select
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from kb.connections import SANDBOX_CONFIG, open_connection, retry_while_locked
from kb.errors import (
    CatalogMissing,
    DatabaseBusy,
    DatabaseError,
    ObjrecallError,
    QueryFailed,
    QueryRefused,
    QueryTimeout,
)
from kb.sql_policy import check_query, error_refusal, error_text, first_line, write_refusal

__all__ = [
    "MAX_ROWS",
    "MAX_TIMEOUT_S",
    "USER_SQL_CONFIG",
    "WORKER_MEMORY_BYTES",
    "SqlAnswer",
    "run_user_sql",
    "unique_columns",
    "warm_up",
]

#: Address-space cap of a user-SQL worker process (python + DuckDB need about 0.1 GB of it).
WORKER_MEMORY_BYTES = 1536 * 1024 * 1024
#: Settings of a user-SQL connection: the sandbox, one thread, memory well under the process cap, no
#: temporary files (nothing spills to disk).
USER_SQL_CONFIG: dict[str, Any] = {
    **SANDBOX_CONFIG,
    "max_memory": "512MB",
    "threads": 1,
    "max_temp_directory_size": "0KB",
}
#: The longest time limit user SQL may ask for (a day; the HTTP service caps it far lower). A longer one is
#: refused with a reason: past about 10**9 s the operating system's timers cannot represent it.
MAX_TIMEOUT_S = 86_400.0
#: The most rows user SQL may ask for: more than an answer can carry (:data:`MAX_ANSWER_BYTES`), and far
#: under the 64-bit count DuckDB's ``fetchmany`` takes (a larger number was its TypeError).
MAX_ROWS = 100_000_000
#: A worker's answer may be at most this large (pickled); a bigger one is refused inside the worker.
MAX_ANSWER_BYTES = 64 * 1024 * 1024
#: Worker processes that may run at once (more callers wait for a free one, within their time limit).
POOL_SIZE = 2
_STARTUP_TIMEOUT_S = 60.0
_HEADER = struct.Struct("!Q")


@dataclass
class SqlAnswer:
    """What the worker returns: column names (made unique), rows, and whether rows were cut at max_rows."""

    columns: list[str]
    rows: list[tuple]
    truncated: bool


# ---------------------------------------------------------------------------------------------- shared
def unique_columns(names: Sequence[str]) -> list[str]:
    """Column names with repeats renamed ``name (2)``, ``name (3)``, ... so that no column is lost."""
    seen: set[str] = set()
    out = []
    for name in names:
        candidate, n = name, 1
        while candidate in seen:
            n += 1
            candidate = f"{name} ({n})"
        seen.add(candidate)
        out.append(candidate)
    return out


# ---------------------------------------------------------------------------------------------- worker side
def _execute(con, request: dict[str, Any]) -> SqlAnswer:
    import duckdb

    query = request["query"]
    check_query(con, query)
    timer = threading.Timer(request["timeout_s"], con.interrupt)
    timer.start()
    try:
        cur = con.execute(query, request["params"])
        columns = unique_columns([d[0] for d in cur.description])
        rows = cur.fetchmany(request["max_rows"] + 1)
    except duckdb.PermissionException as err:
        raise QueryRefused(error_refusal(err) or f"refused: {first_line(err)}") from None
    except duckdb.InterruptException:
        raise QueryTimeout(f"query interrupted after the {request['timeout_s']:g} s time limit") from None
    except (duckdb.OutOfMemoryException, MemoryError):
        raise QueryRefused(_memory_refusal()) from None
    except duckdb.Error as err:
        refusal = error_refusal(err)  # a file or URL read, an extension's function: the sandbox's words
        if refusal is not None:
            raise QueryRefused(refusal) from None
        if "read-only" in str(err).lower():  # DuckDB's text names the database file: never passed on
            raise QueryRefused(write_refusal(query)) from None
        if "out of memory" in str(err).lower() or "bad allocation" in str(err).lower():
            raise QueryRefused(_memory_refusal()) from None
        raise QueryFailed(f"SQL error: {error_text(err)}") from None
    finally:
        timer.cancel()
    max_rows = request["max_rows"]
    return SqlAnswer(columns=columns, rows=rows[:max_rows], truncated=len(rows) > max_rows)


def _answer(request: dict[str, Any]) -> tuple:
    import duckdb

    path = Path(request["path"])
    try:
        if not path.exists():
            raise DatabaseError(str(CatalogMissing(path)))  # sent to the caller as a DatabaseError
        con = retry_while_locked(
            lambda: open_connection(path, read_only=True, config=USER_SQL_CONFIG),
            path=path, busy_timeout=request["busy_timeout"],
        )
        try:
            answer = _execute(con, request)
        finally:
            con.close()
        try:
            data = pickle.dumps(("ok", (answer.columns, answer.rows, answer.truncated)), protocol=pickle.HIGHEST_PROTOCOL)
        except (TypeError, AttributeError, pickle.PicklingError) as err:
            raise QueryFailed(f"a result value cannot be returned: {first_line(err)}") from None
    except ObjrecallError as err:  # sent as the nearest class the caller rebuilds (CatalogUnreadable: DatabaseError)
        kind = next((c.__name__ for c in type(err).__mro__ if c.__name__ in _ERRORS), "QueryFailed")
        return ("error", kind, _mask(str(err), path))
    except (MemoryError, duckdb.OutOfMemoryException):
        return ("error", "QueryRefused", _memory_refusal())
    if len(data) > MAX_ANSWER_BYTES:
        return ("error", "QueryRefused",
                f"refused: result too large ({len(data):,} bytes; at most {MAX_ANSWER_BYTES:,}); "
                "select fewer rows or columns")
    return ("raw", data)


def _memory_refusal() -> str:
    return (f"refused: the query needs more memory than the SQL sandbox allows "
            f"({WORKER_MEMORY_BYTES / 2**30:g} GiB); select less")


def _mask(text: str, path: Path) -> str:
    """``text`` with the catalog's directory replaced, so an error message does not reveal it."""
    for folder in {str(path.resolve().parent), str(path.parent)}:
        if folder not in ("", "."):
            text = text.replace(folder + os.sep, "")
    return text


def _worker_main() -> None:
    """Serve requests on stdin/stdout until stdin closes."""
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (WORKER_MEMORY_BYTES, WORKER_MEMORY_BYTES))
    inp, out = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # nothing but frames on the real stdout
    import duckdb  # noqa: F401  (loaded before the ready frame, so start-up is not query time)

    _write_frame(out, pickle.dumps(("ready",)))
    while True:
        header = inp.read(_HEADER.size)
        if len(header) < _HEADER.size:
            return
        request = pickle.loads(inp.read(_HEADER.unpack(header)[0]))
        try:
            reply = _answer(request)
        except Exception as err:  # a bug, not the user's query: say so instead of dying
            reply = ("error", "QueryFailed", f"SQL worker error: {type(err).__name__}: {first_line(err)}")
        _write_frame(out, reply[1] if reply[0] == "raw" else pickle.dumps(reply))


def _write_frame(out, data: bytes) -> None:
    out.write(_HEADER.pack(len(data)) + data)
    out.flush()


# ---------------------------------------------------------------------------------------------- parent side
class _Worker:
    def __init__(self) -> None:
        env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "from kb.sandbox import _worker_main; _worker_main()"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env,
            cwd=str(Path(__file__).resolve().parent.parent),
        )
        self.ready = False

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        for stream in (self.proc.stdin, self.proc.stdout):
            try:
                stream.close()
            except OSError:
                pass

    def _read_exact(self, n: int, deadline: float) -> bytes:
        fd = self.proc.stdout.fileno()
        chunks, got = [], 0
        while got < n:
            remaining = deadline - time.monotonic()
            if remaining <= 0 or not select.select([fd], [], [], remaining)[0]:
                raise TimeoutError
            chunk = os.read(fd, min(n - got, 1 << 20))
            if not chunk:
                raise EOFError
            chunks.append(chunk)
            got += len(chunk)
        return b"".join(chunks)

    def read_frame(self, deadline: float) -> tuple:
        size = _HEADER.unpack(self._read_exact(_HEADER.size, deadline))[0]
        return pickle.loads(self._read_exact(size, deadline))

    def wait_ready(self) -> None:
        """Wait for the worker's start-up (python and DuckDB loading), which is not query time."""
        if not self.ready:
            self.read_frame(time.monotonic() + _STARTUP_TIMEOUT_S)
            self.ready = True

    def ask(self, request: dict[str, Any], deadline: float) -> tuple:
        data = pickle.dumps(request)
        self.proc.stdin.write(_HEADER.pack(len(data)) + data)
        self.proc.stdin.flush()
        return self.read_frame(deadline)


class _Pool:
    def __init__(self, size: int) -> None:
        self.size = size
        self.idle: list[_Worker] = []
        self.busy = 0
        self.cond = threading.Condition()

    def acquire(self, deadline: float) -> _Worker:
        with self.cond:
            while not self.idle and self.busy >= self.size:
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    raise QueryTimeout(f"all {self.size} SQL workers stayed busy for the whole time limit")
                self.cond.wait(remaining)
            self.busy += 1
            worker = self.idle.pop() if self.idle else None
        if worker is not None and worker.proc.poll() is None:
            return worker
        try:
            return _Worker()
        except BaseException:
            self.release(None)
            raise

    def release(self, worker: _Worker | None) -> None:
        with self.cond:
            self.busy -= 1
            if worker is not None:
                self.idle.append(worker)
            self.cond.notify()

    def close(self) -> None:
        with self.cond:
            idle, self.idle = self.idle, []
        for worker in idle:
            worker.kill()


_POOL = _Pool(POOL_SIZE)
atexit.register(_POOL.close)
_ERRORS: dict[str, type[ObjrecallError]] = {
    cls.__name__: cls for cls in (QueryRefused, QueryFailed, QueryTimeout, DatabaseBusy, DatabaseError)
}


def warm_up() -> None:
    """Start one SQL worker now (python and DuckDB take about a second to load), so the first query does
    not wait for it; the HTTP service calls this at start-up."""
    worker = _POOL.acquire(time.monotonic() + _STARTUP_TIMEOUT_S)
    try:
        worker.wait_ready()
    except BaseException:
        worker.kill()
        _POOL.release(None)
        raise
    _POOL.release(worker)


def run_user_sql(
    path: Path, query: str, params: Sequence[Any] | None, *, max_rows: int, timeout_s: float, busy_timeout: float
) -> SqlAnswer:
    """Run one user statement on the catalog at ``path`` in a sandbox worker (see the module docstring).

    Raises :class:`~kb.errors.QueryRefused`, :class:`~kb.errors.QueryFailed`,
    :class:`~kb.errors.QueryTimeout` (the worker is killed at the deadline) or a database error.
    """
    if not 0 < timeout_s <= MAX_TIMEOUT_S:
        raise QueryFailed(f"timeout_s must be more than 0 and at most {MAX_TIMEOUT_S:g} s, got {timeout_s!r}")
    if not 1 <= max_rows <= MAX_ROWS:
        raise QueryFailed(f"max_rows must be from 1 to {MAX_ROWS:,}, got {max_rows!r}")
    request = {"path": str(Path(path).resolve()), "query": query, "params": list(params) if params else None,
               "max_rows": int(max_rows), "timeout_s": float(timeout_s), "busy_timeout": float(busy_timeout)}
    worker = _POOL.acquire(time.monotonic() + timeout_s)
    keep = False
    try:
        worker.wait_ready()
        reply = worker.ask(request, time.monotonic() + timeout_s + min(0.5, 0.25 * timeout_s))
        keep = True
    except TimeoutError:
        raise QueryTimeout(f"query stopped at the {timeout_s:g} s time limit") from None
    except (EOFError, OSError, pickle.UnpicklingError):
        raise QueryRefused(
            f"refused: the query ended its SQL worker (exit code {worker.proc.poll()}); it may need more memory "
            f"than the sandbox allows ({WORKER_MEMORY_BYTES / 2**30:g} GiB)"
        ) from None
    finally:
        if keep:
            _POOL.release(worker)
        else:
            worker.kill()
            _POOL.release(None)
    if reply[0] == "ok":
        return SqlAnswer(*reply[1])
    raise _ERRORS.get(reply[1], QueryFailed)(reply[2])
