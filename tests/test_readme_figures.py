"""The README's figure tables are what scripts/readme_figures.py renders from the saved results, and the
saved evaluation is what `objrecall evaluate` prints now (recomputed, slow)."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("readme_figures", REPO / "scripts" / "readme_figures.py")
figures = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(figures)


def test_readme_tables_match_the_saved_results():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    assert figures.render_readme(text) == text, (
        "README figures differ from benchmarks/results: after editing a benchmark row by hand run "
        "`python scripts/readme_figures.py --adopt`; after changing recall run it with `--evaluate`"
    )
    assert figures.main(["--check"]) == 0


def test_every_saved_benchmark_row_is_in_the_readme():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    rows = figures.load_benchmark_rows()
    assert len(rows) >= 5
    for row in rows:
        assert f"| {row['benchmark']} | {row['result']} |" in text


def test_blocks_are_replaced_and_a_missing_marker_is_an_error():
    text = "intro\n<!-- figures:x -->\nold\n<!-- /figures:x -->\nend\n"
    assert figures.replace_block(text, "x", "new 1\nnew 2") == (
        "intro\n<!-- figures:x -->\nnew 1\nnew 2\n<!-- /figures:x -->\nend\n"
    )
    with pytest.raises(figures.FiguresError, match="figures:y"):
        figures.replace_block(text, "y", "z")
    with pytest.raises(figures.FiguresError):
        figures.replace_block(text + text, "x", "z")


def test_the_recall_table_shows_each_saved_score():
    saved = json.loads(figures.EVALUATE_JSON.read_text(encoding="utf-8"))
    table = figures.render_recall_table(saved)
    assert len(table.splitlines()) == 2 + len(figures.RECALL_ROWS)
    default = figures._score(saved["dev"]["scores"], "jplog", False)
    assert f"**{default['top1_pct']:g} %**" in table.splitlines()[-1] or default["top1_pct"] == 100


@pytest.mark.slow
def test_saved_evaluation_is_what_evaluate_prints_now():
    saved = json.loads(figures.EVALUATE_JSON.read_text(encoding="utf-8"))
    now = figures.run_evaluate()
    for key in saved:
        assert now[key]["n"] == saved[key]["n"]
        assert now[key]["scores"] == saved[key]["scores"], f"{key}: run python scripts/readme_figures.py --evaluate"


def test_rows_edited_by_hand_are_adopted(tmp_path):
    results = tmp_path / "results"
    results.mkdir()
    (results / "evaluate.json").write_text(figures.EVALUATE_JSON.read_text(encoding="utf-8"))
    (results / "a.json").write_text(json.dumps({"benchmark": "alpha", "result": "1 op/s", "order": 10}))
    (results / "gone.json").write_text(json.dumps({"benchmark": "old", "result": "x", "order": 20}))
    text = "<!-- figures:benchmarks -->\n| benchmark | result |\n|---|---|\n| alpha | 2 op/s |\n| beta | 3 |\n<!-- /figures:benchmarks -->\n"
    assert figures.adopt_benchmark_rows(text, results) == 3
    rows = figures.load_benchmark_rows(results)
    assert [(r["benchmark"], r["result"]) for r in rows] == [("alpha", "2 op/s"), ("beta", "3")]
    assert figures.replace_block(text, "benchmarks", figures.render_benchmark_table(rows)) == text
    assert figures.adopt_benchmark_rows(text, results) == 0


def test_the_corpus_table_merges_language_tags_and_puts_held_out_first(tmp_path):
    c = lambda p, d, m: {"pages": p, "dims": d, "mass": m}  # noqa: E731
    data = {"held_out": {"all": c(3, 2, 1), "stores": 2, "language": {"en": c(1, 1, 0), "en-US": c(2, 1, 1)},
                         "layout": {"table": c(3, 2, 1)}, "part": {}},
            "development": {"all": c(4, 4, 3), "stores": 3, "language": {"de": c(4, 4, 3)},
                            "layout": {"table": c(1, 1, 1), "dl": c(3, 3, 2)}, "part": {}}}  # fmt: skip
    (tmp_path / "corpus_bench.json").write_text(json.dumps({"data": data}))
    lines = figures.render_corpus_table(tmp_path).splitlines()
    assert lines[2] == "| **all** (2 + 3 stores) | 2/3 (0.67) | 1/3 (0.33) | 4/4 (1.00) | 3/4 (0.75) |"
    assert "| language en | 2/3 (0.67) | 1/3 (0.33) | – | – |" in lines  # en and en-US are one language
    assert "| language de | – | – | 4/4 (1.00) | 3/4 (0.75) |" in lines
    assert lines.index("| layout table | 2/3 (0.67) | 1/3 (0.33) | 1/1 (1.00) | 1/1 (1.00) |") < lines.index(
        "| layout dl | – | – | 3/3 (1.00) | 2/3 (0.67) |")  # the most pages first
