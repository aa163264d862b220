"""What the routes share: the settings, the ingestion jobs, and the recall engine over a catalog snapshot.

The service never keeps a database connection open: :meth:`ServiceState.knowledge_base` opens a short
sandboxed read connection per request (retrying while the nightly ingestion holds the file), and recall
works on an in-memory snapshot of the catalog re-checked at most every ``snapshot_ttl`` seconds.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from kb.errors import DatabaseError, ObjrecallError
from kb.service.http.jobs import IngestionJobs
from kb.service.http.renders import RenderCache
from kb.service.http.settings import ENV_SOURCES, ServiceSettings

if TYPE_CHECKING:
    from kb.catalog import KnowledgeBase

__all__ = ["ServiceState"]


class ServiceState:
    """One per app (``app.state.service``); safe to use from the worker threads of concurrent requests."""

    def __init__(self, settings: ServiceSettings, jobs: IngestionJobs):
        self.settings = settings
        self.jobs = jobs
        self._lock = threading.Lock()
        self._snapshot: Any = None
        self._recaller: Any = None
        self._checked = 0.0
        self.renders = RenderCache(settings.render_concurrency, settings.render_cache_entries)

    def knowledge_base(self) -> KnowledgeBase:
        """A read-only view of the catalog for one request."""
        from kb.catalog import KnowledgeBase

        return KnowledgeBase.open(self.settings.db, read_only=True, busy_timeout=self.settings.busy_timeout)

    def writable_knowledge_base(self) -> KnowledgeBase:
        """The catalog for one write (never created or upgraded here: that is ``objrecall init``)."""
        from kb.catalog import KnowledgeBase

        self._require_catalog()
        return KnowledgeBase.open(self.settings.db, busy_timeout=self.settings.busy_timeout, upgrade=False)

    def sources_file(self) -> Path:
        """The sources file ingestion and lookups read; refused when the server was started without one."""
        if self.settings.sources is None:
            raise ObjrecallError(
                f"no sources file configured on the server (start it with --sources FILE or set {ENV_SOURCES})"
            )
        return self.settings.sources

    def recaller(self):
        """The recall engine over a snapshot of the catalog, re-checked at most every snapshot_ttl s."""
        from recall.engine import Recaller
        from recall.snapshot import load_snapshot

        with self._lock:
            if self._recaller is not None and time.monotonic() - self._checked < self.settings.snapshot_ttl:
                return self._recaller
        self._require_catalog()
        snap = load_snapshot(self.settings.db)
        with self._lock:
            if snap is not self._snapshot:
                self._recaller = Recaller(snap)
                self._snapshot = snap
            self._checked = time.monotonic()
            return self._recaller

    def forget_snapshot(self) -> None:
        """After a write: the next recall re-checks the catalog whatever the TTL."""
        with self._lock:
            self._checked = 0.0

    def warm_up(self) -> None:
        """Build the description parser and the recall snapshot (the first parse builds the grammar)."""
        try:
            from recall.parser import parse

            parse("a smooth plastic cup about 10 cm tall, 200 g")
            self.recaller()
            from kb.sandbox import warm_up as start_sql_worker

            start_sql_worker()
        except Exception:  # noqa: BLE001 - warming is best effort; the real request reports any error
            pass

    def _require_catalog(self) -> None:
        if not self.settings.db.exists():
            raise DatabaseError(f"{self.settings.db}: no catalog there (create it with `objrecall init`)")

