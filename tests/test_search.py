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
    """40 000 synthetic objects (log-normal sizes, skewed categories, a few unknown values): above
    SCAN_BELOW, so that the planner chooses among its plans."""
    return synthetic_snapshot(40_000, np.random.default_rng(7), unknown_rate=0.05)


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


@settings(max_examples=90, deadline=None)
@given(query=arbitrary_queries(), k=st.integers(1, 12), plan=st.sampled_from(["scan", "window", "cells", "brute"]))
def test_every_plan_on_its_own_equals_brute_force(query, k, plan):
    """Whatever plan the cost model would pick, each one alone gives the brute force's answer."""
    name, rows, dist = index().plan_and_search(query, k, force=plan)
    brows, bdist = brute_force_top_k(catalog(), query, k)
    assert name == plan or (len(query) == 0 and name == "empty")
    np.testing.assert_array_equal(rows, brows)
    np.testing.assert_array_equal(dist, bdist)


@settings(max_examples=120, deadline=None)
@given(
    feature=st.sampled_from(NUMERIC_FEATURES),
    value=st.one_of(st.sampled_from([1.0, 2.0, 2.5, 12.0, 100.0, 150.0]), st.floats(0.05, 400.0)),
    qualifier=st.sampled_from(["about", "at_least", "at_most"]),
    k=st.sampled_from([1, 2, 5, 40, 300]),
    unknown=st.booleans(),
)
def test_one_number_from_its_sorted_column_equals_brute_force(feature, value, qualifier, k, unknown):
    """One number: the column plan, with ties beyond the rows it reads (thousands of objects share a
    rounded value) and unknown values at the k-th distance, equals the brute force."""
    query = FeatureQuery.from_values({feature: value}, {feature: qualifier})
    if unknown:  # the unknown rows' penalty equal to the distance of common values
        (cond,) = query.numeric
        query = FeatureQuery((type(cond)(cond.feature, cond.value, cond.low, cond.high, cond.qualifier, 1.0),))
    brows, bdist = brute_force_top_k(catalog(), query, k)
    for most in (4096, 8):  # 8: the rows of one value at 0 are more than it reads
        found = index().one_column(catalog().num_cols, catalog().cat_cols, query, k, most=most)
        if found is not None:
            np.testing.assert_array_equal(found[0], brows)
            np.testing.assert_array_equal(found[1], bdist)
    _assert_same(query, k)


@st.composite
def category_queries(draw):
    feats = draw(st.lists(st.sampled_from(sorted(CATEGORIES)), min_size=1, max_size=5, unique=True))
    return FeatureQuery.from_values({f: draw(st.sampled_from(CATEGORIES[f])) for f in feats})


@settings(max_examples=80, deadline=None)
@given(query=category_queries(), k=st.sampled_from([1, 2, 5, 13, 60, 4000]))
def test_category_only_descriptions_are_answered_from_the_combinations(query, k):
    """Categories only: the chosen plan (zero, scan or combinations) and each of scan and combinations
    forced equal the brute force (ties by row), for JP and jplog."""
    brows, bdist = brute_force_top_k(catalog(), query, k)
    for force in (None, "categories", "scan"):
        plan, rows, dist = index().plan_and_search(query, k, force=force)
        assert plan == (force or plan) and plan in ("zero", "scan", "categories")
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)
    lrows, ldist = top_k(catalog(), query, k, metric="jplog")
    np.testing.assert_array_equal(lrows, brows)
    np.testing.assert_array_equal(ldist, bdist)


def test_category_plans_switch_at_their_boundaries():
    """k rows at 0 among the first FIRST_ROWS: the zero plan; else a row pass up to SCAN_ROWS rows, the
    combinations above (each boundary at its exact value)."""
    from recall.combinations import FIRST_ROWS, SCAN_ROWS

    snap = synthetic_snapshot(SCAN_ROWS + 1, np.random.default_rng(3))
    query = FeatureQuery.from_values({"shape": "thin", "material": "glass"})
    rows, dist = brute_force_top_k(snap, query, len(snap))
    zeros = np.sort(rows[dist == 0.0])
    assert 0 < np.searchsorted(zeros, FIRST_ROWS) < len(zeros)
    at = int(np.searchsorted(zeros, FIRST_ROWS))  # rows at 0 among the first FIRST_ROWS
    for n, k, plan in (
        (SCAN_ROWS, at, "zero"),
        (SCAN_ROWS, at + 1, "scan"),
        (SCAN_ROWS + 1, at + 1, "categories"),
    ):
        small = CatalogSnapshot(snap.names[:n], snap.aliases[:n], snap.num[:n], snap.cat[:n])
        got, rows, dist = index_for(small).plan_and_search(query, k)
        brows, bdist = brute_force_top_k(small, query, k)
        assert got == plan
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)


def test_category_levels_of_two_distances_are_scored():
    """Three stated categories: mismatch, mismatch, unknown in different orders are one level (5) but
    two float64 distances; the row pass orders them as the brute force does."""
    rng = np.random.default_rng(5)
    n = 300
    cat = np.zeros((n, 5), dtype=np.int8)
    cat[:, :3] = rng.choice([-1, 1, 2], size=(n, 3), p=[0.3, 0.35, 0.35])
    snap = CatalogSnapshot([f"o{i}" for i in range(n)], [()] * n, np.full((n, 4), 10.0), cat)
    query = FeatureQuery.from_values(
        {"shape": CATEGORIES["shape"][0], "texture": CATEGORIES["texture"][0], "fragility": CATEGORIES["fragility"][0]}
    )
    for k in (1, 7, 40, 150, n):
        for force in ("scan", "categories", None):
            _, rows, dist = index_for(snap).plan_and_search(query, k, force=force)
            brows, bdist = brute_force_top_k(snap, query, k)
            np.testing.assert_array_equal(rows, brows)
            np.testing.assert_array_equal(dist, bdist)


def test_ties_at_zero_are_the_lowest_rows_at_zero():
    """"At most 50 g" puts thousands of rows at 0: the zero plan returns the k lowest of them."""
    for values, quals in (
        ({"mass_g": 50, "a_cm": 30, "b_cm": 20}, {"mass_g": "at_most", "a_cm": "at_most", "b_cm": "at_most"}),
        ({"mass_g": 50, "texture": "grippy", "a_cm": 40}, {"mass_g": "at_most", "a_cm": "at_most"}),
        ({"a_cm": 30, "b_cm": 2, "c_cm": 5}, {"a_cm": "at_most", "b_cm": "at_most", "c_cm": "at_most"}),
    ):
        query = FeatureQuery.from_values(values, quals)
        for k in (1, 5, 40):
            plan, rows, dist = index().plan_and_search(query, k)
            assert plan == "zero" or k > 5  # (40 zeros may not all be in the first pool)
            brows, bdist = brute_force_top_k(catalog(), query, k)
            np.testing.assert_array_equal(rows, brows)
            np.testing.assert_array_equal(dist, bdist)
    with pytest.raises(ValueError, match="distance 0"):
        index().plan_and_search(FeatureQuery.from_values({"a_cm": 12.34567}), 5, force="zero")


def test_small_catalogs_and_little_work_are_scanned():
    from recall.search import SCAN_BELOW, SCAN_WORK

    snap = catalog()
    from recall.metrics import NumericCondition

    # ends not float32 (so not known to be at 0), too many rows in the interval for the column plan
    one = FeatureQuery((NumericCondition("a_cm", 30.1, 0.1, 30.1, "range"),))
    assert index().plan_and_search(FeatureQuery.from_values({"a_cm": 30}, {"a_cm": "at_most"}), 5)[0] == "zero"
    two = FeatureQuery.from_values({"a_cm": 12, "material": "wood"})
    assert 1 * len(snap) <= SCAN_WORK < 2 * len(snap)
    assert index().plan_and_search(one, 5)[0] == "scan"
    assert index().plan_and_search(FeatureQuery.from_values({"a_cm": 12}), 5)[0] == "column"
    assert index().plan_and_search(two, 5)[0] != "scan"
    q = FeatureQuery.from_values({"a_cm": 12, "b_cm": 5, "mass_g": 90, "material": "wood"})
    for n in (SCAN_BELOW, SCAN_BELOW + 1):
        small = CatalogSnapshot(snap.names[:n], snap.aliases[:n], snap.num[:n], snap.cat[:n])
        plan, rows, dist = index_for(small).plan_and_search(q, 5)
        assert (plan == "scan") == (n == SCAN_BELOW)
        brows, bdist = brute_force_top_k(small, q, 5)
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)


def test_one_number_is_read_off_its_column_at_every_size():
    """One number is read off its sorted column: up to LIST_BELOW (= COLUMN_FROM) objects from Python
    lists when at most LISTED_INSIDE rows are in its interval (else brute), above from the arrays."""
    from recall.columns import LIST_BELOW, LISTED_INSIDE
    from recall.search import COLUMN_FROM

    assert LIST_BELOW == COLUMN_FROM
    snap = catalog()
    masses = snap.num_cols[NUMERIC_FEATURES.index("mass_g")][:COLUMN_FROM]
    values, counts = np.unique(masses[~np.isnan(masses)], return_counts=True)
    held = float(values[np.argmax(counts)])  # the most common mass: at least 5 rows, at 0
    assert counts.max() >= 5
    absent = float(np.float32((values[10] + values[11]) / 2))  # no row holds it
    from recall.metrics import NumericCondition

    ordered = np.sort(masses[~np.isnan(masses)])

    def inside(m):  # an interval (ends not float32: not known to be at 0) holding the m heaviest rows
        lo, hi = float(ordered[-m]) * (1 - 1e-12), float(ordered[-1]) * (1 + 1e-12)
        return FeatureQuery((NumericCondition("mass_g", (lo + hi) / 2, lo, hi, "range"),))

    assert ordered[-LISTED_INSIDE - 2] < ordered[-LISTED_INSIDE - 1] < ordered[-LISTED_INSIDE]  # no ties there
    for n in (COLUMN_FROM, COLUMN_FROM + 1):
        small = CatalogSnapshot(snap.names[:n], snap.aliases[:n], snap.num[:n], snap.cat[:n])
        cases = [(FeatureQuery.from_values({"mass_g": v}), "column") for v in (held, absent)]
        cases += [(inside(LISTED_INSIDE), "column"), (inside(LISTED_INSIDE + 1), "brute")]
        for q, plan_up_to in cases:
            plan, rows, dist = index_for(small).plan_and_search(q, 5)
            if n == COLUMN_FROM:
                assert plan == plan_up_to
            else:
                assert plan in ("column", "zero")
            brows, bdist = brute_force_top_k(small, q, 5)
            np.testing.assert_array_equal(rows, brows)
            np.testing.assert_array_equal(dist, bdist)


@settings(max_examples=60, deadline=None)
@given(
    n=st.sampled_from([1024, 1025]),  # LIST_BELOW and one more: bisect on lists, searchsorted on arrays
    feature=st.sampled_from(NUMERIC_FEATURES),
    pick=st.integers(0, 10**6),
    qualifier=st.sampled_from(["about", "at_least", "at_most"]),
    k=st.sampled_from([1, 5, 20]),
)
def test_one_number_below_and_above_list_below_equals_brute_force(n, feature, pick, qualifier, k):
    snap = catalog()
    small = CatalogSnapshot(snap.names[:n], snap.aliases[:n], snap.num[:n], snap.cat[:n])
    col = small.num_cols[NUMERIC_FEATURES.index(feature)]
    known = col[~np.isnan(col)]
    value = float(known[pick % len(known)]) * (1.0 if pick % 3 else 1.37)  # held values and others
    q = FeatureQuery.from_values({feature: value}, {feature: qualifier})
    for force in (None, "brute"):
        plan, rows, dist = index_for(small).plan_and_search(q, k, force=force)
        brows, bdist = brute_force_top_k(small, q, k)
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)


def test_catalogs_up_to_brute_below_are_scored_whole():
    from recall.search import BRUTE_BELOW, COLUMN_FROM

    assert COLUMN_FROM <= BRUTE_BELOW
    snap = catalog()
    q = FeatureQuery.from_values({"a_cm": 12, "mass_g": 90, "material": "wood"})
    for n in (BRUTE_BELOW, BRUTE_BELOW + 1):
        small = CatalogSnapshot(snap.names[:n], snap.aliases[:n], snap.num[:n], snap.cat[:n])
        plan, rows, dist = index_for(small).plan_and_search(q, 5)
        assert plan == ("brute" if n == BRUTE_BELOW else "scan")
        brows, bdist = brute_force_top_k(small, q, 5)
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)


def test_scan_products_are_the_factors_products_within_the_filter_slack():
    """The scan's few-pass products (unknown rows fixed up afterwards, categories in one gather) equal
    the product of recall.ranking.factors (unknown values at their penalty) within FILTER_SLACK."""
    from recall.ranking import FILTER_SLACK, factors

    rng = np.random.default_rng(11)
    for _ in range(40):
        _, q = synthetic_description(catalog(), rng)
        if not len(q):
            continue
        items = [("num", c) for c in q.numeric] + [("cat", c) for c in q.categorical]
        exact = np.ones(len(catalog()))
        for item in items:
            exact *= factors(item, catalog().num_cols, catalog().cat_cols).astype(np.float64)
        got = index().products(q).astype(np.float64)
        np.testing.assert_allclose(got, exact, rtol=FILTER_SLACK / 4)
    q = FeatureQuery.from_values({"a_cm": 12.0, "b_cm": 3.0})
    unknown = np.isnan(catalog().num_cols[0])
    assert unknown.any()
    pen = 1.0 + q.numeric[0].unknown_difference
    assert np.all(index().products(q)[unknown] >= np.float32(pen) * 0.99999)


def test_cost_rules_at_their_boundaries():
    """before_probe / after_probe compare the estimates with <= at each boundary (no timing here)."""
    from recall.costs import CACHE_ROWS, CELLS_TRIAL, SCAN_TRUST, PlanCosts, after_probe, before_probe

    c = PlanCosts(rows=1_000_000, cells=15_625, numbers=3, features=5, categories=True)
    assert c.big and c.scan == 1_000_000 * (1.0 * 3 + 0.6 + 2.25)
    assert c.trusted_scan == c.scan * SCAN_TRUST[1]
    per_row = c.window(1) - c.window(0)
    at = (min(c.probe, c.trusted_scan) - c.window(0)) / per_row  # the window's rows costing the probe
    assert before_probe(c, int(at)) == "window" and before_probe(c, int(at) + 1) is None
    small = PlanCosts(rows=40_000, cells=625, numbers=1, features=2, categories=True)
    assert small.trusted_scan <= small.probe + small.cells_fixed  # no probe can pay on a small catalog
    assert before_probe(small, 10**9) == "scan"
    # after the probe: the cheapest; cells within CELLS_TRIAL of the scan are tried (big catalogs only)
    scan_rows = c.give_up_rows
    assert after_probe(c, 10**9, 0, None) == ("cells", False)
    rows_at_scan = (c.scan - c.cells_fixed) / (c.cell_search(1) - c.cell_search(0))
    assert after_probe(c, 10**9, int(rows_at_scan) + 1, None) == ("cells", True)
    trial_rows = (CELLS_TRIAL * c.scan - c.cells_fixed) / (c.cell_search(1) - c.cell_search(0))
    assert after_probe(c, 10**9, int(trial_rows), None) == ("cells", True)
    assert after_probe(c, 10**9, int(trial_rows) + 1, None) == ("scan", False)
    assert after_probe(c, 10**9, 10**9, 10**9) == ("zero", False)  # a scan at a bound of 0
    assert after_probe(c, 0, 10**9, None) == ("window", False)
    mid = PlanCosts(rows=CACHE_ROWS, cells=4096, numbers=3, features=5, categories=True)
    assert not mid.big and after_probe(mid, 10**9, 10**9, None) == ("scan", False)  # no trial in cache
    # in the cache the others run only below SCAN_TRUST of the scan's estimate
    per_row = mid.cell_search(1) - mid.cell_search(0)
    at = (SCAN_TRUST[0] * mid.scan - mid.cells_fixed) / per_row
    assert mid.cell_search(int(at)) <= SCAN_TRUST[0] * mid.scan < mid.cell_search(int(at) + 1)
    assert after_probe(mid, 10**9, int(at), None) == ("cells", False)
    assert after_probe(mid, 10**9, int(at) + 1, None) == ("scan", False)
    assert scan_rows * (c.cell_search(1) - c.cell_search(0)) == pytest.approx(c.scan)


def test_a_cell_search_that_gives_up_returns_none_and_otherwise_equals_brute_force():
    q = FeatureQuery.from_values({"a_cm": 30, "b_cm": 20, "mass_g": 700, "material": "metal", "shape": "prism"})
    from recall.search import FIRST_POOL, select_top_k

    idx = index()
    items = [("num", c) for c in q.numeric] + [("cat", c) for c in q.categorical]
    pool = np.unique(np.concatenate([idx._nearest(it, FIRST_POOL) for it in items]))
    rows, scores = select_top_k(pool, idx.score(q, pool), 5)
    brows, bdist = brute_force_top_k(catalog(), q, 5)
    assert idx.cells.top_k(q, 5, rows, scores, give_up=0) is None
    got = idx.cells.top_k(q, 5, rows, scores, give_up=10**9)
    np.testing.assert_array_equal(got[0], brows)
    np.testing.assert_array_equal(got[1], bdist)


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


@pytest.fixture(scope="module")
def sql_catalog(tmp_path_factory):
    """The small catalog in a DuckDB file with the macros installed, and its Recaller."""
    from kb.catalog import KnowledgeBase
    from recall.engine import Recaller
    from recall.sql import install_macros

    tmp = tmp_path_factory.mktemp("sql")
    (tmp / "catalog.csv").write_text(CATALOG_CSV)
    kb = KnowledgeBase.open(tmp / "catalog.duckdb")
    kb.import_csv(tmp / "catalog.csv")
    with kb.connect(write=True) as con:
        install_macros(con)
    return kb, Recaller.from_db(tmp / "catalog.duckdb")


@pytest.mark.parametrize("metric", ["jp", "jplog", "euclidean", "minkowski", "cosine", "kdtree"])
@pytest.mark.parametrize(
    "values",
    [
        {"a_cm": 15.5, "b_cm": 8, "c_cm": 1.5, "material": "plastic"},
        {"a_cm": 7, "b_cm": 7, "c_cm": 7, "mass_g": 60, "shape": "radial"},
        {"mass_g": 100, "texture": "rough", "fragility": "medium", "rigidity": "rigid"},
        {"material": "wood"},
        {"shape": "radial", "texture": "rough", "rigidity": "squeezable"},
        {"a_cm": 9.0},
    ],
)
def test_numpy_and_sql_macros_agree(sql_catalog, values, metric):
    kb, recaller = sql_catalog
    args = ", ".join(f"{SQL_PARAMS[f]} := {v!r}" for f, v in values.items())
    columns = "a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity"
    sql_rows = kb.sql(
        f"SELECT name, {metric}_distance({columns}, {args}) AS distance FROM objects ORDER BY distance, name"
    ).rows
    if metric in ("jp", "jplog"):
        assert kb.sql(f"SELECT name, distance FROM {metric}_rank({args})").rows == sql_rows
    result = recaller.recall_features(values, top=len(sql_rows), metric=metric, features_only=True)
    if metric == "kdtree":  # the tree orders tied rows its own way: the same distance of every object
        by_name = dict(sql_rows)
        assert sorted(m.name for m in result.matches) == sorted(by_name)
        for match in result.matches:
            assert match.distance == pytest.approx(by_name[match.name], rel=1e-6, abs=1e-6)
        return
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
    from recall.distances import distances

    logged = catalog().log_scaled
    rows, dist = top_k(catalog(), query, k, metric="jplog")
    brows, bdist = brute_force_top_k(logged, query.log_scaled(), k)
    np.testing.assert_array_equal(rows, brows)
    np.testing.assert_array_equal(dist, bdist)
    # and the one-hot matrix route gives the same distances
    full = distances("jplog", catalog().matrix, query)
    # (the one-hot route takes logarithms of the float32 values in float64; the engine keeps float32 logs)
    np.testing.assert_allclose(full[rows], dist, rtol=1e-5, atol=1e-5)


def test_init_installs_every_metrics_macro_and_sql_recalls_like_the_engine(tmp_path):
    """``objrecall init`` (kb.service.bootstrap.init_db) installs the macros: a recall in plain SQL on
    the seed catalog names the engine's first match, for the hybrid's default metric and the paper's."""
    from kb.service.bootstrap import init_db
    from recall.engine import Recaller
    from recall.sql import MACRO_NAMES

    kb = init_db(tmp_path / "catalog.duckdb", seed=True)
    installed = {r[0] for r in kb.sql("SELECT function_name FROM duckdb_functions() WHERE macro_definition IS NOT NULL").rows}
    assert set(MACRO_NAMES) <= installed
    values = {"a_cm": 6.5, "b_cm": 6.5, "c_cm": 6.5, "material": "fabric"}
    recaller = Recaller.from_db(tmp_path / "catalog.duckdb")
    for metric in ("jplog", "jp"):
        (name,) = kb.sql(f"SELECT name FROM {metric}_rank(qa := 6.5, qb := 6.5, qc := 6.5, qmaterial := 'fabric') LIMIT 1").rows[0]
        assert name == recaller.recall_features(values, metric=metric, features_only=True).best.name


@settings(max_examples=200, deadline=None)
@given(query=arbitrary_queries())
def test_a_query_in_log_units_equals_its_conditions_in_log_units(query):
    """FeatureQuery.log_scaled (one NumPy pass) gives NumericCondition.log_scaled's values exactly."""
    one_by_one = FeatureQuery(tuple(c.log_scaled() for c in query.numeric), query.categorical)
    assert query.log_scaled() == one_by_one
    for a, b in zip(query.log_scaled().numeric, one_by_one.numeric, strict=True):
        assert (a.value, a.low, a.high, a.unknown) == (b.value, b.low, b.high, b.unknown)


@settings(max_examples=100, deadline=None)
@given(
    scores=st.lists(
        st.sampled_from([0.0, 0.5, 0.5 + 2**-52, 1.0, 1.0, 2.0, math.log1p(3.0)]), min_size=1, max_size=60
    ),
    k=st.integers(1, 12),
    given_rows=st.booleans(),
)
def test_select_top_k_orders_by_distance_then_row(scores, k, given_rows):
    """Against a full sort by (distance, row): with rows given (shuffled) or None (0..n-1, the stable
    sort's path), many ties included."""
    scores = np.asarray(scores)
    rows = np.random.default_rng(len(scores)).permutation(len(scores)) + 100 if given_rows else None
    from recall.ranking import select_top_k

    got_rows, got = select_top_k(rows, scores, k)
    all_rows = np.arange(len(scores)) if rows is None else rows
    order = np.lexsort((all_rows, scores))[:k]
    np.testing.assert_array_equal(got_rows, all_rows[order])
    np.testing.assert_array_equal(got, scores[order])
    assert got_rows.dtype == np.int64


def test_one_number_whose_unknown_rows_cost_nothing_ranks_them_at_zero_too():
    """A condition charging unknown values 0 puts them at distance 0 beside the rows holding the value:
    the k lowest rows of both win (the column plan used to return the rows in the interval only)."""
    from recall.metrics import NumericCondition

    for n in (1000, 40_000):  # the lists' plan and the arrays'
        full = catalog()
        snap = full if n == len(full) else CatalogSnapshot(full.names[:n], full.aliases[:n], full.num[:n], full.cat[:n])
        col = snap.num_cols[NUMERIC_FEATURES.index("mass_g")]
        values, counts = np.unique(col[~np.isnan(col)], return_counts=True)
        v = float(values[np.argmax(counts)])
        q = FeatureQuery((NumericCondition("mass_g", v, v, v, "about", 0.0),))
        plan, rows, dist = index_for(snap).plan_and_search(q, 5)
        brows, bdist = brute_force_top_k(snap, q, 5)
        assert np.isnan(col[brows]).any()  # the case: unknown rows among the answer
        np.testing.assert_array_equal(rows, brows)
        np.testing.assert_array_equal(dist, bdist)
