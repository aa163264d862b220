"""Every documented limit pinned at its boundary, on both sides: the exact limit passes, the next value
past it is refused (so turning a ``>`` into ``>=``, or the reverse, fails a test).

Limits: 5 m and 500 kg per feature (kb/features.py), values > 0, the CSV cell limit (131,072 characters)
and name limit (200), the SQL row limit (``max_rows``, and 5,000 over HTTP), the SQL time limit over HTTP
(10 s), the SQL response size (8 MiB), the request body (64 KiB), list pages (500), description length
(5,000 characters) and recall ``top`` (50). The parser's own limits (feet and inches, signs) are pinned in
the parser's tests.
"""

from __future__ import annotations

import json
import math

import pytest
from fastapi.testclient import TestClient

from kb.catalog import KnowledgeBase
from kb.csvio import MAX_CELL_CHARS, MAX_NAME_CHARS, parse_catalog_csv
from kb.errors import CatalogImportError, InvalidFeature
from kb.features import MAX_DIM_CM, MAX_MASS_G, ObjectRecord, validate_features
from kb.service.http import create_app
from kb.service.http.settings import MAX_PAGE, MAX_TEXT_CHARS, MAX_TOP, SQL_MAX_RESPONSE_BYTES, SQL_MAX_ROWS

HEADER = "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity,source\n"


def _past(x: float) -> float:
    return math.nextafter(x, math.inf)


# ---------------------------------------------------------------------------------------------- features
@pytest.mark.parametrize("feature, limit", [("a_cm", MAX_DIM_CM), ("b_cm", MAX_DIM_CM), ("c_cm", MAX_DIM_CM),
                                            ("mass_g", MAX_MASS_G)])
def test_feature_limits_at_the_boundary(feature, limit):
    assert limit == (500_000.0 if feature == "mass_g" else 500.0)
    assert validate_features({feature: limit})[feature if feature == "mass_g" else "a_cm"] == limit
    assert validate_features({feature: str(limit)})[feature if feature == "mass_g" else "a_cm"] == limit
    for over in (_past(limit), limit + 0.001, f"{limit}01"):
        with pytest.raises(InvalidFeature, match="absurd"):
            validate_features({feature: over})
    smallest = math.nextafter(0.0, 1.0)
    assert validate_features({feature: smallest})[feature if feature == "mass_g" else "a_cm"] == smallest
    for not_positive in (0, 0.0, "0", -0.0, math.nextafter(0.0, -1.0), -1):
        with pytest.raises(InvalidFeature, match="greater than zero"):
            validate_features({feature: not_positive})


def test_csv_refuses_just_past_the_feature_limits():
    ok = parse_catalog_csv(HEADER + f"big box,{MAX_DIM_CM:g},50,50,{MAX_MASS_G:g},,,,,,\n")  # 0.4 g/cm³
    assert ok.records[0].a_cm == MAX_DIM_CM and ok.records[0].mass_g == MAX_MASS_G
    for row, column in (("big box,500.0001,1,1,10,,,,,,\n", "a_cm"), ("big box,1,1,1,500000.01,,,,,,\n", "mass_g")):
        with pytest.raises(CatalogImportError) as err:
            parse_catalog_csv(HEADER + row)
        assert err.value.problems[0][:2] == (2, column)


# ---------------------------------------------------------------------------------------------- CSV
def test_csv_cell_limit_at_the_boundary():
    assert MAX_CELL_CHARS == 131_072
    at = parse_catalog_csv(HEADER + "mug,1,1,1,1,,,,,," + "s" * MAX_CELL_CHARS + "\n")
    assert len(at.records[0].source) == MAX_CELL_CHARS
    with pytest.raises(CatalogImportError, match="over 131,072 characters"):
        parse_catalog_csv(HEADER + "mug,1,1,1,1,,,,,," + "s" * (MAX_CELL_CHARS + 1) + "\n")


def test_csv_name_limit_at_the_boundary():
    assert MAX_NAME_CHARS == 200
    at = parse_catalog_csv(HEADER + "n" * MAX_NAME_CHARS + ",1,1,1,1,,,,,,\n")
    assert len(at.records[0].name) == MAX_NAME_CHARS
    with pytest.raises(CatalogImportError, match="implausible name"):
        parse_catalog_csv(HEADER + "n" * (MAX_NAME_CHARS + 1) + ",1,1,1,1,,,,,,\n")


def test_csv_cell_count_at_the_boundary():
    cells = HEADER.count(",") + 1
    assert parse_catalog_csv(HEADER + "mug" + "," * (cells - 1) + "\n").records[0].name == "mug"
    for commas in (cells - 2, cells):
        with pytest.raises(CatalogImportError, match="cells, header has"):
            parse_catalog_csv(HEADER + "mug" + "," * commas + "\n")


# ---------------------------------------------------------------------------------------------- SQL
def test_sql_row_limit_at_the_boundary(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "c.duckdb")
    kb.upsert([ObjectRecord.create(f"thing {i}", mass_g=1) for i in range(7)], source="t", adapter="test")
    exact = kb.sql("SELECT name FROM objects", max_rows=7)
    assert len(exact.rows) == 7 and not exact.truncated
    cut = kb.sql("SELECT name FROM objects", max_rows=6)
    assert len(cut.rows) == 6 and cut.truncated
    assert kb.sql("SELECT name FROM objects", max_rows=8).truncated is False


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    from kb.service.bootstrap import seed_catalog_path

    db = tmp_path_factory.mktemp("limits") / "catalog.duckdb"
    KnowledgeBase.open(db).import_csv(seed_catalog_path())
    return TestClient(create_app(db, token=""), raise_server_exceptions=False, base_url="http://127.0.0.1")


def test_http_sql_row_and_time_limits_at_the_boundary(client):
    q = "SELECT 1 AS one"
    assert client.post("/sql", json={"query": q, "max_rows": SQL_MAX_ROWS}).status_code == 200
    assert client.post("/sql", json={"query": q, "max_rows": SQL_MAX_ROWS + 1}).status_code == 422
    assert client.post("/sql", json={"query": q, "max_rows": 0}).status_code == 422
    assert client.post("/sql", json={"query": q, "timeout_s": 10}).status_code == 200
    assert client.post("/sql", json={"query": q, "timeout_s": _past(10.0)}).status_code == 422
    assert client.post("/sql", json={"query": q, "timeout_s": 0}).status_code == 422
    rows = client.post("/sql", json={"query": "SELECT * FROM range(3)", "max_rows": 3}).json()
    assert len(rows["rows"]) == 3 and rows["truncated"] is False


def test_http_sql_response_size_at_the_boundary(client):
    overhead = len(json.dumps({"columns": ["s"], "rows": [{"s": ""}], "truncated": False}).encode())
    fits = SQL_MAX_RESPONSE_BYTES - overhead
    at = client.post("/sql", json={"query": f"SELECT repeat('x', {fits}) AS s"})
    assert at.status_code == 200 and len(at.content) == SQL_MAX_RESPONSE_BYTES
    over = client.post("/sql", json={"query": f"SELECT repeat('x', {fits + 1}) AS s"})
    assert over.status_code == 400 and "result too large" in over.json()["detail"]


def test_request_body_limit_at_the_boundary(client):
    limit = 64 * 1024
    filler = json.dumps({"text": ""}).encode()
    at = b'{"text": "' + b"a" * (limit - len(filler)) + b'"}'
    assert len(at) == limit
    response = client.post("/parse", content=at, headers={"content-type": "application/json"})
    assert response.status_code != 413  # (422: the text is over the description limit, checked next)
    over = at[:-2] + b'a"}'
    assert len(over) == limit + 1
    response = client.post("/parse", content=over, headers={"content-type": "application/json"})
    assert response.status_code == 413 and response.json()["error"] == "PayloadTooLarge"


def test_page_text_and_top_limits_at_the_boundary(client):
    assert client.get(f"/objects?limit={MAX_PAGE}").status_code == 200
    assert client.get(f"/objects?limit={MAX_PAGE + 1}").status_code == 422
    assert client.get("/objects?limit=0").status_code == 422
    text = "a red mug " * (MAX_TEXT_CHARS // 10)
    assert len(text) == MAX_TEXT_CHARS
    assert client.post("/parse", json={"text": text}).status_code == 200
    too_long = client.post("/parse", json={"text": text + "x"})  # the recall API's own error (test_description_limit)
    assert too_long.status_code == 400 and "description too long" in too_long.json()["detail"]
    assert client.post("/recall", json={"text": "a red mug", "top": MAX_TOP}).status_code == 200
    assert client.post("/recall", json={"text": "a red mug", "top": MAX_TOP + 1}).status_code == 422
    assert client.post("/recall", json={"text": "a red mug", "top": 0}).status_code == 422
