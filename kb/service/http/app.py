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
(lazily, inside the endpoints). No ``from __future__ import annotations`` here: FastAPI reads the route
signatures, whose models are defined inside :func:`create_app`.
"""

import hmac
import json
import os
import tempfile
import threading
import time
from contextlib import asynccontextmanager
from dataclasses import replace
from pathlib import Path
from typing import Annotated, Any, Literal

from kb.errors import (
    DatabaseBusy,
    DatabaseError,
    ObjectNotFound,
    ObjrecallError,
    QueryFailed,
    QueryTimeout,
    RecallError,
    RequestTimeout,
    WritesDisabled,
)
from kb.jsonable import to_jsonable
from kb.service.http.jobs import IngestionJobs, objrecall_command
from kb.service.http.limits import LimitsWrapped
from kb.service.http.settings import (
    DEFAULT_PAGE,
    ENV_SOURCES,
    ENV_TOKEN,
    ENV_TOKEN_FILE,
    MAX_PAGE,
    MAX_TEXT_CHARS,
    MAX_TOP,
    SQL_MAX_RESPONSE_BYTES,
    ServiceSettings,
    allowed_hosts_from,
    load_token,
    status_for,
)

__all__ = ["create_app"]


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
):
    """The FastAPI application serving the catalog at ``db_path``.

    ``token`` enables writes (None: read from the environment, see :func:`load_token`; "" disables them).
    ``sources`` is the sources file ``POST /ingestion/runs`` ingests (default ``$OBJRECALL_SOURCES``).
    ``ingest_command`` replaces the command prefix that runs ``objrecall`` (tests, containers).
    ``allowed_hosts`` lists the Host header names answered (default ``$OBJRECALL_ALLOWED_HOSTS``, else
    loopback only; ``["*"]`` answers any). ``warm`` builds the description parser and the recall snapshot in a background thread at start-up
    (the first parse builds the grammar, which takes seconds), so the first requests are not slow.
    """
    from fastapi import Depends, Query, Request
    from fastapi import Path as PathParam
    from fastapi.exceptions import RequestValidationError
    from fastapi.responses import FileResponse, JSONResponse, Response
    from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer
    from fastapi.staticfiles import StaticFiles
    from fastapi_offline import FastAPIOffline
    from pydantic import BaseModel, ConfigDict, Field
    from starlette.exceptions import HTTPException as StarletteHTTPException

    from kb.catalog import KnowledgeBase
    from kb.features import CATEGORIES, FEATURES, ObjectRecord

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
    try:
        from recall.metrics import METRICS
    except ImportError:  # pragma: no cover - the recall package is part of the project
        METRICS = ("jp",)
    MetricName = Literal[tuple(METRICS)]  # type: ignore[valid-type]

    @asynccontextmanager
    async def lifespan(app):
        if warm:
            threading.Thread(target=_warm_up, name="objrecall-warm-up", daemon=True).start()
        yield
        # stop a running ingestion child with the server: its one write transaction rolls back if open
        job = app.state.jobs.running()
        if job is not None and job.process is not None:
            job.process.terminate()

    def _warm_up() -> None:
        try:
            from recall.parser import parse

            parse("a smooth plastic cup about 10 cm tall, 200 g")
            recaller()
        except Exception:  # noqa: BLE001 - warming is best effort; the real request reports any error
            pass

    # /docs and /redoc with Swagger UI / ReDoc served by this server (fastapi-offline), not from a CDN
    app = FastAPIOffline(
        lifespan=lifespan,
        title="objrecall knowledge service",
        version=_package_version(),
        description="Recall household objects from descriptions, browse the catalog, plan grasps. "
        "Reads are open; writes need `Authorization: Bearer <token>`. See kb/SERVICE.md.",
    )
    app.state.settings = settings
    app.state.jobs = IngestionJobs(Path(tempfile.gettempdir()) / f"objrecall-ingest-logs-{os.getpid()}")
    recall_cache: dict[str, Any] = {"snapshot": None, "recaller": None, "checked": 0.0}
    recall_lock = threading.Lock()

    def knowledge_base() -> KnowledgeBase:
        return KnowledgeBase.open(settings.db, read_only=True, busy_timeout=settings.busy_timeout)

    def recaller():
        """The recall engine over a snapshot of the catalog, re-checked at most every snapshot_ttl s."""
        from recall.engine import Recaller
        from recall.snapshot import load_snapshot

        with recall_lock:
            now = time.monotonic()
            if recall_cache["recaller"] is not None and now - recall_cache["checked"] < settings.snapshot_ttl:
                return recall_cache["recaller"]
        if not settings.db.exists():
            raise DatabaseError(f"{settings.db}: no catalog there (create it with `objrecall init`)")
        snap = load_snapshot(settings.db)
        with recall_lock:
            if snap is not recall_cache["snapshot"]:
                recall_cache["recaller"] = Recaller(snap)
                recall_cache["snapshot"] = snap
            recall_cache["checked"] = time.monotonic()
            return recall_cache["recaller"]

    # -- errors as JSON
    @app.exception_handler(ObjrecallError)
    async def objrecall_error(request: Request, err: ObjrecallError):
        headers = {"Retry-After": "5"} if isinstance(err, DatabaseBusy) else None
        return JSONResponse(
            {"error": type(err).__name__, "detail": " ".join(str(err).split())},
            status_code=status_for(err),
            headers=headers,
        )

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, err: StarletteHTTPException):
        names = {401: "Unauthorized", 403: "Forbidden", 404: "NotFound", 405: "MethodNotAllowed"}
        return JSONResponse(
            {"error": names.get(err.status_code, "HTTPError"), "detail": str(err.detail)},
            status_code=err.status_code,
            headers=getattr(err, "headers", None),
        )

    @app.exception_handler(RequestValidationError)
    async def validation_error(request: Request, err: RequestValidationError):
        problems = []
        for e in err.errors():
            where = ".".join(str(p) for p in e.get("loc", ()) if p != "body") or "body"
            problems.append(f"{where}: {e.get('msg', 'invalid')}")
        return JSONResponse(
            {"error": "ValidationError", "detail": "; ".join(problems) or "invalid request"}, status_code=422
        )

    @app.exception_handler(Exception)
    async def unexpected(request: Request, err: Exception):  # a bug: say so without leaking internals
        return JSONResponse(
            {"error": "InternalError", "detail": f"internal error ({type(err).__name__}); please report it"},
            status_code=500,
        )

    # -- auth
    bearer = HTTPBearer(auto_error=False, description="The API token configured on the server.")

    def require_token(creds: Annotated[HTTPAuthorizationCredentials | None, Depends(bearer)]) -> None:
        from fastapi import HTTPException

        if settings.token is None:
            raise WritesDisabled(
                f"writes are disabled: no API token is configured on the server (set {ENV_TOKEN} "
                f"or {ENV_TOKEN_FILE})"
            )
        if creds is None or creds.scheme.lower() != "bearer":
            raise HTTPException(
                401, "this endpoint needs 'Authorization: Bearer <token>'", {"WWW-Authenticate": "Bearer"}
            )
        if not hmac.compare_digest(creds.credentials.encode(), settings.token.encode()):
            raise HTTPException(401, "invalid API token", {"WWW-Authenticate": "Bearer"})

    # -- models
    class Page(BaseModel):
        total: int
        limit: int
        offset: int
        items: list[dict[str, Any]]

    class TextIn(BaseModel):
        model_config = ConfigDict(extra="forbid")
        text: str = Field(min_length=1, max_length=MAX_TEXT_CHARS, description="A description of an object.")

    class RecallIn(TextIn):
        top: int = Field(5, ge=1, le=MAX_TOP, description="How many ranked matches.")
        metric: MetricName | None = Field(  # type: ignore[valid-type]
            None,
            description="Distance metric; default: jplog with object names (the hybrid), or the paper's jp "
            "with features_only (recall/RECALL.md).",
        )
        features_only: bool = Field(False, description="Ignore object names in the text (features only).")

    class LookupIn(RecallIn):
        budget_s: float = Field(10.0, gt=0, le=60, description="Seconds the lookup may take.")
        max_pages: int = Field(12, ge=1, le=50, description="Requests the lookup may make, over all stores.")
        force: bool = Field(False, description="Ask the stores even when the catalog recall is good.")

    class PlanIn(BaseModel):
        model_config = ConfigDict(extra="forbid")
        text: str | None = Field(None, min_length=1, max_length=MAX_TEXT_CHARS, description="A description.")
        name: str | None = Field(None, min_length=1, max_length=200, description="A catalog name or alias.")
        top: int = Field(3, ge=1, le=15, description="How many ranked grasp plans.")

    class SqlIn(BaseModel):
        model_config = ConfigDict(extra="forbid")
        query: str = Field(min_length=1, max_length=20_000, description="One read-only SELECT statement.")
        max_rows: int = Field(1000, ge=1, le=settings.sql_max_rows)
        timeout_s: float = Field(5.0, gt=0, le=settings.sql_max_timeout)

    class ObjectIn(BaseModel):
        """Feature values of an object (catalog units); omitted or null values stay as stored."""

        model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
        a_cm: float | None = Field(None, description="Largest extent, cm.")
        b_cm: float | None = Field(None, description="Middle extent, cm.")
        c_cm: float | None = Field(None, description="Smallest extent, cm.")
        mass_g: float | None = Field(None, description="Mass, g.")
        shape: str | None = Field(
            None, max_length=40, description=f"One of {', '.join(CATEGORIES['shape'])}."
        )
        texture: str | None = Field(
            None, max_length=40, description=f"One of {', '.join(CATEGORIES['texture'])}."
        )
        fragility: str | None = Field(
            None, max_length=40, description=f"One of {', '.join(CATEGORIES['fragility'])}."
        )
        material: str | None = Field(
            None, max_length=40, description=f"One of {', '.join(CATEGORIES['material'])}."
        )
        rigidity: str | None = Field(
            None, max_length=40, description=f"One of {', '.join(CATEGORIES['rigidity'])}."
        )
        aliases: list[Annotated[str, Field(max_length=200)]] = Field(default_factory=list, max_length=50)
        source: str | None = Field(None, max_length=500, description="Where the values come from.")

    limit_q = Annotated[int, Query(ge=1, le=MAX_PAGE, description=f"Page size (at most {MAX_PAGE}).")]
    offset_q = Annotated[int, Query(ge=0, le=10_000_000, description="Items to skip.")]
    name_p = Annotated[str, PathParam(min_length=1, max_length=200, description="A catalog name or alias.")]

    # -- reads
    @app.get("/health", tags=["service"])
    def health() -> dict[str, Any]:
        """Liveness: the process answers; ``catalog`` says whether the database file exists."""
        return {"status": "ok", "catalog": settings.db.exists()}

    @app.get("/version", tags=["service"])
    def version() -> dict[str, Any]:
        """Versions of the service, the schema and the catalog contents."""
        kb = knowledge_base()
        count, max_id, updated = kb.catalog_version()
        try:
            from sim.planner import PLANNER_VERSION
        except ImportError:  # pragma: no cover
            PLANNER_VERSION = None
        with kb.connect() as con:
            row = con.execute("SELECT max(version_num) FROM alembic_version").fetchone()
        return {
            "objrecall": _package_version(),
            "schema_revision": row[0] if row else None,
            "catalog": {"objects": count, "max_id": max_id, "updated_at": updated},
            "planner_version": PLANNER_VERSION,
            "writes_enabled": settings.token is not None,
        }

    @app.get("/objects", tags=["catalog"], response_model=Page)
    def list_objects(limit: limit_q = DEFAULT_PAGE, offset: offset_q = 0) -> dict[str, Any]:
        """Catalog objects ordered by name, one page at a time (``total`` counts them all)."""
        kb = knowledge_base()
        items = [r.to_dict() for r in kb.list_objects(limit=limit, offset=offset)]
        for item in items:
            item.pop("extra", None)
        return {"total": kb.count_objects(), "limit": limit, "offset": offset, "items": to_jsonable(items)}

    @app.get("/objects/{name}", tags=["catalog"])
    def get_object(name: name_p) -> dict[str, Any]:
        """One object by name or alias, with the provenance of its values (newest first)."""
        kb = knowledge_base()
        record = kb.get_object(name).to_dict()
        record.pop("extra", None)
        record["provenance"] = kb.provenance(record["name"])
        return to_jsonable(record)

    @app.post("/parse", tags=["recall"])
    def parse_text(body: TextIn) -> dict[str, Any]:
        """The features a description states, with the words each came from."""
        from recall.parser import parse

        return to_jsonable(parse(body.text).to_dict())

    @app.post("/recall", tags=["recall"])
    def recall(body: RecallIn) -> dict[str, Any]:
        """Ranked catalog objects for a description, each with per-feature contributions (lower = closer),
        a calibrated confidence and the open-set flag."""
        result = recaller().recall_text(
            body.text, top=body.top, metric=body.metric, features_only=body.features_only
        )
        return to_jsonable(result.to_dict())

    def _record_of(result):
        """A catalog object of the result (its matches and closest of the same kind) by name, from the
        snapshot the result came from (no second read of the catalog)."""
        known = {m.name: m for m in (*result.matches, *result.same_kind)}

        def get(name: str) -> ObjectRecord:
            m = known[name]
            return ObjectRecord.create(m.name, **{f: m.features.get(f) for f in FEATURES})

        return get

    @app.post("/grasp/plan", tags=["grasp"])
    def grasp_plan(body: PlanIn) -> dict[str, Any]:
        """Ranked grasp plans for a catalog object (``name``) or the best match of a description (``text``)."""
        from sim.planner import plan_grasps

        if (body.text is None) == (body.name is None):
            raise ObjrecallError("give exactly one of 'text' (a description) or 'name' (a catalog object)")
        if body.name is not None:
            obj = knowledge_base().get_object(body.name)
            how: dict[str, Any] = {"method": "name"}
        else:
            from recall.target import grasp_target

            result = recaller().recall_text(body.text, top=3)
            if not result.matches:
                raise RecallError("the description states no feature and names no catalog object")
            obj, how = grasp_target(result, _record_of(result))
        plans = plan_grasps(obj, top=body.top)
        return to_jsonable(
            {
                "object": obj.name,
                "recalled": how,
                "features": obj.features(),
                "plans": [p.to_dict() for p in plans],
            }
        )

    @app.get("/grasp/validations", tags=["grasp"], response_model=Page)
    def grasp_validations(
        object: Annotated[str | None, Query(max_length=200, description="Only this object.")] = None,
        limit: limit_q = DEFAULT_PAGE,
        offset: offset_q = 0,
    ) -> dict[str, Any]:
        """Stored MuJoCo grasp trials (``objrecall grasp validate``), optionally for one object (name or
        alias), ordered by object, rank, grasp type and seed."""
        from kb.features import normalize_name

        where, params = "", []
        if object is not None:
            where, params = "WHERE object_name = ?", [normalize_name(object)]
            try:
                params = [knowledge_base().get_object(object).name]
            except ObjectNotFound:
                pass  # trials of an object since removed from the catalog are still listed
        with knowledge_base().connect() as con:
            total = con.execute(f"SELECT count(*) FROM grasp_validations {where}", params).fetchone()[0]
            cur = con.execute(
                f"SELECT * FROM grasp_validations {where} ORDER BY object_name, rank, grasp_type, seed, id "
                "LIMIT ? OFFSET ?",
                [*params, limit, offset],
            )
            cols = [d[0] for d in cur.description]
            items = [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]
        return {"total": int(total), "limit": limit, "offset": offset, "items": to_jsonable(items)}

    @app.post("/sql", tags=["catalog"])
    def run_sql(body: SqlIn) -> Response:
        """One read-only SELECT in the sandbox: no writes, files, network, ATTACH or extensions; at most
        ``max_rows`` rows (``truncated`` says when there were more) and ``timeout_s`` seconds (504)."""
        try:
            # The statement must stop before the request's own time limit: a request that timed out would
            # otherwise leave its worker thread inside DuckDB (and a process exiting then aborts).
            timeout_s = min(body.timeout_s, max(0.1, 0.9 * settings.request_timeout))
            result = knowledge_base().sql(body.query, max_rows=body.max_rows, timeout_s=timeout_s)
        except QueryTimeout as err:
            raise RequestTimeout(str(err)) from None
        payload = to_jsonable(
            {"columns": result.columns, "rows": result.to_dicts(), "truncated": result.truncated}
        )
        data = json.dumps(payload, ensure_ascii=False).encode()
        if len(data) > SQL_MAX_RESPONSE_BYTES:
            raise QueryFailed(
                f"result too large: {len(data):,} bytes as JSON (at most {SQL_MAX_RESPONSE_BYTES:,}); "
                "select fewer rows or columns"
            )
        return Response(content=data, media_type="application/json")

    @app.get("/ingestion/runs", tags=["ingestion"])
    def ingestion_runs(limit: Annotated[int, Query(ge=1, le=200)] = 20) -> dict[str, Any]:
        """Recent ingestion runs recorded in the catalog (newest first), and any job this service started."""
        runs = knowledge_base().ingestion_runs(limit=limit)
        jobs = [j.to_dict() for j in app.state.jobs.jobs.values()]
        return to_jsonable({"runs": runs, "jobs": jobs})

    @app.get("/ingestion/jobs/{job_id}", tags=["ingestion"])
    def ingestion_job(job_id: Annotated[str, PathParam(max_length=40)]) -> dict[str, Any]:
        """Status and log tail of an ingestion job started by ``POST /ingestion/runs``."""
        return app.state.jobs.get(job_id).to_dict()

    # -- writes
    @app.post("/ingestion/runs", tags=["ingestion"], status_code=202, dependencies=[Depends(require_token)])
    def start_ingestion() -> dict[str, Any]:
        """Start ``objrecall ingest --sources <configured file> --db <catalog>`` as a child process; 202 with
        the job handle (poll ``/ingestion/jobs/{id}``). 409 while a job started here still runs."""
        if settings.sources is None:
            raise ObjrecallError(
                f"no sources file configured on the server (start it with --sources FILE or set {ENV_SOURCES})"
            )
        command = [
            *settings.ingest_command,
            "ingest",
            "--sources",
            str(settings.sources),
            "--db",
            str(settings.db),
        ]
        job = app.state.jobs.start(command)
        return {"id": job.id, "status": job.status, "status_url": f"/ingestion/jobs/{job.id}"}

    @app.post("/recall/lookup", tags=["recall"], dependencies=[Depends(require_token)])
    def recall_lookup(body: LookupIn) -> dict[str, Any]:
        """Recall, and when the catalog does not know the object (open set, or confidence below 0.5, or
        ``force``), search the configured stores, add the products that fit, and recall again
        (``recall.lookup``). A write: it needs the token. The answer's ``result`` is the recall to act on;
        ``looked_up``, ``found``, ``message`` and ``stores`` say what the lookup did."""
        import requests

        from recall.lookup import recall_with_lookup
        from scrapers.sources import load_sources

        if settings.sources is None:
            raise ObjrecallError(
                f"no sources file configured on the server (start it with --sources FILE or set {ENV_SOURCES})"
            )
        plan = load_sources(settings.sources)
        with requests.Session() as session:
            result = recall_with_lookup(
                settings.db, body.text, sources=plan, session=session,
                budget_s=min(body.budget_s, max(0.5, 0.8 * settings.request_timeout)),
                max_pages=body.max_pages, force=body.force, top=body.top, metric=body.metric,
                features_only=body.features_only,
            )  # fmt: skip
        return to_jsonable(result.to_dict())

    @app.put("/objects/{name}", tags=["catalog"], dependencies=[Depends(require_token)])
    def put_object(name: name_p, body: ObjectIn) -> JSONResponse:
        """Insert or edit an object: given values replace stored ones (validated like the CSV import),
        and every change is kept in its provenance with source ``api``. 201 when the object is new."""
        values = body.model_dump()
        aliases = values.pop("aliases")
        source = values.pop("source") or "api"
        record = ObjectRecord.create(name, aliases=aliases, source=source, **values)
        if not settings.db.exists():
            raise DatabaseError(f"{settings.db}: no catalog there (create it with `objrecall init`)")
        kb = KnowledgeBase.open(settings.db, busy_timeout=settings.busy_timeout, upgrade=False)
        try:  # an alias edits the object it names
            record = replace(record, name=kb.get_object(record.name).name)
        except ObjectNotFound:
            pass
        report = kb.upsert([record], source=source, adapter="api")
        stored = kb.get_object(record.name).to_dict()
        stored.pop("extra", None)
        stored["provenance"] = kb.provenance(record.name)
        with recall_lock:
            recall_cache["checked"] = 0.0
        return JSONResponse(to_jsonable(stored), status_code=201 if report.new else 200)

    # -- the web page
    static = Path(__file__).parent / "static"
    app.mount("/static", StaticFiles(directory=static), name="static")

    @app.get("/", include_in_schema=False)
    def index() -> FileResponse:
        return FileResponse(static / "index.html", headers={"Cache-Control": "no-cache"})

    return LimitsWrapped(app, settings)


def _package_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("objrecall")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree without installing
        return "0+unknown"
