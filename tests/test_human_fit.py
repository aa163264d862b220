"""The family rule fitted on real people (sim/human_fit.py): cross-validated by object, every choice in the
inner loop, with its interval and confusion table."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim import family_models, human_fit
from sim.grasps import FAMILIES
from sim.human_families import YALE_DEV_CSV, YaleObject, planner_features, read_yale_families
from sim.human_fit import (
    CANDIDATES,
    Candidate,
    compare,
    confusion,
    family_features,
    feature_vector,
    fit_family_rule,
    inner_choice,
    nested_cv_predictions,
    training_rows,
    wilson_interval,
)

needs_data = pytest.mark.skipif(not YALE_DEV_CSV.is_file(), reason="shared human grasp data absent")

LOGISTIC = Candidate("logistic", "planner", 1.0)
SMALL = (LOGISTIC, Candidate("tree", "planner", 2, leaf=3), Candidate("knn", "ratios", 5))


def _obj(name: str, mass: float, majority: str, n: int = 3, shares: dict | None = None) -> YaleObject:
    if shares is None:
        shares = {"power": 0.0, "intermediate": 0.0, "precision": 0.0}
        shares[majority] = 1.0
    return YaleObject(name, 10.0, 3.0, 3.0, mass, "rigid", "a", n, shares, majority)


@given(st.integers(1, 500).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))))
def test_wilson_interval_holds_the_proportion_within_zero_and_one(kn):
    k, n = kn
    lo, hi = wilson_interval(k, n)
    assert 0.0 <= lo <= k / n <= hi <= 1.0


def test_wilson_interval_known_values_and_edges():
    lo, hi = wilson_interval(81, 126)  # the planner's figure on the shared half
    assert (round(lo, 3), round(hi, 3)) == (0.556, 0.721)
    assert wilson_interval(0, 10)[0] == 0.0 and wilson_interval(10, 10)[1] == 1.0
    assert wilson_interval(0, 0) == (0.0, 1.0)
    with pytest.raises(ValueError, match="within 0..5"):
        wilson_interval(6, 5)


def test_candidates_are_the_written_list_distinct_and_simplest_first():
    labels = [c.label for c in CANDIDATES]
    assert len(CANDIDATES) == 92 and len(set(labels)) == 92
    assert Counter_of(c.model for c in CANDIDATES) == {"logistic": 40, "tree": 36, "knn": 16}
    assert CANDIDATES[0] == Candidate("logistic", "planner", 0.03)  # a tie goes to the most regularised
    assert {c.features for c in CANDIDATES} == {"planner", "ratios"}
    assert not any(c.soft or c.balanced for c in CANDIDATES if c.model == "knn")


def Counter_of(xs) -> dict:
    out: dict = {}
    for x in xs:
        out[x] = out.get(x, 0) + 1
    return out


def test_folds_hold_out_whole_objects():
    """Identical features: left out, an object is scored by the majority of the others only."""
    x = np.zeros((12, 3))
    y = np.array([0, 2] * 6)
    y[:2] = [0, 0]  # 7 power, 5 precision: leaving a power object out leaves 6 and 5
    pred, _ = nested_cv_predictions(x, y, candidates=(LOGISTIC,), repeats=1)
    assert (pred[y == 0] == 0).all()  # power stays the majority without any one power object
    y2 = np.array([0, 2] * 6)  # 6 and 6: leaving one out makes the other label the majority
    pred2, chosen = nested_cv_predictions(np.zeros((12, 3)), y2, candidates=(LOGISTIC,), repeats=1)
    assert (pred2 != y2).all() and chosen == [LOGISTIC] * 12


def test_soft_training_weighs_every_recorded_family_but_scores_the_majority():
    """7 objects mostly (0.55) power, 5 all precision, same features: by majority, power (7 to 5); by
    shares, precision (3.85 power to 8.15 precision)."""
    x = np.zeros((12, 2))
    y = np.array([0] * 7 + [2] * 5)
    shares = np.array([[0.55, 0.0, 0.45]] * 7 + [[0.0, 0.0, 1.0]] * 5)
    hard = family_models.fit_candidate(Candidate("logistic", "planner", 1.0), x, y, shares)
    soft = family_models.fit_candidate(Candidate("logistic", "planner", 1.0, soft=True), x, y, shares)
    assert hard.predict(x[:1])[0] == 0 and soft.predict(x[:1])[0] == 2
    tree = family_models.fit_candidate(Candidate("tree", "planner", 2, leaf=3, soft=True), x, y, shares)
    assert tree.predict(x[:1])[0] == 2


def test_training_rows_one_per_positive_share_and_balanced_families_weigh_alike():
    target = np.array([[1.0, 0.0, 0.0]] * 6 + [[0.0, 0.0, 1.0]] * 2 + [[0.5, 0.5, 0.0]])
    rows, fams, w = training_rows(target)
    assert len(rows) == 10 and w.sum() == pytest.approx(9.0)
    rows, fams, w = training_rows(target, balanced=True)
    totals = [w[fams == f].sum() for f in range(3)]
    assert totals == pytest.approx([3.0, 3.0, 3.0]) and w.sum() == pytest.approx(9.0)
    _, fams2, w2 = training_rows(np.array([[1.0, 0, 0], [1.0, 0, 0], [0, 0, 1.0]]), balanced=True)
    assert [w2[fams2 == f].sum() for f in (0, 2)] == pytest.approx([1.5, 1.5])  # absent family: no weight


def test_inner_choice_picks_the_model_the_data_need_and_breaks_ties_to_the_earlier():
    """Precision only in a middle band of mass: a tree separates it, a linear rule cannot."""
    mass = np.linspace(1, 9, 40)
    x = np.column_stack([mass, np.zeros(40)])
    y = np.where((mass > 3.5) & (mass < 6.5), 2, 0)
    assert inner_choice({"planner": x, "ratios": x}, y, None, SMALL[:2]).model == "tree"
    twins = (LOGISTIC, Candidate("logistic", "planner", 1.0, balanced=False, soft=False, distance=True))
    assert inner_choice({"planner": x, "ratios": x}, y, None, twins) is twins[0]


def test_a_separable_rule_is_learned_and_the_planner_is_scored_on_the_same_objects():
    objs = [_obj(f"heavy{i}", 800.0 + i, "power") for i in range(8)]
    objs += [_obj(f"light{i}", 5.0 + i, "precision") for i in range(8)]
    result = compare(objs, candidates=SMALL, repeats=1)
    assert result.n == 16 and result.fitted_hits == 16 and result.fitted_agreement == 1.0
    assert result.fitted_ci95[1] == 1.0 and result.fitted_ci95[0] < 1.0
    assert result.always_power == 0.5
    assert result.only_fitted == result.n - result.planner_hits and result.only_planner == 0
    assert sum(result.chosen.values()) == 16 and result.n_candidates == 3
    assert result.fitted_confusion["power"] == {"power": 8, "intermediate": 0, "precision": 0}
    assert sum(sum(r.values()) for r in result.planner_confusion.values()) == 16


def test_confusion_counts_each_object_once_with_hits_on_the_diagonal():
    y = np.array([0, 0, 1, 2, 2, 2])
    p = np.array([0, 2, 2, 2, 0, 2])
    table = confusion(y, p)
    assert table["power"] == {"power": 1, "intermediate": 0, "precision": 1}
    assert table["intermediate"]["precision"] == 1 and table["precision"]["precision"] == 2
    assert sum(table[f][f] for f in FAMILIES) == int((y == p).sum())


def test_min_grasps_keeps_objects_at_the_limit_and_refuses_too_few():
    objs = [_obj(f"o{i}", 10.0 * (i + 1), "power" if i % 2 else "precision", n=5 if i < 10 else 4)
            for i in range(14)]
    assert compare(objs, min_grasps=5, candidates=(LOGISTIC,), repeats=1).n == 10  # 5 kept, 4 dropped
    with pytest.raises(ValueError, match="at least 10 objects with 6\\+ grasps, have 0"):
        compare(objs, min_grasps=6)


def test_features_are_the_planners_not_the_name():
    a = _obj("cord", 65.0, "power")
    b = _obj("something else entirely", 65.0, "precision")
    assert family_features(a) == family_features(b)
    assert len(family_features(a)) == 11 and len(family_features(a, "ratios")) == 15
    assert family_features(a) == feature_vector(planner_features(a))  # a catalog dict gives the same
    with pytest.raises(ValueError, match="features must be one of"):
        feature_vector(planner_features(a), "names")


def test_ratio_features_are_logs_of_sorted_extents_volume_and_density():
    f = feature_vector({"a_cm": 2.0, "b_cm": 8.0, "c_cm": 4.0, "mass_g": 64.0, "shape": "prism"}, "ratios")
    b_over_a, c_over_a, volume, density = f[-4:]
    assert b_over_a == pytest.approx(np.log(0.5)) and c_over_a == pytest.approx(np.log(0.25))
    assert volume == pytest.approx(np.log(64.0)) and density == pytest.approx(0.0)
    assert f[6:11] == [0.0, 0.0, 1.0, 0.0, 0.0]  # the prism flag
    tiny = feature_vector({"a_cm": 0.0, "b_cm": 0.0, "c_cm": 0.0, "mass_g": 0.0}, "planner")
    assert tiny[:4] == pytest.approx([np.log(0.05)] * 4)  # floored, never log(0)


def test_fitted_rule_answers_for_a_planner_feature_dict():
    objs = [_obj(f"heavy{i}", 800.0 + i, "power") for i in range(8)]
    objs += [_obj(f"light{i}", 5.0 + i, "precision") for i in range(8)]
    rule = fit_family_rule(objs, candidates=SMALL)
    assert rule.candidate in SMALL
    heavy = {"a_cm": 10.0, "b_cm": 3.0, "c_cm": 3.0, "mass_g": 900.0, "shape": "long", "rigidity": "rigid"}
    assert rule.family(heavy) == "power" and rule.family({**heavy, "mass_g": 6.0}) == "precision"


def test_cli_reports_an_error_for_a_missing_file(tmp_path, capsys):
    assert human_fit.main(["--human-data", str(tmp_path / "none.csv")]) == 1
    assert "Error" in capsys.readouterr().err


@needs_data
def test_real_data_subset_runs_end_to_end():
    """The shared Yale half, objects of 10+ grasps, one candidate (the full nested figure: sim/PLANNER.md)."""
    objs = [o for o in read_yale_families() if o.n_grasps >= 10]
    x = np.array([family_features(o) for o in objs])
    y = np.array([FAMILIES.index(o.majority) for o in objs])
    pred, cs = nested_cv_predictions(x, y, candidates=(LOGISTIC,), repeats=1)
    assert len(pred) == len(objs) >= 40 and set(cs) == {LOGISTIC}
    assert 0.3 < (pred == y).mean() < 0.9  # well above chance, far from memorised


def _csv(tmp_path) -> str:
    rows = ["object,a_cm,b_cm,c_cm,mass_g,rigidity,roundness,n_grasps,power,intermediate,precision,majority"]
    for i in range(12):
        fam = "power" if i % 2 else "precision"
        shares = "1,0,0" if fam == "power" else "0,0,1"
        rows.append(f"o{i},10,3,3,{900 if fam == 'power' else 5},rigid,a,3,{shares},{fam}")
    path = tmp_path / "y.csv"
    path.write_text("\n".join(rows) + "\n")
    return str(path)


def test_cli_json(tmp_path, capsys):
    assert human_fit.main(["--human-data", _csv(tmp_path), "--json", "--model", "knn", "--inner-repeats", "1"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n"] == 12 and out["fitted_hits"] == 12 and out["n_candidates"] == 16
    assert all(label.startswith("knn") for label in out["chosen"])


def test_cli_text_prints_the_confusion_tables(tmp_path, capsys):
    assert human_fit.main(["--human-data", _csv(tmp_path), "--model", "knn", "--inner-repeats", "1"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("REAL DATA") and "fitted rule predicts" in out and "planner predicts" in out
    assert "people precision" in out and "recall" in out


@settings(deadline=None, max_examples=30)  # scikit-learn's search is slow on a busy machine
@given(st.integers(0, 10_000), st.sampled_from([1, 5, 9]), st.booleans())
def test_neighbours_vote_as_scikit_learns_brute_force_search(seed, k, distance):
    from sklearn.neighbors import KNeighborsClassifier

    rng = np.random.default_rng(seed)
    x, y, q = rng.normal(size=(30, 3)), rng.integers(0, 3, 30), rng.normal(size=(6, 3))
    weights = "distance" if distance else "uniform"
    theirs = KNeighborsClassifier(k, weights=weights, algorithm="brute").fit(x, y).predict(q)
    assert (family_models._Neighbours(k, distance).fit(x, y).predict(q) == theirs).all()
