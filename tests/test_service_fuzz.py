"""Property-based fuzzing of the knowledge service from its own OpenAPI document (schemathesis): whatever
the generated request (valid or not), the answer is never a 5xx, and every error is a JSON body with a
message. Writes are enabled with a token, so the fuzzer edits a throw-away catalog too."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest

schemathesis = pytest.importorskip(
    "schemathesis", reason="schemathesis is a test dependency (pip install schemathesis)"
)

from hypothesis import HealthCheck, settings  # noqa: E402

from kb.service.http import create_app  # noqa: E402

TOKEN = "fuzz-token"
MAX_EXAMPLES = int(os.environ.get("OBJRECALL_FUZZ_EXAMPLES", "20"))


def _catalog() -> Path:
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    path = Path(tempfile.mkdtemp(prefix="objrecall-fuzz-")) / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(seed_catalog_path())
    return path


_DB = _catalog()
app = create_app(_DB, token=TOKEN, request_timeout=20.0, allowed_hosts=["testserver"])  # the ASGI client's Host
schema = schemathesis.openapi.from_asgi("/openapi.json", app)


@pytest.fixture(scope="module", autouse=True)
def _cleanup():
    yield
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
