"""Inside one process, many catalog readers or one writer at a time.

DuckDB refuses two connections with different settings (read-only sandbox vs read-write) on one file in one
process, so :class:`kb.catalog.KnowledgeBase` takes this lock around every connection it opens. Between
processes DuckDB's own file lock applies (see :mod:`kb.catalog`).
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["ReadWriteLock", "lock_for"]


class ReadWriteLock:
    """Many readers or one writer, inside one process."""

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self._readers = 0
        self._writer = False

    @contextmanager
    def read(self) -> Iterator[None]:
        with self._cond:
            while self._writer:
                self._cond.wait()
            self._readers += 1
        try:
            yield
        finally:
            with self._cond:
                self._readers -= 1
                self._cond.notify_all()

    @contextmanager
    def write(self) -> Iterator[None]:
        with self._cond:
            while self._writer or self._readers:
                self._cond.wait()
            self._writer = True
        try:
            yield
        finally:
            with self._cond:
                self._writer = False
                self._cond.notify_all()


_LOCKS: dict[str, ReadWriteLock] = {}
_LOCKS_GUARD = threading.Lock()


def lock_for(path: Path) -> ReadWriteLock:
    """The one lock of the catalog file at ``path`` in this process (same file, same lock)."""
    key = str(path.resolve())
    with _LOCKS_GUARD:
        return _LOCKS.setdefault(key, ReadWriteLock())
