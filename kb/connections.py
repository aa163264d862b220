"""Connections to the catalog file: the read settings every connection shares, opening one without
DuckDB's progress bar, and waiting while another process holds the file.

User SQL never runs on these connections in the caller's process: :mod:`kb.sandbox` runs it in a worker
process, on a connection opened here with :data:`kb.sandbox.USER_SQL_CONFIG`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from kb.errors import CatalogUnreadable, DatabaseBusy

__all__ = [
    "CATALOG_READ_CONFIG", "SANDBOX_CONFIG", "database_reason", "innermost_error", "is_lock_conflict",
    "is_unreadable_file", "open_connection", "retry_while_locked",
]

#: Settings of every read connection: read-only, no file or network access, no extensions, configuration
#: locked so a query cannot undo any of it, and a memory cap.
SANDBOX_CONFIG: dict[str, Any] = {
    "enable_external_access": False,
    "autoinstall_known_extensions": False,
    "autoload_known_extensions": False,
    "allow_community_extensions": False,
    "allow_unsigned_extensions": False,
    "max_memory": "2GB",
    "lock_configuration": True,
}
#: Settings of the catalog's own read connections (:meth:`kb.catalog.KnowledgeBase.connect`): the sandbox
#: without the configuration lock. Only the project's own statements run on them (user SQL runs in a worker
#: process, :func:`run_user_sql`), and a lock set after connecting would make every later connection to the
#: file in this process differ from the first one's settings, which DuckDB refuses.
CATALOG_READ_CONFIG: dict[str, Any] = {k: v for k, v in SANDBOX_CONFIG.items() if k != "lock_configuration"}

def open_connection(path: Path | str, *, read_only: bool, config: dict[str, Any] | None = None):
    """A DuckDB connection to ``path`` that never draws DuckDB's progress bar, then ``config``; a file that
    is no DuckDB database, or a damaged one, raises :class:`~kb.errors.CatalogUnreadable` naming it.

    DuckDB draws a progress bar on stdout for any statement over 2 s, terminal or not, which corrupts the
    output of ``--json`` and CSV commands. The bar can only be turned off per connection (not as a connect
    setting), so the configuration lock of ``config`` is applied after turning it off. A locked connection
    must be the process's only one to the file (as in a user-SQL worker): DuckDB refuses a second connection
    whose settings differ from the first's, and the lock changed them.
    """
    import duckdb

    settings = dict(config or {})
    lock = settings.pop("lock_configuration", False)
    try:
        con = duckdb.connect(str(path), read_only=read_only, config=settings)
    except duckdb.Error as err:
        if not is_unreadable_file(err):
            raise
        raise CatalogUnreadable(path, database_reason(err)) from None  # not DuckDB, or damaged: name it
    try:
        con.execute("SET enable_progress_bar = false")
        if lock:
            con.execute("SET lock_configuration = true")
    except BaseException:
        con.close()
        raise
    return con



def is_lock_conflict(err: Exception) -> bool:
    """True when ``err`` says another process holds the database file."""
    text = str(err).lower()
    return "lock" in text and ("conflict" in text or "could not set" in text)


def retry_while_locked(fn: Callable[[], Any], *, path: Path, busy_timeout: float) -> Any:
    """``fn()``, retried with a short backoff while another process holds the database file, for up to
    ``busy_timeout`` seconds; then :class:`~kb.errors.DatabaseBusy`."""
    deadline = time.monotonic() + busy_timeout
    delay = 0.01
    while True:
        try:
            return fn()
        except Exception as err:  # duckdb.IOException, or wrapped by SQLAlchemy / MigrationError
            if not is_lock_conflict(err):
                raise
            if time.monotonic() >= deadline:
                raise DatabaseBusy(
                    f"{path}: another process has held the database for over {busy_timeout:g} s"
                ) from None
            time.sleep(delay)
            delay = min(delay * 2, 0.25)


def innermost_error(err: BaseException) -> BaseException:
    """The error at the bottom of ``err``'s chain: SQLAlchemy's ``orig`` (the driver's error) and each
    ``__cause__`` (``raise ... from``) followed to the end, however many wrappers (Alembic's, SQLAlchemy's,
    a MigrationError) lie between; ``err`` itself when it wraps nothing. A loop in the chain ends it."""
    inner, seen = err, {id(err)}
    while True:
        nxt = getattr(inner, "orig", None) or inner.__cause__
        if not isinstance(nxt, BaseException) or id(nxt) in seen:
            return inner
        seen.add(id(nxt))
        inner = nxt


def is_unreadable_file(err: BaseException) -> bool:
    """True when ``err`` (or the error it wraps, :func:`innermost_error`) says the file itself cannot be read
    as a DuckDB database: not one, or damaged (DuckDB's I/O and serialization errors, and its "Corrupt
    database file" checksum error); not when another process holds the file (:func:`is_lock_conflict`)."""
    import duckdb

    inner = innermost_error(err)
    if is_lock_conflict(inner):
        return False
    if isinstance(inner, (duckdb.IOException, duckdb.SerializationException)):
        return True
    return isinstance(inner, duckdb.Error) and "corrupt" in str(inner).lower()


def database_reason(err: BaseException) -> str:
    """The reason of a database failure in one line: the innermost error's first line, without the
    driver's class prefix ("(_duckdb.IOException) ") and SQLAlchemy's "(Background on this error ...)"."""
    inner = innermost_error(err)
    text = (str(inner).strip().splitlines() or [type(inner).__name__])[0]
    if text.startswith("(") and ") " in text:
        text = text.split(") ", 1)[1]
    return text.split(" (Background on this error", 1)[0].strip()
