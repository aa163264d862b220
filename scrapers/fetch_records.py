"""What one fetch gives back: the page (:class:`FetchResult`), its version validators, and error kinds."""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime

from kb.errors import FetchError, PageTooLarge, RobotsDisallowed

__all__ = ["FetchResult", "Validators", "fetch_error_kind"]


@dataclass(frozen=True)
class Validators:
    """What a previous fetch of a page said about its version (sent back as a conditional request)."""

    etag: str | None = None
    last_modified: str | None = None

    def headers(self) -> dict[str, str]:
        h: dict[str, str] = {}
        if self.etag:
            h["If-None-Match"] = self.etag
        if self.last_modified:
            h["If-Modified-Since"] = self.last_modified
        return h


@dataclass
class FetchResult:
    """One fetched page. ``body`` is None when ``not_modified`` (a 304 answer to a conditional request)."""

    url: str
    final_url: str
    status: int
    body: bytes | None
    content_type: str | None
    etag: str | None
    last_modified: str | None
    fetched_at: datetime
    attempts: int = 1
    redirects: int = 0
    retry_after: str | None = None  # the Retry-After header of a 408/429/5xx answer

    @property
    def not_modified(self) -> bool:
        return self.status == 304

    @property
    def validators(self) -> Validators:
        return Validators(self.etag, self.last_modified)


def fetch_error_kind(err: FetchError) -> str:
    """A short, stable key for what went wrong (used to count rejections by reason)."""
    kind = getattr(err, "kind", None)
    if kind:
        return kind
    if isinstance(err, RobotsDisallowed):
        return "robots_disallowed"
    if isinstance(err, PageTooLarge):
        return "too_large"
    return "fetch_failed"


def tagged_error(cls: type[FetchError], url: str, kind: str, detail: str) -> FetchError:
    """A fetch error carrying the short ``kind`` key :func:`fetch_error_kind` reports."""
    err = cls(url, detail)
    err.kind = kind  # type: ignore[attr-defined]
    return err
