"""Whether a catalog file can be used: :func:`check_catalog` (``objrecall serve`` refuses to start on a
file that cannot, and ``GET /health`` reports it, :class:`CatalogState`)."""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass
from pathlib import Path

import duckdb

from kb.connections import database_reason
from kb.errors import CatalogMissing, CatalogUnreadable, DatabaseBusy

__all__ = ["CatalogState", "CatalogWatch", "check_catalog"]


def check_catalog(path: str | Path) -> None:
    """Return when ``path`` is a catalog that can be read; else raise :class:`CatalogMissing`, or
    :class:`CatalogUnreadable` naming the file and the reason (no DuckDB database, a damaged one, or one
    without the catalog's tables). :class:`~kb.errors.DatabaseBusy` passes through (a writer holds it)."""
    from kb.catalog import KnowledgeBase

    path = Path(path)
    if not path.exists():
        raise CatalogMissing(path)
    try:
        KnowledgeBase.open(path, read_only=True, busy_timeout=2.0).count_objects()
    except duckdb.Error as err:
        raise CatalogUnreadable(path, database_reason(err)) from None


@dataclass(frozen=True)
class CatalogState:
    """``state``: "ok", "missing", "unreadable" or "busy" (a writer held it past the check's wait);
    ``error``: the one-line reason when not ok."""

    state: str
    error: str | None = None


class CatalogWatch:
    """The state of one catalog file, re-checked only when the file's size or modification time changed
    (so ``/health`` stays cheap); thread-safe."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self._lock = threading.Lock()
        self._key: tuple[int, int] | None = None
        self._state = CatalogState("missing")

    def state(self) -> CatalogState:
        try:
            st = os.stat(self.path)
        except OSError:
            return CatalogState("missing", str(CatalogMissing(self.path)))
        key = (st.st_mtime_ns, st.st_size)
        with self._lock:
            if key == self._key:
                return self._state
        try:
            check_catalog(self.path)
            state = CatalogState("ok")
        except DatabaseBusy as err:
            return CatalogState("busy", str(err))  # not remembered: checked again next time
        except (CatalogMissing, CatalogUnreadable) as err:
            state = CatalogState("missing" if isinstance(err, CatalogMissing) else "unreadable", str(err))
        with self._lock:
            self._key, self._state = key, state
        return state
