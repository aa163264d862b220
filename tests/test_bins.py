"""A binned catalog's classes (bins.csv, recall.catalog_folder) in the ranking: NumPy and SQL agree.

The engine ranks a binned catalog by the stated intervals widened to the classes
(:meth:`recall.metrics.FeatureQuery.within_classes`); the SQL macros given the same widened intervals
(``jp_range_term``, ``jplog_range_term``) rank alike, with the same distances. On the real Yale catalog."""

import math
from pathlib import Path

import pytest

from recall.catalog_folder import read_bins
from recall.metrics import FeatureQuery

CATALOG = Path(__file__).parent / "data" / "catalog_yale" / "catalog.csv"
COLUMNS = {"a_cm": "qa", "b_cm": "qb", "c_cm": "qc", "mass_g": "qmass"}


@pytest.fixture(scope="module")
def yale(tmp_path_factory):
    from kb.catalog import KnowledgeBase
    from recall.evaluation import _recaller_from_catalog

    tmp = tmp_path_factory.mktemp("bins")
    recaller = _recaller_from_catalog(CATALOG, tmp)
    assert recaller.bins == read_bins(CATALOG)  # the folder's classes, read with the catalog
    return KnowledgeBase.open(tmp / "evaluation.duckdb"), recaller


def _sql_term(metric: str, feature: str, low: float, high: float, value: float) -> str:
    lo = "NULL" if low <= 0 else repr(low)
    return f"{metric}_range_term({feature}, {lo}, {high!r}, {value!r})"


@pytest.mark.parametrize("metric", ["jplog", "jp"])
@pytest.mark.parametrize(
    "values",
    [
        {"a_cm": 45.0, "b_cm": 40.0, "c_cm": 12.0, "mass_g": 4000.0},  # a drawer, whole
        {"a_cm": 9.0, "b_cm": 6.0, "mass_g": 110.0},
        {"mass_g": 20.0},
        {"c_cm": 0.5, "mass_g": 700.0},
    ],
)
def test_numpy_and_sql_rank_a_binned_catalog_alike(yale, values, metric):
    kb, recaller = yale
    # the interval the recaller ranks by: widened to the classes, its ends above a floor read as the floor
    widened = FeatureQuery.from_values(values).within_classes(recaller.bins).within_floors(recaller.floors)
    terms = " + ".join(_sql_term(metric, c.feature, c.low, c.high, c.value) for c in widened.numeric)
    rows = kb.sql(f"SELECT name, {terms} AS distance FROM objects ORDER BY distance, name").rows
    result = recaller.recall_features(values, top=len(rows), metric=metric, features_only=True)
    assert [m.name for m in result.matches] == [r[0] for r in rows]
    for match, (_, distance) in zip(result.matches, rows, strict=True):
        assert match.distance == pytest.approx(distance, rel=1e-5, abs=1e-5)


def test_a_class_widens_the_stated_interval_at_its_ends():
    q = FeatureQuery.from_values({"a_cm": 30.0, "mass_g": 300.0})
    widened = {c.feature: (c.low, c.high, c.value) for c in q.within_classes(
        {"a_cm": (1.0, math.inf), "mass_g": (1.5, 2.0)}).numeric}  # fmt: skip
    assert widened["a_cm"] == (0.0, 30.0, 30.0)  # any part up to the stated size: a lower bound
    assert widened["mass_g"] == pytest.approx((150.0, 450.0, 300.0))  # x in [v / above, v * below]
    assert q.within_classes({}) == q  # no classes: the query itself


def test_an_open_top_bin_reads_the_stated_ends_above_its_floor_as_the_floor():
    """``floors.csv``: a stored value at the floor stands for "the floor or more", so the ranking reads a
    stated value above it as the floor (the top bin); values at or below the floor are unchanged."""
    floors = {"mass_g": 1000.0}
    (c,) = FeatureQuery.from_values({"mass_g": 7000.0}).within_floors(floors).numeric
    assert (c.value, c.low, c.high) == (1000.0, 1000.0, 1000.0)
    at = FeatureQuery.from_values({"mass_g": 1000.0})
    assert at.within_floors(floors) == at  # the floor itself: unchanged
    below = FeatureQuery.from_values({"mass_g": 999.0, "a_cm": 80.0})
    assert below.within_floors(floors) == below  # below the floor, or a feature without one
    ranged = FeatureQuery.from_values({"mass_g": 1500.0}, {"mass_g": "range"}, {"mass_g": (800.0, 2000.0)})
    (r,) = ranged.within_floors(floors).numeric
    assert (r.low, r.high) == (800.0, 1000.0)


def test_the_top_bin_ranks_above_an_unknown_value(tmp_path):
    from recallers import from_sizes

    rows = [("unknown mass", 30, 20, 10, None), ("top bin", 30, 20, 10, 1000), ("lighter one", 30, 20, 10, 700)]
    r = from_sizes(tmp_path / "c.csv", [(n, a, b, c, "" if g is None else g) for n, a, b, c, g in rows])
    assert r.recall_text("about 7 kg").matches[0].name == "unknown mass"  # no floors: 7x off the 1000 g
    r.floors = {"mass_g": 1000.0}
    result = r.recall_text("about 7 kg")
    assert result.matches[0].name == "top bin" and not result.open_set
    assert [m.name for m in result.matches][1:] == ["lighter one", "unknown mass"]
