"""What one ingestion run did: each page's outcome (:class:`PageOutcome`), the run's counts
(:class:`IngestionReport`), and a page's identity as a source (:func:`page_identity`).

Plain records shared by the job (:mod:`scrapers.ingest`), its write plan (:mod:`scrapers.write_set`) and
its transaction (:mod:`scrapers.catalog_write`).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from datetime import datetime
from typing import Any
from urllib.parse import urlsplit

from kb.features import ObjectRecord
from scrapers.records import ProductRecord

__all__ = ["LOCAL_HOSTS", "IngestionReport", "PageOutcome", "page_identity"]


@dataclass
class PageOutcome:
    """What happened to one page in this run (kept in memory until the write transaction)."""

    url: str
    store: str
    outcome: str = "pending"  # extracted | not_modified | rejected
    stage: str | None = None  # fetch | extract | validate (where a rejected page stopped)
    reason: str | None = None  # short key, counted in rejected_reasons
    detail: str | None = None
    status: int | None = None
    final_url: str | None = None
    etag: str | None = None
    last_modified: str | None = None
    content_sha256: str | None = None
    fetched_at: datetime | None = None
    record: ProductRecord | None = None
    clean: ObjectRecord | None = None
    packages: list[dict[str, float]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def source(self) -> str:
        """The page's identity as a source: its canonical URL when on the same host, else the final URL
        (:func:`page_identity`: a local server's port is not part of it)."""
        final = self.final_url or self.url
        canonical = self.record.canonical_url if self.record is not None else None
        if canonical and urlsplit(canonical).netloc == urlsplit(final).netloc:
            return page_identity(canonical)
        return page_identity(final)

    @property
    def key(self) -> str:
        """The page's row in the ``pages`` table (its URL as listed, without a local server's port)."""
        return page_identity(self.url)


#: Hosts of servers on this machine: their port changes from run to run (the demo store picks a free one).
LOCAL_HOSTS = frozenset({"localhost", "127.0.0.1", "::1", "[::1]"})


def page_identity(url: str) -> str:
    """``url`` as a page's identity: a loopback server's port removed (``http://127.0.0.1:53211/p/x`` ->
    ``http://127.0.0.1/p/x``), anything else unchanged. A page served by a local server on another port
    next run is the same page; a real store's port is part of its address and kept."""
    parts = urlsplit(url)
    host = (parts.hostname or "").lower()
    if parts.port is None or not (host in LOCAL_HOSTS or host.startswith("127.")):
        return url
    netloc = f"[{host}]" if ":" in host else host
    if parts.username or parts.password:
        return url
    return parts._replace(netloc=netloc).geturl()


@dataclass
class IngestionReport:
    """The counts of one run (also stored as a row of ``ingestion_runs``)."""

    run_id: int | None
    status: str
    sources: str
    started_at: datetime
    finished_at: datetime | None = None
    duration_s: float = 0.0
    pages: int = 0
    fetched: int = 0
    not_modified: int = 0
    extracted: int = 0
    rejected: int = 0
    rejected_reasons: dict[str, int] = field(default_factory=dict)
    new: int = 0
    updated: int = 0
    unchanged: int = 0
    observations_added: int = 0
    aliases_added: int = 0
    new_objects: list[str] = field(default_factory=list)
    updated_objects: list[str] = field(default_factory=list)
    errors: list[dict[str, str]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    write_s: float = 0.0

    @property
    def pages_per_s(self) -> float:
        return self.pages / self.duration_s if self.duration_s > 0 else 0.0

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["pages_per_s"] = round(self.pages_per_s, 2)
        return d
