"""What the routes share: the settings, the ingestion jobs, and the recall engine over a catalog snapshot.

The service never keeps a database connection open: :meth:`ServiceState.knowledge_base` opens a short
sandboxed read connection per request (retrying while the nightly ingestion holds the file), and recall
works on an in-memory recaller re-checked at most every ``snapshot_ttl`` seconds: it is loaded by
``Recaller.from_db`` (from the recall index stored beside the catalog while the catalog has not changed,
``recall/stored_index.py``) and replaced only when the catalog's content version differs from the one it
was built from (an alias-only change included).
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from kb.catalog_check import CatalogWatch
from kb.errors import CatalogMissing, ObjrecallError
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
        self._loading = threading.Lock()  # one check / load at a time (the others wait for its recaller)
        self._recaller: Any = None
        self._checked = 0.0
        self.renders = RenderCache(settings.render_concurrency, settings.render_cache_entries)
        self.catalog = CatalogWatch(settings.db)  # what /health reports

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
        """The recall engine over the catalog, re-checked at most every snapshot_ttl s (see the module)."""
        with self._lock:
            if self._fresh():
                return self._recaller
        self._require_catalog()
        with self._loading:
            with self._lock:
                if self._fresh():  # another request checked it while this one waited
                    return self._recaller
                held = self._recaller
            recaller = self._load(held)
            with self._lock:
                self._recaller, self._checked = recaller, time.monotonic()
                return recaller

    def _fresh(self) -> bool:
        return self._recaller is not None and time.monotonic() - self._checked < self.settings.snapshot_ttl

    def _load(self, held):
        """``held`` while the catalog's content is the one it was built from, else a new recaller."""
        from recall.engine import Recaller

        db = self.settings.db
        if db.suffix.lower() == ".csv":  # a catalog CSV: the snapshot cache decides
            from recall.snapshot import load_snapshot

            snap = load_snapshot(db)
            return held if held is not None and held.snapshot is snap else Recaller(snap)
        from recall.stored_index import current_version

        if held is not None and held.snapshot.version == current_version(db):
            return held
        return Recaller.from_db(db)

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
            raise CatalogMissing(self.settings.db)

