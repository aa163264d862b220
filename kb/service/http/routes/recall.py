"""``POST /parse`` (the features a description states) and ``POST /recall`` (the catalog objects it is about)."""

from typing import Any

from fastapi import APIRouter

from kb.jsonable import to_jsonable
from kb.service.http.models import RecallIn, TextIn
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
