"""`objrecall recall`: one description or a CSV of them, human tables and JSON (Lines)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from kb.service.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


@pytest.fixture(scope="module")
def seeded(tmp_path_factory):
    db = tmp_path_factory.mktemp("recall-cli") / "seed.duckdb"
    res = run("init", "--seed", "--db", db)
    assert res.exit_code == 0, res.output
    return db


def test_recall_json(seeded):
    res = run(
        "recall", "a remote control, about 16 cm long and 3.5 cm wide, plastic", "--db", seeded, "--json"
    )
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["matches"][0]["name"] == "tv remote"
    assert {"name", "distance", "contributions", "matched_by_name"} <= set(out["matches"][0])
    assert 0 <= out["confidence"] <= 1 and out["open_set"] is False
    assert out["parsed"]["a_cm"] == 16 and out["parsed"]["material"] == "plastic"
    assert out["metric"] == "jplog" and out["unknown_noun"] is None and 0 <= out["closeness"] <= 1


def test_recall_options(seeded):
    text = "a tennis ball"
    out = json.loads(run("recall", text, "--db", seeded, "--json", "--top", "2", "--features-only").stdout)
    assert len(out["matches"]) == 2 and out["features_only"] is True
    assert not any(m["matched_by_name"] for m in out["matches"])
    out = json.loads(run("recall", text, "--db", seeded, "--json", "--metric", "kdtree").stdout)
    assert out["metric"] == "kdtree" and out["matches"][0]["name"] == "tennis ball"


def test_recall_human_table(seeded):
    res = run(
        "recall", "A watermelon, about 30 cm long and 20 cm across, around 5 kilograms.", "--db", seeded
    )
    assert res.exit_code == 0, res.output
    assert "mass_g" in res.stdout and "open set" in res.stdout
    res = run("recall", "qwerty uiop", "--db", seeded)
    assert res.exit_code == 0 and "nothing to recall" in res.stdout


def test_recall_file_json_lines_in_order(seeded, tmp_path):
    path = tmp_path / "d.csv"
    path.write_text(
        'id,description\n1,"A metallic water bottle, 21 cm long, 7 cm across"\n2,\n3,a golf ball\n4,"zzz, 12 kg"\n'
    )
    res = run("recall", "--file", path, "--db", seeded, "--json")
    assert res.exit_code == 0, res.output
    lines = [json.loads(line) for line in res.stdout.splitlines()]
    assert len(lines) == 4
    assert lines[0]["matches"][0]["name"] == "water bottle"
    assert lines[1]["matches"] == [] and lines[1]["confidence"] == 0.0
    assert lines[2]["matches"][0]["name"] == "golf ball"
    assert lines[3]["matches"]  # a mass alone still ranks objects


def test_recall_errors_are_one_line(seeded, tmp_path):
    res = run("recall", "a ball", "--db", seeded, "--metric", "hamming")
    assert res.exit_code == 1 and "Error: unknown metric 'hamming'" in res.output
    res = run("recall", "--db", seeded)
    assert res.exit_code == 1 and "Error:" in res.output
    bad = tmp_path / "bad.csv"
    bad.write_text("text\nhello\n")
    res = run("recall", "--file", bad, "--db", seeded)
    assert res.exit_code == 1 and "no 'description' column" in res.output
    res = run("recall", "a ball", "--db", tmp_path / "missing.duckdb")
    assert res.exit_code == 1 and "Error:" in res.output and "Traceback" not in res.output


def test_recall_file_that_is_not_text(seeded, tmp_path):
    path = tmp_path / "binary.csv"
    path.write_bytes(b"description\n\xff\xfe\x00bad\n")
    res = run("recall", "--file", path, "--db", seeded, "--json")
    assert res.exit_code == 1 and "not UTF-8" in res.output and "Traceback" not in res.output
