import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import InvalidFeature
from kb.features import (
    CATEGORIES,
    VECTOR_COLUMNS,
    ObjectRecord,
    encode,
    normalize_category,
    validate_features,
)


def test_dimensions_are_sorted_largest_first():
    rec = ObjectRecord.create("Box", a_cm=2, b_cm=10, c_cm="5")
    assert rec.dims_cm == (10.0, 5.0, 2.0)
    assert rec.name == "box"


@pytest.mark.parametrize(
    ("features", "field", "reason"),
    [
        ({"a_cm": -1}, "a_cm", "greater than zero"),
        ({"b_cm": 0}, "b_cm", "greater than zero"),
        ({"a_cm": 600}, "a_cm", "absurd"),
        ({"mass_g": 600_000}, "mass_g", "absurd"),
        ({"mass_g": "heavy"}, "mass_g", "not a number"),
        ({"c_cm": float("inf")}, "c_cm", "finite"),
        ({"shape": "blob"}, "shape", "unknown shape"),
        ({"material": "unobtainium"}, "material", "unknown material"),
    ],
)
def test_invalid_values_name_field_and_reason(features, field, reason):
    with pytest.raises(InvalidFeature) as info:
        ObjectRecord.create("thing", **features)
    assert info.value.field == field
    assert reason in info.value.reason


@pytest.mark.parametrize("name", [None, "", "   "])
def test_missing_name_is_refused(name):
    with pytest.raises(InvalidFeature, match="missing name"):
        ObjectRecord.create(name, a_cm=1)


def test_unknown_feature_is_refused():
    with pytest.raises(InvalidFeature, match="not a known feature"):
        ObjectRecord.create("x", colour="red")


def test_category_aliases_map_to_canonical_words():
    assert normalize_category("rigidity", "Soft") == "squeezable"  # the paper's stiffness column
    assert normalize_category("material", "metallic") == "metal"
    assert normalize_category("shape", " ") is None


def test_encode_one_hot_and_mask():
    vec, mask = encode({"a_cm": 10.0, "shape": "long"})
    cols = dict(zip(VECTOR_COLUMNS, range(len(VECTOR_COLUMNS)), strict=True))
    assert vec[cols["a_cm"]] == 10.0 and mask[cols["a_cm"]]
    assert not mask[cols["mass_g"]] and math.isnan(vec[cols["mass_g"]])
    block = [cols[f"shape={s}"] for s in CATEGORIES["shape"]]
    assert vec[block].sum() == 1.0 and vec[cols["shape=long"]] == 1.0 and mask[block].all()
    assert not mask[[cols[f"material={m}"] for m in CATEGORIES["material"]]].any()


dims = st.floats(min_value=0.01, max_value=500, allow_nan=False)


@given(dims, dims, dims, st.one_of(st.none(), st.floats(min_value=0.1, max_value=500_000)))
def test_validated_dims_always_sorted(a, b, c, m):
    out = validate_features({"a_cm": a, "b_cm": b, "c_cm": c, "mass_g": m})
    assert out["a_cm"] >= out["b_cm"] >= out["c_cm"] > 0
    assert sorted([a, b, c], reverse=True) == [out["a_cm"], out["b_cm"], out["c_cm"]]


@given(st.dictionaries(st.sampled_from(list(CATEGORIES)), st.text(max_size=12)))
def test_category_validation_accepts_or_names_the_field(values):
    try:
        out = validate_features(values)
    except InvalidFeature as err:
        assert err.field in CATEGORIES
    else:
        for feat, val in out.items():
            assert val is None or val in CATEGORIES.get(feat, ()) or feat in ("a_cm", "b_cm", "c_cm", "mass_g")
    vec, mask = encode({})
    assert not mask.any() and np.isnan(vec).all()
