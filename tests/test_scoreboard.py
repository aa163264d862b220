"""`objrecall evaluate --all` (recall.scoreboard): one row per description set, counted right."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from recall.scoreboard import BLIND_SETS, DEVELOPMENT_SETS, DescriptionSet, score_set, scoreboard

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def small_repo(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("repo")
    (root / "kb" / "data").mkdir(parents=True)
    shutil.copy(REPO / "kb" / "data" / "seed_catalog.csv", root / "kb" / "data" / "seed_catalog.csv")
    (root / "recall" / "data").mkdir(parents=True)
    (root / "recall" / "data" / "dev_descriptions.csv").write_text(
        "object,description\n"
        'tennis ball,"A fuzzy tennis ball, 6.7 cm across, 57 g."\n'
        'golf ball,"A golf ball, 4.3 cm, 46 g."\n'
        'golf ball,"A leather baseball, 7.4 cm, 145 g."\n',  # labelled wrong on purpose: a miss
        encoding="utf-8",
    )
    (root / "recall" / "data" / "open_set_descriptions.csv").write_text(
        "description\nAn orange of 7 cm diameter.\nA fuzzy tennis ball, 6.7 cm across, 57 g.\n", encoding="utf-8"
    )
    return root


def test_a_set_is_counted_per_mode(small_repo):
    row = score_set(DEVELOPMENT_SETS[0], small_repo)
    assert (row.name, row.n, row.open_set_n) == ("dev", 3, 2)
    hybrid = next(m for m in row.modes if m.mode == "jplog+names")
    assert hybrid.top1 == pytest.approx(2 / 3)
    assert hybrid.detected == 1  # the orange; the tennis ball in the open-set list is a close match
    assert hybrid.false_flags == 0
    assert 0.0 <= hybrid.ece <= 1.0 and 0.0 <= hybrid.brier <= 1.0
    assert row.features_only_top1["jp"] == pytest.approx(2 / 3)
    assert set(row.to_dict()) == {"name", "n", "open_set_n", "modes", "features_only_top1"}


def test_missing_sets_are_skipped_and_a_set_without_open_set_has_no_detection(small_repo):
    rows = scoreboard(repo=small_repo)
    assert [r.name for r in rows] == ["dev"]
    spec = DescriptionSet("no-open", "kb/data/seed_catalog.csv", "recall/data/dev_descriptions.csv")
    assert all(m.detected is None for m in score_set(spec, small_repo).modes)


def test_every_listed_set_is_in_the_repository():
    for spec in DEVELOPMENT_SETS + BLIND_SETS:
        for path in (spec.catalog, spec.descriptions, spec.open_set):
            assert path is None or (REPO / path).is_file(), path


def test_evaluate_needs_files_or_all():
    from kb.service.cli import app

    result = CliRunner().invoke(app, ["evaluate"])
    assert result.exit_code != 0 and "--all" in result.output


def test_evaluate_all_prints_a_reliability_plot_per_mode_and_split(small_repo):
    from rich.console import Console

    from kb.service.cli.recall import _print_reliability

    rows = scoreboard(repo=small_repo)  # "dev", a set the confidence is fitted on
    console = Console(record=True, width=140)
    _print_reliability(console, rows)
    text = console.export_text()
    for mode in ("jp", "jplog+names"):
        assert f"Reliability, {mode}, sets the confidence was fitted on:" in text
    assert "held out" not in text  # no held-out set in this repository
    assert text.count("confidence    n   mean  accuracy") == 2
