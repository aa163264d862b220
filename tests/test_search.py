"""Exact top-k search: the pruned Joint Probability index equals brute force; NumPy and SQL agree."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.features import CATEGORIES, NUMERIC_FEATURES
from recall.metrics import FeatureQuery
from recall.search import JPIndex, brute_force_top_k, index_for, top_k
from recall.snapshot import CatalogSnapshot, synthetic_description, synthetic_snapshot


@functools.cache
def catalog() -> CatalogSnapshot:
    """20 000 synthetic objects (log-normal sizes, skewed categories, a few unknown values)."""
    return synthetic_snapshot(20_000, np.random.default_rng(7), unknown_rate=0.05)


@functools.cache
def index() -> JPIndex:
    return index_for(catalog())


def _assert_same(query: FeatureQuery, k: int) -> None:
    rows, dist = index().top_k(query, k)
    brows, bdist = brute_force_top_k(catalog(), query, k)
    np.testing.assert_array_equal(rows, brows)
    np.testing.assert_array_equal(dist, bdist)  # bit for bit: the same float64 code scores both


@settings(max_examples=80, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), k=st.sampled_from([1, 3, 5, 20]))
def test_pruned_top_k_equals_brute_force_on_human_like_descriptions(seed, k):
    _, query = synthetic_description(catalog(), np.random.default_rng(seed))
    _assert_same(query, k)


@st.composite
def arbitrary_queries(draw):
    values, qualifiers = {}, {}
    for feat in NUMERIC_FEATURES:
        if draw(st.booleans()):
            hi = 100_000.0 if feat == "mass_g" else 300.0
            values[feat] = draw(st.floats(min_value=0.05, max_value=hi))
            qualifiers[feat] = draw(st.sampled_from(["about", "exact", "at_least", "at_most"]))
    for feat, vals in CATEGORIES.items():
        if draw(st.booleans()):
            values[feat] = draw(st.sampled_from(vals))
    return FeatureQuery.from_values(values, qualifiers)


@settings(max_examples=80, deadline=None)
@given(query=arbitrary_queries(), k=st.integers(1, 12))
def test_pruned_top_k_equals_brute_force_on_arbitrary_queries(query, k):
    _assert_same(query, k)


def test_ties_are_broken_by_row_like_brute_force():
    # category-only descriptions: thousands of rows at distance 0
    for values in ({"shape": "radial"}, {"material": "other", "rigidity": "floppy"}, {"texture": "grippy"}):
        _assert_same(FeatureQuery.from_values(values), 5)
    _assert_same(FeatureQuery.from_values({"mass_g": 50}, {"mass_g": "at_most"}), 7)


def test_edge_cases():
    snap = catalog()
    rows, dist = index().top_k(FeatureQuery(), 3)  # nothing stated: every object at 0, first rows
    assert rows.tolist() == [0, 1, 2] and dist.tolist() == [0.0, 0.0, 0.0]
    assert len(index().top_k(FeatureQuery.from_values({"a_cm": 3}), 0)[0]) == 0
    small = CatalogSnapshot(snap.names[:10], snap.aliases[:10], snap.num[:10], snap.cat[:10])
    q = FeatureQuery.from_values({"a_cm": 12, "material": "wood"})
    rows, _ = index_for(small).top_k(q, 50)
    assert sorted(rows.tolist()) == list(range(10))
    assert top_k(small, q, 4)[0].tolist() == brute_force_top_k(small, q, 4)[0].tolist()


def test_other_metrics_rank_every_row():
    q = FeatureQuery.from_values({"a_cm": 12, "b_cm": 6, "shape": "prism"})
    snap = CatalogSnapshot(
        catalog().names[:500], catalog().aliases[:500], catalog().num[:500], catalog().cat[:500]
    )
    for metric in ("euclidean", "minkowski", "cosine", "kdtree"):
        rows, dist = top_k(snap, q, 5, metric=metric)
        assert len(rows) == 5 and np.all(np.diff(dist) >= 0)


# --------------------------------------------------------------------------------------- SQL agreement
CATALOG_CSV = """name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity,aliases
calculator,15.4,7.9,1.5,116,thin,medium,medium,plastic,rigid,scientific calculator
water bottle,21.5,7.2,7.2,660,prism,smooth,sturdy,metal,rigid,
wood cylinder,8,2.9,2.9,21,prism,rough,sturdy,wood,rigid,
cardboard box,15.5,9,1.8,,thin,rough,medium,paper,rigid,
tennis ball,6.4,6.4,6.4,56,radial,rough,medium,fabric,squeezable,
mystery thing,10,5,,80,,,,,,
plastic cap,3.4,3.4,1.3,5,compact,grippy,medium,plastic,rigid,bottle cap
"""

SQL_PARAMS = {
    "a_cm": "qa", "b_cm": "qb", "c_cm": "qc", "mass_g": "qmass", "shape": "qshape", "texture": "qtexture",
    "fragility": "qfragility", "material": "qmaterial", "rigidity": "qrigidity",
}  # fmt: skip


@pytest.mark.parametrize(
    "values",
    [
        {"a_cm": 15.5, "b_cm": 8, "c_cm": 1.5, "material": "plastic"},
        {"a_cm": 7, "b_cm": 7, "c_cm": 7, "mass_g": 60, "shape": "radial"},
        {"mass_g": 100, "texture": "rough", "fragility": "medium", "rigidity": "rigid"},
        {"material": "wood"},
        {"a_cm": 9.0},
    ],
)
def test_numpy_and_sql_macros_agree(tmp_path, values):
    from kb.catalog import KnowledgeBase
    from recall.engine import Recaller
    from recall.sql import install_macros

    csv_path = tmp_path / "catalog.csv"
    csv_path.write_text(CATALOG_CSV)
    db = tmp_path / "catalog.duckdb"
    kb = KnowledgeBase.open(db)
    kb.import_csv(csv_path)
    with kb.connect(write=True) as con:
        install_macros(con)
    args = ", ".join(f"{SQL_PARAMS[f]} := {v!r}" for f, v in values.items())
    sql_rows = kb.sql(f"SELECT name, distance FROM jp_rank({args})").rows
    recaller = Recaller.from_db(db)
    result = recaller.recall_features(values, top=len(sql_rows), features_only=True)
    assert [m.name for m in result.matches] == [r[0] for r in sql_rows]
    for match, (_, distance) in zip(result.matches, sql_rows, strict=True):
        # the engine holds float32 values (6e-8 relative), SQL the stored doubles
        assert match.distance == pytest.approx(distance, rel=1e-6, abs=1e-6)
    # the scalar macro on one row, with a NULL (unknown) catalog value
    with kb.connect() as con:
        (d,) = con.execute(
            "SELECT jp_distance(10, 5, NULL, 80, NULL, NULL, NULL, NULL, NULL, qc := 2.0)"
        ).fetchone()
    assert d == pytest.approx(math.log1p(0.5 * 2.0))


@settings(max_examples=80, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), k=st.sampled_from([1, 5, 10]))
def test_best_first_cells_alone_equal_brute_force(seed, k):
    """The cell search from scratch (no first bound), on its own, is exact too."""
    _, query = synthetic_description(catalog(), np.random.default_rng(seed))
    rows, dist = index().cells.top_k(query, k, np.empty(0, dtype=np.int64), np.empty(0))
    brows, bdist = brute_force_top_k(catalog(), query, k)
    np.testing.assert_array_equal(rows, brows)
    np.testing.assert_array_equal(dist, bdist)


@settings(max_examples=40, deadline=None)
@given(query=arbitrary_queries(), k=st.integers(1, 8))
def test_jplog_top_k_equals_brute_force(query, k):
    """JP in log units searches the log-scaled snapshot with the same pruned index: still exact."""
    from recall.metrics import distances

    logged = catalog().log_scaled
    rows, dist = top_k(catalog(), query, k, metric="jplog")
    brows, bdist = brute_force_top_k(logged, query.log_scaled(), k)
    np.testing.assert_array_equal(rows, brows)
    np.testing.assert_array_equal(dist, bdist)
    # and the one-hot matrix route gives the same distances
    full = distances("jplog", catalog().matrix, query)
    # (the one-hot route takes logarithms of the float32 values in float64; the engine keeps float32 logs)
    np.testing.assert_allclose(full[rows], dist, rtol=1e-5, atol=1e-5)
