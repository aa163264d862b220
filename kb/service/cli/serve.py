"""``objrecall serve``: the HTTP service (:mod:`kb.service.http`) on uvicorn."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from kb.service.cli.common import DbOption, resolve_db
from kb.service.http.settings import (
    DEFAULT_HEADER_TIMEOUT_S,
    ENV_ALLOWED_HOSTS,
    ENV_INGEST_LOG_DIR,
    ENV_SOURCES,
    allowed_hosts_from,
)


def serve(
    host: Annotated[
        str, typer.Option("--host", help="Interface to listen on (0.0.0.0 exposes it).")
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option("--port", min=1, max=65535, help="TCP port.")] = 8000,
    db: DbOption = None,
    sources: Annotated[
        Path | None,
        typer.Option(
            "--sources", help=f"Sources file that POST /ingestion/runs ingests (env {ENV_SOURCES})."
        ),
    ] = None,
    request_timeout: Annotated[
        float, typer.Option("--request-timeout", min=1.0, help="Answer 504 after this many seconds.")
    ] = 30.0,
    log_level: Annotated[str, typer.Option("--log-level", help="uvicorn log level.")] = "info",
    allowed_host: Annotated[
        list[str] | None,
        typer.Option(
            "--allowed-host",
            help=f"Host header name to answer (repeatable; '*' answers any). Default: env {ENV_ALLOWED_HOSTS} "
            "(comma-separated), else loopback names and the --host address.",
        ),
    ] = None,
    header_timeout: Annotated[
        float,
        typer.Option("--header-timeout", min=0.1, help="Close a connection whose request has not fully "
                     "arrived within this many seconds."),
    ] = DEFAULT_HEADER_TIMEOUT_S,
    ingest_log_dir: Annotated[
        Path | None,
        typer.Option(
            "--ingest-log-dir",
            help=f"Folder for the logs of ingestion jobs started over HTTP, kept (env {ENV_INGEST_LOG_DIR}). "
            "Default: a temporary folder removed when the server stops.",
        ),
    ] = None,
) -> None:
    """Serve the catalog over HTTP: the JSON API (OpenAPI at /docs) and the web page at /.

    Reads are open; writes need the bearer token from $OBJRECALL_API_TOKEN or the file named by
    $OBJRECALL_API_TOKEN_FILE (without one, writes are disabled).
    """
    import uvicorn

    from kb.service.http import create_app
    from kb.service.http.protocol import protocol_with_timeout

    path = resolve_db(db)
    if path.exists():
        from kb.catalog_check import check_catalog

        check_catalog(path)  # a corrupt file: refused now, naming it, not a 500 on every read later
    hosts = list(allowed_hosts_from(allowed_host))
    if not allowed_host and host not in ("0.0.0.0", "::", ""):
        hosts.append(host)  # the address it listens on is a name it is reached by
    app = create_app(
        path, sources=sources, request_timeout=request_timeout, warm=True, allowed_hosts=hosts,
        ingest_log_dir=ingest_log_dir,
    )  # fmt: skip
    if app.settings.token is None:
        sys.stderr.write("objrecall serve: no API token configured; writes are disabled\n")
    uvicorn.run(app, host=host, port=port, log_level=log_level, access_log=log_level == "debug",
                http=protocol_with_timeout(header_timeout), timeout_keep_alive=5)


def register(app: typer.Typer) -> None:
    """Add ``objrecall serve``."""
    app.command("serve")(serve)
