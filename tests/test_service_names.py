"""Catalog names over HTTP: a name holding "/" is reached by GET and PUT (``{name:path}``), a missing one is
a 404 ``ObjectNotFound`` naming it, and names with characters no name may hold are refused."""

from __future__ import annotations

from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from kb.catalog import KnowledgeBase
from kb.features import CSV_COLUMNS
from kb.service.http import create_app

TOKEN = "test-token-not-secret"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
LOCAL = {"raise_server_exceptions": False, "base_url": "http://127.0.0.1"}


@pytest.fixture
def writer(tmp_path: Path) -> TestClient:
    """A writable app on a catalog imported from a CSV holding a name with "/"."""
    csv = tmp_path / "slash.csv"
    rows = [",".join(CSV_COLUMNS), "salt/pepper shaker,9,4,4,80,prism,,,,", "mug,10,8,8,300,prism,,,,"]
    csv.write_text("\n".join(rows) + "\n", encoding="utf-8")
    db = tmp_path / "c.duckdb"
    KnowledgeBase.open(db).import_csv(csv)
    return TestClient(create_app(db, token=TOKEN), **LOCAL)


@pytest.mark.parametrize("path", ["/objects/salt%2Fpepper%20shaker", "/objects/salt/pepper%20shaker"])
def test_a_name_with_a_slash_is_reached_by_get_and_put(writer, path):
    got = writer.get(path)
    assert got.status_code == 200, got.text
    assert got.json()["name"] == "salt/pepper shaker" and got.json()["mass_g"] == 80
    put = writer.put(path, json={"mass_g": 85}, headers=AUTH)
    assert put.status_code == 200, put.text  # an edit of the stored object, not a new one
    assert writer.get("/objects/salt%2Fpepper%20shaker").json()["mass_g"] == 85
    assert writer.get("/objects").json()["total"] == 2


def test_put_creates_a_name_with_slashes(writer):
    put = writer.put("/objects/cup%2Fsaucer%2Fset", json={"a_cm": 15, "mass_g": 400}, headers=AUTH)
    assert put.status_code == 201, put.text
    assert writer.get("/objects/cup/saucer/set").json()["name"] == "cup/saucer/set"


@pytest.mark.parametrize(
    ("path", "name"),
    [("/objects/salt%2Fno", "salt/no"), ("/objects/salt/no", "salt/no"), ("/objects/no%20such", "no such")],
)
def test_a_missing_object_is_object_not_found_naming_it(writer, path, name):
    r = writer.get(path)
    assert r.status_code == 404
    assert r.json()["error"] == "ObjectNotFound" and repr(name) in r.json()["detail"], r.text


def test_other_routes_are_untouched(writer):
    assert writer.get("/objects", params={"limit": 1}).json()["total"] == 2
    assert writer.get("/objects/").status_code == 422  # an empty name, said so
    assert writer.get("/health").status_code == 200
