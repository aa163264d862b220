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


# ------------------------------------------------------------- invisible characters (Unicode Cc, Cf)
def _refused_characters() -> list[str]:
    import sys
    import unicodedata

    return [chr(c) for c in range(128, sys.maxunicode + 1) if unicodedata.category(chr(c)) in ("Cc", "Cf")]


def test_every_control_and_format_character_is_refused_in_names_and_aliases():
    from kb.errors import InvalidFeature
    from kb.features import ObjectRecord

    chars = _refused_characters()
    assert len(chars) > 150 and "\u202e" in chars and "\u200b" in chars and "\x9b" in chars
    whitespace = {ch for ch in chars if ch.isspace()}  # U+0085 NEL: white space, read as one space
    for ch in chars:
        if ch in whitespace:
            assert ObjectRecord.create(f"a{ch}b").name == "a b"
            continue
        with pytest.raises(InvalidFeature, match=f"U\\+{ord(ch):04X}"):
            ObjectRecord.create(f"mug {ch}x")
        with pytest.raises(InvalidFeature, match="aliases"):
            ObjectRecord.create("mug", aliases=[f"cup{ch}"])


@pytest.mark.parametrize(
    ("name", "stored"),
    [
        ("a\u2029b", "a b"),  # U+2029 paragraph separator (Zp), just before U+202A: white space
        ("a\u202fb", "a b"),  # U+202F narrow no-break space (Zs), just after U+202E: white space
        ("a\u2065b", "a\u2065b"),  # U+2065 (unassigned), just before U+2066: not a format character
        ("café crème", "café crème"),  # letters and marks beyond ASCII are names
        ("日本茶 cup", "日本茶 cup"),
    ],
)
def test_the_neighbours_of_the_refused_ranges_are_accepted(name, stored):
    from kb.features import ObjectRecord

    assert ObjectRecord.create(name).name == stored


@pytest.mark.parametrize(
    ("path", "body", "words"),
    [
        ("/objects/%E2%80%AEevil%E2%80%AC", {"mass_g": 5}, "U+202E RIGHT-TO-LEFT OVERRIDE"),
        ("/objects/zero%E2%80%8Bwidth", {"mass_g": 5}, "U+200B ZERO WIDTH SPACE"),
        ("/objects/widget", {"mass_g": 5, "aliases": ["wid\u2066get"]}, "U+2066 LEFT-TO-RIGHT ISOLATE"),
        ("/objects/c1%C2%9Bctl", {"mass_g": 5}, "control character U+009B"),
    ],
)
def test_put_refuses_invisible_characters_naming_them(writer, path, body, words):
    r = writer.put(path, json=body, headers=AUTH)
    assert r.status_code == 400 and r.json()["error"] == "InvalidFeature", r.text
    assert words in r.json()["detail"]
    assert writer.get("/objects").json()["total"] == 2  # nothing written


def test_csv_import_refuses_a_bidi_override_in_a_name_or_alias(tmp_path):
    from kb.errors import CatalogImportError

    for row in ["\u202eevil\u202c,9,4,4,80,prism,,,,,", "mug,10,8,8,300,prism,,,,,cup\u200b;beaker"]:
        csv = tmp_path / "bidi.csv"
        csv.write_text(",".join([*CSV_COLUMNS, "aliases"]) + "\n" + row + "\n", encoding="utf-8")
        kb = KnowledgeBase.open(tmp_path / f"{len(row)}.duckdb")
        with pytest.raises(CatalogImportError, match="invisible format character"):
            kb.import_csv(csv)
        assert kb.count_objects() == 0
