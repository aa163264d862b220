"""The knowledge service: the catalog, the parser, recall and the grasp planner over HTTP (FastAPI).

``objrecall serve [--host 127.0.0.1] [--port 8000] [--db PATH]`` (:mod:`kb.service.cli.serve`) runs
:func:`create_app` on uvicorn. The
endpoints, authentication and deployment are described in ``kb/SERVICE.md``; the OpenAPI document is at
``/openapi.json`` (browsable at ``/docs``) and a small web page at ``/``.

Design notes
------------
* **One writer at a time.** The service never keeps a database connection open: every request opens a
  short sandboxed read connection through :class:`~kb.catalog.KnowledgeBase` (which retries while the nightly
  ingestion holds the file), so a read waits at most one write transaction and never fails because of it.
  Recall works on an in-memory snapshot of the catalog, re-checked at most every ``snapshot_ttl`` seconds.
* **Errors.** Every :class:`~kb.errors.ObjrecallError` becomes a JSON body ``{"error": <class>, "detail":
  <one line>}`` with a 4xx/5xx status from :data:`ERROR_STATUS` (404 not found, 400 bad input, 503 busy,
  504 timeout); a request the schema refuses gets 422. A 500 is a bug.
* **Limits.** Request bodies over ``max_body_bytes`` get 413, requests running over ``request_timeout``
  get 504, lists are paged (``limit`` at most :data:`MAX_PAGE`), user SQL runs in the sandbox of
  :meth:`KnowledgeBase.sql <kb.catalog.KnowledgeBase.sql>` with capped row count and time.
* **Writes** (``PUT /objects/{name}``, ``POST /ingestion/runs``) need ``Authorization: Bearer <token>``;
  the token comes from configuration (:data:`ENV_TOKEN`, or a file named by :data:`ENV_TOKEN_FILE`). With no
  token configured, writes are disabled (403). Reads are open; the default host is loopback.

Like the CLI, this module is part of the service face and imports the recall, scrapers and sim packages
(lazily, inside the endpoints). The routes are in ``kb/service/http/routes/`` (one router per group),
their bodies in ``models.py``, what they share in ``state.py``.
"""

import os
import threading
from contextlib import asynccontextmanager
from pathlib import Path

from kb.service.http.jobs import IngestionJobs, objrecall_command
from kb.service.http.limits import LimitsWrapped
from kb.service.http.settings import (
    ENV_INGEST_LOG_DIR,
    ENV_SOURCES,
    ServiceSettings,
    allowed_hosts_from,
    load_token,
    package_version,
)
from kb.service.http.state import ServiceState

__all__ = ["create_app"]

STATIC = Path(__file__).parent / "static"


def create_app(
    db_path: str | Path,
    *,
    token: str | None = None,
    sources: str | Path | None = None,
    max_body_bytes: int = 64 * 1024,
    request_timeout: float = 30.0,
    snapshot_ttl: float = 1.0,
    busy_timeout: float = 30.0,
    ingest_command: list[str] | None = None,
    warm: bool = False,
    allowed_hosts: list[str] | tuple[str, ...] | None = None,
    ingest_log_dir: str | Path | None = None,
) -> LimitsWrapped:
    """The FastAPI application serving the catalog at ``db_path``.

    ``token`` enables writes (None: read from the environment, see :func:`load_token`; "" disables them).
    ``sources`` is the sources file ``POST /ingestion/runs`` ingests (default ``$OBJRECALL_SOURCES``).
    ``ingest_command`` replaces the command prefix that runs ``objrecall`` (tests, containers).
    ``ingest_log_dir`` is where the ingestion jobs' logs go, kept (default ``$OBJRECALL_INGEST_LOG_DIR``, else
    a temporary folder removed when the service shuts down; :mod:`kb.service.http.jobs`).
    ``allowed_hosts`` lists the Host header names answered (default ``$OBJRECALL_ALLOWED_HOSTS``, else
    loopback only; ``["*"]`` answers any). ``warm`` builds the description parser and the recall snapshot in a background thread at start-up
    (the first parse builds the grammar, which takes seconds), so the first requests are not slow.
    """
    from fastapi_offline import FastAPIOffline

    from kb.service.http.handlers import install_error_handlers
    from kb.service.http.routes import catalog, grasp, ingestion, recall, service

    if token is None:
        token = load_token()
    if sources is None and os.environ.get(ENV_SOURCES):
        sources = os.environ[ENV_SOURCES]
    settings = ServiceSettings(
        db=Path(db_path),
        token=token or None,
        sources=Path(sources) if sources else None,
        max_body_bytes=max_body_bytes,
        request_timeout=request_timeout,
        snapshot_ttl=snapshot_ttl,
        busy_timeout=busy_timeout,
        ingest_command=list(ingest_command) if ingest_command else objrecall_command(),
        allowed_hosts=allowed_hosts_from(allowed_hosts),
    )
    if ingest_log_dir is None and os.environ.get(ENV_INGEST_LOG_DIR):
        ingest_log_dir = os.environ[ENV_INGEST_LOG_DIR]
    state = ServiceState(settings, IngestionJobs(Path(ingest_log_dir) if ingest_log_dir else None))
    # /docs and /redoc with Swagger UI / ReDoc served by this server (fastapi-offline), not from a CDN
    app = FastAPIOffline(
        lifespan=_lifespan(state, warm),
        title="objrecall knowledge service",
        version=package_version(),
        description="Recall household objects from descriptions, browse the catalog, plan grasps. "
        "Reads are open; writes need `Authorization: Bearer <token>`. See kb/SERVICE.md.",
    )
    app.state.service, app.state.settings, app.state.jobs = state, settings, state.jobs
    install_error_handlers(app)
    for module in (service, catalog, recall, grasp, ingestion):
        app.include_router(module.router)
    _mount_page(app)
    return LimitsWrapped(app, settings)


def _lifespan(state: ServiceState, warm: bool):
    @asynccontextmanager
    async def lifespan(app):
        if warm:
            threading.Thread(target=state.warm_up, name="objrecall-warm-up", daemon=True).start()
        yield
        # stop a running ingestion child with the server (its one write transaction rolls back if open)
        # and remove the temporary log folder
        state.jobs.close()

    return lifespan


def _mount_page(app) -> None:
    """The web page at ``/`` and its script and style under ``/static/``."""
    from fastapi.responses import FileResponse
    from fastapi.staticfiles import StaticFiles

    app.mount("/static", StaticFiles(directory=STATIC), name="static")

    @app.get("/", include_in_schema=False)
    def index() -> FileResponse:
        return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-cache"})
