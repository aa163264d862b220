"""`objrecall parse`: one description, a CSV batch as JSON Lines, errors as one line."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from kb.features import FEATURES
from kb.service.cli import app

BOTTLE = (
    "A metallic water bottle of about seven and quarter centimeters in diameter and twenty one and half "
    "centimeters long. It is filled with about half a liter of water and is heavy."
)
runner = CliRunner()


def test_parse_json() -> None:
    result = runner.invoke(app, ["parse", BOTTLE, "--json"])
    assert result.exit_code == 0, result.output
    d = json.loads(result.output)
    assert set(FEATURES) <= set(d)
    assert d["a_cm"] == 21.5 and d["b_cm"] == d["c_cm"] == 7.25
    assert d["mass_g"] == 500.0 and d["qualifiers"]["mass_g"] == "at_least"
    assert d["material"] == "metal" and d["texture"] is None and d["mass_hint"] == "heavy"


def test_parse_json_with_tree() -> None:
    result = runner.invoke(app, ["parse", "about 3 in long", "--json", "--tree"])
    assert result.exit_code == 0, result.output
    d = json.loads(result.output)
    assert d["a_cm"] == pytest.approx(7.62)
    assert d["tree"].startswith("(S") and "(DIM" in d["tree"]


def test_parse_human_table_and_tree() -> None:
    result = runner.invoke(app, ["parse", BOTTLE, "--tree"])
    assert result.exit_code == 0, result.output
    assert "a_cm" in result.output and "21.5" in result.output and "at_least" in result.output
    assert "mass hint: heavy" in result.output
    assert "(QUANT" in result.output
    empty = runner.invoke(app, ["parse", "hello there"])
    assert empty.exit_code == 0 and "No features stated" in empty.output


def _write_csv(path: Path, rows: list[dict[str, str]]) -> Path:
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return path


def test_parse_file_json_lines_in_order(tmp_path: Path) -> None:
    path = _write_csv(
        tmp_path / "d.csv",
        [
            {"object": "bottle", "description": BOTTLE},
            {"object": "none", "description": "nothing to see"},
            {"object": "box", "description": "a box 10 x 5 x 2 cm, 1.5 lb"},
        ],
    )
    result = runner.invoke(app, ["parse", "--file", str(path), "--json"])
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in result.output.splitlines()]
    assert len(lines) == 3
    assert lines[0]["a_cm"] == 21.5
    assert all(lines[1][f] is None for f in FEATURES)
    assert (lines[2]["a_cm"], lines[2]["b_cm"], lines[2]["c_cm"]) == (10.0, 5.0, 2.0)
    assert lines[2]["mass_g"] == pytest.approx(680.389, rel=1e-4)
    table = runner.invoke(app, ["parse", "--file", str(path)])
    assert table.exit_code == 0 and "21.5" in table.output


def test_parse_errors_are_one_line(tmp_path: Path) -> None:
    no_input = runner.invoke(app, ["parse"])
    assert no_input.exit_code == 1 and "Error:" in no_input.output and "Traceback" not in no_input.output
    bad = _write_csv(tmp_path / "bad.csv", [{"name": "x", "text": "y"}])
    result = runner.invoke(app, ["parse", "--file", str(bad), "--json"])
    assert result.exit_code == 1 and "no 'description' column" in result.output
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"description\n\xff\xfe\x00bad\n")
    result = runner.invoke(app, ["parse", "--file", str(binary), "--json"])
    assert result.exit_code == 1 and "not UTF-8" in result.output and "Traceback" not in result.output
    missing = runner.invoke(app, ["parse", "--file", str(tmp_path / "nope.csv")])
    assert missing.exit_code == 1 and "nope.csv" in missing.output


def test_real_subprocess_with_empty_nltk_data(tmp_path: Path, cli_env: dict[str, str]) -> None:
    empty = tmp_path / "nltk_data"
    empty.mkdir()
    env = {**cli_env, "NLTK_DATA": str(empty)}
    path = _write_csv(tmp_path / "d.csv", [{"description": BOTTLE}, {"description": "a 3 cm cube, 12 g"}])
    proc = subprocess.run(
        [sys.executable, "-m", "kb.service.cli", "parse", "--file", str(path), "--json"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    lines = [json.loads(line) for line in proc.stdout.splitlines()]
    assert lines[0]["material"] == "metal"
    assert (lines[1]["a_cm"], lines[1]["b_cm"], lines[1]["c_cm"], lines[1]["mass_g"]) == (3.0, 3.0, 3.0, 12.0)
    assert list(empty.iterdir()) == []  # nothing was downloaded
