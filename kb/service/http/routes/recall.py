"""``POST /parse`` (the features a description states), ``POST /recall`` (the catalog objects it is about)
and ``POST /recall/lookup`` (a write: recall, and ask the stores when the catalog does not know it)."""

from typing import Any

from fastapi import APIRouter, Depends

from kb.jsonable import to_jsonable
from kb.service.http.auth import require_token
from kb.service.http.models import LookupIn, RecallIn, TextIn
from kb.service.http.routes import State

router = APIRouter(tags=["recall"])


@router.post("/parse")
def parse_text(body: TextIn) -> dict[str, Any]:
    """The features a description states, with the words each came from."""
    from recall.parser import parse

    return to_jsonable(parse(body.text).to_dict())


@router.post("/recall")
def recall(body: RecallIn, state: State) -> dict[str, Any]:
    """Ranked catalog objects for a description, each with per-feature contributions (lower = closer),
    a calibrated confidence and the open-set flag."""
    result = state.recaller().recall_text(
        body.text, top=body.top, metric=body.metric, features_only=body.features_only
    )
    return to_jsonable(result.to_dict())


@router.post("/recall/lookup", dependencies=[Depends(require_token)])
def recall_lookup(body: LookupIn, state: State) -> dict[str, Any]:
    """Recall, and when the catalog does not know the object (open set, or confidence below 0.5, or
    ``force``), search the configured stores, add the products that fit, and recall again
    (``recall.lookup``). A write: it needs the token. The answer's ``result`` is the recall to act on;
    ``looked_up``, ``found``, ``message`` and ``stores`` say what the lookup did."""
    import requests

    from recall.lookup import recall_with_lookup
    from scrapers.sources import load_sources

    settings = state.settings
    plan = load_sources(state.sources_file())
    with requests.Session() as session:
        result = recall_with_lookup(
            settings.db, body.text, sources=plan, session=session,
            budget_s=min(body.budget_s, max(0.5, 0.8 * settings.request_timeout)),
            max_pages=body.max_pages, force=body.force, top=body.top, metric=body.metric,
            features_only=body.features_only,
        )  # fmt: skip
    return to_jsonable(result.to_dict())
