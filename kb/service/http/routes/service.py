"""``GET /health`` and ``GET /version``."""

from typing import Any

from fastapi import APIRouter

from kb.service.http.routes import State
from kb.service.http.settings import package_version

router = APIRouter(tags=["service"])


@router.get("/health")
def health(state: State) -> dict[str, Any]:
    """Liveness: the process answers (HTTP 200); ``catalog`` says whether the database file exists,
    ``catalog_state`` whether it can be read ("ok", "missing", "unreadable", "busy"; checked again only
    when the file changed) and ``catalog_error`` why not; ``status`` is "ok" only with a readable catalog,
    else "degraded"."""
    catalog = state.catalog.state()
    return {
        "status": "ok" if catalog.state == "ok" else "degraded",
        "catalog": catalog.state != "missing",
        "catalog_state": catalog.state,
        "catalog_error": catalog.error,
    }


@router.get("/version")
def version(state: State) -> dict[str, Any]:
    """Versions of the service, the schema and the catalog contents."""
    from sim.planner import PLANNER_VERSION

    kb = state.knowledge_base()
    v = kb.catalog_version()
    with kb.connect() as con:
        row = con.execute("SELECT max(version_num) FROM alembic_version").fetchone()
    return {
        "objrecall": package_version(),
        "schema_revision": row[0] if row else None,
        "catalog": {"objects": v.objects, "max_id": v.max_id, "updated_at": v.updated_at, "aliases": v.aliases},
        "planner_version": PLANNER_VERSION,
        "writes_enabled": state.settings.token is not None,
    }
