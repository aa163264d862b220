"""How the HTTP service runs: its limits, the write token, and the HTTP status of each error class."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from kb.errors import (
    CatalogError,
    CatalogImportError,
    DatabaseBusy,
    DatabaseError,
    DescriptionError,
    IngestionBusy,
    InvalidFeature,
    JobNotFound,
    ObjectNotFound,
    ObjrecallError,
    QueryFailed,
    QueryRefused,
    RecallError,
    RenderBusy,
    RequestTimeout,
    WritesDisabled,
)
from recall.descriptions import MAX_DESCRIPTION_CHARS

__all__ = [
    "DEFAULT_ALLOWED_HOSTS",
    "DEFAULT_HEADER_TIMEOUT_S",
    "DEFAULT_PAGE",
    "ENV_ALLOWED_HOSTS",
    "ENV_INGEST_LOG_DIR",
    "ENV_SOURCES",
    "ENV_TOKEN",
    "ENV_TOKEN_FILE",
    "ERROR_STATUS",
    "MAX_PAGE",
    "MAX_TEXT_CHARS",
    "MAX_TOP",
    "SQL_MAX_RESPONSE_BYTES",
    "SQL_MAX_ROWS",
    "SQL_MAX_TIMEOUT_S",
    "ServiceSettings",
    "allowed_hosts_from",
    "load_token",
    "package_version",
    "status_for",
]

ENV_TOKEN = "OBJRECALL_API_TOKEN"
ENV_TOKEN_FILE = "OBJRECALL_API_TOKEN_FILE"
ENV_SOURCES = "OBJRECALL_SOURCES"
ENV_ALLOWED_HOSTS = "OBJRECALL_ALLOWED_HOSTS"
#: Where the ingestion jobs started by the service write their logs (kept); unset: a temporary folder.
ENV_INGEST_LOG_DIR = "OBJRECALL_INGEST_LOG_DIR"
#: ``objrecall serve`` closes a connection whose request has not fully arrived within this (seconds).
DEFAULT_HEADER_TIMEOUT_S = 10.0
#: Host header values served by default: loopback only, so a page on another site that rebinds its DNS
#: name to 127.0.0.1 cannot read the API (its requests carry its own name as Host).
DEFAULT_ALLOWED_HOSTS: tuple[str, ...] = ("127.0.0.1", "localhost", "::1")

#: Largest page of any list endpoint.
MAX_PAGE = 500
DEFAULT_PAGE = 50
#: Caps of the SQL endpoint (a request may ask for less, never more).
SQL_MAX_ROWS = 5_000
SQL_MAX_TIMEOUT_S = 10.0
SQL_MAX_RESPONSE_BYTES = 8 * 1024 * 1024
MAX_TEXT_CHARS = MAX_DESCRIPTION_CHARS  # the recall API's one limit (recall.descriptions); refused there
MAX_TOP = 50

#: HTTP status of each error class (the most specific class listed wins).
ERROR_STATUS: dict[type[ObjrecallError], int] = {
    ObjectNotFound: 404,
    CatalogImportError: 400,
    CatalogError: 400,
    InvalidFeature: 400,
    QueryRefused: 400,
    QueryFailed: 400,
    DescriptionError: 400,
    RecallError: 400,
    DatabaseBusy: 503,
    DatabaseError: 503,
    WritesDisabled: 403,
    IngestionBusy: 409,
    RenderBusy: 503,
    JobNotFound: 404,
    RequestTimeout: 504,
    ObjrecallError: 400,
}


def status_for(err: ObjrecallError) -> int:
    for cls in type(err).__mro__:
        if cls in ERROR_STATUS:
            return ERROR_STATUS[cls]
    return 400


@dataclass
class ServiceSettings:
    """How the service runs; the defaults are the ones ``objrecall serve`` uses."""

    db: Path
    token: str | None = None
    sources: Path | None = None
    max_body_bytes: int = 64 * 1024
    request_timeout: float = 30.0
    sql_max_rows: int = SQL_MAX_ROWS
    sql_max_timeout: float = SQL_MAX_TIMEOUT_S
    snapshot_ttl: float = 1.0
    busy_timeout: float = 30.0
    ingest_command: list[str] = field(default_factory=list)
    #: Host header names (without port) answered; ``"*"`` answers any. Others get 400.
    allowed_hosts: tuple[str, ...] = DEFAULT_ALLOWED_HOSTS
    #: ``GET /grasp/render``: renders made at once (more get 503 and Retry-After) and renders kept.
    render_concurrency: int = 2
    render_cache_entries: int = 64


def allowed_hosts_from(values: list[str] | tuple[str, ...] | None, environ: dict[str, str] | None = None) -> tuple[str, ...]:
    """The Host allow-list: ``values`` if given, else ``$OBJRECALL_ALLOWED_HOSTS`` (comma-separated), else
    :data:`DEFAULT_ALLOWED_HOSTS`. Names are lower-cased; IPv6 brackets are dropped."""
    env = os.environ if environ is None else environ
    if not values:
        values = [v for v in (env.get(ENV_ALLOWED_HOSTS) or "").split(",") if v.strip()]
    names = tuple(dict.fromkeys(v.strip().lower().strip("[]") for v in values if v.strip()))
    return names or DEFAULT_ALLOWED_HOSTS


def load_token(environ: dict[str, str] | None = None) -> str | None:
    """The write token from ``$OBJRECALL_API_TOKEN``, else from the file ``$OBJRECALL_API_TOKEN_FILE``
    (a docker secret, say); None when neither is set (writes disabled). Blank tokens count as none."""
    env = os.environ if environ is None else environ
    token = (env.get(ENV_TOKEN) or "").strip()
    if token:
        return token
    path = (env.get(ENV_TOKEN_FILE) or "").strip()
    if path:
        try:
            token = Path(path).read_text(encoding="utf-8").strip()
        except OSError as err:
            raise ObjrecallError(f"{path}: cannot read the API token file ({err.strerror})") from None
        return token or None
    return None


def package_version() -> str:
    """The installed objrecall version (``0+unknown`` from a source tree that was never installed)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("objrecall")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree without installing
        return "0+unknown"
