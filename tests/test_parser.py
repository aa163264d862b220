"""The description parser (recall/parser.py): Table III end to end, dimension patterns, units, hedges,
categories, odd input, and the development-set scores."""

from __future__ import annotations

import json
import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from kb.errors import DescriptionError
from kb.features import CATEGORIES, FEATURES
from recall import lexicon
from recall.parser import (
    MAX_TEXT_CHARS,
    QUALIFIERS,
    FeatureEvidence,
    ParsedDescription,
    default_parser,
    parse,
)
from recall.toolkit import Tree

approx = pytest.approx

# ---------------------------------------------------------------------- the paper's Table III, end to end
TABLE_III = [
    (
        "A scientific calculator with plastic body. It is about fifteen and half centimeters long, 8 "
        "centimeters wide and appears to be more than one and half centimeters thick.",
        {"a_cm": 15.5, "b_cm": 8.0, "c_cm": 1.5, "material": "plastic"},
        {"a_cm": "about", "b_cm": "exact", "c_cm": "at_least"},
        None,
    ),
    (
        "A metallic water bottle of about seven and quarter centimeters in diameter and twenty one and half "
        "centimeters long. It is filled with about half a liter of water and is heavy.",
        {"a_cm": 21.5, "b_cm": 7.25, "c_cm": 7.25, "mass_g": 500.0, "material": "metal", "shape": "prism"},
        {"a_cm": "exact", "b_cm": "about", "mass_g": "at_least"},
        "heavy",
    ),
    (
        "A cylindrical wood block of about eight centimeters long and about three centimeters in diameter. "
        "It is light weight. It has a rough surface.",
        {"a_cm": 8.0, "b_cm": 3.0, "c_cm": 3.0, "material": "wood", "shape": "prism", "texture": "rough"},
        {"a_cm": "about", "b_cm": "about"},
        "light",
    ),
    (
        "An empty cardboard box about fifteen centimeters in length, nine centimeters wide and about two "
        "centimeters thick. It is very light weight. It weighs about sixty grams.",
        {"a_cm": 15.0, "b_cm": 9.0, "c_cm": 2.0, "mass_g": 60.0, "material": "paper"},
        {"a_cm": "about", "b_cm": "exact", "c_cm": "about", "mass_g": "about"},
        "light",
    ),
    (
        "A mini rubix cube of about three centimeters wide. It is made of plastic and has smooth texture.",
        {
            "a_cm": 3.0,
            "b_cm": 3.0,
            "c_cm": 3.0,
            "material": "plastic",
            "shape": "compact",
            "texture": "smooth",
        },
        {"a_cm": "about"},
        None,
    ),
]


@pytest.mark.parametrize(("text", "values", "qualifiers", "hint"), TABLE_III)
def test_table_iii(text: str, values: dict, qualifiers: dict, hint: str | None) -> None:
    parsed = parse(text)
    got = parsed.values()
    for feature, value in values.items():
        assert got[feature] == (approx(value) if isinstance(value, float) else value), feature
    for feature, qualifier in qualifiers.items():
        assert parsed.features[feature].qualifier == qualifier, feature
    assert parsed.mass_hint == hint


def test_evidence_points_at_the_words() -> None:
    text = TABLE_III[1][0]
    parsed = parse(text)
    ev = parsed.features["b_cm"]
    assert isinstance(ev, FeatureEvidence)
    assert ev.words == "about seven and quarter centimeters in diameter"
    assert text[ev.start : ev.end] == ev.words
    mass = parsed.features["mass_g"]
    assert mass.low == approx(500.0) and mass.high is None
    assert "half a liter" in mass.words


def test_chunk_tree_has_the_papers_chunks() -> None:
    tree = parse(TABLE_III[0][0]).tree
    assert isinstance(tree, Tree) and tree.label() == "S"
    labels = {t.label() for t in tree.subtrees()}
    assert {"NUM", "UNIT", "HEDGE", "QUANT", "DIM"} <= labels
    dims = [" ".join(w for w, _t in t.leaves()) for t in tree.subtrees(lambda t: t.label() == "DIM")]
    assert dims == [
        "about fifteen and half centimeters long",
        "8 centimeters wide",
        "more than one and half centimeters thick",
    ]


# ---------------------------------------------------------------------------------------- dimensions
DIMENSION_CASES = [
    ("10 x 5 x 2 cm", (10, 5, 2)),
    ("2 x 10 x 5 cm", (10, 5, 2)),
    ("10cm x 5cm x 2cm", (10, 5, 2)),
    ("10×5×2 cm", (10, 5, 2)),
    ("three by four centimeters", (4, 3, None)),
    ("6 by 3.5 inches, under an inch thick", (15.24, 8.89, 2.54)),
    ("about 3 cm on each side", (3, 3, 3)),
    ("a cube of 4 cm", (4, 4, 4)),
    ("a cube about three centimeters wide", (3, 3, 3)),
    ("a ball 6.5 cm in diameter", (6.5, 6.5, 6.5)),
    ("a ball with a radius of 3 cm", (6, 6, 6)),
    # a circumference is pi diameters (values rounded to 4 places as the parser gives them): "around" after a length states it, before a number it hedges
    ("a ball about 30 cm around, 400 g", (9.5493,) * 3),
    ("a ball around 30 cm, 400 g", (30, 30, 30)),
    ("a jar 9 inches around and 5 inches tall", (12.7, 7.2766, 7.2766)),
    ("a tube with a circumference of 12 cm, 20 cm long", (20, 3.8197, 3.8197)),
    ("a ball 7 inches in circumference", (5.6595,) * 3),
    ("a box 10 cm around 50 g", (10, None, None)),  # "around 50 g": a hedge on the mass
    ("a can 12 cm tall and 6.6 cm in diameter", (12, 6.6, 6.6)),
    ("a wooden disc 7 cm across and 2 cm thick", (7, 7, 2)),
    ("a round dish about 27 cm across and 2.5 cm tall", (27, 27, 2.5)),
    ("a mug 9.5 cm tall and 8 cm wide", (9.5, 8, 8)),
    ("a cylinder 3 cm in diameter", (None, 3, 3)),
    ("a coin 2.3 cm in diameter", (2.3, 2.3, None)),
    ("15 cm long, 8 cm wide and 1.5 cm thick", (15, 8, 1.5)),
    ("1.5 cm thick, 15 cm long, 8 cm wide", (15, 8, 1.5)),
    ("length 15 cm, width 8 cm", (15, 8, None)),
    ("its length is about 20 cm", (20, None, None)),
    ("30 cm long and 1 mm thick", (30, None, 0.1)),
    ("9 cm wide and 2 cm thick", (None, 9, 2)),
    ("fifteen centimeters long, eight wide and two thick", (15, 8, 2)),  # unit carried over
    ("about 18 inches long, 6 inches deep and an inch thick", (45.72, 15.24, 2.54)),
    ("a 30 cm ruler", (30, None, None)),
    ("a 5-cm-long stick", (5, None, None)),
    ("about a foot long", (30.48, None, None)),
    ('a 4" wide card', (None, 10.16, None)),
    ("3 ft tall", (91.44, None, None)),
    ("4 in long", (10.16, None, None)),
    ("a round lid an inch and a half across", (3.81, 3.81, None)),
    ("an inch and a half across", (None, 3.81, None)),
    ("12 3/4 by 9 inches", (32.385, 22.86, None)),
    ("7½ cm long", (7.5, None, None)),
    ("7,5 cm long", (7.5, None, None)),
    ("150 mm long", (15, None, None)),
    ("0.3 m long", (30, None, None)),
    ("5 ft 3 in tall", (160.02, None, None)),
    ("approx. 25cm long x 3cm wide", (25, 3, None)),
    ("3 in. long", (7.62, None, None)),
    ("diameter 7cm height 12cm", (12, 7, 7)),
    ("7 cm diameter, 12 cm height", (12, 7, 7)),
    ("a length of 19 cm, a width of 3 cm and a height of 2 cm", (19, 3, 2)),
    ("It is 20 cm tall and 5 cm thick", (20, None, 5)),
    ("a car tire, about 65 cm across and 20 cm wide", (65, 65, 20)),
    # across and a smaller height / thickness / depth, no round cue: a squat thing's diameter
    ("Small plastic thing, 3 cm across and 1.5 cm tall", (3, 3, 1.5)),
    ("a metal tin 3.3 inches across and 1.3 inches tall", (8.382, 8.382, 3.302)),
    ("a thing 10 cm across, 3 cm deep", (10, 10, 3)),
    ("a thing 3 cm across and 3 cm tall", (3, 3, None)),  # not smaller: one width, sorted as before
    ("a thing 5 cm across and 8 cm tall", (8, 5, None)),  # taller than across: a width
    ("a thing 10 cm long, 4 cm across and 2 cm thick", (10, 4, 2)),  # a length: across is a width
]


@pytest.mark.parametrize(("text", "dims"), DIMENSION_CASES)
def test_dimension_patterns(text: str, dims: tuple) -> None:
    got = parse(text).values()
    for name, expected in zip(("a_cm", "b_cm", "c_cm"), dims, strict=True):
        if expected is None:
            assert name not in got, (name, got)
        else:
            assert got.get(name) == approx(expected), (name, got)


def test_dimensions_are_sorted() -> None:
    got = parse("It is 2 cm long, 10 cm wide and 5 cm thick").values()
    assert got["a_cm"] >= got["b_cm"] >= got["c_cm"]


# -------------------------------------------------------------------------------------- mass and units
MASS_CASES = [
    ("it weighs 60 g", 60),
    ("about 1.5 kg", 1500),
    ("weighs 10 oz", 283.495),
    ("2 lbs", 907.185),
    ("half a pound", 226.796),
    ("a pound and a half", 680.389),
    ("an ounce and a half", 42.524),
    ("a quarter of a kilogram", 250),
    ("a third of a kilo", 333.333),
    ("under half an ounce", 14.175),
    ("a couple of kilos", 2000),
    ("weighs a dozen grams", 12),
    ("1,200 grams", 1200),
    ("it weighs one hundred and fifty grams", 150),
    ("It weighs 1 lb 2 oz", 510.291),
    ("one pound two ounces", 510.291),
    ("2 kg, and 30 cm long", 2000),
    ("21 x 16 x 4 cm 200 g", 200),
]


@pytest.mark.parametrize(("text", "grams"), MASS_CASES)
def test_mass(text: str, grams: float) -> None:
    assert parse(text).values()["mass_g"] == approx(grams, rel=1e-4)


def test_contents_give_a_lower_bound_on_mass() -> None:
    ev = parse("A steel bottle filled with 750 ml of water.").features["mass_g"]
    assert (ev.value, ev.qualifier, ev.low) == (approx(750), "at_least", approx(750))
    assert "mass_g" not in parse("A bottle with 750 ml capacity.").features
    assert "mass_g" not in parse("A 1 liter bottle, empty.").features
    assert parse("a 2 L bottle, full of water").features["mass_g"].qualifier == "at_least"
    # a stated mass wins over contents
    assert parse("A jug full of water, 2 liters, weighs 2.3 kg").values()["mass_g"] == approx(2300)


def test_unit_table_is_built_with_pint_once() -> None:
    from kb.measures.units import description_units

    table = description_units()
    assert table is description_units()
    assert table["inches"].factor == approx(2.54)
    assert table["lb"].factor == approx(453.59237)
    assert table["kg"].kind == "mass" and table["ml"].kind == "volume" and table["'"].kind == "length"
    # every unit word of the lexicon is in the table
    for words in (lexicon.LENGTH_UNITS, lexicon.MASS_UNITS, lexicon.VOLUME_UNITS):
        assert set(words) <= set(table)


def test_quarter_is_a_number_not_pints_unit() -> None:
    assert parse("seven and a quarter inches long").values()["a_cm"] == approx(7.25 * 2.54)
    assert "mass_g" not in parse("the top quarter is red").features


# -------------------------------------------------------------------------------------- hedges, ranges
HEDGE_CASES = [
    ("about 5 cm long", "about", 5, None, None),
    ("roughly 5 cm long", "about", 5, None, None),
    ("around 5 cm long", "about", 5, None, None),
    ("nearly 5 cm long", "about", 5, None, None),
    ("almost 5 cm long", "about", 5, None, None),
    ("5 cm or so long", "about", 5, None, None),
    ("more than 5 cm long", "at_least", 5, 5, None),
    ("a bit over 5 cm long", "at_least", 5, 5, None),
    ("at least 5 cm long", "at_least", 5, 5, None),
    ("just under 5 cm long", "at_most", 5, None, 5),
    ("less than 5 cm long", "at_most", 5, None, 5),
    ("exactly 5 cm long", "exact", 5, None, None),
    ("5 cm long", "exact", 5, None, None),
    ("3 to 4 cm long", "range", 3.5, 3, 4),
    ("3-4 cm long", "range", 3.5, 3, 4),
    ("between 3 and 4 cm long", "range", 3.5, 3, 4),
    ("3 cm to 4 cm long", "range", 3.5, 3, 4),
    ("3 or 4 cm long", "range", 3.5, 3, 4),
    ("3 to 4 inches long", "range", 8.89, 7.62, 10.16),
]


@pytest.mark.parametrize(("text", "qualifier", "value", "low", "high"), HEDGE_CASES)
def test_hedges_and_ranges(text: str, qualifier: str, value: float, low, high) -> None:
    ev = parse(text).features["a_cm"]
    assert ev.qualifier == qualifier and ev.qualifier in QUALIFIERS
    assert ev.value == approx(value)
    assert ev.low == (None if low is None else approx(low))
    assert ev.high == (None if high is None else approx(high))


# ----------------------------------------------------------------------------------------- categories
CATEGORY_CASES = [
    ("a metallic thing", "material", "metal"),
    ("made of stainless steel", "material", "metal"),
    ("an aluminum can", "material", "metal"),
    ("a wooden spoon", "material", "wood"),
    ("a cardboard box", "material", "paper"),
    ("cotton", "material", "fabric"),
    ("a ceramic mug", "material", "other"),
    ("a glass jar", "material", "glass"),
    ("a rubber duck", "material", "rubber"),
    ("a paper clip made of steel", "material", "metal"),
    ("a cylindrical thing", "shape", "prism"),
    ("a ball", "shape", "radial"),
    ("flat", "shape", "thin"),
    ("a cube", "shape", "compact"),
    ("a long stick", "shape", "long"),
    ("it is 7 cm in diameter and round", "shape", "radial"),
    ("it is squeezable", "rigidity", "squeezable"),
    ("soft and squishy", "rigidity", "squeezable"),
    ("floppy", "rigidity", "floppy"),
    ("hard", "rigidity", "rigid"),
    ("a smooth surface", "texture", "smooth"),
    ("grippy", "texture", "grippy"),
    ("fuzzy", "texture", "rough"),
    ("ridged edge", "texture", "grippy"),
    ("medium texture", "texture", "medium"),
    ("fragile", "fragility", "fragile"),
    ("delicate", "fragility", "fragile"),
    ("sturdy", "fragility", "sturdy"),
    ("not fragile", "fragility", "sturdy"),
]


@pytest.mark.parametrize(("text", "feature", "value"), CATEGORY_CASES)
def test_categories(text: str, feature: str, value: str) -> None:
    assert parse(text).values().get(feature) == value


def test_long_as_a_dimension_is_not_a_shape() -> None:
    assert "shape" not in parse("it is 15 cm long").features


def test_negated_category_is_dropped_and_light_colours_are_not_weights() -> None:
    assert "material" not in parse("it is not plastic").features
    assert parse("a light blue cup").mass_hint is None
    assert parse("it is not heavy").mass_hint == "light"
    assert parse("quite heavy").mass_hint == "heavy"


def test_lexicon_values_are_canonical() -> None:
    for feature, table in lexicon.TABLES.items():
        assert set(table.values()) <= set(CATEGORIES[feature]), feature
    assert set(lexicon.HEDGES.values()) <= set(QUALIFIERS)


# ---------------------------------------------------------------------------------------- odd input
@pytest.mark.parametrize(
    "text", ["", "   ", "hello world", "the quick brown fox jumps", "x x x", "cm cm cm", "!!!", "in in in"]
)
def test_no_features_gives_an_empty_result(text: str) -> None:
    parsed = parse(text)
    assert parsed.is_empty() and parsed.features == {} and parsed.values() == {}
    d = parsed.to_dict()
    assert all(d[f] is None for f in FEATURES)


@pytest.mark.parametrize("bad", [None, 42, b"bytes", ["a list"]])
def test_non_text_is_refused(bad) -> None:
    with pytest.raises(DescriptionError):
        parse(bad)  # type: ignore[arg-type]


def test_too_long_text_is_refused() -> None:
    with pytest.raises(DescriptionError, match="too long"):
        parse("a" * (MAX_TEXT_CHARS + 1))


def test_absurd_values_are_dropped() -> None:
    assert parse("it is 9000 m long and weighs 3000 kg").features == {}


def test_to_dict_is_json_with_all_features() -> None:
    parsed = parse(TABLE_III[1][0])
    d = json.loads(json.dumps(parsed.to_dict()))
    assert set(FEATURES) <= set(d)
    assert d["mass_hint"] == "heavy" and d["qualifiers"]["mass_g"] == "at_least"
    assert d["evidence"]["a_cm"]["words"] == "twenty one and half centimeters long"
    assert d["texture"] is None


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow], deadline=None)
@given(st.text(max_size=300))
def test_any_unicode_text_parses(text: str) -> None:
    parsed = parse(text)
    assert isinstance(parsed, ParsedDescription)
    for feature, ev in parsed.features.items():
        assert feature in FEATURES and ev.qualifier in QUALIFIERS
        assert 0 <= ev.start <= ev.end <= len(text)
        if isinstance(ev.value, float):
            assert ev.value > 0


_VOCAB = [
    "about", "more", "than", "and", "a", "half", "quarter", "of", "x", "by", "to", "-", "in", "cm", "inch",
    "inches", "mm", "lb", "oz", "kg", "g", "liter", "long", "wide", "thick", "diameter", "each", "side",
    "one", "twenty", "hundred", "dozen", "couple", "7", "1/2", "½", "3.5", "7,5", "plastic", "ball", "cube",
    "heavy", "light", "not", "filled", "with", ".", ",", "between", "or", "so", '"', "'",
]  # fmt: skip


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow], deadline=None)
@given(st.lists(st.sampled_from(_VOCAB), max_size=80))
def test_random_domain_word_salad_parses(words: list[str]) -> None:
    parsed = parse(" ".join(words))
    dims = [parsed.values().get(d) for d in ("a_cm", "b_cm", "c_cm")]
    known = [d for d in dims if d is not None]
    assert known == sorted(known, reverse=True)


@pytest.mark.timeout(60)
def test_100kb_of_text_parses() -> None:
    rng = random.Random(7)
    texts = [t for t, *_rest in TABLE_III] + [
        "lorem ipsum dolor sit amet " * 3,
        "x" * 500,
        "1 2 3 4 5 6 " * 20,
    ]
    chunks: list[str] = []
    size = 0
    while size < 100_000:
        piece = rng.choice(texts)
        chunks.append(piece)
        size += len(piece) + 1
    text = " ".join(chunks)
    parsed = default_parser().read(text)  # the stages past the faces' limit
    # sane: the first description's features win, and nothing crashed
    assert parsed.values()["material"] in ("plastic", "metal", "wood", "paper")
    assert len(parsed.tree.leaves()) > 10_000


def test_one_long_sentence_without_punctuation_parses() -> None:
    text = " ".join(["about fifteen and half centimeters long and"] * 3000)
    assert default_parser().read(text).values()["a_cm"] == approx(15.5)


# ------------------------------------------------------------------------------------ development set
def test_development_set_scores() -> None:
    from recall.parse_eval import DEV_SET, load_labeled, score_parses

    if not DEV_SET.exists():
        pytest.skip("no development set")
    labeled = load_labeled()
    assert len(labeled) >= 80
    scores = score_parses((parse(text), rec) for text, rec in labeled)
    assert scores.r2_dims is not None and scores.r2_dims >= 0.98
    assert scores.r2_mass is not None and scores.r2_mass >= 0.95
    assert scores.category_accuracy["material"] >= 0.9
    d = scores.to_dict()
    assert d["n"] == len(labeled) and set(d["category_accuracy"]) == set(CATEGORIES)


def test_parser_doc_lists_every_lexicon_word() -> None:
    from pathlib import Path

    doc = (Path(lexicon.__file__).parent / "PARSER.md").read_text(encoding="utf-8")
    tables = [*lexicon.TABLES.values(), lexicon.MASS_HINT_WORDS, lexicon.DIMENSION_WORDS, lexicon.HEDGES]
    missing = sorted(w for table in tables for w in table if w not in doc)
    assert not missing, f"recall/PARSER.md does not list: {missing}"
    from recall.parser import GRAMMAR

    assert GRAMMAR.strip() in doc


@pytest.mark.timeout(120)
@pytest.mark.parametrize(
    "text",
    [
        "1,234," * 16_000,  # digit-comma chains once made the tokenizer backtrack quadratically
        "1,234,567" + ",123" * 24_000 + "4",
        "-".join(["a"] * 50_000),
        "1.1.1.1." * 12_000,
        "½" * 50_000,
        '"' * 50_000,
        "7 " * 50_000,
        "and half " * 11_000,
        "about more than x by " * 5_000,
    ],
)
def test_hostile_100kb_inputs_complete(text: str) -> None:
    parsed = default_parser().read(text[:100_000])
    assert isinstance(parsed.tree, Tree)
    for ev in parsed.features.values():
        assert ev.qualifier in QUALIFIERS


# ------------------------------------------------------------- general patterns (red-team hold-out review)
# Each pattern with several phrasings written here (not the hold-out sentences); see PARSER.md.
PATTERN_DIMENSIONS = [
    # 1. length together with height: both kept, sorted
    ("a crate 20 cm long, 10 cm wide, 5 cm tall", (20, 10, 5)),
    ("it stands 5 cm tall and is 20 cm long", (20, 5, None)),
    ("6 cm high, 18 cm long and 9 cm deep", (18, 9, 6)),
    ("a tray 2 inches tall, 12 inches long, 8 inches wide", (30.48, 20.32, 5.08)),
    # 2. the label on the first number of a chain
    ("a sponge 9 cm long by 6 by 3", (9, 6, 3)),
    ("40 cm long by 25 cm by 12 cm", (40, 25, 12)),
    ("3 in wide by 2 by 1", (7.62, 5.08, 2.54)),
    ("a bar 12 cm long by 4 cm in diameter", (12, 4, 4)),
    ("7cm dia x 12cm long", (12, 7, 7)),
    ("a tube 3 cm dia x 15 cm", (15, 3, 3)),
    ("30cm long x 20cm wide x 10cm high", (30, 20, 10)),
    # 3. a pair after labelled extents adds to them
    ("a vase 30 cm tall with a 10 x 10 cm base", (30, 10, 10)),
    ("18 cm high, footprint 6 by 6 cm", (18, 6, 6)),
    ("21 x 15 cm and about a centimetre thick", (21, 15, 1)),
    # 4. a size before a noun: the main extent alone, and it never breaks a tuple
    ("an 8 inch frying pan", (20.32, None, None)),
    ("a 15 cm kitchen knife", (15, None, None)),
    ("A 3m extension lead. The plug is 5 x 4 x 2 cm.", (5, 4, 2)),
    ("a 2 m rope coiled into a 12 by 10 by 6 cm bundle", (12, 10, 6)),
    # 5. role phrases
    ("40 cm side to side, 30 cm front to back, 12 cm top to bottom", (40, 30, 12)),
    ("a jug 20 cm tall, 14 cm wide including the handle", (20, 14, None)),
    ("a cup 8 cm tall, 7 cm across, 10 cm with the handle", (10, 8, 7)),
    ("a pen 14 cm overall", (14, None, None)),
    ("a beam 50 cm long, 4 cm square", (50, 4, 4)),
    ("a 25 cm square tile", (25, 25, None)),
    ("a 6 cm square cross section and 40 cm long", (40, 6, 6)),
    # 6. diameter with depth/height/thickness; a flat thing's width stays a width
    ("a saucepan 20 cm diameter and 9 cm deep", (20, 20, 9)),
    ("a skillet, 26 cm in diameter, 45 cm long with the handle, 4 cm deep", (45, 26, 4)),
    ("a round wok 30 cm across, 8 cm deep", (30, 30, 8)),
    ("a flat rubber bottle, 30 cm long and 18 cm wide", (30, 18, None)),
    ("a floppy plastic tube, 25 cm long, 6 cm wide", (25, 6, None)),
    ("a mixing bowl 24 cm across and 11 cm deep", (24, 24, 11)),
    ("a metal bucket 30 cm wide and 28 cm tall", (30, 30, 28)),
    ("a spoon 18 cm long, 4 cm wide at the bowl", (18, 4, None)),
    ("the blade is 20 cm long, 33 cm overall", (33, None, None)),
    ("the handle is 10 cm long and the whole thing is 30 cm long overall", (30, None, None)),
    # 7. balls: compounds ending in "ball", round things "across"
    ("a basketball about 24 cm in diameter", (24, 24, 24)),
    ("a baseball, 3 inches across", (7.62, 7.62, 7.62)),
    ("a used tennis ball 6.7 cm across", (6.7, 6.7, 6.7)),
    ("a glass marble 1.5 cm in diameter", (1.5, 1.5, 1.5)),
    ("an apple roughly 8 cm across", (8, 8, 8)),
    ("a coin, a quarter, 2.4 cm across", (2.4, 2.4, None)),
    ("a baseball cap 20 cm across", (None, 20, None)),
    # 8. equal values
    ("11 wide and 11 high", (11, 11, None)),
    ("a box 10 cm long, 10 cm wide and 10 cm high", (10, 10, 10)),
    # 9. compound quantities
    ("a board 1 foot 2 inches long", (35.56, None, None)),
    ("a shelf 2 ft 6 in long", (76.2, None, None)),
    # 10. lists and letter labels
    ("30, 20 and 10 cm", (30, 20, 10)),
    ("12, 8, 4 inches", (30.48, 20.32, 10.16)),
    ("L 30 x W 20 x H 10 cm", (30, 20, 10)),
    ("30L x 20W x 10H cm", (30, 20, 10)),
    ("dimensions: l 12 x w 9 x h 3 cm", (12, 9, 3)),
    # fractions as words
    ("three and three eighths inches by two and an eighth inches", (8.5725, 5.3975, None)),
    ("five sixteenths of an inch thick", (None, None, 0.7937)),
    ("one and five eighths inches long", (4.1275, None, None)),
]


@pytest.mark.parametrize(("text", "dims"), PATTERN_DIMENSIONS)
def test_general_dimension_patterns(text: str, dims: tuple) -> None:
    got = parse(text).values()
    for name, expected in zip(("a_cm", "b_cm", "c_cm"), dims, strict=True):
        if expected is None:
            assert name not in got, (name, got)
        else:
            assert got.get(name) == approx(expected), (name, got)


PATTERN_MASSES = [
    ("it weighs 1 lb 4 oz", 566.99, "exact"),
    ("2 lbs 8 oz", 1133.98, "exact"),
    ("1kg 200g", 1200, "exact"),
    ("2 kg 500 g", 2500, "exact"),
    ("300-ish grams", 300, "about"),
    ("300ish g", 300, "about"),
    ("~300 g", 300, "about"),
    ("300g-ish", 300, "about"),
    ("a steel flask full of water, about a pound and a half", 680.39, "about"),
    ("a jar filled with coffee beans, weighs 600 g", 600, "exact"),
    ("a bottle filled with 12 oz of juice", 340.19, "at_least"),
]


@pytest.mark.parametrize(("text", "grams", "qualifier"), PATTERN_MASSES)
def test_general_mass_patterns(text: str, grams: float, qualifier: str) -> None:
    ev = parse(text).features["mass_g"]
    assert (ev.value, ev.qualifier) == (approx(grams, rel=1e-3), qualifier)


def test_a_glued_litre_is_not_a_tuple_label() -> None:
    parsed = parse("a 2L bottle, full of water")
    assert parsed.features["mass_g"].qualifier == "at_least"
    assert parsed.values()["mass_g"] == approx(2000)


PATTERN_CATEGORIES = [
    ("a cordless drill with a rubber grip, made of plastic", "material", "plastic"),
    ("a wooden spoon with a plastic handle", "material", "wood"),
    ("a torch with a rubber grip and an aluminium body", "material", "metal"),
    ("a hammer, steel head, rubber grip", "material", "metal"),
    ("a candle in a glass jar, wax", "material", "other"),
    ("bread in a plastic bag, soft", "material", "plastic"),  # the only material stated
    ("a cardboard box with a plastic window", "material", "paper"),
    ("a ceramic cup, plastic lid", "material", "other"),
    ("a rubber band ball", "material", "rubber"),
    ("a champagne flute with a long stem", "shape", None),
    ("a wine glass with a long stem, cylindrical bowl", "shape", "prism"),
    ("a bottle opener, steel", "shape", None),
    ("a plastic bottle cap", "shape", "compact"),
    ("a bar of soap", "shape", None),
    ("a tube of crisps with a foil lid and plastic cap", "shape", "prism"),
    ("a long stick", "shape", "long"),
    ("it is 7 cm in diameter and round", "shape", "radial"),
    ("a bottle made of thin plastic", "shape", "prism"),
]


@pytest.mark.parametrize(("text", "feature", "value"), PATTERN_CATEGORIES)
def test_general_category_patterns(text: str, feature: str, value: str | None) -> None:
    assert parse(text).values().get(feature) == value


def test_tag_cache_gives_the_same_parse_again() -> None:
    from recall.parser import DescriptionParser

    parser = DescriptionParser()
    text = "A metallic bottle, 20 cm tall, 7 cm in diameter, weighs 300-ish grams; zyzzyva qwerty."
    first = parser.parse(text)
    assert {"zyzzyva", "metallic", "300"} <= set(parser.tagger.cache)
    again = parser.parse(text)
    assert first.values() == again.values() and first.tree == again.tree
    assert first.values()["mass_g"] == approx(300)


_ROLE_PHRASES = {
    "length": ["{v} cm long", "a length of {v} cm", "{v} cm in length", "{v} cm end to end"],
    "height": ["{v} cm tall", "{v} cm high", "a height of {v} cm", "{v} cm top to bottom"],
    "width": ["{v} cm wide", "{v} cm side to side", "width {v} cm", "{v} cm in width"],
    "depth": ["{v} cm deep", "{v} cm front to back", "depth: {v} cm"],
    "thickness": ["{v} cm thick", "a thickness of {v} cm"],
}
_SEPARATORS = [", ", " and ", ", and ", "; ", ". It is "]


@settings(max_examples=120, deadline=None)
@given(
    st.lists(st.sampled_from(sorted(_ROLE_PHRASES)), min_size=3, max_size=3, unique=True),
    st.lists(st.integers(1, 400), min_size=3, max_size=3),
    st.data(),
)
def test_three_labelled_extents_are_all_kept_and_sorted(roles: list[str], tenths: list[int], data) -> None:
    """Any three different roles, in any order, any phrasing, equal values or not: a >= b >= c are the
    three stated values (the hold-out's "long" + "tall" and "11 wide and 11 high" patterns)."""
    values = [t / 10 for t in tenths]
    parts = [
        data.draw(st.sampled_from(_ROLE_PHRASES[r])).format(v=f"{v:g}")
        for r, v in zip(roles, values, strict=True)
    ]
    text = "A thing, " + parts[0]
    for part in parts[1:]:
        text += data.draw(st.sampled_from(_SEPARATORS)) + part
    got = parse(text).values()
    assert [got.get("a_cm"), got.get("b_cm"), got.get("c_cm")] == approx(sorted(values, reverse=True)), text


@settings(max_examples=80, deadline=None)
@given(
    st.lists(st.integers(1, 400), min_size=3, max_size=3),
    st.sampled_from(
        [
            "{0} x {1} x {2} cm",
            "{0} cm long by {1} by {2}",
            "{0} cm x {1} cm x {2} cm",
            "L {0} x W {1} x H {2} cm",
            "{0}L x {1}W x {2}H cm",
            "{0}, {1} and {2} cm",
            "{0}, {1}, {2} cm",
            "A 5m tape. The case is {0} x {1} x {2} cm",
        ]
    ),
)
def test_tuples_and_lists_keep_all_three_values(tenths: list[int], form: str) -> None:
    values = [t / 10 for t in tenths]
    text = form.format(*(f"{v:g}" for v in values))
    got = parse(text).values()
    assert [got.get("a_cm"), got.get("b_cm"), got.get("c_cm")] == approx(sorted(values, reverse=True)), text


# Failure patterns found by the parser owner's blind set (tests/data/holdout2/), fixed generally; the
# phrasings below are new, not the set's.
PATTERN_DIMENSIONS_2 = [
    # letters naming single extents, outside a tuple
    ("Tray - L 40 cm, W 30 cm, H 6 cm", (40, 30, 6)),
    ("L=15cm W=4cm H=3cm, 90g", (15, 4, 3)),
    ("L 25 W 12 H 8 cm", (25, 12, 8)),
    ("candle L=12cm D=6cm", (12, 6, 6)),  # D without a W is a diameter
    ("crate: W 30 cm, D 20 cm, H 10 cm", (30, 20, 10)),  # D next to a W is a depth
    ("a pan, L 40 cm with handle, dia 24 cm, depth 6 cm", (40, 24, 6)),
    # "in" before "diameter" is inches when the text's other units are imperial
    ("a ball 2.5 in diameter, 3 oz", (6.35, 6.35, 6.35)),
    ("a can 5 in tall and 3 in diameter", (12.7, 7.62, 7.62)),
    ("a disc 7 in diameter and 2 cm thick", (7, 7, 2)),  # a metric length: "in" stays a preposition
    # a dimension noun that grabbed the mass after it leaves the length before it
    ("a jar ~ 12cm tall ~ 8cm diameter ~ 0.4 kg", (12, 8, 8)),
    # a dimension word before its hedged value (non-native word order)
    ("the box is long about 20 centimetre and wide around 10 centimetre", (20, 10, None)),
    ("a book, thick maybe 3 cm, long about 22 cm", (22, None, 3)),
    # a tolerance is neither a range nor a second value
    ("a board 60 cm +/- 2 cm long and 20 cm wide", (60, 20, None)),
    # relative extents
    ("a tile, three times as long as it is wide, about 5 cm wide", (15, 5, None)),
    ("a strip about 4 cm wide and twice as long", (8, 4, None)),
    ("a slab half as wide as it is long, 30 cm long", (30, 15, None)),
    # thickness of a long round thing is its diameter
    ("a crayon 9 cm long and 8 mm thick", (9, 0.8, 0.8)),
    ("a wooden dowel, 2 feet long and an inch thick", (60.96, 2.54, 2.54)),
    ("a book 24 cm long and 3 cm thick", (24, None, 3)),  # not round: the thickness only
]


@pytest.mark.parametrize(("text", "dims"), PATTERN_DIMENSIONS_2)
def test_owner_blind_set_dimension_patterns(text: str, dims: tuple) -> None:
    got = parse(text).values()
    for name, expected in zip(("a_cm", "b_cm", "c_cm"), dims, strict=True):
        if expected is None:
            assert name not in got, (name, got)
        else:
            assert got.get(name) == approx(expected), (name, got)


@pytest.mark.parametrize(
    ("text", "grams"),
    [
        ("a melon, 1.5 kg +/- 100 g", 1500),
        ("a pack of rice, 1 kg ± 50 g", 1000),
        ("weighs 250 g plus or minus 20 g", 250),
        ("a bag 300g +- 30g", 300),
    ],
)
def test_a_tolerance_is_not_a_range(text: str, grams: float) -> None:
    ev = parse(text).features["mass_g"]
    assert ev.value == approx(grams)
    assert ev.qualifier != "range"


@pytest.mark.parametrize(
    ("text", "material"),
    [
        ("a tray, not made of metal or glass, it is wooden", "wood"),
        ("a cup that isn't glass or ceramic; plastic", "plastic"),
        ("neither wood nor metal, the toy is rubber", "rubber"),
        ("a vase made of glass or crystal", "glass"),  # no negation: kept
    ],
)
def test_a_negation_covers_the_materials_joined_by_or(text: str, material: str) -> None:
    assert parse(text).values().get("material") == material


def test_a_proportion_is_not_a_long_shape() -> None:
    assert "shape" not in parse("a tile three times as long as it is wide").values()
    assert parse("a long stick").values()["shape"] == "long"


@given(st.integers(min_value=2, max_value=60), st.integers(min_value=1, max_value=9))
def test_a_tolerance_never_changes_the_value(value: int, tolerance: int) -> None:
    got = parse(f"about {value} cm +/- {tolerance} cm long, {value * 10} g ± {tolerance} g").values()
    assert got["a_cm"] == approx(value)
    assert got["mass_g"] == approx(value * 10)


@pytest.mark.parametrize(
    ("text", "grams"),
    [
        ("next to my 3 kg kettlebell sits a pear of 150 g", 150),
        ("it is lighter than my 1 kg bag of rice, about 250 g", 250),
        ("my 5 lb sack of flour is heavier; the jar is 400 g", 400),
        ("This is my 2 kg dumbbell, cast iron", 2000),  # no comparison: the object itself
        ("my 2 kg dumbbell, 22 cm long; it weighs 2.1 kg", 2100),  # a plain mass wins over an owned one
    ],
)
def test_another_objects_mass_is_not_the_mass(text: str, grams: float) -> None:
    assert parse(text).values()["mass_g"] == approx(grams)


def test_a_compared_objects_mass_alone_states_no_mass() -> None:
    parsed = parse("a bowl, much lighter than my 2 kg dumbbell, 15 cm across")
    assert "mass_g" not in parsed.values()
    assert parsed.values()["a_cm"] == approx(15)


@pytest.mark.parametrize(
    ("text", "shape"),
    [
        ("A superball, rubber, 3 cm across", "radial"),
        ("a softball, 9.7 cm", "radial"),
        ("a basketball", "radial"),
        ("a baseball cap, cotton", "compact"),  # the cap's shape: the ball word only names what it is for
        ("a cotton baseball jersey", None),
    ],
)
def test_a_ball_compound_is_a_ball_shape(text: str, shape: str | None) -> None:
    assert parse(text).values().get("shape") == shape


# ------------------------------------------------------------ a length restated in parentheses (issue 23)
def test_a_length_restated_in_parentheses_is_one_extent():
    chain = parse("a steel chain, a bit over a metre (about 115 cm), 100 grams").values()
    assert chain["a_cm"] == 100.0 and "b_cm" not in chain  # was 115 and 100: a length and a width
    box = parse("a box, 10 inches (25 cm) long, 4 in (10 cm) wide").values()
    assert (box["a_cm"], box["b_cm"]) == pytest.approx((25.4, 10.16)) and "c_cm" not in box


@pytest.mark.parametrize("text, b", [
    ("a rod 30 cm (45 cm) and more", None),  # 1.5x: still the same extent
    ("a rod 30 cm (46 cm) and more", 30.0),  # over 1.5x: another extent
    ("a rod 30 cm, (31 cm) and more", 30.0),  # not right after it
    ("a rod 30 cm (31 cm and more", 30.0),  # not closed right after the value
])  # fmt: skip
def test_a_restatement_agrees_within_its_factor_and_follows_at_once(text, b):
    from recall.parser import RESTATED_FACTOR

    assert RESTATED_FACTOR == 1.5
    assert parse(text).values().get("b_cm") == b


@given(st.floats(min_value=2.0, max_value=200.0))
def test_a_unit_conversion_in_parentheses_never_adds_an_extent(cm):
    inches = round(cm / 2.54, 1)
    values = parse(f"a wooden rod, {cm:g} cm ({inches:g} in), plastic").values()
    assert values["a_cm"] == pytest.approx(cm, abs=0.01) and "b_cm" not in values
