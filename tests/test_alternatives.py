"""Category words that allow more than one class (recall/alternatives.py): ambiguous shape words and
mixed materials are soft evidence in the hybrid, the paper's JP keeps the stated class."""

from __future__ import annotations

import numpy as np
import pytest

from kb.catalog import ObjectRecord
from recall.alternatives import (
    FINISH_WORDS,
    SHAPE_ALTERNATIVES,
    alternatives,
    finish_word,
    mixed_materials,
    with_alternatives,
)
from recall.engine import Recaller
from recall.lexicon import MATERIAL_WORDS, SHAPE_WORDS
from recall.metrics import LN2, MISMATCH_TERM, FeatureQuery
from recall.parser import parse

# Three objects of the same size and mass, filed under different shapes and materials.
_OBJECTS = [
    ObjectRecord(name="steel padlock", a_cm=6.0, b_cm=5.0, c_cm=2.5, mass_g=300.0, shape="compact", material="metal"),
    ObjectRecord(name="steel bar", a_cm=6.0, b_cm=5.0, c_cm=2.5, mass_g=300.0, shape="prism", material="metal"),
    ObjectRecord(name="rubber ball", a_cm=6.0, b_cm=5.0, c_cm=2.5, mass_g=300.0, shape="radial", material="rubber"),
    ObjectRecord(name="glass thing", a_cm=6.0, b_cm=5.0, c_cm=2.5, mass_g=300.0, shape="compact", material="glass"),
    ObjectRecord(name="mystery lump", a_cm=6.0, b_cm=5.0, c_cm=2.5, mass_g=300.0, material="plastic"),
]  # fmt: skip


def _recaller() -> Recaller:
    return Recaller.from_records(_OBJECTS)


def _by_name(res) -> dict[str, object]:
    return {m.name: m for m in res.matches}


def test_every_alternative_is_another_class_of_a_lexicon_shape_word():
    for word, others in SHAPE_ALTERNATIVES.items():
        assert word in SHAPE_WORDS and SHAPE_WORDS[word][0] not in others


def test_an_ambiguous_shape_word_costs_half_a_mismatch_for_its_second_class():
    res = _recaller().recall_text("a metal block, 6 cm long, 300 g", top=5)
    m = _by_name(res)
    assert "shape" not in res.query["values"]  # scored as soft evidence, not by the metric
    assert m["steel bar"].vague_part == 0.0  # "block" is the lexicon's prism
    assert m["steel padlock"].vague_part == pytest.approx(LN2)  # its second class: half
    assert m["rubber ball"].vague_part == pytest.approx(MISMATCH_TERM)  # any other class: whole
    assert m["mystery lump"].vague_part == pytest.approx(LN2)  # unknown shape: half, as the metric's rule
    assert any(w.startswith("block -> shape prism (or compact") for w in res.vague)


def test_an_unambiguous_shape_word_and_the_papers_jp_keep_the_whole_mismatch():
    r = _recaller()
    res = r.recall_text("a metal ball, 6 cm long, 300 g", top=5)
    assert res.query["values"]["shape"] == "radial" and res.vague == []
    assert _by_name(res)["steel padlock"].contributions["shape"] == pytest.approx(MISMATCH_TERM)
    paper = r.recall_text("a metal block, 6 cm long, 300 g", top=5, features_only=True)
    assert paper.query["values"]["shape"] == "prism" and paper.vague == []
    assert _by_name(paper)["steel padlock"].contributions["shape"] == pytest.approx(MISMATCH_TERM)


def test_three_stated_extents_leave_the_shape_to_the_geometry():
    parsed = parse("a metal block 6 by 5 by 2.5 cm")
    assert alternatives(FeatureQuery.from_parsed(parsed), parsed) is None
    parsed = parse("a metal block 6 by 5 cm")
    alt = alternatives(FeatureQuery.from_parsed(parsed), parsed)
    assert alt is not None and alt.allowed["shape"] == (frozenset({"prism"}), frozenset({"compact"}))


def test_a_shape_word_whose_class_was_replaced_allows_nothing_more():
    parsed = parse("a metal block 6 by 5 cm")
    query = FeatureQuery.from_parsed(parsed)
    replaced = FeatureQuery(
        query.numeric, tuple((f, "thin" if f == "shape" else v) for f, v in query.categorical)
    )
    alt = alternatives(replaced, parsed)
    assert alt is None or "shape" not in alt.allowed


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Metal and plastic, 3 inches across", {"metal", "plastic"}),
        ("plastic & steel", {"metal", "plastic"}),
        ("glass or ceramic", {"glass", "other"}),
        ("wood/metal handle", {"wood", "metal"}),
        ("steel and aluminium", None),  # one class
        ("a plastic bottle and a metal cap", None),  # not joined
        ("plastic", None),
    ],
)
def test_mixed_materials(text, expected):
    got = mixed_materials(text)
    assert (set(got) if got else None) == expected


def test_either_stated_material_is_a_match_and_neither_is_a_whole_mismatch():
    res = _recaller().recall_text("Plastic and metal, 6 cm long, 300 g", top=5)
    m = _by_name(res)
    assert "material" not in res.query["values"]
    assert m["steel bar"].vague_part == pytest.approx(m["mystery lump"].vague_part)  # both allowed
    assert m["glass thing"].vague_part == pytest.approx(MISMATCH_TERM)
    assert m["rubber ball"].vague_part == pytest.approx(MISMATCH_TERM)
    features_only = _recaller().recall_text("Plastic and metal, 6 cm long, 300 g", top=5, features_only=True)
    assert "material" in features_only.query["values"]  # the paper's method reads one material


def test_soft_categories_count_in_the_closeness_as_the_metric_would():
    r = _recaller()
    parsed = parse("a rubber block, 6 cm long, 300 g")
    query = FeatureQuery.from_parsed(parsed)
    _, soft = with_alternatives(query, None, alternatives(query, parsed), r.snapshot.cat_cols)
    names = list(r.snapshot.names)
    assert soft.errors_of(names.index("steel bar")) == {"shape": 0.0}
    assert soft.errors_of(names.index("steel padlock")) == {"shape": pytest.approx(0.5)}
    assert soft.errors_of(names.index("rubber ball")) == {"shape": 1.0}
    # without a prism, the padlock is best, half a class off: its closeness says so
    no_prism = Recaller.from_records([o for o in _OBJECTS if o.shape != "prism"])
    res = no_prism.recall_text("a metal block, 6 cm long, 300 g", top=5)
    assert res.best.name == "steel padlock" and res.closeness == pytest.approx(np.mean([0, 0, 0, 0.5]))


def test_wire_and_foil_are_metal():
    assert parse("wire loops, 11 inches long").values()["material"] == "metal"
    assert parse("a foil tray").values()["material"] == "metal"


@pytest.mark.parametrize("word", ["porous", "prickly", "spiky", "scaly", "thorny"])
def test_surface_words_that_are_rough(word):
    assert parse(f"soft and {word}, 4 by 3 by 1.5 inches").values()["texture"] == "rough"


# ------------------------------------------------------------------ light words, relative to the size
def test_light_words_compare_a_row_with_the_objects_of_its_size():
    from recall.vague import MIN_OF_SIZE, SIZE_FACTOR, VERY_LIGHT_Q, soft_evidence

    # 20 small objects (2 cm, 1-20 g) and 20 large ones (40 cm, 100-2000 g)
    a = np.array([2.0] * 20 + [40.0] * 20)
    m = np.concatenate([np.arange(1.0, 21.0), np.arange(100.0, 2100.0, 100.0)])
    ev = soft_evidence("it is very light", {}, None, [a, a, a, m])
    small_limit, large_limit = np.quantile(m[:20], VERY_LIGHT_Q), np.quantile(m[20:], VERY_LIGHT_Q)
    assert np.all(ev.penalty[:20][m[:20] <= small_limit] == 0.0) and np.all(
        ev.penalty[:20][m[:20] > small_limit] > 0
    )
    # a 300 g object is very light for 40 cm, though heavier than every small one
    assert np.all(ev.penalty[20:][m[20:] <= large_limit] == 0.0) and ev.penalty[22] == 0.0
    assert np.all(ev.penalty[20:][m[20:] > large_limit] > 0)
    assert SIZE_FACTOR < 40 / 2 and MIN_OF_SIZE <= 20


def test_light_words_use_the_whole_catalog_when_few_objects_have_the_size():
    from recall.vague import MIN_OF_SIZE, VERY_LIGHT_Q, soft_evidence

    n = MIN_OF_SIZE - 1  # too few of either size
    a = np.array([2.0] * n + [40.0] * n + [np.nan])
    m = np.concatenate([np.arange(1.0, n + 1.0), np.arange(100.0, 100.0 * (n + 1), 100.0), [50.0]])
    ev = soft_evidence("weighs almost nothing", {}, None, [a, a, a, m])
    limit = np.quantile(m, VERY_LIGHT_Q)
    assert np.all((ev.penalty == 0.0) == (m <= limit))  # the unknown size too


def test_heavy_words_stay_on_the_whole_catalog():
    from recall.vague import soft_evidence

    a = np.array([2.0] * 20 + [40.0] * 20)
    m = np.concatenate([np.arange(1.0, 21.0), np.arange(100.0, 2100.0, 100.0)])
    ev = soft_evidence("a very heavy thing", {}, None, [a, a, a, m])
    assert np.all(ev.penalty[:20] > 0)  # no small object is heavy for the catalog


# ------------------------------------------------------------ pruned search equals the full scan
def _random_catalog(n: int, seed: int) -> Recaller:
    from kb.features import CATEGORIES

    rng = np.random.default_rng(seed)
    recs = []
    for i in range(n):
        dims = sorted(np.exp(rng.normal(2.0, 0.8, 3)).round(1) + 0.1, reverse=True)
        recs.append(
            ObjectRecord(
                name=f"zq{i}",
                a_cm=float(dims[0]), b_cm=float(dims[1]), c_cm=float(dims[2]),
                mass_g=float(np.exp(rng.normal(4.5, 1.2)).round(1)) if rng.random() > 0.03 else None,
                shape=str(rng.choice(CATEGORIES["shape"])) if rng.random() > 0.05 else None,
                material=str(rng.choice(CATEGORIES["material"])) if rng.random() > 0.05 else None,
            )
        )  # fmt: skip
    return Recaller.from_records(recs)


@pytest.mark.parametrize(
    "text",
    [
        "a metal block, 6 cm long, 300 g",
        "a round plastic thing about 4 inches across",
        "plastic and metal, 15 cm long, 8 cm wide, 200 g, a flat one",
        "a wooden cylinder 20 cm long",
        "glass or ceramic, 12 cm tall, 9 oz",
    ],
)
def test_alternatives_search_the_union_of_the_variants_and_equal_a_full_scan(text):
    r = _random_catalog(6000, 7)
    res = r.recall_text(text, top=10)
    parsed = parse(text)
    query = FeatureQuery.from_parsed(parsed)
    stripped, soft = with_alternatives(query, None, alternatives(query, parsed), r.snapshot.cat_cols)
    assert soft is not None and not soft.scan and len(soft.variants) >= 2
    rows = np.arange(len(r.snapshot), dtype=np.int64)
    score = r.shortlist.distances_of(stripped, rows, "jplog") + soft.penalty
    best = np.argsort(score, kind="stable")[:10]
    assert [m.score for m in res.matches] == pytest.approx(score[best].tolist())
    assert {m.name for m in res.matches} <= {
        r.snapshot.names[i] for i in np.flatnonzero(score <= score[best[-1]])
    }


def test_curved_is_a_vague_long_shape_that_a_geometric_word_beats():
    assert parse("curved and soft, about 7.5 inches long").values()["shape"] == "long"
    assert parse("a curved cylindrical thing").values()["shape"] == "prism"  # priority 3 wins


@pytest.mark.parametrize(
    ("text", "word"),
    [
        ("a copper lamp shade, 45 cm across", "copper"),
        ("a chrome desk lamp", "chrome"),
        ("a silver laptop, 1.3 kg", "silver"),
        ("Solid brass padlock, 6 cm tall", "brass"),
        ("a chrome steel bowl", None),  # steel names the material
        ("a copper and steel pan", None),  # a mixed material, either a match
        ("a metallic copper kettle", None),  # stated by "metallic"
        ("a steel padlock", None),
    ],
)
def test_a_finish_word_is_the_material_only_when_every_material_word_is_one(text, word):
    assert finish_word(parse(text)) == word
    assert FINISH_WORDS <= set(MATERIAL_WORDS)


def test_a_finish_word_makes_its_metal_a_match_and_another_material_half_a_mismatch():
    res = _recaller().recall_text("a copper thing, 6 cm long, 300 g", top=5)
    m = _by_name(res)
    assert "material" not in res.query["values"]
    assert m["steel bar"].vague_part == pytest.approx(0.0)
    assert m["glass thing"].vague_part == pytest.approx(LN2)  # half a mismatch, not 2 ln 2
    assert m["mystery lump"].vague_part == pytest.approx(LN2)
    parsed = parse("a copper thing, 6 cm long, 300 g")
    query = FeatureQuery.from_parsed(parsed)
    r = _recaller()
    _, soft = with_alternatives(query, None, alternatives(query, parsed), r.snapshot.cat_cols)
    names = list(r.snapshot.names)
    assert soft.errors_of(names.index("steel padlock")) == {"material": 0.0}
    assert soft.errors_of(names.index("glass thing")) == {"material": pytest.approx(0.5)}
    # a plain metal word stays in the JP query: another material pays the whole mismatch there
    assert _recaller().recall_text("a steel thing, 6 cm long, 300 g").query["values"]["material"] == "metal"
