"""``GET /ingestion/runs``, ``GET /ingestion/jobs/{id}`` and ``POST /ingestion/runs`` (a write: starts
``objrecall ingest`` as a child process)."""

from typing import Annotated, Any

from fastapi import APIRouter, Depends, Query
from fastapi import Path as PathParam

from kb.jsonable import to_jsonable
from kb.service.http.auth import require_token
from kb.service.http.routes import State

router = APIRouter(tags=["ingestion"])


@router.get("/ingestion/runs")
def ingestion_runs(state: State, limit: Annotated[int, Query(ge=1, le=200)] = 20) -> dict[str, Any]:
    """Recent ingestion runs recorded in the catalog (newest first), and any job this service started."""
    runs = state.knowledge_base().ingestion_runs(limit=limit)
    jobs = [j.to_dict() for j in state.jobs.jobs.values()]
    return to_jsonable({"runs": runs, "jobs": jobs})


@router.get("/ingestion/jobs/{job_id}")
def ingestion_job(job_id: Annotated[str, PathParam(max_length=40)], state: State) -> dict[str, Any]:
    """Status and log tail of an ingestion job started by ``POST /ingestion/runs``."""
    return state.jobs.get(job_id).to_dict()


@router.post("/ingestion/runs", status_code=202, dependencies=[Depends(require_token)])
def start_ingestion(state: State) -> dict[str, Any]:
    """Start ``objrecall ingest --sources <configured file> --db <catalog>`` as a child process; 202 with
    the job handle (poll ``/ingestion/jobs/{id}``). 409 while a job started here still runs."""
    settings = state.settings
    command = [*settings.ingest_command, "ingest", "--sources", str(state.sources_file()), "--db", str(settings.db)]
    job = state.jobs.start(command)
    return {"id": job.id, "status": job.status, "status_url": f"/ingestion/jobs/{job.id}"}
