"""The README's main-job command, end to end, as a real process with no network."""

import json
import subprocess

import pytest

from kb.service.mainjob import ingest_line


@pytest.mark.slow
def test_demo_runs_end_to_end(tmp_path, cli_env):
    db, out = tmp_path / "demo.duckdb", tmp_path / "out"
    proc = subprocess.run(
        ["objrecall", "demo", "--db", str(db), "--out", str(out), "--json"],
        capture_output=True, text=True, env=cli_env, timeout=900,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    summary = json.loads(proc.stdout.strip().splitlines()[-1])
    steps = summary["steps"]
    assert steps["seed"]["objects"] >= 100
    assert steps["ingest"]["new"] >= 25 and steps["ingest"]["rejected"] >= 3
    tops = [r["top"] for r in steps["recall"]]
    assert tops[:6] == ["calculator", "water bottle", "wood cylinder", "cardboard box", "mini rubix cube", "tv remote"]
    teapot = steps["recall"][-1]  # sold only through the demo store's search: recalled after a lookup
    assert teapot["looked_up"] and teapot["added"] == ["glazed ceramic teapot 1.2 l"]
    assert teapot["top"] == "glazed ceramic teapot 1.2 l" and not teapot["open_set"]
    assert not steps["recall"][0]["looked_up"]  # the calculator is known: no lookup
    orange = steps["recall"][6]  # the paper's open-set case: no orange in the catalog, nor in the stores
    assert orange["not_in_catalog"] and orange["open_set"] and orange["same_kind"][0] == "apple"
    assert steps["grasp"]["ran"] + steps["grasp"]["skipped"] == steps["grasp"]["trials"] > 0
    assert steps["grasp"]["errors"] == 0
    report = out / "grasp-report" / "index.html"
    html = report.read_text()
    assert "calculator" in html and list((out / "grasp-report").glob("*.png"))
    assert (out / "demo_summary.json").exists()
    # output not on a terminal: one summary line per step, no progress bar
    lines = proc.stderr.splitlines()
    for step in ("catalog ", "ingest: ", "recall: ", "grasp: ", "main job done"):
        assert any(line.startswith(step) for line in lines), (step, proc.stderr[-3000:])
    grasp_line = next(line for line in lines if line.startswith("grasp: "))
    assert f"{steps['grasp']['trials']} trials" in grasp_line and f"{steps['grasp']['succeeded']} succeeded" in grasp_line
    assert not any("grasp trials" in line for line in lines) and "\r" not in proc.stderr  # no progress bar
    # the closed-loop outcome counts every trial, stored before or run now
    choice = steps["grasp"]["choice_summary"]
    joined = " ".join(proc.stderr.split())
    assert f"first choice holds for {choice['first_holds']} of {choice['objects']} objects" in joined
    assert f"a validated grasp for {choice['validated']}" in joined


def test_ingest_line_says_why_pages_were_rejected_so_the_counts_add_up():
    ing = {"pages": 51, "fetched": 47, "extracted": 45, "rejected": 7, "new": 32, "updated": 5,
           "rejected_reasons": {"absurd_value": 1, "no_product": 2, "robots_disallowed": 1, "timeout": 1,
                                "http_500": 1, "too_large": 1}}
    line = ingest_line(ing)
    assert line.startswith("ingest: 51 pages listed, 47 fetched, 45 extracted, 7 rejected at any stage (")
    assert "absurd_value 1" in line and "no_product 2" in line and "robots_disallowed 1" in line
    assert line.endswith("; 32 new and 5 updated objects")


def test_ingest_line_without_rejections_or_page_count():
    line = ingest_line({"fetched": 3, "extracted": 3, "rejected": 0, "new": 1, "updated": 0})
    assert line == "ingest: 3 fetched, 3 extracted, 0 rejected at any stage; 1 new and 0 updated objects"
