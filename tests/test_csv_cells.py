"""Spreadsheet-safe CSV cells: every CSV the project writes marks formula-like text with ', and the catalog
reader takes the mark off, so export -> import gives back the exact names."""

from __future__ import annotations

import csv
import json

import pytest
from typer.testing import CliRunner

from kb.catalog import KnowledgeBase
from kb.csvio import read_spreadsheet_cell, spreadsheet_cell
from kb.features import ObjectRecord
from kb.service.cli import app
from sim.report import write_report

#: Names a catalog may hold that start like a formula; the first is an ordinary product name.
FORMULA_LIKE_NAMES = [
    "-18 °c freezer thermometer",
    '=hyperlink("http://x","y")',
    "+1 pencil",
    "@home mug",
    "'=already marked mug",
    "''-twice marked mug",
]


@pytest.mark.parametrize(
    ("text", "cell"),
    [
        ("=1+1", "'=1+1"),
        ("+1 pencil", "'+1 pencil"),
        ("-18 °c freezer thermometer", "'-18 °c freezer thermometer"),
        ("@sum(a1)", "'@sum(a1)"),
        ("\tx", "'\tx"),
        ("\rx", "'\rx"),
        ("-", "'-"),
        ("-2+3", "'-2+3"),  # a formula, though it starts like a number
        ("-5", "-5"),  # plain numbers are numbers to a spreadsheet, not formulas
        ("+1.5e3", "+1.5e3"),
        ("-.5", "-.5"),
        ("mug", "mug"),
        ("", ""),
        (" =x", " =x"),  # a leading space keeps a spreadsheet from reading a formula
        ("'n sync mug", "'n sync mug"),  # a quote before ordinary text is text
        ("'=x", "''=x"),  # a quote before formula-like text is marked too, so it reads back
        ("'-5", "''-5"),
    ],
)
def test_spreadsheet_cell_marks_formula_like_text_and_reads_back(text, cell):
    assert spreadsheet_cell(text) == cell
    assert read_spreadsheet_cell(cell) == text


def test_hand_written_cells_without_the_mark_read_as_written():
    for cell in ("-5", "'n sync mug", "=x", "'", "''", "'x"):
        assert read_spreadsheet_cell(cell) == cell


def test_catalog_export_marks_formula_like_cells_and_import_round_trips(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "a.duckdb")
    records = [
        ObjectRecord.create(name, a_cm=10, b_cm=5, c_cm=2, mass_g=100, aliases=[f"-alias {i}"])
        for i, name in enumerate(FORMULA_LIKE_NAMES)
    ]
    kb.upsert(records, source="=source", adapter="csv")
    out = tmp_path / "export.csv"
    kb.export_csv(out)
    with out.open(newline="", encoding="utf-8") as fh:
        raw = list(csv.DictReader(fh))
    for row in raw:  # nothing in the file starts like a formula
        for column, cell in row.items():
            stripped = cell.lstrip("'")
            assert not (stripped[:1] in "=+-@" and stripped and stripped == cell), (column, cell)
    assert {r["name"] for r in raw} == {"'" + n for n in FORMULA_LIKE_NAMES}
    assert all(r["mass_g"] == "100" for r in raw)  # number cells are not marked
    other = KnowledgeBase.open(tmp_path / "b.duckdb")
    assert sorted(other.import_csv(out).new) == sorted(FORMULA_LIKE_NAMES)
    assert other.list_objects() == kb.list_objects()
    assert kb.import_csv(out).unchanged == len(FORMULA_LIKE_NAMES)


def test_negative_number_cell_is_still_refused_as_a_number(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "a.duckdb")
    f = tmp_path / "neg.csv"
    f.write_text(
        "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\nmug,-5,8,8,300,,,,,\n"
    )
    report = kb.import_csv(f, skip_invalid=True)
    (skipped,) = report.skipped
    assert skipped.row == 2 and skipped.column in ("a_cm", "dimensions")


def test_grasp_plan_reads_an_exported_catalog_with_the_exact_names(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "a.duckdb")
    kb.upsert(
        [ObjectRecord.create(FORMULA_LIKE_NAMES[0], a_cm=12, b_cm=3, c_cm=2, mass_g=40)],
        source="t",
        adapter="csv",
    )
    out = tmp_path / "export.csv"
    kb.export_csv(out)
    result = CliRunner().invoke(
        app, ["grasp", "plan", "--catalog", str(out), "--json"], catch_exceptions=False
    )
    assert result.exit_code == 0, result.output
    (line,) = (json.loads(x) for x in result.output.splitlines())
    assert line["name"] == FORMULA_LIKE_NAMES[0]


def test_report_csv_marks_text_but_not_numbers(tmp_path):
    row = {
        "object_name": FORMULA_LIKE_NAMES[0], "grasp_type": "power_sphere", "family": "power", "rank": 0,
        "seed": 0, "outcome": "failure", "success": False, "reason": "-slipped", "slip_cm": -0.25,
        "rotation_deg": "-3.5", "grip_force_n": 5.5, "max_contact_force_n": 12.0, "simulator": "mujoco 3",
        "hand_version": "h", "planner_version": "1", "features_hash": "abc", "details": "{}",
        "shape": "prism", "material": "plastic",
    }  # fmt: skip
    write_report([row], tmp_path)
    with (tmp_path / "results.csv").open(newline="", encoding="utf-8") as fh:
        (line,) = list(csv.DictReader(fh))
    assert line["object_name"] == "'" + FORMULA_LIKE_NAMES[0]
    assert read_spreadsheet_cell(line["object_name"]) == FORMULA_LIKE_NAMES[0]
    assert line["reason"] == "'-slipped"
    assert line["slip_cm"] == "-0.25" and line["rotation_deg"] == "-3.5"


def test_every_csv_writer_in_the_project_escapes_its_cells():
    """A module that writes CSV (csv.writer / DictWriter, pandas or polars writers) marks its cells with
    spreadsheet_cell; a new writer without it fails here."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    writers = ("csv.writer(", "csv.DictWriter(", ".to_csv(", ".write_csv(")
    found = {}
    for package in ("kb", "scrapers", "recall", "sim", "benchmarks", "scripts"):
        for path in (root / package).rglob("*.py"):
            text = path.read_text(encoding="utf-8")
            if any(w in text for w in writers):
                found[path.relative_to(root).as_posix()] = "spreadsheet_cell" in text
    assert {"kb/csvio.py", "sim/report.py"} <= set(found)  # the two writers there are today
    assert [p for p, escaped in found.items() if not escaped] == []
