"""The distance metrics: the paper's Joint Probability over the stated features, and the baselines."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.errors import InvalidFeature, RecallError
from kb.features import CATEGORIES, NUMERIC_FEATURES, ObjectRecord, encode
from recall.distances import distances
from recall.metrics import (
    AT_LEAST_SPAN,
    LN2,
    METRICS,
    MISMATCH_TERM,
    UNKNOWN_NUMERIC_FRACTION,
    FeatureQuery,
    feature_terms,
)
from recall.snapshot import CatalogSnapshot

dims = st.floats(min_value=0.1, max_value=300, allow_nan=False)
masses = st.floats(min_value=0.5, max_value=100_000, allow_nan=False)


@st.composite
def records(draw, name="x"):
    values = {f: draw(st.none() | dims) for f in ("a_cm", "b_cm", "c_cm")}
    values["mass_g"] = draw(st.none() | masses)
    for feat, vals in CATEGORIES.items():
        values[feat] = draw(st.none() | st.sampled_from(vals))
    return ObjectRecord.create(name, plausible=False, **values)  # the metrics' math, not kb/plausibility.py


@st.composite
def queries(draw):
    values = {}
    for feat in NUMERIC_FEATURES:
        if draw(st.booleans()):
            values[feat] = draw(masses if feat == "mass_g" else dims)
    for feat, vals in CATEGORIES.items():
        if draw(st.booleans()):
            values[feat] = draw(st.sampled_from(vals))
    return FeatureQuery.from_values(values)


def _snap(*recs: ObjectRecord) -> CatalogSnapshot:
    return CatalogSnapshot.from_records(list(recs))


def test_jp_is_the_papers_formula_over_stated_features():
    calc = ObjectRecord.create(
        "calculator", a_cm=15.4, b_cm=7.9, c_cm=1.5, mass_g=116, shape="thin", material="plastic"
    )
    q = FeatureQuery.from_values({"a_cm": 15.5, "b_cm": 8, "material": "plastic"})
    d = distances("jp", _snap(calc).matrix, q)[0]
    # the snapshot holds float32 values: 15.4 is 15.39999962, so 0.1 is off by 4e-7
    assert d == pytest.approx(math.log(1 + 0.1) + math.log(1 + 0.1) + 0.0, rel=1e-5)
    assert d != pytest.approx(math.log(1 + 0.1) + math.log(1 + 0.1) + 0.01, rel=1e-5)


def test_categorical_mismatch_costs_two_one_hot_columns_and_unknown_half_of_it():
    a = ObjectRecord.create("a", material="wood")
    b = ObjectRecord.create("b", material="metal")
    c = ObjectRecord.create("c")
    q = FeatureQuery.from_values({"material": "wood"})
    d = distances("jp", _snap(a, b, c).matrix, q)
    assert d.tolist() == pytest.approx([0.0, MISMATCH_TERM, LN2])
    assert MISMATCH_TERM == pytest.approx(2 * math.log(2))


def test_unknown_catalog_number_costs_a_fixed_fraction_of_the_stated_value():
    rec = ObjectRecord.create("no mass", a_cm=10)
    q = FeatureQuery.from_values({"mass_g": 200})
    d = distances("jp", _snap(rec).matrix, q)[0]
    assert d == pytest.approx(math.log1p(UNKNOWN_NUMERIC_FRACTION * 200))


def test_unstated_features_do_not_count():
    a = ObjectRecord.create("a", a_cm=10, mass_g=100, material="wood")
    b = ObjectRecord.create("b", a_cm=10, mass_g=9000, material="glass")
    q = FeatureQuery.from_values({"a_cm": 10})
    for metric in METRICS:
        d = distances(metric, _snap(a, b).matrix, q)
        assert d[0] == pytest.approx(d[1]), metric


def test_qualifiers_make_an_interval():
    recs = [ObjectRecord.create(str(c), a_cm=c) for c in (1.0, 1.5, 2.0, 4.0)]
    m = _snap(*recs).matrix
    at_least = FeatureQuery.from_values({"a_cm": 1.5}, {"a_cm": "at_least"})
    d = distances("jp", m, at_least)
    assert d[1] == 0.0 and d[2] == 0.0  # 1.5 and 2.0 are "more than 1.5 cm" (within [v, 1.5 v])
    assert d[0] == pytest.approx(math.log1p(0.5))
    assert d[3] == pytest.approx(math.log1p(4.0 - 1.5 * AT_LEAST_SPAN))
    at_most = FeatureQuery.from_values({"a_cm": 2.0}, {"a_cm": "at_most"})
    assert distances("jp", m, at_most)[:3].tolist() == [0.0, 0.0, 0.0]
    rng = FeatureQuery.from_values({"a_cm": 2}, {"a_cm": "range"}, {"a_cm": (1.2, 2.0)})
    assert distances("jp", m, rng)[1] == 0.0
    assert distances("jp", m, rng)[3] == pytest.approx(math.log1p(2.0))


def test_baselines_on_known_values():
    a = ObjectRecord.create("a", a_cm=10, b_cm=4)
    b = ObjectRecord.create("b", a_cm=13, b_cm=8)
    q = FeatureQuery.from_values({"a_cm": 10, "b_cm": 4})
    m = _snap(a, b).matrix
    assert distances("euclidean", m, q)[1] == pytest.approx(5.0)
    assert distances("minkowski", m, q)[1] == pytest.approx((3**4 + 4**4) ** 0.25)
    assert distances("kdtree", m, q).tolist() == pytest.approx([0.0, 5.0])
    cos = distances("cosine", m, q)
    assert cos[0] == pytest.approx(0.0, abs=1e-12)
    assert cos[1] == pytest.approx(1 - (10 * 13 + 4 * 8) / (math.hypot(10, 4) * math.hypot(13, 8)))


def test_unknown_metric_and_bad_values_are_refused():
    with pytest.raises(RecallError, match="unknown metric"):
        distances("manhattan", np.zeros((1, 27)), FeatureQuery.from_values({"a_cm": 1}))
    with pytest.raises(InvalidFeature):
        FeatureQuery.from_values({"mass_g": -3})
    with pytest.raises(InvalidFeature):
        FeatureQuery.from_values({"material": "unobtainium"})


@settings(max_examples=60, deadline=None)
@given(st.lists(records(), min_size=1, max_size=8), queries())
def test_jp_properties(recs, q):
    snap = CatalogSnapshot.from_records(recs)
    d = distances("jp", snap.matrix, q)
    assert np.all(d >= 0) and np.all(np.isfinite(d))
    # the one-hot sum equals the per-feature terms (the contributions a match reports)
    terms = feature_terms(snap.num, snap.cat, q)
    total = sum(terms.values()) if terms else np.zeros(len(recs))
    np.testing.assert_allclose(d, total, rtol=1e-12, atol=1e-12)
    for metric in METRICS:
        dm = distances(metric, snap.matrix, q)
        assert dm.shape == (len(recs),) and np.all(np.isfinite(dm))


@settings(max_examples=40, deadline=None)
@given(records())
def test_an_object_is_at_distance_zero_from_its_own_known_features(rec):
    q = FeatureQuery.from_values(rec.known_features())
    snap = CatalogSnapshot.from_records([rec])
    assert distances("jp", snap.matrix, q)[0] == pytest.approx(0.0, abs=1e-12)
    assert distances("euclidean", snap.matrix, q)[0] == pytest.approx(0.0, abs=1e-9)


def test_encoding_matches_kb_features():
    rec = ObjectRecord.create("x", a_cm=3, b_cm=2, c_cm=1, mass_g=5, shape="thin", material="wood")
    vec, mask = encode(rec)
    m = CatalogSnapshot.from_records([rec]).matrix[0]
    np.testing.assert_array_equal(np.isnan(m), ~mask)
    np.testing.assert_array_equal(m[mask], vec[mask])


@settings(max_examples=60, deadline=None)
@given(recs=st.lists(records(), min_size=1, max_size=6), query=queries(), factor=st.floats(0.01, 100))
def test_jplog_is_unchanged_when_every_size_and_mass_is_scaled(recs, query, factor):
    """JP in log units depends on ratios only: scaling catalog and description alike changes nothing
    (the paper's JP in grams does change)."""
    snap = CatalogSnapshot.from_records(recs)
    scaled = CatalogSnapshot(snap.names, snap.aliases, snap.num * factor, snap.cat)
    q2 = FeatureQuery(
        tuple(
            type(c)(c.feature, c.value * factor, c.low * factor, c.high * factor, c.qualifier)
            for c in query.numeric
        ),
        query.categorical,
    )
    a = distances("jplog", snap.matrix, query)
    b = distances("jplog", scaled.matrix, q2)
    # float32 values: a scaled value is rounded again (1.2e-7 of it = 1.3e-6 log units)
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-5)


@settings(max_examples=80, deadline=None)
@given(rec=records(), query=queries(), factor=st.floats(0.01, 100))
def test_relative_errors_are_in_0_1_zero_on_a_match_and_scale_free(rec, query, factor):
    from recall.metrics import relative_errors

    snap = CatalogSnapshot.from_records([rec])
    errors = relative_errors(snap.num[0], snap.cat[0], query)
    assert set(errors) == set(query.stated)
    assert all(0.0 <= e <= 1.0 for e in errors.values())
    scaled = relative_errors(
        snap.num[0] * factor,
        snap.cat[0],
        FeatureQuery(
            tuple(
                type(c)(c.feature, c.value * factor, c.low * factor, c.high * factor, c.qualifier)
                for c in query.numeric
            ),
            query.categorical,
        ),
    )
    for feat, e in errors.items():
        assert scaled[feat] == pytest.approx(e, abs=1e-9)
    # the object's own values are a perfect match
    own = FeatureQuery.from_values({f: getattr(rec, f) for f in query.stated})
    assert all(e == 0.0 for e in relative_errors(snap.num[0], snap.cat[0], own).values())
