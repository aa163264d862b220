"""`objrecall grasp plan` and `objrecall grasp validate` through the CLI runner (real DuckDB, real MuJoCo)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.service.cli import app

runner = CliRunner()

CSV = """name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity
tv remote,16,3.5,2,110,long,medium,medium,plastic,rigid
tennis ball,6.4,6.4,6.4,56,radial,rough,medium,fabric,squeezable
small cube,5,5,5,100,compact,medium,sturdy,wood,rigid
"""


@pytest.fixture
def db(tmp_path):
    csv = tmp_path / "objects.csv"
    csv.write_text(CSV)
    path = tmp_path / "kb.duckdb"
    KnowledgeBase.open(path).import_csv(csv)
    return path


def invoke(*args):
    return runner.invoke(app, list(args), catch_exceptions=False)


def test_plan_catalog_json_lines_one_per_row_in_order(tmp_path):
    csv = tmp_path / "c.csv"
    csv.write_text(
        "name,a_cm,b_cm,c_cm,mass_g,shape,human_grasp\n"
        "tv remote,16,3.5,2,110,long,thumb_4_finger\n"
        "orange,7,7,7,150,radial,power_sphere\n"
        "mystery,,,,,,\n"
        "broken,-1,2,2,5,long,\n"
        "tv remote,16,3.5,2,110,long,thumb_4_finger\n"
    )
    result = invoke("grasp", "plan", "--catalog", str(csv), "--json")
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in result.output.splitlines()]
    assert [x["name"] for x in lines] == ["tv remote", "orange", "mystery", "broken", "tv remote"]
    assert lines[0]["family"] == "precision" and lines[0]["grasp_type"] in (
        "thumb_4_finger",
        "thumb_3_finger",
    )
    assert lines[1]["grasp_type"] == "power_sphere" and lines[1]["family"] == "power"
    assert lines[0]["alternatives"] and all(
        {"grasp_type", "family", "score"} <= set(a) for a in lines[0]["alternatives"]
    )
    assert "grasp_type" in lines[2]  # unknown features still get a plan
    assert lines[3]["grasp_type"] and "a_cm" in lines[3]["warnings"][0]  # invalid value -> unknown, named


def test_plan_catalog_accepts_the_papers_header_words_and_keeps_names_as_written(tmp_path):
    csv = tmp_path / "c.csv"
    csv.write_text(
        "\ufeffObject,a,b,c,mass,shape,texture,fragility,material,stiffness\n"
        "Tennis Ball,6.4,6.4,6.4,56,radial,rough,medium,fabric,soft\n"
        "Odd Thing,5,5,5,100,blob,,,,\n"
        ",1,1,1,1,,,,,\n"
    )
    result = invoke("grasp", "plan", "--catalog", str(csv), "--json")
    assert result.exit_code == 0, result.output
    first, odd, nameless = (json.loads(line) for line in result.output.splitlines())
    assert first["name"] == "Tennis Ball" and first["grasp_type"] == "power_sphere"
    assert "shape" in odd["warnings"][0] and odd["grasp_type"]
    assert nameless["error"] and nameless["row"] == 4


def test_plan_catalog_without_name_column_is_one_error_line(tmp_path):
    csv = tmp_path / "c.csv"
    csv.write_text("a_cm,b_cm\n1,2\n")
    result = runner.invoke(app, ["grasp", "plan", "--catalog", str(csv), "--json"])
    assert result.exit_code == 1
    assert "Error:" in result.output and "name" in result.output and "Traceback" not in result.output


def test_plan_by_catalog_name(db):
    result = invoke("grasp", "plan", "TV Remote", "--db", str(db), "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["object"] == "tv remote" and data["recalled"]["method"] == "name"
    assert data["plans"][0]["family"] == "precision" and len(data["plans"]) == 3
    human = invoke("grasp", "plan", "tv remote", "--db", str(db))
    assert "thumb_" in human.output and "Feix" in human.output


def test_plan_recalls_the_described_object(db):
    result = invoke(
        "grasp", "plan", "a fuzzy fabric ball about 6.5 cm across, 55 grams", "--db", str(db), "--json"
    )
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["object"] == "tennis ball" and data["recalled"]["method"] == "recall"
    assert data["plans"][0]["grasp_type"] == "power_sphere"


def test_plan_without_a_catalog_plans_for_the_parsed_features(tmp_path):
    text = "a plastic thing 16 cm long, 3.5 cm wide and 2 cm thick"
    result = invoke("grasp", "plan", text, "--db", str(tmp_path / "none.duckdb"), "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["recalled"]["method"] == "parsed" and data["features"]["a_cm"] == 16
    assert data["plans"][0]["family"] == "precision"


def test_plan_simulate_runs_one_real_trial_per_plan_and_shows_both_choices(db):
    result = invoke("grasp", "plan", "small cube", "--db", str(db), "--simulate", "--json", "--top", "2")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    trial = data["trial"]
    assert trial["outcome"] in ("success", "failure", "error")
    assert trial["simulator"].startswith("mujoco")
    assert [t["grasp_type"] for t in data["trials"]] == [p["grasp_type"] for p in data["plans"]]
    assert data["trials"][0] == trial  # "trial" stays the first choice's
    for t in data["trials"]:  # a failed trial says why, in the hand's terms (sim/diagnosis.py)
        assert ("why" in t) == (not t["success"])
        assert not t.get("why") or t["why"].split(":")[0] in ("aperture", "mass", "size", "friction", "moment", "error")
    choice = data["choice"]
    assert choice["first"] == data["plans"][0]["grasp_type"]
    assert choice["first_holds"] == (trial["outcome"] == "success")
    holding = [t["grasp_type"] for t in data["trials"] if t["success"]]
    assert choice["validated"] == (holding[0] if holding else None)
    text = invoke("grasp", "plan", "small cube", "--db", str(db), "--simulate", "--top", "2").output
    assert "first choice " + choice["first"] in text and "validated choice" in text
    assert text.count(" program): ") == 2


def test_plan_needs_a_description_or_catalog():
    result = runner.invoke(app, ["grasp", "plan"])
    assert result.exit_code == 1 and "Error:" in result.output


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], "--all"),
        (["tv remote", "--all"], "not both"),
        (["--all", "--executor", "pigeon"], "--executor"),
        (["--all", "--address", "ray://x:1"], "--address"),
        (["no such object"], "no object named"),
    ],
)
def test_validate_errors_are_one_line(db, args, message):
    result = runner.invoke(app, ["grasp", "validate", *args, "--db", str(db)])
    assert result.exit_code == 1
    assert "Error:" in result.output and message in result.output and "Traceback" not in result.output


def test_validate_missing_database(tmp_path):
    result = runner.invoke(app, ["grasp", "validate", "--all", "--db", str(tmp_path / "none.duckdb")])
    assert result.exit_code == 1 and "objrecall init" in result.output


def test_validate_end_to_end_with_real_physics_report_and_resume(db, tmp_path):
    """Real MuJoCo trials in two worker processes, stored; a rerun with --report runs no trial again but
    renders the best grasp of each object for the report."""
    args = ["grasp", "validate", "tennis ball", "small cube", "--top", "2", "--workers", "2", "--db", str(db)]
    result = invoke(*args, "--json")
    assert result.exit_code == 0, result.output
    summary = json.loads(result.output)
    assert summary["trials"] == 4 and summary["ran"] == 4 and summary["not_stored"] == 0
    assert summary["succeeded"] + summary["failed"] + summary["errors"] == 4
    stored = KnowledgeBase.open(db, read_only=True).grasp_results()
    assert len(stored) == 4
    from sim.hand import HAND_VERSION

    assert all(r["simulator"].startswith("mujoco") and r["hand_version"] == HAND_VERSION for r in stored)
    cube = next(r for r in stored if r["object_name"] == "small cube" and r["family"] == "power")
    assert cube["success"] is True, cube["reason"]  # a 5 cm, 100 g cube holds in a power grasp

    assert summary["choice_summary"]["objects"] == 2
    assert {c["object_name"] for c in summary["choices"]} == {"tennis ball", "small cube"}
    assert all(c["first"] == next(r["grasp_type"] for r in summary["results"]
                                  if r["object_name"] == c["object_name"] and r["rank"] == 0)
               for c in summary["choices"])  # fmt: skip
    text = invoke(*args).output
    assert "first choice holds for" in text and "a validated grasp" in text
    for c in summary["choices"]:
        assert (f"{c['object_name']}: first choice" in text) == c["differs"]
    assert text.count("    why: ") == sum(c["validated"] is None for c in summary["choices"])

    report = tmp_path / "report"
    again = json.loads(invoke(*args, "--report", str(report), "--json").output)
    assert again["ran"] == 0 and again["skipped"] == 4
    assert (report / "index.html").is_file() and (report / "results.csv").is_file()
    images = sorted((report / "images").glob("*.png"))
    differing = sum(c["differs"] and c["validated"] is not None for c in again["choices"])
    assert len(images) == 2 + differing, "a render of the first choice per object, and of a differing validated one"
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in images)
    page = (report / "index.html").read_text()
    assert all(f"images/{p.name}" in page for p in images)
    assert len(json.loads((report / "results.json").read_text())["results"]) == 4


def test_validate_says_why_nothing_holds_in_the_hands_terms(tmp_path):
    csv = tmp_path / "big.csv"
    csv.write_text(CSV.splitlines()[0] + "\nbeach ball,30,30,30,300,radial,smooth,medium,plastic,squeezable\n")
    path = tmp_path / "big.duckdb"
    KnowledgeBase.open(path).import_csv(csv)
    out = invoke("grasp", "validate", "beach ball", "--top", "1", "--db", str(path), "--no-progress").output
    text = " ".join(out.split())  # rich wraps long lines
    assert "a validated grasp (best-ranked that holds) for 0" in text
    assert "validated choice: none of the 1 candidates holds" in text
    assert "why: aperture: its smallest side (30 cm) is wider than the hand's 12 cm span: it needs two hands" in text
    assert out.count("    why: ") == 1


def test_plan_uses_the_saved_experience_and_says_why(tmp_path):
    """The service plans with what the seed catalog's trials learned (sim/data/experience.json): an egg's
    rules put a precision sphere first (the precision_circular program); on radial objects of its class the
    trials held the power sphere, so the CLI's first choice is the power sphere. The planner without
    experience keeps the rules' order."""
    from sim.experience import saved_experience
    from sim.planner import plan_grasps

    csv = tmp_path / "c.csv"
    csv.write_text(
        "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\n"
        "egg,5.7,4.4,4.4,58,radial,smooth,fragile,other,rigid\n"
    )
    rules_first = plan_grasps(
        {"name": "egg", "a_cm": 5.7, "b_cm": 4.4, "c_cm": 4.4, "mass_g": 58, "shape": "radial",
         "texture": "smooth", "fragility": "fragile", "material": "other", "rigidity": "rigid"}, top=3
    )[0].grasp_type  # fmt: skip
    assert rules_first == "precision_sphere"  # runs the precision_circular program
    assert saved_experience().counts  # the shipped file is read
    result = invoke("grasp", "plan", "--catalog", str(csv), "--json")
    assert result.exit_code == 0, result.output
    line = json.loads(result.output.splitlines()[0])
    assert line["grasp_type"] == "power_sphere"
