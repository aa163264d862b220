"""The knowledge service in-process (the ASGI app through Starlette's test client): endpoints, errors, auth,
limits and the SQL sandbox. The same app over real HTTP is in tests/test_service_live.py."""

from __future__ import annotations

from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from kb.service.http import ERROR_STATUS, MAX_PAGE, create_app, load_token

TOKEN = "test-token-not-secret"
AUTH = {"Authorization": f"Bearer {TOKEN}"}

#: TestClient options: server errors as responses, and a loopback Host (the default allow-list).
LOCAL = {"raise_server_exceptions": False, "base_url": "http://127.0.0.1"}


@pytest.fixture(scope="module")
def shared_db(tmp_path_factory) -> Path:
    """One seeded catalog for the read-only tests of this module."""
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    path = tmp_path_factory.mktemp("service") / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(seed_catalog_path())
    return path


@pytest.fixture(scope="module")
def client(shared_db: Path) -> TestClient:
    return TestClient(create_app(shared_db, token=""), **LOCAL)


@pytest.fixture
def writer(seeded_db: Path) -> TestClient:
    """A client of an app with writes enabled, on a fresh seeded catalog."""
    return TestClient(create_app(seeded_db, token=TOKEN), **LOCAL)


def assert_error(response, status: int, error: str | None = None, words: str | None = None) -> dict:
    assert response.status_code == status, response.text
    body = response.json()
    assert set(body) >= {"error", "detail"} and body["detail"]
    if error:
        assert body["error"] == error
    if words:
        assert words in body["detail"]
    return body


# ------------------------------------------------------------------------------------------ reads
def test_health_and_version(client):
    assert client.get("/health").json() == {"status": "ok", "catalog": True, "catalog_state": "ok", "catalog_error": None}
    v = client.get("/version").json()
    assert v["catalog"]["objects"] > 100
    assert v["schema_revision"]
    assert v["writes_enabled"] is False


def test_objects_are_paged_with_a_total(client):
    first = client.get("/objects", params={"limit": 10}).json()
    second = client.get("/objects", params={"limit": 10, "offset": 10}).json()
    assert first["total"] == second["total"] > 20
    assert len(first["items"]) == len(second["items"]) == 10
    names = [o["name"] for o in first["items"] + second["items"]]
    assert names == sorted(names) and len(set(names)) == 20
    everything = client.get("/objects", params={"limit": MAX_PAGE}).json()
    assert len(everything["items"]) == everything["total"]
    assert_error(client.get("/objects", params={"limit": MAX_PAGE + 1}), 422, "ValidationError", "limit")
    assert_error(client.get("/objects", params={"offset": -1}), 422)
    past_end = client.get("/objects", params={"offset": 100_000}).json()
    assert past_end["items"] == [] and past_end["total"] == first["total"]


def test_object_by_name_or_alias_with_provenance(client):
    mug = client.get("/objects/mug").json()  # an alias
    assert mug["name"] == "coffee mug" and "mug" in mug["aliases"]
    assert mug["provenance"], "the seed import records where each value came from"
    assert {p["feature"] for p in mug["provenance"]} >= {"mass_g", "material"}
    assert all(p["adapter"] == "csv" for p in mug["provenance"])
    assert_error(client.get("/objects/no%20such%20thing"), 404, "ObjectNotFound", "no such thing")


def test_parse(client):
    body = client.post("/parse", json={"text": "a glass jar about 12 cm tall weighing 400 g"}).json()
    assert body["a_cm"] == pytest.approx(12.0)
    assert body["mass_g"] == pytest.approx(400.0)
    assert body["material"] == "glass"
    assert body["evidence"]["mass_g"]["words"]
    assert_error(client.post("/parse", json={"text": ""}), 422)
    assert_error(client.post("/parse", json={}), 422, "ValidationError", "text")
    assert_error(client.post("/parse", json={"text": 5}), 422)
    assert_error(
        client.post("/parse", content=b"{not json", headers={"content-type": "application/json"}), 422
    )


def test_recall_ranks_with_explanations(client):
    body = client.post(
        "/recall", json={"text": "a yellow fuzzy tennis ball, about 6.5 cm across, 58 g", "top": 3}
    ).json()
    assert body["matches"][0]["name"] == "tennis ball"
    assert len(body["matches"]) == 3
    assert 0.0 <= body["confidence"] <= 1.0
    assert set(body["matches"][0]["contributions"]) >= {"mass_g"}
    features_only = client.post(
        "/recall",
        json={"text": "a tennis ball", "features_only": True, "metric": "euclidean"},
    ).json()
    assert features_only["features_only"] is True and features_only["metric"] == "euclidean"
    assert_error(client.post("/recall", json={"text": "a ball", "metric": "nonsense"}), 422, words="metric")
    assert_error(client.post("/recall", json={"text": "a ball", "top": 0}), 422, words="top")
    assert_error(client.post("/recall", json={"text": "a ball", "top": 10_000}), 422, words="top")
    nonsense = client.post("/recall", json={"text": "qwx zzzt"}).json()
    assert nonsense["matches"] == [] and nonsense["confidence"] == 0.0


def test_grasp_plan_by_name_and_by_description(client):
    by_name = client.post("/grasp/plan", json={"name": "tennis ball"}).json()
    assert by_name["object"] == "tennis ball" and by_name["recalled"]["method"] == "name"
    assert by_name["plans"][0]["grasp_type"] and by_name["plans"][0]["rationale"]
    by_text = client.post("/grasp/plan", json={"text": "a fuzzy yellow tennis ball, 58 g", "top": 2}).json()
    assert by_text["object"] == "tennis ball" and by_text["recalled"]["method"] == "recall"
    assert len(by_text["plans"]) == 2
    assert_error(client.post("/grasp/plan", json={}), 400, words="exactly one")
    assert_error(client.post("/grasp/plan", json={"text": "a", "name": "b"}), 400, words="exactly one")
    assert_error(client.post("/grasp/plan", json={"name": "unicorn horn"}), 404, "ObjectNotFound")
    assert_error(client.post("/grasp/plan", json={"text": "qwx zzzt"}), 400, "RecallError")


def test_not_in_the_catalog_the_same_over_http(client):
    body = client.post("/recall", json={"text": "An orange of 7 cm diameter."}).json()
    assert body["not_in_catalog"] and body["open_set"] and body["described"]["noun"] == "orange"
    assert body["same_kind"][0]["name"] == "apple" and body["confidence"] <= 0.05
    plan = client.post("/grasp/plan", json={"text": "a ceramic teapot about 22 cm wide, 900 g"}).json()
    how = plan["recalled"]
    assert plan["object"] == "described teapot" and how["hint"] == "pitcher" and how["not_in_catalog"]
    assert plan["features"]["mass_g"] == 900 and how["why"].startswith("planned for the described teapot")


def test_grasp_validations_paged_and_filtered(writer, seeded_db):
    from kb.catalog import KnowledgeBase

    rows = [
        {"object_name": name, "grasp_type": "power_sphere", "family": "power", "rank": 1, "success": True,
         "outcome": "held", "seed": seed, "hand_version": "t", "features_hash": "h"}
        for name in ("tennis ball", "coffee mug") for seed in range(3)
    ]  # fmt: skip
    KnowledgeBase.open(seeded_db).record_grasp_results(rows)
    everything = writer.get("/grasp/validations").json()
    assert everything["total"] == 6
    page = writer.get("/grasp/validations", params={"object": "Tennis Ball", "limit": 2, "offset": 1}).json()
    assert page["total"] == 3 and len(page["items"]) == 2
    assert {r["object_name"] for r in page["items"]} == {"tennis ball"}
    assert writer.get("/grasp/validations", params={"object": "nothing"}).json()["total"] == 0
    assert writer.get("/grasp/validations", params={"object": "mug"}).json()["total"] == 3  # an alias
    seeds = [
        r["seed"] for r in writer.get("/grasp/validations", params={"object": "coffee mug"}).json()["items"]
    ]
    assert seeds == [0, 1, 2]


def test_ingestion_runs_list(client):
    body = client.get("/ingestion/runs").json()
    assert body == {"runs": [], "jobs": []}
    assert_error(client.get("/ingestion/runs", params={"limit": 0}), 422)
    assert_error(client.get("/ingestion/jobs/abc"), 404, "JobNotFound")


# ------------------------------------------------------------------------------------ the SQL sandbox
def test_sql_select(client):
    body = client.post(
        "/sql", json={"query": "SELECT name, mass_g FROM objects WHERE name = 'tennis ball'"}
    ).json()
    assert body["columns"] == ["name", "mass_g"]
    assert body["rows"] == [{"name": "tennis ball", "mass_g": pytest.approx(body["rows"][0]["mass_g"])}]
    assert body["truncated"] is False


@pytest.mark.parametrize(
    "query",
    [
        "SELECT * FROM read_csv('/etc/passwd')",
        "SELECT * FROM read_text('/etc/hostname')",
        "SELECT * FROM '/etc/passwd'",
        "COPY objects TO '/tmp/objrecall-stolen.csv'",
        "COPY (SELECT 1) TO '/tmp/objrecall-stolen.parquet' (FORMAT parquet)",
        "ATTACH '/tmp/objrecall-other.duckdb' AS other",
        "INSTALL httpfs",
        "LOAD httpfs",
        "SELECT * FROM read_json('http://127.0.0.1:1/x.json')",
        "DELETE FROM objects",
        "DROP TABLE objects",
        "UPDATE objects SET mass_g = 1",
        "INSERT INTO objects (name) VALUES ('x')",
        "CREATE TABLE t AS SELECT 1",
        "SET enable_external_access = true",
        "PRAGMA database_list; SELECT 1",
        "SELECT 1; DROP TABLE objects",
        "EXPORT DATABASE '/tmp/objrecall-export'",
    ],
)
def test_sql_refuses_hostile_queries(client, query):
    body = assert_error(client.post("/sql", json={"query": query}), 400)
    assert body["error"] in ("QueryRefused", "QueryFailed")
    assert not Path("/tmp/objrecall-stolen.csv").exists()
    assert client.get("/version").json()["catalog"]["objects"] > 100  # nothing was deleted


def test_sql_row_limit_and_caps(client):
    body = client.post("/sql", json={"query": "SELECT * FROM range(1000000000)", "max_rows": 100}).json()
    assert len(body["rows"]) == 100 and body["truncated"] is True
    default = client.post("/sql", json={"query": "SELECT * FROM range(1000000000)"}).json()
    assert len(default["rows"]) == 1000 and default["truncated"] is True
    assert_error(client.post("/sql", json={"query": "SELECT 1", "max_rows": 10**7}), 422, words="max_rows")
    assert_error(client.post("/sql", json={"query": "SELECT 1", "timeout_s": 3600}), 422, words="timeout_s")
    assert_error(client.post("/sql", json={"query": "SELEC nothing"}), 400, "QueryFailed", "SQL error")


def test_sql_result_size_is_capped(client):
    body = assert_error(
        client.post("/sql", json={"query": "SELECT repeat('x', 9000000) AS big"}), 400, "QueryFailed"
    )
    assert "result too large" in body["detail"]


def test_sql_slow_scan_times_out(client):
    body = assert_error(
        client.post(
            "/sql",
            json={"query": "SELECT sum(hash(i)) FROM range(100000000000) t(i)", "timeout_s": 0.5},
        ),
        504,
        "RequestTimeout",
    )
    assert "time limit" in body["detail"]
    assert client.post("/sql", json={"query": "SELECT 42 AS x"}).json()["rows"] == [{"x": 42}]


# ------------------------------------------------------------------------------------ writes and auth
def test_writes_disabled_without_a_configured_token(client):
    body = assert_error(
        client.put("/objects/widget", json={"mass_g": 5}, headers=AUTH), 403, "WritesDisabled"
    )
    assert "OBJRECALL_API_TOKEN" in body["detail"]
    assert_error(client.post("/ingestion/runs", headers=AUTH), 403, "WritesDisabled")


def test_writes_need_the_right_bearer_token(writer):
    missing = assert_error(writer.put("/objects/widget", json={"mass_g": 5}), 401, "Unauthorized")
    assert "Bearer" in missing["detail"]
    wrong = writer.put("/objects/widget", json={"mass_g": 5}, headers={"Authorization": "Bearer nope"})
    assert_error(wrong, 401, "Unauthorized", "invalid API token")
    assert wrong.headers["www-authenticate"] == "Bearer"
    basic = writer.put("/objects/widget", json={"mass_g": 5}, headers={"Authorization": f"Basic {TOKEN}"})
    assert basic.status_code == 401
    assert_error(writer.get("/objects/widget"), 404)  # nothing was written


def test_put_object_inserts_then_edits_with_provenance(writer):
    new = writer.put(
        "/objects/Brass%20Door%20Knob",
        json={"a_cm": 5.5, "b_cm": 6, "c_cm": 5.5, "mass_g": 180, "material": "metal", "shape": "radial",
              "aliases": ["doorknob"], "source": "measured by hand"},
        headers=AUTH,
    )  # fmt: skip
    assert new.status_code == 201, new.text
    obj = new.json()
    assert (
        obj["name"] == "brass door knob" and obj["a_cm"] == 6.0 and obj["c_cm"] == 5.5
    )  # sorted a >= b >= c
    assert obj["aliases"] == ["doorknob"]
    assert {p["adapter"] for p in obj["provenance"]} == {"api"}
    edited = writer.put("/objects/doorknob", json={"mass_g": 200}, headers=AUTH)
    assert edited.status_code == 200
    assert edited.json()["name"] == "brass door knob" and edited.json()["mass_g"] == 200
    again = writer.get("/objects/brass door knob").json()
    assert again["material"] == "metal"  # values not given stay as stored
    recall = writer.post("/recall", json={"text": "a brass door knob"}).json()
    assert recall["matches"][0]["name"] == "brass door knob"  # the recall snapshot sees the edit


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ({"mass_g": -3}, "mass_g"),
        ({"a_cm": 1e9}, "a_cm"),
        ({"shape": "hexagonal"}, "shape"),
        ({"material": "unobtainium"}, "material"),
        ({"colour": "red"}, "colour"),
        ({"mass_g": "heavy"}, "mass_g"),
        (b'{"a_cm": NaN}', "a_cm"),
        (b'{"mass_g": Infinity}', "mass_g"),
    ],
)
def test_put_object_refuses_invalid_values(writer, body, words):
    if isinstance(body, bytes):  # JSON extensions Python's parser accepts
        r = writer.put("/objects/widget", content=body, headers={**AUTH, "content-type": "application/json"})
    else:
        r = writer.put("/objects/widget", json=body, headers=AUTH)
    assert r.status_code in (400, 422), r.text
    assert words in r.json()["detail"]
    assert writer.get("/objects/widget").status_code == 404


@pytest.mark.parametrize(("path", "body"), [
    ("/objects/bt%00nul", {"mass_g": 5}),  # a NUL in the name
    ("/objects/bell%07", {"mass_g": 5}),  # another control character
    ("/objects/widget", {"mass_g": 5, "aliases": ["ok", "wid\x00get"]}),  # in an alias
])  # fmt: skip
def test_put_object_refuses_control_characters_in_names_and_aliases(writer, path, body):
    """Validated like the CSV import: an object the import would refuse is never written (a NUL name was
    accepted and then broke export -> import)."""
    r = writer.put(path, json=body, headers=AUTH)
    assert r.status_code in (400, 422), r.text
    assert "control character" in r.json()["detail"]
    assert writer.get("/objects/widget").status_code == 404
    assert writer.get("/objects/ok").status_code == 404


def test_an_object_written_over_http_survives_export_and_import(seeded_db, tmp_path):
    from kb.catalog import KnowledgeBase

    writer = TestClient(create_app(seeded_db, token=TOKEN), **LOCAL)
    put = writer.put("/objects/tab%09name", json={"mass_g": 5, "aliases": ["new\tline"]}, headers=AUTH)
    assert put.status_code == 201, put.text  # a tab is white space: one space in the name
    out = tmp_path / "export.csv"
    KnowledgeBase.open(seeded_db, read_only=True).export_csv(out)
    again = KnowledgeBase.open(tmp_path / "again.duckdb")
    again.import_csv(out)
    assert again.get_object("tab name").mass_g == 5 and again.get_object("new line").name == "tab name"


def test_trigger_ingestion_needs_configured_sources(writer):
    assert_error(writer.post("/ingestion/runs", headers=AUTH), 400, words="no sources file")


def test_token_from_env_or_file(tmp_path):
    assert load_token({}) is None
    assert load_token({"OBJRECALL_API_TOKEN": " abc \n"}) == "abc"
    secret = tmp_path / "token"
    secret.write_text("from-file\n")
    assert load_token({"OBJRECALL_API_TOKEN_FILE": str(secret)}) == "from-file"
    assert load_token({"OBJRECALL_API_TOKEN": "env", "OBJRECALL_API_TOKEN_FILE": str(secret)}) == "env"
    secret.write_text("  \n")
    assert load_token({"OBJRECALL_API_TOKEN_FILE": str(secret)}) is None
    from kb.errors import ObjrecallError

    with pytest.raises(ObjrecallError, match="cannot read"):
        load_token({"OBJRECALL_API_TOKEN_FILE": str(tmp_path / "missing")})


# ---------------------------------------------------------------------------------------------- limits
def test_request_body_size_limit(client):
    big = {"text": "a mug " * 20_000}
    assert_error(client.post("/parse", json=big), 413, "PayloadTooLarge")

    def chunks():  # no Content-Length: chunked upload
        for _ in range(100):
            yield b"x" * 1024

    assert_error(client.post("/parse", content=chunks(), headers={"content-type": "application/json"}), 413)


def test_request_body_limit_is_exact(shared_db):
    """A body of exactly ``max_body_bytes`` is read (the schema then judges it: 422); one byte more is 413."""
    limit = 1000
    small = TestClient(create_app(shared_db, token="", max_body_bytes=limit), **LOCAL)
    for n, status in ((limit, 422), (limit + 1, 413)):
        assert small.post("/parse", content=b"x" * n, headers={"content-type": "application/json"}).status_code == status


@pytest.mark.parametrize("declared", [False, True])
@pytest.mark.parametrize("sizes, passed", [
    ((250, 250, 250, 250), True),  # exactly the limit, in chunks
    ((250, 250, 250, 250, 1), False),  # one byte over, after a chunk that ends at the limit
    ((1001,), False),
])  # fmt: skip
def test_body_limit_over_asgi_chunks(sizes, passed, declared):
    """The middleware itself, fed ASGI body messages: the app sees the whole body or the client gets 413."""
    import asyncio

    from kb.service.http.limits import LimitsMiddleware

    seen: list[bytes] = []

    async def app(scope, receive, send):
        seen.append((await receive())["body"])
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    messages = [{"type": "http.request", "body": b"x" * n, "more_body": i < len(sizes) - 1} for i, n in enumerate(sizes)]
    sent: list[dict] = []

    async def receive():
        return messages.pop(0)

    async def send(message):
        sent.append(message)

    headers = [(b"content-length", str(sum(sizes)).encode())] if declared else []
    middleware = LimitsMiddleware(app, max_body_bytes=1000, timeout=5.0)
    asyncio.run(middleware({"type": "http", "path": "/parse", "headers": headers}, receive, send))
    assert sent[0]["status"] == (200 if passed else 413)
    assert seen == ([b"x" * 1000] if passed else [])


@pytest.mark.parametrize("before_start", [True, False], ids=["late start", "late body"])
def test_the_time_limit_never_cuts_a_started_answer(before_start):
    """Past the limit, an answer not yet started becomes a 504; one whose start was sent is finished (cutting
    it off left an empty body behind a 504 the route itself had built: seen in CI under load)."""
    import asyncio

    from kb.service.http.limits import LimitsMiddleware

    async def app(scope, receive, send):
        await receive()
        if before_start:
            await asyncio.sleep(0.3)
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await asyncio.sleep(0.3)
        await send({"type": "http.response.body", "body": b'{"ok": true}'})

    sent: list[dict] = []

    async def receive():
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)

    middleware = LimitsMiddleware(app, max_body_bytes=1000, timeout=0.1)
    asyncio.run(middleware({"type": "http", "path": "/sql", "headers": []}, receive, send))
    starts = [m for m in sent if m["type"] == "http.response.start"]
    bodies = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    assert len(starts) == 1
    if before_start:
        assert starts[0]["status"] == 504 and b"RequestTimeout" in bodies
    else:
        assert starts[0]["status"] == 200 and bodies == b'{"ok": true}'


def test_request_time_limit(shared_db):
    slow = TestClient(create_app(shared_db, token="", request_timeout=0.5), **LOCAL)
    r = slow.post(
        "/sql", json={"query": "SELECT sum(hash(i)) FROM range(100000000000) t(i)", "timeout_s": 3}
    )
    # the statement is interrupted just inside the request's 0.5 s limit, so no thread is left in DuckDB
    assert_error(r, 504, "RequestTimeout", "limit")


def test_missing_catalog_is_a_clear_503(tmp_path):
    c = TestClient(create_app(tmp_path / "none.duckdb", token=""), **LOCAL)
    health = c.get("/health").json()
    assert (health["status"], health["catalog"], health["catalog_state"]) == ("degraded", False, "missing")
    assert "no catalog there" in health["catalog_error"]
    assert_error(c.get("/objects"), 503, "CatalogMissing", "objrecall init")
    assert_error(c.post("/recall", json={"text": "a mug"}), 503, "CatalogMissing")


def test_every_error_class_has_a_status():
    import kb.errors as errors

    for name in errors.__all__:
        cls = getattr(errors, name)
        status = next(ERROR_STATUS[c] for c in cls.__mro__ if c in ERROR_STATUS)
        assert 400 <= status < 600 and status != 500, name
    assert ERROR_STATUS[errors.ObjectNotFound] == 404
    assert ERROR_STATUS[errors.DatabaseBusy] == 503
    assert ERROR_STATUS[errors.QueryRefused] == 400


# ----------------------------------------------------------------------------------- OpenAPI and page
def test_openapi_and_docs(client):
    spec = client.get("/openapi.json").json()
    paths = spec["paths"]
    for path in ("/health", "/version", "/objects", "/objects/{name}", "/parse", "/recall", "/grasp/plan",
                 "/grasp/validations", "/sql", "/ingestion/runs"):  # fmt: skip
        assert path in paths, path
    assert "put" in paths["/objects/{name}"] and "post" in paths["/ingestion/runs"]
    assert "HTTPBearer" in spec["components"]["securitySchemes"]
    assert client.get("/docs").status_code == 200


def test_web_page_is_served_with_a_strict_policy(client):
    page = client.get("/")
    assert page.status_code == 200 and "text/html" in page.headers["content-type"]
    assert "script-src 'self'" in page.headers["content-security-policy"]
    js = client.get("/static/app.js")
    assert js.status_code == 200
    assert (
        ".innerHTML" not in js.text
        and "insertAdjacentHTML" not in js.text
        and "document.write" not in js.text
    )
    assert client.get("/static/style.css").status_code == 200
    assert client.get("/static/../service.py").status_code == 404


def test_grasp_plan_carries_the_latest_validation_and_the_render_shows_it(writer, seeded_db):
    """The web page's grasp: the plan, the stored validation with the current hand (first vs validated
    choice) and a real MuJoCo render of the shown grasp."""
    from kb.catalog import KnowledgeBase
    from sim.worker import current_hand_version

    assert writer.post("/grasp/plan", json={"name": "tennis ball"}).json()["validation"] is None
    plans = writer.post("/grasp/plan", json={"name": "tennis ball"}).json()["plans"]
    first, second = plans[0]["grasp_type"], plans[1]["grasp_type"]
    base = {"object_name": "tennis ball", "seed": 0, "features_hash": "h", "family": "power"}
    KnowledgeBase.open(seeded_db).record_grasp_results([
        {**base, "grasp_type": first, "rank": 0, "success": False, "outcome": "failure", "reason": "turned 20 deg",
         "hand_version": current_hand_version()},
        {**base, "grasp_type": second, "rank": 1, "success": True, "outcome": "success", "reason": "held",
         "hand_version": current_hand_version()},
        {**base, "grasp_type": second, "rank": 1, "success": False, "outcome": "failure", "reason": "old hand",
         "seed": 1, "hand_version": "an older hand"},  # another hand's trials are not this hand's validation
    ])  # fmt: skip
    v = writer.post("/grasp/plan", json={"name": "tennis ball"}).json()["validation"]
    assert (v["first"], v["first_holds"], v["validated"], v["differs"]) == (first, False, second, True)
    png = writer.get("/grasp/render", params={"object": "tennis ball", "grasp_type": second})
    assert png.status_code == 200 and png.headers["content-type"] == "image/png"
    assert png.content[:8] == b"\x89PNG\r\n\x1a\n"
    assert_error(writer.get("/grasp/render", params={"object": "tennis ball", "grasp_type": "fist"}), 400,
                 words="not a planned grasp")  # fmt: skip
    assert_error(writer.get("/grasp/render", params={"object": "unicorn", "grasp_type": first}), 404)


# ------------------------------------------------------------------- the recaller and the stored index
def test_the_service_recalls_from_the_stored_index_and_reloads_it_when_the_catalog_changes(seeded_db, monkeypatch):
    """The service loads its recaller with Recaller.from_db (the index stored beside the catalog: written
    on the first load, reloaded after), keeps it while the catalog's content is unchanged, and loads a new
    one after any write that changes what recall reads (an alias only, made by another writer)."""
    from kb.catalog import KnowledgeBase
    from recall.engine import Recaller
    from recall.stored_index import index_path

    loads = []
    real = Recaller.from_db.__func__
    monkeypatch.setattr(Recaller, "from_db", classmethod(lambda cls, db: loads.append(db) or real(cls, db)))
    client = TestClient(create_app(seeded_db, token="", snapshot_ttl=0.0), **LOCAL)

    def top(text: str) -> str:
        response = client.post("/recall", json={"text": text, "top": 1})
        assert response.status_code == 200, response.text
        return response.json()["matches"][0]["name"]

    first = top("a tennis ball")
    assert index_path(seeded_db).exists() and len(loads) == 1
    assert top("a tennis ball") == first and len(loads) == 1  # checked again (ttl 0), unchanged: kept
    with KnowledgeBase.open(seeded_db).connect(write=True) as con:
        (target,) = con.execute("SELECT name FROM objects WHERE name <> ? ORDER BY name LIMIT 1", [first]).fetchone()
        con.execute("INSERT INTO object_aliases SELECT 'zorbulator', id FROM objects WHERE name = ?", [target])
    assert top("a zorbulator") == target and len(loads) == 2
    assert top("a zorbulator") == target and len(loads) == 2
