"""Property-based fuzzing of the knowledge service from its own OpenAPI document (schemathesis): whatever
the generated request (valid or not), the answer is never a 5xx, and every error is a JSON body with a
message. Writes are enabled with a token, so the fuzzer edits a throw-away catalog too."""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from pathlib import Path

import pytest

schemathesis = pytest.importorskip(
    "schemathesis", reason="schemathesis is a test dependency (pip install schemathesis)"
)

from hypothesis import HealthCheck, settings  # noqa: E402

from kb.service.http import create_app  # noqa: E402

TOKEN = "fuzz-token"
MAX_EXAMPLES = int(os.environ.get("OBJRECALL_FUZZ_EXAMPLES", "20"))


#: The throw-away catalog: only a name at import (the schema below needs the app then, and a module collected
#: but not run must leave nothing behind); :func:`_catalog` makes it for the run and removes it afterwards.
_DB = Path(tempfile.gettempdir()) / f"objrecall-fuzz-{uuid.uuid4().hex}" / "catalog.duckdb"
app = create_app(_DB, token=TOKEN, request_timeout=20.0, allowed_hosts=["testserver"])  # the ASGI client's Host
schema = schemathesis.openapi.from_asgi("/openapi.json", app)


@pytest.fixture(scope="module", autouse=True)
def _catalog():
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    _DB.parent.mkdir()
    try:
        KnowledgeBase.open(_DB).import_csv(seed_catalog_path())
        yield
    finally:
        shutil.rmtree(_DB.parent, ignore_errors=True)


@schema.parametrize()
@settings(
    max_examples=MAX_EXAMPLES,
    deadline=None,
    suppress_health_check=list(HealthCheck),
    derandomize=True,
)
def test_no_server_errors(case):
    headers = {"Authorization": f"Bearer {TOKEN}"}
    response = case.call(headers=headers)
    where = f"{case.method} {case.formatted_path}: {response.status_code} {response.text}"
    if response.status_code == 504:  # the documented answer when a generated query hits its time limit
        assert case.path == "/sql" and response.json()["error"] == "RequestTimeout", where
        return
    assert response.status_code < 500, where
    if response.status_code >= 400:
        body = response.json()
        assert body.get("detail"), body
