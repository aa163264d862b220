"""The catalog over HTTP: ``GET /objects``, ``GET /objects/{name}``, ``PUT /objects/{name}`` (a write) and
``POST /sql`` (one read-only statement in the sandbox).

A name is the rest of the path, "/" included (``{name:path}``): catalog names may hold a "/" ("salt/pepper
shaker", from a CSV or a store page), and ``/objects/salt%2Fpepper%20shaker`` or ``/objects/salt/pepper
shaker`` reach it. Nothing else is routed under ``/objects/``."""

import json
from dataclasses import replace
from typing import Any

from fastapi import APIRouter, Depends
from fastapi.responses import JSONResponse, Response

from kb.errors import ObjectNotFound, QueryFailed, QueryTimeout, RequestTimeout
from kb.jsonable import to_jsonable
from kb.service.http.auth import require_token
from kb.service.http.models import LimitQ, NameP, ObjectIn, OffsetQ, Page, SqlIn
from kb.service.http.routes import State
from kb.service.http.settings import DEFAULT_PAGE, SQL_MAX_RESPONSE_BYTES

router = APIRouter(tags=["catalog"])


def object_with_provenance(kb, name: str) -> dict[str, Any]:
    """One stored object as the API shows it: its values and the provenance of each (newest first)."""
    record = kb.get_object(name).to_dict()
    record.pop("extra", None)
    record["provenance"] = kb.provenance(record["name"])
    return to_jsonable(record)


@router.get("/objects", response_model=Page)
def list_objects(state: State, limit: LimitQ = DEFAULT_PAGE, offset: OffsetQ = 0) -> dict[str, Any]:
    """Catalog objects ordered by name, one page at a time (``total`` counts them all)."""
    kb = state.knowledge_base()
    items = [r.to_dict() for r in kb.list_objects(limit=limit, offset=offset)]
    for item in items:
        item.pop("extra", None)
    return {"total": kb.count_objects(), "limit": limit, "offset": offset, "items": to_jsonable(items)}


@router.get("/objects/{name:path}")
def get_object(name: NameP, state: State) -> dict[str, Any]:
    """One object by name or alias, with the provenance of its values (newest first)."""
    return object_with_provenance(state.knowledge_base(), name)


@router.post("/sql")
def run_sql(body: SqlIn, state: State) -> Response:
    """One read-only SELECT in the sandbox: no writes, files, network, ATTACH or extensions; at most
    ``max_rows`` rows (``truncated`` says when there were more) and ``timeout_s`` seconds (504)."""
    try:
        # The statement must stop before the request's own time limit: a request that timed out would
        # otherwise leave its worker thread inside DuckDB (and a process exiting then aborts).
        timeout_s = min(body.timeout_s, max(0.1, 0.9 * state.settings.request_timeout))
        result = state.knowledge_base().sql(body.query, max_rows=body.max_rows, timeout_s=timeout_s)
    except QueryTimeout as err:
        raise RequestTimeout(str(err)) from None
    payload = to_jsonable({"columns": result.columns, "rows": result.to_dicts(), "truncated": result.truncated})
    data = json.dumps(payload, ensure_ascii=False).encode()
    if len(data) > SQL_MAX_RESPONSE_BYTES:
        raise QueryFailed(
            f"result too large: {len(data):,} bytes as JSON (at most {SQL_MAX_RESPONSE_BYTES:,}); "
            "select fewer rows or columns"
        )
    return Response(content=data, media_type="application/json")


@router.put("/objects/{name:path}", dependencies=[Depends(require_token)])
def put_object(name: NameP, body: ObjectIn, state: State) -> JSONResponse:
    """Insert or edit an object: given values replace stored ones (validated like the CSV import),
    and every change is kept in its provenance with source ``api``. 201 when the object is new."""
    from kb.features import ObjectRecord

    values = body.model_dump()
    aliases = values.pop("aliases")
    source = values.pop("source") or "api"
    record = ObjectRecord.create(name, aliases=aliases, source=source, **values)
    kb = state.writable_knowledge_base()
    try:  # an alias edits the object it names
        record = replace(record, name=kb.get_object(record.name).name)
    except ObjectNotFound:
        pass
    report = kb.upsert([record], source=source, adapter="api")
    stored = object_with_provenance(kb, record.name)
    state.forget_snapshot()
    return JSONResponse(stored, status_code=201 if report.new else 200)
