"""Recall that knows what it does not know (issue 16): nouns not in the catalog, vague words as soft
evidence, the score columns, and the calibration measures."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from recallers import seed

from recall.calibration import brier_score, calibration, expected_calibration_error
from recall.engine import NOT_IN_CATALOG_CONFIDENCE
from recall.vague import VAGUE_WEIGHT, soft_evidence


# ---------------------------------------------------------------------------------- not in the catalog
def test_the_papers_orange_is_not_in_the_catalog_with_the_closest_ball_and_fruit():
    res = seed().recall_text("An orange of 7 cm diameter.")
    assert res.not_in_catalog and res.open_set
    assert res.described is not None and (res.described.noun, res.described.kind) == ("orange", "fruit")
    assert res.confidence <= NOT_IN_CATALOG_CONFIDENCE
    # the physically closest objects are round things of about 7 cm
    assert all(m.features["shape"] == "radial" and 5.5 <= m.features["a_cm"] <= 8.5 for m in res.matches[:3])
    # and among the fruit an apple (plastic fruit is a toy)
    assert res.same_kind_as == "fruit" and res.same_kind[0].name == "apple"
    out = res.to_dict()
    assert out["not_in_catalog"] and out["described"]["noun"] == "orange" and out["same_kind"][0]["name"] == "apple"


def test_a_teapot_is_not_in_the_catalog_and_the_jug_kind_gives_the_pitcher():
    res = seed().recall_text("a ceramic teapot about 22 cm wide, 900 g")
    assert res.not_in_catalog and res.described.kind == "jug"
    assert [m.name for m in res.same_kind] == ["pitcher"]
    assert res.confidence <= NOT_IN_CATALOG_CONFIDENCE


def test_a_catalog_noun_a_synonym_and_a_compound_on_catalog_words_are_in_the_catalog():
    for text in ("a tennis ball", "a steel bottle, 20 cm", "a spanner, 20 cm long, 150 g", "a plastic bottle cap"):
        res = seed().recall_text(text)
        assert not res.not_in_catalog, text
    res = seed().recall_text("a tennis ball")
    assert res.confidence > 0.8


def test_a_compound_with_a_word_the_catalog_lacks_is_not_in_it():
    res = seed().recall_text("A bowling ball, 8.5 inches in diameter, weighs about 14 pounds.")
    assert res.not_in_catalog and res.described.noun == "bowling ball" and res.same_kind_as == "ball"


def test_the_noun_after_of_when_the_subject_is_a_measure_of_something():
    res = seed().recall_text("A bar of soap, 9 x 6 x 2.5 cm, 110 g")
    assert res.not_in_catalog and res.described.noun == "soap"
    assert not seed().recall_text("a bunch of keys, 10 cm, 70 g").not_in_catalog


def test_a_noun_not_in_the_catalog_with_no_feature_returns_nothing_but_says_so():
    res = seed().recall_text("a moka pot")
    assert res.matches == [] and res.not_in_catalog and res.confidence == 0.0


def test_features_only_is_the_papers_method_and_knows_no_nouns():
    res = seed().recall_text("An orange of 7 cm diameter.", features_only=True)
    assert not res.not_in_catalog and res.described is None


def test_a_name_in_the_text_beats_a_foreign_subject():
    # the text names a catalog object exactly: the subject noun does not make it foreign
    res = seed().recall_text("an orange tennis ball, 6.5 cm")
    assert res.best.name == "tennis ball" and not res.not_in_catalog


# ------------------------------------------------------------------------------------------ vague words
def test_something_small_and_round_is_no_basketball():
    res = seed().recall_text("something small and round", top=10)
    names = [m.name for m in res.matches]
    assert "basketball" not in names and "soccer ball" not in names
    assert all(m.vague_part == 0.0 for m in res.matches[:5])
    assert res.vague and res.vague[0].startswith("small -> a_cm <=")
    assert res.confidence < 0.2  # dozens of small round things: a vague description is no answer


def test_big_and_heavy_ball_prefers_big_heavy_balls():
    res = seed().recall_text("a big heavy ball")
    assert {m.name for m in res.matches[:2]} == {"soccer ball", "basketball"}


def test_heavy_steel_tool_about_a_foot_is_the_hammer_not_the_ruler():
    res = seed().recall_text("heavy steel tool, about a foot long")
    assert res.best.name == "hammer"


def test_vague_size_word_is_ignored_when_a_dimension_is_stated():
    res = seed().recall_text("a small ball, 22 cm across")
    assert res.vague == [] and res.best.name in {"soccer ball", "basketball"}


def _num(a, m):
    """Numeric columns (a, b, c, mass) with b = c = a."""
    a, m = np.asarray(a, dtype=float), np.asarray(m, dtype=float)
    return [a, a, a, m]


def test_soft_range_boundaries():
    # small: at most the 33rd percentile of a_cm; 0 up to the limit, then W * ln(x / limit) / ln 2,
    # the whole weight from twice the limit on, half for an unknown value
    a = np.concatenate([np.linspace(1.0, 40.0, 400), [np.nan]])
    num = _num(a, np.ones(len(a)))
    ev = soft_evidence("something small", {}, None, num)
    (feature, limit, side), = ev.limits
    assert (feature, side) == ("a_cm", -1) and limit == pytest.approx(np.quantile(a[:-1], 0.33))
    x = a[:-1]
    want = VAGUE_WEIGHT * np.minimum(1.0, np.maximum(0.0, np.log(x / limit)) / math.log(2))
    assert np.allclose(ev.penalty[:-1], want)
    assert np.all(ev.penalty[:-1][x <= limit] == 0.0) and np.all(ev.penalty[:-1][x > limit] > 0.0)
    assert np.all(ev.penalty[:-1][x >= 2 * limit] == pytest.approx(VAGUE_WEIGHT))
    assert ev.penalty[-1] == pytest.approx(VAGUE_WEIGHT / 2)
    # big: the other side of the 67th percentile
    big = soft_evidence("a big one", {}, None, num)
    (_, hi, side), = big.limits
    assert side == +1 and np.all(big.penalty[:-1][x >= hi] == 0.0) and np.all(big.penalty[:-1][x < hi] > 0.0)
    assert VAGUE_WEIGHT < 2 * math.log(2)  # less than one category mismatch


def test_soft_words_and_their_conditions():
    num = _num(np.arange(1.0, 11.0), np.arange(10.0, 110.0, 10.0))
    assert soft_evidence("a big box", {}, None, num).words[0].startswith("big -> a_cm >=")
    assert soft_evidence("it weighs almost nothing", {}, None, num).words[0].startswith(
        "weighs almost nothing -> mass_g in the lightest"
    )
    assert soft_evidence("heavy", {}, "heavy", num).penalty[0] > 0  # the parser's hint
    assert soft_evidence("heavy", {"mass_g": 50.0}, "heavy", num) is None  # a stated mass wins
    assert soft_evidence("a little over 5 cm", {}, None, num) is None  # not a size word
    assert soft_evidence("a red box", {}, None, num) is None


# ------------------------------------------------------------------------------------ the score columns
@pytest.mark.parametrize(
    "text", ["a plastic ball about 7 cm", "a light hollow ball, two and a half inches", "a small metal tool, 15 cm"]
)
def test_scores_are_sorted_and_made_of_their_shown_parts(text):
    res = seed().recall_text(text, top=5)
    scores = [m.score for m in res.matches]
    assert scores == sorted(scores)
    for m in res.matches:
        assert m.score == pytest.approx(m.distance - m.name_part + m.vague_part)
        assert m.distance == pytest.approx(sum(m.contributions.values()))


def test_confidence_does_not_depend_on_how_many_matches_are_shown():
    a = seed().recall_text("a plastic ball about 7 cm", top=1)
    b = seed().recall_text("a plastic ball about 7 cm", top=8)
    assert a.confidence == pytest.approx(b.confidence)


# ---------------------------------------------------------------------------------------- calibration
def test_calibration_of_known_points():
    cal = calibration([1.0, 1.0, 0.0, 0.0], [True, True, False, False])
    assert cal.brier == 0.0 and cal.ece == 0.0 and cal.bins[-1].n == 2  # 1.0 falls in the last bin
    assert brier_score([0.5] * 4, [True, False, True, False]) == pytest.approx(0.25)
    assert expected_calibration_error([0.9] * 10, [True] * 9 + [False]) == pytest.approx(0.0)
    assert expected_calibration_error([0.9] * 10, [True] * 5 + [False] * 5) == pytest.approx(0.4)
    assert any("|" in line for line in cal.plot())
    with pytest.raises(ValueError):
        calibration([0.5], [True, False])
    with pytest.raises(ValueError):
        calibration([1.5], [True])


@given(st.lists(st.tuples(st.floats(0, 1), st.booleans()), min_size=1, max_size=50), st.integers(1, 20))
def test_calibration_properties(points, bins):
    conf = [c for c, _ in points]
    right = [r for _, r in points]
    cal = calibration(conf, right, bins)
    assert 0.0 <= cal.brier <= 1.0 and 0.0 <= cal.ece <= 1.0 + 1e-12
    assert sum(b.n for b in cal.bins) == len(points)
    # predicting the outcome exactly is perfect
    exact = calibration([float(r) for r in right], right, bins)
    assert exact.brier == 0.0 and exact.ece == pytest.approx(0.0)


# ------------------------------------------------------------------------------- shape from geometry
def test_three_extents_decide_a_proportion_class_over_a_shape_word():
    from recall.metrics import FeatureQuery

    r = seed()
    box = FeatureQuery.from_values({"a_cm": 15.5, "b_cm": 9.0, "c_cm": 1.8, "shape": "prism"})
    assert r._shape_from_geometry(box).values()["shape"] == "thin"
    # a round word stays: proportions cannot tell a ball from a cube
    ball = FeatureQuery.from_values({"a_cm": 15.5, "b_cm": 9.0, "c_cm": 1.8, "shape": "radial"})
    assert r._shape_from_geometry(ball).values()["shape"] == "radial"
    # two extents are not enough, and no shape word means nothing to replace
    two = FeatureQuery.from_values({"a_cm": 15.5, "b_cm": 9.0, "shape": "prism"})
    assert r._shape_from_geometry(two) == two
    none = FeatureQuery.from_values({"a_cm": 15.5, "b_cm": 9.0, "c_cm": 1.8})
    assert r._shape_from_geometry(none) == none


def test_geometry_votes_need_a_clear_majority():
    from recall.geometry import MIN_VOTES, K, ShapeGeometry, overrides

    codes = {"thin": 0, "compact": 1, "prism": 2, "long": 3, "radial": 4}
    flat = [[20.0, 10.0, 1.0]] * K
    cubes = [[5.0, 5.0, 5.0]] * (K // 2 + 1) + [[5.1, 5.0, 5.0]] * (K // 2 + 1)
    num = np.array(flat + cubes)
    shapes = np.array([codes["thin"]] * K + [codes["compact"]] * (K // 2 + 1) + [codes["radial"]] * (K // 2 + 1))
    geo = ShapeGeometry(num, shapes)
    assert geo.classify(21.0, 10.0, 1.1) == "thin"
    assert geo.classify(5.0, 5.0, 5.0) is None  # split vote
    assert geo.classify(1.0, 2.0, 3.0) is None  # not sorted
    assert MIN_VOTES <= K
    assert overrides("thin", "prism") and overrides("prism", "long") and not overrides("thin", "radial")
    assert not overrides("radial", "compact") and not overrides("compact", "prism")


# ----------------------------------------------------------- what the catalog is silent on (issue 23)
def test_a_category_the_catalog_does_not_hold_is_left_out_of_the_closeness():
    from recall.fit import closeness_of

    errors = {"mass_g": 0.1, "material": 0.5, "shape": 1.0}
    assert closeness_of(errors) == pytest.approx(1.6 / 3)
    assert closeness_of(errors, ("material",)) == pytest.approx(1.1 / 2)  # the record has no material
    assert closeness_of({"material": 0.5}, ("material",)) is None  # nothing left to compare
    assert closeness_of({}) is None


def test_a_right_match_on_a_catalog_without_categories_fits_whatever_categories_are_stated():
    # a catalog of sizes and masses only (like the YCB tables): "blue metal, rectangular" says nothing
    # against its objects; each stated category counted half a mismatch (0.33 > 0.30: not a close match)
    from kb.features import ObjectRecord
    from recall.engine import Recaller

    r = Recaller.from_records(
        [ObjectRecord.create("potted meat can", a_cm=10.7, b_cm=9.9, c_cm=6.2, mass_g=370),
         ObjectRecord.create("tuna fish can", a_cm=8.6, b_cm=8.6, c_cm=4.2, mass_g=171)]
    )  # fmt: skip
    res = r.recall_text("blue metal, rectangular, 370 grams")
    assert res.best.name == "potted meat can" and res.closeness == pytest.approx(0.0) and not res.open_set
    assert r.recall_text("blue metal, rectangular, 1500 grams").open_set  # the mass still decides
    known = Recaller.from_records([ObjectRecord.create("box", a_cm=10, mass_g=370, material="plastic")])
    assert known.recall_text("metal, 370 grams").closeness == pytest.approx(0.5)  # a held value still counts


def test_an_unseen_noun_names_an_object_only_when_a_determiner_introduces_it():
    from recall.subject import introduced

    assert introduced("A flyswatter, steel, 33 cm long", "flyswatter")
    assert introduced("the holder for the toilet brush, 15 cm", "holder")
    assert introduced("I found this toy apple, 7 cm", "apple")
    assert not introduced("spring-loaded jaws, 11 cm, 60 g", "jaw")
    assert not introduced("kitchen flipper, nylon, a spatula", "flipper")  # only the first clause counts
    assert not introduced("small, beeps, 100 g", "beep")
    r = seed()
    bare = r.recall_text("spring-loaded jaws, 11 cm, 60 g")
    assert not bare.not_in_catalog and bare.unknown_noun == "jaw"  # doubted by the features, no verdict
    assert r.recall_text("A flyswatter, steel, 33 cm long, 600 g.").not_in_catalog
    # the price: a bare unseen noun is only doubted, so a close match of another object fits (the hammer)
    price = r.recall_text("Flyswatter with a steel mesh, 33 cm long, 600 g.")
    assert price.unknown_noun == "flyswatter" and not price.not_in_catalog and price.best.name == "hammer"


def test_a_later_phrase_names_the_object_only_when_a_determiner_introduces_it():
    from recall.subject import introduced, noun_phrase

    assert noun_phrase("Steel, 15 cm long, a nutcracker") == ("nutcracker",)
    assert noun_phrase("plastic, handset on a base, 700 g") == ("plastic",)  # a part of the thing described
    assert introduced("steel, 15 cm long, a nutcracker", "nutcracker")  # the clause that has it decides
    assert not introduced("tiny, two screw caps, 8 g", "cap")


def test_a_count_of_a_plural_noun_lists_parts_and_names_no_object():
    from recall.subject import counted_parts

    assert counted_parts("tiny, two screw caps, 8 g", ("two", "screw", "cap"))
    assert counted_parts("five fingers, 19 cm long", ("five", "finger"))
    assert not counted_parts("one screw cap, 8 g", ("one", "screw", "cap"))  # one: the thing itself
    assert not counted_parts("two screw cap, 8 g", ("two", "screw", "cap"))  # not said in the plural
    assert not counted_parts("screw caps, 8 g", ("screw", "cap"))  # no count
    assert not seed().recall_text("tiny, two screw caps, 8 g").not_in_catalog


def test_a_bare_word_read_as_a_misspelt_foreign_noun_is_no_verdict():
    # "five fingers" is one edit from the lexicon's "ginger": in a bare list of features no verdict
    r = seed()
    assert not r.recall_text("five fingers, 19 cm long").not_in_catalog
    slip = r.recall_text("screwdiver, 20 cm long, 90 g")  # bare too, but misspelt for a catalog word
    assert slip.described is not None and slip.described.noun == "screwdriver" and not slip.not_in_catalog


def test_a_material_word_an_article_counts_is_a_thing_the_catalog_lacks():
    from recall.openset import counted_material

    vocabulary = frozenset({"glass", "bottle", "wine"})
    assert counted_material("a walnut, in the shell, 3.5 cm, 12 grams", vocabulary) == "walnut"
    assert counted_material("walnut, 3.5 cm, 12 grams", vocabulary) is None  # a material: not counted
    assert counted_material("a walnut box, 12 cm", vocabulary) is None  # the head is "box"
    assert counted_material("a glass, 12 cm", vocabulary) is None  # the catalog's glasses
    assert counted_material("a marble, 1.6 cm", vocabulary) is None  # a lexicon noun: its own rule
    res = seed().recall_text("A walnut, in the shell, 3.5 cm, 12 grams.")
    assert res.not_in_catalog and res.described.noun == "walnut"


def test_a_synonyms_english_name_is_in_the_catalog_by_its_head_before_of():
    # "bunch" is the lexicon's synonym of "bunch of keys" (the seed catalog's): its head is "bunch", so a
    # catalog with keys but no bunch ("chuck key") does not have "a bunch of grapes"
    from kb.features import ObjectRecord
    from recall.engine import Recaller
    from recall.words import head_noun

    assert head_noun(("bunch", "of", "key")) == "bunch" and head_noun(("mustard", "bottle")) == "bottle"
    assert head_noun(("of",)) == "of" and head_noun(()) is None
    keys = Recaller.from_records([ObjectRecord.create("chuck key", a_cm=8, mass_g=60),
                                  ObjectRecord.create("sugar box", a_cm=18, b_cm=10, c_cm=5, mass_g=514)])
    assert keys.recall_text("a bunch of grapes, about 20 cm long, a pound").not_in_catalog
    assert not seed().recall_text("a bunch of keys, 10 cm, 70 g").not_in_catalog
