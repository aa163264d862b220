"""`objrecall evaluate`: the paper's Fig. 5 on labelled descriptions, with the hybrid and the misses."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from kb.errors import RecallError
from kb.service.cli import app
from recall.evaluation import DEV_SET, SEED_CATALOG, evaluate, read_descriptions

runner = CliRunner()

CATALOG = """name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity,aliases
calculator,15.4,7.9,1.5,116,thin,medium,medium,plastic,rigid,
tennis ball,6.4,6.4,6.4,56,radial,rough,medium,fabric,squeezable,
plastic ball,6.5,6.5,6.5,20,radial,smooth,medium,plastic,rigid,
wood disk,7.2,7.2,2,60,compact,rough,sturdy,wood,rigid,
"""
DESCRIPTIONS = """object,description
calculator,"A calculator, 15 cm long and 8 cm wide, plastic"
tennis ball,"A tennis ball, about 6.5 cm across"
plastic ball,"a ball about 6.5 cm across, weighs 20 grams"
wood disk,"a light ball, 6.5 cm"
unicorn,"a unicorn, 2 m tall"
"""


@pytest.fixture
def small(tmp_path):
    cat, desc = tmp_path / "c.csv", tmp_path / "d.csv"
    cat.write_text(CATALOG)
    desc.write_text(DESCRIPTIONS)
    return cat, desc


def test_small_evaluation_counts_hits_and_explains_misses(small):
    report = evaluate(*small)
    assert report.n == 4 and report.unknown_objects == ["unicorn"]
    jp = report.score("jp")
    # features only: "about 6.5 cm across" is nearer the plastic ball (6.5) than the tennis ball (6.4),
    # and the "light ball" is no wood disk; the hybrid reads the name "tennis ball"
    assert (jp.top1, jp.top3) == (2, 4)
    missed = {m.object: m for m in report.misses if m.mode == "jp"}
    assert set(missed) == {"tennis ball", "wood disk"}
    assert missed["tennis ball"].got == "plastic ball"
    assert "a_cm: stated 6.5, tennis ball 6.4" in missed["tennis ball"].reason
    assert "not stated: texture (rough vs smooth)" in missed["tennis ball"].reason
    assert "pulled ahead by " in missed["tennis ball"].reason
    assert missed["tennis ball"].reason.startswith("jp plastic ball ")
    assert report.score("jp", features_only=False).top1 == 3
    assert {s.metric for s in report.scores} == {"jp", "euclidean", "minkowski", "cosine", "kdtree", "jplog"}
    assert report.parse["n"] == 4


def test_evaluate_command_json_and_table(small):
    res = runner.invoke(
        app, ["evaluate", "--catalog", str(small[0]), "--descriptions", str(small[1]), "--json"]
    )
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    assert out["n"] == 4 and out["scores"][0]["metric"] == "jp" and out["scores"][0]["paper_top1_pct"] == 92
    res = runner.invoke(app, ["evaluate", "--catalog", str(small[0]), "--descriptions", str(small[1])])
    assert res.exit_code == 0 and "Fig. 5" in res.stdout and "Misses" in res.stdout


def test_bad_descriptions_file(tmp_path, small):
    bad = tmp_path / "bad.csv"
    bad.write_text("name,text\nx,y\n")
    with pytest.raises(RecallError, match="object"):
        read_descriptions(bad)
    res = runner.invoke(app, ["evaluate", "--catalog", str(small[0]), "--descriptions", str(bad)])
    assert res.exit_code == 1 and res.output.startswith("Error:")
    res = runner.invoke(
        app, ["evaluate", "--catalog", str(tmp_path / "nope.csv"), "--descriptions", str(bad)]
    )
    assert res.exit_code == 1 and "Error:" in res.output


def test_development_set_goals():
    """The issue's goals on the development set: JP ahead of every baseline, >= 92 % top-1 features only;
    the hybrid ahead of JP (97.1 % when written; the assertion leaves room for parser changes)."""
    assert Path(DEV_SET).is_file() and Path(SEED_CATALOG).is_file()
    report = evaluate(SEED_CATALOG, DEV_SET)
    jp = report.score("jp")
    assert jp.n >= 200
    assert jp.top1_pct >= 92.0
    for metric in ("euclidean", "minkowski", "cosine", "kdtree"):
        assert jp.top1 > report.score(metric).top1, metric
    hybrid = report.score("jplog", features_only=False)  # the default hybrid
    assert hybrid.top1 > jp.top1 and hybrid.top1_pct >= 97.0
    assert report.score("jplog").top1 >= jp.top1


def test_evaluate_counts_open_set_flags(small, tmp_path):
    opens = tmp_path / "open.csv"
    opens.write_text(
        "description\n"
        '"A refrigerator, about 180 cm tall, 70 cm wide, 70 cm deep, 70 kg"\n'
        '"A tennis ball, 6.4 cm across"\n'
    )
    report = evaluate(*small, open_set_csv=opens)
    assert report.open_set_n == 2
    assert report.open_set == {"jp": 1, "jplog+names": 1}  # the fridge; the tennis ball is in the catalog
    assert set(report.false_flags) == {"jp", "jplog+names"}
    assert report.to_dict()["open_set_flagged"] == report.open_set
    res = runner.invoke(
        app,
        ["evaluate", "--catalog", str(small[0]), "--descriptions", str(small[1]), "--open-set", str(opens)],
    )
    assert res.exit_code == 0, res.output
    out = " ".join(res.stdout.split())
    assert "Open-set descriptions flagged (detection rate): jp 1/2 (50.0 %" in out
    assert "(false-flag rate)" in out and "Brier" in out and "ECE" in out


CATALOG2 = Path(__file__).parent / "data" / "catalog2"


def test_a_second_catalog_of_near_twins():
    """Generalisation: a catalog the weights and thresholds were not fitted on (``tests/data/catalog2``: the
    paper's lab objects and many near twins, some unknown values). When written: jp 95.8 %, the default
    hybrid 99.2 %, jp + names 96.6 %, no false open-set flags, 6 of 12 out-of-catalog objects flagged; the
    floors leave room for parser changes."""
    report = evaluate(
        CATALOG2 / "catalog.csv", CATALOG2 / "descriptions.csv", open_set_csv=CATALOG2 / "open_set.csv"
    )
    assert report.n >= 110 and not report.unknown_objects
    jp = report.score("jp")
    assert jp.top1_pct >= 90.0
    for metric in ("euclidean", "minkowski", "cosine", "kdtree"):
        assert jp.top1 > report.score(metric).top1, metric
    assert report.score("jplog", features_only=False).top1_pct >= 95.0
    assert report.score("jp", features_only=False).top1_pct >= 93.0
    # "a wood plate" (the flat wood piece) names a plate the catalog does not have: 2 of 119 flagged
    # not in the catalog; the goal is at most 2 % of full in-catalog descriptions
    assert report.false_flags["jplog+names"] <= 0.02 * report.n
    assert report.open_set_n == 12 and report.open_set["jplog+names"] >= 10


def test_labels_written_differently_from_the_catalog_names_still_count(tmp_path):
    cat, desc = tmp_path / "c.csv", tmp_path / "d.csv"
    cat.write_text(
        "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\n"
        "Wood_Cylinder,8,2.9,2.9,21,prism,rough,sturdy,wood,rigid\n"
        "rubiks cube,5.7,5.7,5.7,90,compact,smooth,sturdy,plastic,rigid\n"
        "wood-cylinders,30,30,30,2000,prism,rough,sturdy,wood,rigid\n"
    )
    desc.write_text(
        "object,description\n"
        'wood cylinder,"a wooden cylinder, 8 cm long, 3 cm across"\n'
        'Rubik\'s Cube,"a puzzle cube, 5.5 cm, 85 g"\n'
        'unicorn,"a unicorn, 2 m tall"\n'
    )
    report = evaluate(cat, desc)
    # "wood cylinder" is ambiguous loosely (Wood_Cylinder, wood-cylinders): it stays unknown
    assert report.n == 1 and report.score("jp").top1 == 1
    assert sorted(report.unknown_objects) == ["unicorn", "wood cylinder"]
    cat.write_text("\n".join(cat.read_text().splitlines()[:3]) + "\n")
    report = evaluate(cat, desc)
    assert report.n == 2 and report.score("jp").top1 == 2 and report.unknown_objects == ["unicorn"]


def test_description_header_in_any_case_or_with_name(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text('Object,Description\ncup,"a cup"\n')
    assert read_descriptions(path) == [("cup", "a cup")]
    path.write_text('name,description,notes\nCup,"a cup",x\n')
    assert read_descriptions(path) == [("cup", "a cup")]
    path.write_text('thing,text\ncup,"a cup"\n')
    with pytest.raises(RecallError, match="missing column"):
        read_descriptions(path)


@pytest.mark.parametrize(
    ("descriptions", "open_set", "flagged", "max_brier"),
    [
        # when written (issue 16): 15/15, 1/242 false flags, Brier 0.020; hold-out 6/10, 0/120, 0.027
        (DEV_SET, Path(DEV_SET).with_name("open_set_descriptions.csv"), 14, 0.04),
        (
            Path(__file__).parent / "data" / "holdout" / "holdout_descriptions.csv",
            Path(__file__).parent / "data" / "holdout" / "holdout_open_set.csv",
            6,
            0.05,
        ),
    ],
)
def test_open_set_detection_false_flags_and_calibration_floors(descriptions, open_set, flagged, max_brier):
    report = evaluate(SEED_CATALOG, descriptions, open_set_csv=open_set)
    assert report.open_set["jplog+names"] >= flagged
    assert report.false_flags["jplog+names"] <= 0.02 * report.n  # the goal for full descriptions
    cal = report.calibration("jplog+names")
    assert cal.n == report.n + report.open_set_n and cal.brier <= max_brier and cal.ece <= 0.08
    assert report.to_dict()["calibration"]["jplog+names"]["brier"] == cal.brier
