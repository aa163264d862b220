"""Category words that allow more than one class (recall/alternatives.py): ambiguous shape words and
mixed materials are soft evidence in the hybrid, the paper's JP keeps the stated class."""

from __future__ import annotations

import numpy as np
import pytest

from kb.catalog import ObjectRecord
from recall.alternatives import SHAPE_ALTERNATIVES, alternatives, mixed_materials, with_alternatives
from recall.engine import Recaller
from recall.lexicon import SHAPE_WORDS
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
