"""The family rule fitted on real people (sim/human_fit.py): cross-validated by object, with its interval."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sim import human_fit
from sim.human_families import YALE_DEV_CSV, YaleObject, read_yale_families
from sim.human_fit import compare, family_features, nested_cv_predictions, wilson_interval

needs_data = pytest.mark.skipif(not YALE_DEV_CSV.is_file(), reason="shared human grasp data absent")


def _obj(name: str, mass: float, majority: str, n: int = 3) -> YaleObject:
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


def test_folds_hold_out_whole_objects():
    """Identical features, labels two and two: a rule that saw the scored object would get half right;
    left out, the other label is always the majority of the rest, so every prediction misses."""
    x = np.zeros((12, 3))
    y = np.array([0, 2] * 6)
    y[:2] = [0, 0]  # 7 power, 5 precision: leaving a power object out leaves 6 and 5
    pred, _ = nested_cv_predictions(x, y, grid=(1.0,))
    assert (pred[y == 0] == 0).all()  # power stays the majority without any one power object
    x2 = np.zeros((12, 3))
    y2 = np.array([0, 2] * 6)  # 6 and 6: leaving one out makes the other label the majority
    pred2, _ = nested_cv_predictions(x2, y2, grid=(1.0,))
    assert (pred2 != y2).all()


def test_a_separable_rule_is_learned_and_the_planner_is_scored_on_the_same_objects():
    objs = [_obj(f"heavy{i}", 800.0 + i, "power") for i in range(8)]
    objs += [_obj(f"light{i}", 5.0 + i, "precision") for i in range(8)]
    result = compare(objs)
    assert result.n == 16 and result.fitted_hits == 16 and result.fitted_agreement == 1.0
    assert result.fitted_ci95[1] == 1.0 and result.fitted_ci95[0] < 1.0
    assert result.always_power == 0.5
    assert result.only_fitted == result.n - result.planner_hits and result.only_planner == 0
    assert sum(result.chosen_c.values()) == 16


def test_min_grasps_keeps_objects_at_the_limit_and_refuses_too_few():
    objs = [_obj(f"o{i}", 10.0 * (i + 1), "power" if i % 2 else "precision", n=5 if i < 10 else 4)
            for i in range(14)]
    assert compare(objs, min_grasps=5).n == 10  # n_grasps == 5 kept, 4 dropped
    with pytest.raises(ValueError, match="at least 10 objects with 6\\+ grasps, have 0"):
        compare(objs, min_grasps=6)


def test_features_are_the_planners_not_the_name():
    a = _obj("cord", 65.0, "power")
    b = _obj("something else entirely", 65.0, "precision")
    assert family_features(a) == family_features(b)
    assert len(family_features(a)) == 11


def test_cli_reports_an_error_for_a_missing_file(tmp_path, capsys):
    assert human_fit.main(["--human-data", str(tmp_path / "none.csv")]) == 1
    assert "Error" in capsys.readouterr().err


@needs_data
def test_real_data_subset_runs_end_to_end(capsys):
    """The shared Yale half, objects of 10+ grasps, one C (the full nested figure: sim/PLANNER.md)."""
    objs = [o for o in read_yale_families() if o.n_grasps >= 10]
    x = np.array([family_features(o) for o in objs])
    y = np.array([["power", "intermediate", "precision"].index(o.majority) for o in objs])
    pred, cs = nested_cv_predictions(x, y, grid=(1.0,))
    assert len(pred) == len(objs) >= 40 and set(cs) == {1.0}
    assert 0.3 < (pred == y).mean() < 0.9  # well above chance, far from memorised


def test_cli_json(tmp_path, capsys):
    rows = ["object,a_cm,b_cm,c_cm,mass_g,rigidity,roundness,n_grasps,power,intermediate,precision,majority"]
    for i in range(12):
        fam = "power" if i % 2 else "precision"
        shares = "1,0,0" if fam == "power" else "0,0,1"
        rows.append(f"o{i},10,3,3,{900 if fam == 'power' else 5},rigid,a,3,{shares},{fam}")
    path = tmp_path / "y.csv"
    path.write_text("\n".join(rows) + "\n")
    assert human_fit.main(["--human-data", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n"] == 12 and out["fitted_hits"] == 12
