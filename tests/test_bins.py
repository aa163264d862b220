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
    widened = FeatureQuery.from_values(values).within_classes(recaller.bins)
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
