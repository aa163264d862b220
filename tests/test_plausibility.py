"""Plausibility of a whole object (kb/plausibility.py): size, mass and density limits at their boundaries,
on every path into the catalog (Python, CSV import, HTTP, partial updates), and the simulator's clear
reason for an object it cannot build."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from kb.catalog import KnowledgeBase
from kb.errors import CatalogImportError, InvalidFeature, SimulationError
from kb.features import CSV_COLUMNS, FEATURES, ObjectRecord
from kb.plausibility import (
    MAX_DENSITY_G_CM3,
    MIN_DENSITY_G_CM3,
    MIN_EXTENT_CM,
    MIN_LARGEST_EXTENT_CM,
    MIN_MASS_G,
    check_plausible,
)
from kb.service.http import create_app

ROOT = Path(__file__).resolve().parents[1]
TOKEN = "test-token-not-secret"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
LOCAL = {"raise_server_exceptions": False, "base_url": "http://127.0.0.1"}


def _refusal(**features) -> InvalidFeature:
    with pytest.raises(InvalidFeature) as err:
        ObjectRecord.create("thing", **features)
    return err.value


# ------------------------------------------------------------------------------------ the limits
@pytest.mark.parametrize(
    ("ok", "bad", "field"),
    [
        (dict(a_cm=MIN_LARGEST_EXTENT_CM), dict(a_cm=MIN_LARGEST_EXTENT_CM * 0.999), "a_cm"),
        (dict(a_cm=20, b_cm=10, c_cm=MIN_EXTENT_CM, mass_g=1), dict(a_cm=20, b_cm=10, c_cm=0.000999, mass_g=1), "c_cm"),
        (dict(mass_g=MIN_MASS_G), dict(mass_g=MIN_MASS_G * 0.999), "mass_g"),
        # a 1 cm cube: 45 g is the densest allowed, just over refused
        (dict(a_cm=1, b_cm=1, c_cm=1, mass_g=MAX_DENSITY_G_CM3), dict(a_cm=1, b_cm=1, c_cm=1, mass_g=45.01), "mass_g"),
        # a 100 cm cube: 50 g is the lightest allowed (5e-5 g/cm3)
        (dict(a_cm=100, b_cm=100, c_cm=100, mass_g=50), dict(a_cm=100, b_cm=100, c_cm=100, mass_g=49.9), "mass_g"),
    ],
)  # fmt: skip
def test_limits_at_their_boundaries(ok, bad, field):
    ObjectRecord.create("thing", **ok)  # the limit itself is accepted
    err = _refusal(**bad)
    assert err.field == field
    assert repr(err.value) in str(err) or f"{err.value:g}" in str(err)  # the reason names the value


def test_the_blind_testers_objects_are_refused_with_the_value_named():
    tiny = _refusal(a_cm=1e-7, mass_g=1e-5)
    assert tiny.field == "a_cm" and "1e-07" in str(tiny) and "too small" in str(tiny)
    dense = _refusal(a_cm=1, b_cm=1, c_cm=1, mass_g=400_000)
    assert (
        dense.field == "mass_g" and "400,000 g/cm³" in str(dense) and "denser than any material" in str(dense)
    )


def test_unknown_extents_refuse_only_what_no_value_could_make_plausible():
    # b and c unknown: at most 1 cm each, so 400 kg is at least 400,000 g/cm3
    assert "at least" in str(_refusal(a_cm=1, mass_g=400_000))
    ObjectRecord.create("thing", a_cm=1, mass_g=MAX_DENSITY_G_CM3)  # a 1 cm cube of 45 g could be
    ObjectRecord.create("thing", a_cm=1, b_cm=1, mass_g=MAX_DENSITY_G_CM3)
    assert _refusal(a_cm=1, b_cm=0.5, mass_g=MAX_DENSITY_G_CM3 * 0.5 * 0.5 + 0.01).field == "mass_g"
    # c unknown: at least 10 µm thick, so 1 g over 1 m x 1 m could be no lighter than 1e-4 g/cm3 (allowed) ...
    ObjectRecord.create("thing", a_cm=100, b_cm=100, mass_g=1)
    # ... while 0.01 g over 5 m x 5 m is too light even at 10 µm
    assert "too light for its size" in str(_refusal(a_cm=500, b_cm=500, mass_g=0.01))
    ObjectRecord.create("thing", mass_g=500_000)  # no size: no density to check


def test_check_plausible_reads_catalog_values_and_ignores_the_rest():
    check_plausible({"a_cm": None, "b_cm": None, "c_cm": None, "mass_g": None, "shape": "radial"})
    check_plausible({})
    with pytest.raises(InvalidFeature):
        check_plausible({"a_cm": 2.0, "b_cm": 2.0, "c_cm": 2.0, "mass_g": 8 * MIN_DENSITY_G_CM3 * 0.99})


def _catalog_rows(path: Path) -> list[dict[str, str]]:
    with path.open(encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


@pytest.mark.parametrize(
    "path", ["kb/data/seed_catalog.csv", "tests/data/catalog2/catalog.csv", "sim/data/human_grasps.csv"]
)
def test_every_catalog_file_written_here_passes(path):
    rows = _catalog_rows(ROOT / path)
    assert len(rows) > 20
    for row in rows:
        values = {f: row.get(f) or None for f in FEATURES}
        ObjectRecord.create(row.get("name") or row.get("object"), **values)


# ------------------------------------------------------------------------------ every path in
def test_csv_import_refuses_an_impossible_row_and_imports_nothing(tmp_path):
    path = tmp_path / "dense.csv"
    lines = [",".join(CSV_COLUMNS), "pebble,2,2,2,10,compact,,,,", "lead cube,1,1,1,400000,compact,,,,"]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    kb = KnowledgeBase.open(tmp_path / "c.duckdb")
    with pytest.raises(CatalogImportError, match="denser than any material"):
        kb.import_csv(path)
    assert kb.count_objects() == 0
    report = kb.import_csv(path, skip_invalid=True)
    assert report.new == ["pebble"] and "denser" in report.skipped[0].reason


def test_a_partial_update_is_checked_with_the_stored_values(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "c.duckdb")
    kb.upsert([ObjectRecord.create("die", a_cm=1.6, b_cm=1.6, c_cm=1.6, mass_g=4)], source="t", adapter="t")
    heavy = ObjectRecord.create("die", mass_g=400_000)  # alone: no size, nothing to check
    with pytest.raises(InvalidFeature, match=r"denser than any material.*'die'.*a_cm=1\.6"):
        kb.upsert([heavy], source="t", adapter="t")
    assert kb.get_object("die").mass_g == 4
    unchecked = ObjectRecord(name="speck", a_cm=1e-7, mass_g=1e-5)  # the plain constructor trusts its input
    with pytest.raises(InvalidFeature, match="too small"):
        kb.upsert([unchecked], source="t", adapter="t")


def test_http_put_refuses_impossible_objects(seeded_db):
    writer = TestClient(create_app(seeded_db, token=TOKEN), **LOCAL)
    for name, body, words in [
        ("tiny", {"a_cm": 1e-7, "mass_g": 1e-5}, "a_cm=1e-07: too small"),
        ("denseobj", {"a_cm": 1, "b_cm": 1, "c_cm": 1, "mass_g": 400_000}, "denser than any material"),
    ]:
        r = writer.put(f"/objects/{name}", json=body, headers=AUTH)
        assert r.status_code == 400 and r.json()["error"] == "InvalidFeature", r.text
        assert words in r.json()["detail"]
        assert writer.get(f"/objects/{name}").status_code == 404
    # an edit that would make a stored object impossible is refused too
    r = writer.put("/objects/dice", json={"mass_g": 400_000}, headers=AUTH)
    assert r.status_code == 400 and "denser than any material" in r.json()["detail"], r.text


# ------------------------------------------------------------------------------- the simulator
def test_an_impossible_stored_row_gets_a_clear_reason_from_render_and_validate(seeded_db):
    """A row stored before the limits (written straight into the table here): the render and the
    validation name the object and why, never MuJoCo's compile error."""
    import duckdb

    from sim.worker import validate

    with duckdb.connect(str(seeded_db)) as con:
        con.execute(
            "UPDATE objects SET a_cm = 1e-7, b_cm = NULL, c_cm = NULL, mass_g = 1e-5 WHERE name = 'dice'"
        )
    client = TestClient(create_app(seeded_db, token=""), **LOCAL)
    r = client.get("/grasp/render", params={"object": "dice", "grasp_type": "thumb_index_finger"})
    assert r.status_code == 400, r.text
    detail = r.json()["detail"]
    assert "'dice' (1e-07 x" in detail and "too small or too light for MuJoCo to simulate" in detail, detail
    assert "Error:" not in detail and "compile" not in detail
    kb = KnowledgeBase.open(seeded_db)
    summary = validate(kb, ["dice"], top=1, seeds=[0], workers=1, executor="serial", progress=False)
    reasons = [row["reason"] for row in summary.results]
    assert reasons and all("too small or too light for MuJoCo" in why for why in reasons), reasons


def test_a_described_object_is_not_held_to_the_catalog_limits():
    """The object a description asks a grasp for is never stored (recall/target.py): "a spoon 1 cm long"
    with a catalog spoon's 50 g is planned for as stated."""
    with pytest.raises(InvalidFeature):
        ObjectRecord.create("spoon", a_cm=1, b_cm=1, c_cm=1, mass_g=50)
    assert ObjectRecord.create("spoon", plausible=False, a_cm=1, b_cm=1, c_cm=1, mass_g=50).mass_g == 50


def test_sim_names_the_object_when_mujoco_cannot_simulate_it():
    """Plausible for kb, under MuJoCo's minimum inertia: a 5 m thread 10 µm thick of 10 mg."""
    from sim.planner import plan_grasps
    from sim.world import build_world

    thread = ObjectRecord.create(
        "thread", a_cm=500, b_cm=MIN_EXTENT_CM, c_cm=MIN_EXTENT_CM, mass_g=MIN_MASS_G
    )
    with pytest.raises(SimulationError) as err:
        build_world(thread, plan_grasps(thread, top=1)[0])
    assert "'thread' (500 x 0.001 x 0.001 cm, 0.01 g) is too small or too light for MuJoCo" in str(err.value)
    assert "Error:" not in str(err.value)  # MuJoCo's own text is not passed on
