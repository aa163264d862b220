"""The fusion rule (scrapers/fusion.py): product values only, one vote per source, median, majority."""

from __future__ import annotations

from datetime import datetime, timedelta

import pytest
from hypothesis import given
from hypothesis import strategies as st

from scrapers.fusion import Observation, fuse, is_curated, is_provisional

T0 = datetime(2026, 11, 1)


def obs(feature, value, source, *, role="product", days=0, id=0):
    return Observation(feature, value, source, role=role, fetched_at=T0 + timedelta(days=days), id=id)


def test_median_of_the_latest_value_per_source():
    fused = fuse(
        [
            obs("mass_g", 300.0, "https://a/x"),
            obs("mass_g", 320.0, "https://a/x", days=1),  # supersedes a's 300
            obs("mass_g", 310.0, "https://b/y"),
            obs("mass_g", 900.0, "https://c/z"),  # one wrong source cannot move a median of three
        ]
    )
    assert fused.values["mass_g"] == 320.0
    assert fused.support["mass_g"] == 3
    assert any("disagree on mass_g" in w for w in fused.warnings)


def test_two_web_sources_meet_in_the_middle_and_agreeing_sources_do_not_warn():
    fused = fuse([obs("a_cm", 10.0, "https://b/y"), obs("a_cm", 10.5, "https://a/x")])
    assert fused.values["a_cm"] == 10.25 and not fused.warnings


def test_a_curated_value_stands_against_any_number_of_stores():
    stores = [obs("a_cm", 12.0, f"https://s{i}/p") for i in range(5)]
    fused = fuse([obs("a_cm", 10.0, "csv:seed.csv"), *stores])
    assert fused.values["a_cm"] == 10.0 and fused.support["a_cm"] == 1
    assert any("kept the curated" in w and "a_cm" in w for w in fused.warnings)


def test_stores_fill_what_no_curated_source_states():
    fused = fuse([obs("a_cm", 10.0, "csv:seed.csv"), obs("mass_g", 250.0, "https://s/p")])
    assert fused.values == {"a_cm": 10.0, "mass_g": 250.0}
    assert not fused.warnings


@pytest.mark.parametrize(("web", "warned"), [(11.0, False), (11.0001, True), (9.091, False), (9.09, True)])
def test_a_store_disagreeing_with_a_curated_value_is_warned_past_the_ratio(web, warned):
    fused = fuse([obs("mass_g", 10.0, "csv:seed.csv"), obs("mass_g", web, "https://s/p")])
    assert fused.values["mass_g"] == 10.0
    assert any("kept the curated" in w for w in fused.warnings) is warned


def test_two_curated_sources_still_take_their_median_and_words_their_majority():
    fused = fuse([obs("a_cm", 10.0, "csv:a.csv"), obs("a_cm", 12.0, "csv:b.csv"), obs("a_cm", 50.0, "https://s")])
    assert fused.values["a_cm"] == 11.0
    words = [obs("material", "wood", "csv:a"), obs("material", "metal", "https://s"),
             obs("material", "metal", "https://t")]  # fmt: skip
    fused = fuse(words)
    assert fused.values["material"] == "wood"
    assert any("stores state material metal" in w for w in fused.warnings)
    same = fuse([obs("material", "wood", "csv:a"), obs("material", "wood", "https://s")])
    assert not same.warnings


def test_package_values_never_become_catalog_values():
    fused = fuse([obs("a_cm", 30.0, "https://a/x", role="package"), obs("mass_g", 5.0, "https://a/x")])
    assert "a_cm" not in fused.values and fused.values["mass_g"] == 5.0


def test_words_by_majority_ties_to_the_newest():
    three = [
        obs("material", "metal", "https://a"),
        obs("material", "metal", "https://b"),
        obs("material", "wood", "https://c", days=5),
    ]
    assert fuse(three).values["material"] == "metal"
    web_tie = [obs("shape", "compact", "https://a", days=3), obs("shape", "prism", "https://b", days=1)]
    assert fuse(web_tie).values["shape"] == "compact"
    assert any("disagree on shape" in w for w in fuse(web_tie).warnings)


def test_curated_sources():
    assert is_curated("csv:seed_catalog.csv") and is_curated("typical value (estimate)")
    assert not is_curated("https://shop.example/p/1") and not is_curated("http://127.0.0.1:8765/p")


def test_ties_in_time_are_broken_by_id():
    same_time = [obs("mass_g", 1.0, "https://a", id=1), obs("mass_g", 2.0, "https://a", id=2)]
    assert fuse(same_time).values["mass_g"] == 2.0


values = st.floats(min_value=0.1, max_value=400, allow_nan=False)


@given(st.lists(st.tuples(values, values, values), min_size=1, max_size=8))
def test_fused_dims_stay_sorted_and_within_the_sources(triples):
    observations = []
    for i, triple in enumerate(triples):
        a, b, c = sorted(triple, reverse=True)
        observations += [
            obs("a_cm", a, f"https://s{i}"),
            obs("b_cm", b, f"https://s{i}"),
            obs("c_cm", c, f"https://s{i}"),
        ]
    fused = fuse(observations).values
    assert fused["a_cm"] >= fused["b_cm"] >= fused["c_cm"]
    for k, feat in enumerate(("a_cm", "b_cm", "c_cm")):
        column = [sorted(t, reverse=True)[k] for t in triples]
        assert min(column) <= fused[feat] <= max(column)


@given(st.lists(values, min_size=1, max_size=9), st.randoms(use_true_random=False))
def test_fusion_ignores_the_order_observations_arrive_in(masses, rnd):
    observations = [obs("mass_g", m, f"https://s{i}") for i, m in enumerate(masses)]
    shuffled = observations[:]
    rnd.shuffle(shuffled)
    assert fuse(shuffled).values == fuse(observations).values


@given(st.lists(values, min_size=1, max_size=6), values)
def test_a_source_repeating_itself_does_not_outvote_others(others, repeated):
    base = [obs("mass_g", m, f"https://s{i}") for i, m in enumerate(others)]
    once = fuse([*base, obs("mass_g", repeated, "https://loud")]).values["mass_g"]
    many = fuse([*base, *(obs("mass_g", repeated, "https://loud", id=k) for k in range(10))]).values["mass_g"]
    assert once == pytest.approx(many)


# -- rule 5: a lookup's values are provisional -------------------------------------------------------
def lookup_obs(feature, value, source, **kw):
    return Observation(feature, value, source, fetched_at=T0 + timedelta(days=9), adapter="lookup:jsonld", **kw)


def test_a_lookup_page_never_moves_a_curated_or_crawled_value():
    curated = obs("mass_g", 900.0, "csv:seed_catalog.csv")
    crawled = Observation("mass_g", 880.0, "https://a/x", fetched_at=T0, adapter="jsonld")
    wrong = lookup_obs("mass_g", 9000.0, "https://b/y")
    assert fuse([curated, wrong]).values["mass_g"] == 900.0
    assert fuse([crawled, wrong]).values["mass_g"] == 880.0
    assert fuse([curated, crawled, wrong]).values["mass_g"] == 900.0  # rule 3: the curated value stands
    assert fuse([curated, wrong]).support["mass_g"] == 1


def test_lookup_words_never_outvote_a_settled_word_even_as_a_majority():
    votes = [lookup_obs("material", "metal", f"https://s{i}") for i in range(3)]
    assert fuse([*votes, obs("material", "glass", "csv:s")]).values["material"] == "glass"


def test_lookup_values_count_where_nothing_else_is_known():
    only = [lookup_obs("mass_g", 800.0, "https://a"), lookup_obs("mass_g", 1000.0, "https://b")]
    assert fuse(only).values["mass_g"] == 900.0
    # a feature the settled sources do not state is still filled from the lookup
    mixed = fuse([obs("a_cm", 22.0, "csv:s"), lookup_obs("mass_g", 800.0, "https://a")])
    assert mixed.values == {"a_cm": 22.0, "mass_g": 800.0}


def test_only_the_lookup_prefix_makes_a_value_provisional():
    assert is_provisional(lookup_obs("mass_g", 1.0, "https://a"))
    for adapter in (None, "jsonld", "catalog", "lookup", "jsonld:lookup"):
        assert not is_provisional(Observation("mass_g", 1.0, "https://a", adapter=adapter))
