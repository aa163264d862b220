"""``POST /grasp/plan`` (ranked grasp plans for an object or a description, with its latest validation),
``GET /grasp/validations`` (the stored MuJoCo trials) and ``GET /grasp/render`` (a PNG of a planned grasp)."""

from typing import Annotated, Any

from fastapi import APIRouter, Query
from fastapi.responses import Response

from kb.errors import ObjectNotFound, ObjrecallError, RecallError
from kb.features import MAX_NAME_CHARS
from kb.jsonable import to_jsonable
from kb.service.http.models import LimitQ, OffsetQ, Page, PlanIn
from kb.service.http.routes import State
from kb.service.http.settings import DEFAULT_PAGE

router = APIRouter(tags=["grasp"])


def _record_of(result):
    """A catalog object of the result (its matches and closest of the same kind) by name, from the
    snapshot the result came from (no second read of the catalog)."""
    from kb.features import FEATURES, ObjectRecord

    known = {m.name: m for m in (*result.matches, *result.same_kind)}

    def get(name: str) -> ObjectRecord:
        m = known[name]
        return ObjectRecord.create(m.name, **{f: m.features.get(f) for f in FEATURES})

    return get


@router.post("/grasp/plan")
def grasp_plan(body: PlanIn, state: State) -> dict[str, Any]:
    """Ranked grasp plans for a catalog object (``name``) or the best match of a description (``text``)."""
    from sim.experience import saved_experience
    from sim.planner import plan_grasps

    if (body.text is None) == (body.name is None):
        raise ObjrecallError("give exactly one of 'text' (a description) or 'name' (a catalog object)")
    if body.name is not None:
        obj = state.knowledge_base().get_object(body.name)
        how: dict[str, Any] = {"method": "name"}
    else:
        from recall.target import grasp_target

        result = state.recaller().recall_text(body.text, top=3)
        if not result.matches:
            raise RecallError("the description states no feature and names no catalog object")
        obj, how = grasp_target(result, _record_of(result))
    plans = plan_grasps(obj, top=body.top, experience=saved_experience())
    return to_jsonable(
        {
            "object": obj.name,
            "recalled": how,
            "features": obj.features(),
            "plans": [p.to_dict() for p in plans],
            "validation": _latest_validation(state, obj.name),
        }
    )


def _latest_validation(state: State, name: str) -> dict[str, Any] | None:
    """The stored trials of ``name`` with the current hand (``objrecall grasp validate``) as its first and
    validated choice (sim/choice.py), or None when it was not validated with this hand."""
    from sim.choice import choose
    from sim.worker import current_hand_version

    with state.knowledge_base().connect() as con:
        cur = con.execute(
            "SELECT object_name, grasp_type, rank, seed, success, outcome, reason FROM grasp_validations "
            "WHERE object_name = ? AND hand_version = ? ORDER BY rank, seed",
            [name, current_hand_version()],
        )
        cols = [d[0] for d in cur.description]
        rows = [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]
    return choose(rows)[0].to_dict() if rows else None


@router.get("/grasp/render")
def grasp_render(
    state: State,
    object: Annotated[str, Query(min_length=1, max_length=MAX_NAME_CHARS, description="A catalog name or alias.")],
    grasp_type: Annotated[str, Query(max_length=40, description="One of the object's planned types.")],
) -> Response:
    """A PNG of the simulated grasp (MuJoCo, to the end of the hold, seed 0) of one of the object's planned
    grasp types: what the hand does, to look at rather than read. A render costs about a CPU-second: at
    most ``render_concurrency`` run at once (more get 503 with Retry-After) and renders are cached by
    object, features, grasp type, planner and hand (``X-Render-Cache: hit`` or ``miss``)."""
    from sim.hand import HAND_VERSION
    from sim.planner import PLANNER_VERSION, plan_grasps
    from sim.render import render_trial

    obj = state.knowledge_base().get_object(object)
    plan = next((p for p in plan_grasps(obj) if p.grasp_type == grasp_type), None)
    if plan is None:
        raise ObjrecallError(f"{grasp_type!r} is not a planned grasp of {obj.name!r}")
    key = (obj.name, tuple(sorted(obj.features().items())), grasp_type, PLANNER_VERSION, HAND_VERSION)
    png, hit = state.renders.get_or_render(key, lambda: render_trial(obj, plan, seed=0, width=480, height=360))
    headers = {"Cache-Control": "max-age=300", "X-Render-Cache": "hit" if hit else "miss"}
    return Response(content=png, media_type="image/png", headers=headers)


@router.get("/grasp/validations", response_model=Page)
def grasp_validations(
    state: State,
    object: Annotated[str | None, Query(max_length=MAX_NAME_CHARS, description="Only this object.")] = None,
    limit: LimitQ = DEFAULT_PAGE,
    offset: OffsetQ = 0,
) -> dict[str, Any]:
    """Stored MuJoCo grasp trials (``objrecall grasp validate``), optionally for one object (name or
    alias), ordered by object, rank, grasp type and seed."""
    from kb.features import normalize_name

    kb = state.knowledge_base()
    where, params = "", []
    if object is not None:
        where, params = "WHERE object_name = ?", [normalize_name(object)]
        try:
            params = [kb.get_object(object).name]
        except ObjectNotFound:
            pass  # trials of an object since removed from the catalog are still listed
    with kb.connect() as con:
        total = con.execute(f"SELECT count(*) FROM grasp_validations {where}", params).fetchone()[0]
        cur = con.execute(
            f"SELECT * FROM grasp_validations {where} ORDER BY object_name, rank, grasp_type, seed, id "
            "LIMIT ? OFFSET ?",
            [*params, limit, offset],
        )
        cols = [d[0] for d in cur.description]
        items = [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]
    return {"total": int(total), "limit": limit, "offset": offset, "items": to_jsonable(items)}
