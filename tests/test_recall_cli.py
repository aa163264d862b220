"""`objrecall recall`: one description or a CSV of them, human tables and JSON (Lines)."""

from __future__ import annotations

import json
import re

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


def test_recall_table_says_not_in_the_catalog_with_the_closest_of_the_kind(seeded):
    res = run("recall", "An orange of 7 cm diameter.", "--db", seeded)
    assert res.exit_code == 0, res.output
    text = " ".join(res.stdout.split())
    assert "NOT IN THE CATALOG (open set): no 'orange' (kind: fruit)" in text
    assert "closest of the same kind (fruit)" in text and "closest fruit: apple" in text
    assert "confidence 0.0" in text


def test_recall_table_shows_the_ranking_score_sorted_with_its_name_part(seeded):
    res = run("recall", "a tennis ball, 60 g", "--db", seeded, "--json")
    out = json.loads(res.stdout)
    scores = [m["score"] for m in out["matches"]]
    assert scores == sorted(scores)
    first = out["matches"][0]
    assert first["score"] == pytest.approx(first["distance"] - first["name_part"] + first["vague_part"])
    table = run("recall", "a tennis ball, 60 g", "--db", seeded).stdout
    header = next(line for line in table.splitlines() if "object" in line)
    assert "score" in header and "name" in header and "distance" not in header
    rows = [line for line in table.splitlines() if line.startswith("│ ")]
    shown = [float(r.split("│")[3]) for r in rows if r.split("│")[3].strip()]
    assert shown == sorted(shown) and len(shown) >= 3


def test_a_vague_description_says_it_is_a_guess(seeded):
    res = run("recall", "something small and round", "--db", seeded)
    text = " ".join(res.stdout.split())
    assert "vague: small -> a_cm <=" in text and "a guess: many objects fit" in text
    assert "basketball" not in text


def test_grasp_plan_for_a_teapot_plans_for_the_described_object(seeded):
    res = run("grasp", "plan", "a ceramic teapot about 22 cm wide, 900 g", "--db", seeded, "--json")
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    how = out["recalled"]
    assert out["object"] == "described teapot" and how["not_in_catalog"] and how["hint"] == "pitcher"
    assert out["features"]["b_cm"] == 22 or out["features"]["a_cm"] == 22
    assert out["features"]["mass_g"] == 900 and out["features"]["material"] == "other"
    assert how["stated"] == ["b_cm", "mass_g", "material"] and "a_cm" in how["from_hint"]
    table = run("grasp", "plan", "a ceramic teapot about 22 cm wide, 900 g", "--db", seeded).stdout
    assert "planned for the described teapot: not in the catalog (no 'teapot')" in " ".join(table.split())
    close = json.loads(run("grasp", "plan", "a tennis ball, 6.5 cm", "--db", seeded, "--json").stdout)
    assert close["object"] == "tennis ball" and close["recalled"]["planned_for"] == "tennis ball"


def test_grasp_plan_simulate_a_teapot_simulates_the_described_object(seeded):
    res = run(
        "grasp", "plan", "a ceramic teapot about 22 cm wide, 900 g", "--db", seeded, "--simulate", "--json",
        "--top", "1",
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["object"] == "described teapot" and out["recalled"]["open_set"]
    # the recall's own verdict line, the same as `objrecall recall --json` and POST /recall give
    assert out["recalled"]["verdict"]["label"] == "not in the catalog"
    assert out["recalled"]["verdict"]["text"].startswith("NOT IN THE CATALOG (open set): no 'teapot'")
    assert out["trial"]["outcome"] in ("success", "failure", "error") and out["features"]["mass_g"] == 900


def test_the_table_prints_a_zero_name_part_unsigned_and_counts_candidates_in_whole_numbers(seeded):
    res = run("recall", "a red plastic mug 10 cm tall", "--db", seeded)
    assert res.exit_code == 0, res.output
    assert "-0.00" not in res.stdout and "0.00" in res.stdout  # the unnamed rows' name part
    guess = run("recall", "something small and round", "--db", seeded)
    text = " ".join(guess.stdout.split())
    assert re.search(r"about \d+ candidates as good", text), text  # a soft count, said as a whole number


@pytest.mark.parametrize(
    ("text", "words"), [("a mug 501 kg", "'501 kg'"), ("a mug -5 cm, 300 g", "'-5 cm'"), ("a pen 1e308 cm", "1e308")]
)
def test_the_table_says_which_stated_value_was_not_used(seeded, text, words):
    """A refused value (beyond the catalog's limits, negative) is said above the table, so a recall
    without it never looks like one with it (a blind test saw "a mug 501 kg" answered at 0.79 silently)."""
    res = run("recall", text, "--db", seeded)
    assert res.exit_code == 0, res.output
    flat = " ".join(res.stdout.split())
    assert "Not used: " in flat and words in flat and "recalled without it" in flat, flat


def test_the_table_says_nothing_was_refused_when_nothing_was(seeded):
    res = run("recall", "a red mug 9 cm tall, 300 g", "--db", seeded)
    assert res.exit_code == 0 and "Not used" not in res.stdout


def test_a_long_row_refuses_the_whole_file_naming_its_rows(seeded, tmp_path):
    """Checked before any row is recalled: the batch is refused whole, not cut off at its first long row."""
    from recall.descriptions import MAX_DESCRIPTION_CHARS

    path = tmp_path / "d.csv"
    rows = ["a ball", "x" * (MAX_DESCRIPTION_CHARS + 1), "a mug", "y" * MAX_DESCRIPTION_CHARS]
    path.write_text("description\n" + "\n".join(rows) + "\n")
    res = run("recall", "--file", path, "--db", seeded, "--json")
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert "row 2 (5,001 characters)" in res.output and "row 4" not in res.output  # exactly at the limit is fine
    assert "nothing recalled" in res.output and '"matches"' not in res.output  # row 1 was not printed first


def test_more_than_three_long_rows_are_counted(tmp_path):
    from kb.errors import DescriptionError
    from recall.descriptions import MAX_DESCRIPTION_CHARS, read_description_column

    path = tmp_path / "d.csv"
    path.write_text("description\n" + "\n".join(["z" * (MAX_DESCRIPTION_CHARS + 1)] * 5) + "\n")
    with pytest.raises(DescriptionError, match=r"row 1 .*row 2 .*row 3 \(5,001 characters\) and 2 more"):
        read_description_column(path)
    path.write_text("description\n" + "\n".join(["z" * MAX_DESCRIPTION_CHARS] * 5) + "\n")
    assert len(read_description_column(path)) == 5
