"""``objrecall serve``: the HTTP service (:mod:`kb.service.http`) on uvicorn."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from kb.service.cli.common import DbOption, resolve_db
from kb.service.http.settings import ENV_SOURCES


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
) -> None:
    """Serve the catalog over HTTP: the JSON API (OpenAPI at /docs) and the web page at /.

    Reads are open; writes need the bearer token from $OBJRECALL_API_TOKEN or the file named by
    $OBJRECALL_API_TOKEN_FILE (without one, writes are disabled).
    """
    import uvicorn

    from kb.service.http import create_app

    path = resolve_db(db)
    app = create_app(path, sources=sources, request_timeout=request_timeout, warm=True)
    if app.settings.token is None:
        sys.stderr.write("objrecall serve: no API token configured; writes are disabled\n")
    uvicorn.run(app, host=host, port=port, log_level=log_level, access_log=log_level == "debug")


def register(app: typer.Typer) -> None:
    """Add ``objrecall serve``."""
    app.command("serve")(serve)
