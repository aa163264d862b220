"""The request and response bodies of the HTTP service (pydantic), and the shared query and path
parameters. A request these refuse gets 422 naming each problem."""

from typing import Annotated, Any, Literal

from fastapi import Path as PathParam
from fastapi import Query
from pydantic import BaseModel, ConfigDict, Field

from kb.features import CATEGORIES, MAX_NAME_CHARS
from kb.service.http.settings import MAX_PAGE, MAX_TEXT_CHARS, MAX_TOP, SQL_MAX_ROWS, SQL_MAX_TIMEOUT_S
from recall.metrics import METRICS

__all__ = ["LimitQ", "LookupIn", "NameP", "ObjectIn", "OffsetQ", "Page", "PlanIn", "RecallIn", "SqlIn", "TextIn"]

MetricName = Literal[tuple(METRICS)]  # type: ignore[valid-type]

LimitQ = Annotated[int, Query(ge=1, le=MAX_PAGE, description=f"Page size (at most {MAX_PAGE}).")]
OffsetQ = Annotated[int, Query(ge=0, le=10_000_000, description="Items to skip.")]
NameP = Annotated[str, PathParam(min_length=1, max_length=MAX_NAME_CHARS, description="A catalog name or alias.")]


class Page(BaseModel):
    total: int
    limit: int
    offset: int
    items: list[dict[str, Any]]


class TextIn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    text: str = Field(min_length=1, description=f"A description of an object (at most {MAX_TEXT_CHARS:,} characters).")


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
    max_pages: int = Field(20, ge=1, le=50, description="Requests the lookup may make, over all stores.")
    force: bool = Field(False, description="Ask the stores even when the catalog recall is good.")


class PlanIn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    text: str | None = Field(None, min_length=1, description=f"A description (at most {MAX_TEXT_CHARS:,} characters).")
    name: str | None = Field(None, min_length=1, max_length=MAX_NAME_CHARS, description="A catalog name or alias.")
    top: int = Field(3, ge=1, le=15, description="How many ranked grasp plans.")


class SqlIn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    query: str = Field(min_length=1, max_length=20_000, description="One read-only SELECT statement.")
    max_rows: int = Field(1000, ge=1, le=SQL_MAX_ROWS)
    timeout_s: float = Field(5.0, gt=0, le=SQL_MAX_TIMEOUT_S)


def _category(feature: str) -> Any:
    return Field(None, max_length=40, description=f"One of {', '.join(CATEGORIES[feature])}.")


class ObjectIn(BaseModel):
    """Feature values of an object (catalog units); omitted or null values stay as stored."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    a_cm: float | None = Field(None, description="Largest extent, cm.")
    b_cm: float | None = Field(None, description="Middle extent, cm.")
    c_cm: float | None = Field(None, description="Smallest extent, cm.")
    mass_g: float | None = Field(None, description="Mass, g.")
    shape: str | None = _category("shape")
    texture: str | None = _category("texture")
    fragility: str | None = _category("fragility")
    material: str | None = _category("material")
    rigidity: str | None = _category("rigidity")
    aliases: list[Annotated[str, Field(max_length=MAX_NAME_CHARS)]] = Field(default_factory=list, max_length=50)
    source: str | None = Field(None, max_length=500, description="Where the values come from.")
