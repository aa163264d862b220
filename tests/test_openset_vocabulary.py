"""The household vocabulary of the open set (issue 16, fourth session): synonyms of catalog objects,
kind names as hypernyms, compounds the lexicon lists, compounds on a catalog noun with an unknown head,
and the confidence of an unknown noun (recall/openset.py, kb/data/kind_nouns.csv, RECALL.md "A household
vocabulary")."""

from __future__ import annotations

from pathlib import Path

import pytest
from recallers import catalog2, seed

from kb.kinds import nouns, words_of
from recall.catalog_kinds import KindIndex
from recall.confidence import confidence_of
from recall.engine import NOT_IN_CATALOG_CONFIDENCE, Recaller
from recall.names import GENERIC_NOUNS
from recall.openset import compound_head, described_noun, names_inside, synonym_rows
from recall.subject import feature_words, is_adjective, said_in_plural, subject_phrase


def _described(recaller: Recaller, subject: tuple[str, ...]):
    idx = recaller.names
    return described_noun(subject, idx.phrases, idx.heads, idx.vocabulary, GENERIC_NOUNS, (), recaller.kinds)


# ------------------------------------------------------------------------------------------- synonyms
@pytest.mark.parametrize(
    ("text", "name"),
    [
        ("My cellphone, 15 by 7 by 0.8 cm, about 170 g, glass and metal.", "smartphone"),
        ("A frypan, metal, 28 cm across, 1 kg.", "frying pan"),
        ("A pen drive, plastic and metal, 5 cm long, 10 g.", "usb stick"),
    ],
)
def test_a_synonym_of_a_catalog_object_is_no_unknown_noun_and_names_it(text, name):
    res = seed().recall_text(text)
    assert res.best.name == name
    assert not res.open_set and not res.not_in_catalog and res.unknown_noun is None
    assert res.described is not None and res.described.in_catalog


def test_synonym_rows_are_the_rows_of_the_english_name_only():
    rec = seed()
    phone = rec.snapshot.names.index("smartphone")
    assert synonym_rows(rec.described("a cellphone, 15 cm"), rec.names.phrases) == {phone}
    assert synonym_rows(rec.described("a teapot, 15 cm"), rec.names.phrases) == set()  # not in the catalog
    assert synonym_rows(None, rec.names.phrases) == set()


def test_a_synonym_names_a_sort_of_its_english_names_head_in_another_catalog():
    # catalog 2 spells its cubes "rubix cube": "rubik's cube" is no name there, but a cube is
    got = _described(catalog2(), ("rubik", "cube"))
    assert got is not None and got.in_catalog


# ------------------------------------------------------------------------------------------ hypernyms
def test_a_kinds_own_name_is_a_hypernym_where_the_catalog_has_that_kind():
    assert _described(seed(), ("cup",)) is None  # a mug is a cup
    assert _described(seed(), ("battery",)) is None
    got = _described(catalog2(), ("jar",))  # catalog 2 has a jar lid, no jar
    assert got is not None and not got.in_catalog
    got = _described(catalog2(), ("battery",))
    assert got is not None and not got.in_catalog


def test_kind_index_has_kind_counts_kinds_below():
    kinds = KindIndex(["coffee mug", "apple"], [(), ()])
    assert kinds.has_kind("cup") and kinds.has_kind("container") and kinds.has_kind("fruit")
    assert not kinds.has_kind("jar") and not kinds.has_kind("bottle")


def test_a_large_catalog_is_not_scanned_for_its_kinds_to_tell_a_hypernym():
    from recall.catalog_kinds import KIND_SCAN_LIMIT

    names = ["apple"] * (KIND_SCAN_LIMIT + 1)
    kinds = KindIndex(names, [()] * len(names))
    assert kinds.has_kind("jar") and kinds._rows is None  # assumed, nothing worked out
    small = KindIndex(names[:KIND_SCAN_LIMIT], [()] * KIND_SCAN_LIMIT)
    assert not small.has_kind("jar") and small._rows is not None


# ------------------------------------------------------------------------------------------ compounds
def test_a_listed_compound_is_another_object_even_with_catalog_words_in_it():
    for subject in (("egg", "cup"), ("toilet", "brush"), ("watering", "can"), ("garlic", "bulb")):
        got = _described(seed(), subject)
        assert got is not None and not got.in_catalog, subject
    # a catalog head after material or colour words only is the catalog's object
    got = _described(catalog2(), ("metal", "cap"))
    assert got is not None and got.in_catalog
    # a sort of the catalog's objects has the catalog word as its English name
    got = _described(catalog2(), ("bottle", "cap"))
    assert got is not None and got.in_catalog


def test_a_catalog_name_inside_the_described_compound_does_not_name_it():
    res = seed().recall_text("A ceramic egg cup, 5 cm tall.")
    assert (
        res.not_in_catalog and res.described.noun == "egg cup" and res.confidence <= NOT_IN_CATALOG_CONFIDENCE
    )
    res = seed().recall_text("a lemon squeezer, glass, 14 cm across, 300 g")
    assert res.not_in_catalog
    noun = seed().described("an egg cup, 5 cm")
    assert (
        names_inside(noun, ("egg",))
        and not names_inside(noun, ("egg", "plate"))
        and not names_inside(noun, ())
    )
    assert not names_inside(None, ("egg",))


def test_a_compound_on_a_generic_noun_is_an_object_the_generic_noun_alone_is_not():
    assert seed().recall_text("A glue stick, 9 cm long, 2.5 cm across, 30 g.").not_in_catalog
    assert seed().recall_text("A kiwi fruit, 7 cm long, 5 cm across, 75 g.").not_in_catalog
    assert _described(seed(), ("stick",)) is None and _described(seed(), ("fruit",)) is None


def test_an_unknown_head_after_a_catalog_noun_is_an_unseen_compound():
    assert compound_head(("bottle", "warmer"), seed().names.vocabulary) == "warmer"
    assert compound_head(("remote", "control"), seed().names.vocabulary) is None  # a catalog word
    assert compound_head(("warmer",), seed().names.vocabulary) is None  # not a compound
    assert compound_head(("dowel", "offcut"), seed().names.vocabulary) is None  # a piece: generic
    res = seed().recall_text("A bottle warmer, plastic, 15 cm tall, 500 g.")
    assert res.not_in_catalog and res.described.noun == "bottle warmer"
    assert not seed().recall_text("A remote control, plastic, 18 by 5 by 2 cm, 100 g.").open_set


def test_a_measure_of_a_catalog_thing_is_no_unseen_object():
    res = seed().recall_text("A pint of milk in a carton, 20 cm tall, 1 kg.")
    assert not res.not_in_catalog and res.best.name == "milk carton"


def test_a_gerund_modifier_says_what_a_catalog_object_is_for():
    res = seed().recall_text("A baking potato, 12 cm long, 250 g.")
    assert res.best.name == "potato" and res.foreign_modifier is None and not res.open_set


# ------------------------------------------------------------------------------------ the subject phrase
def test_a_participle_before_a_function_word_ends_the_subject_and_a_number_word_is_skipped():
    assert subject_phrase("A kitchen timer shaped like a tomato, plastic") == ("kitchen", "timer")
    assert subject_phrase("a tin filled with buttons, 10 cm") == ("tin",)
    assert subject_phrase("A folded towel, 30 cm") == ("folded", "towel")  # no function word after it
    assert subject_phrase("A two-slice toaster, 28 cm") == ("slice", "toaster")


# -------------------------------------------------------------------------------------------- the data
def test_no_single_lexicon_noun_is_a_material_or_unit_word_but_the_objects_named_by_one():
    # a material or unit word at the head of a subject states a feature ("Iron, 10 cm, 500 g"); only the
    # nouns that name an object and a material alike are in both (a cork, a marble, a sponge, a cup)
    from recall import lexicon as lx

    features = set(lx.MATERIAL_WORDS) | set(lx.LENGTH_UNITS) | set(lx.MASS_UNITS) | set(lx.VOLUME_UNITS)
    singles = {k[0] for k, n in nouns().items() if len(k) == 1 and n.lang == "en"}
    # "micrometer": a unit (48d194b) and a measuring tool (the Yale catalog's), as "cup" is a unit and a cup
    both = {"carton", "cork", "cup", "glass", "marble", "micrometer", "paper", "soap", "sponge", "stone", "tin"}
    assert singles & features <= both, (singles & features) - both
    assert "iron" not in singles and "wool" not in singles and "felt" not in singles
    assert "short" not in singles and "tight" not in singles  # "shorts", "tights" would make them nouns
    assert feature_words()  # the filter of the lexicon's additions (see RECALL.md)


def test_the_lexicon_is_a_broad_household_vocabulary_and_synonyms_name_catalog_objects():
    english = [n for n in nouns().values() if n.lang == "en"]
    assert len({n.words for n in english}) >= 2000
    catalog = {tuple(words_of(n)) for n in seed().snapshot.names}
    synonyms = {n.text: n.english for n in english if n.english != n.text}
    for noun in ("cellphone", "frypan", "jotter", "joypad", "clicker", "superball"):
        assert tuple(words_of(synonyms[noun])) in catalog, noun


# --------------------------------------------------------------------------------------- confidence
def test_an_unknown_named_noun_lowers_confidence():
    for margin, closeness in ((10.0, 0.1), (10.0, 0.0), (6.0, 0.05)):
        assert confidence_of(margin, closeness, True, "jplog") < confidence_of(
            margin, closeness, False, "jplog"
        )
    for margin, closeness in ((2.0, 0.05), (0.5, 0.2)):  # never higher, also where the margin caps both
        assert confidence_of(margin, closeness, True, "jplog") <= confidence_of(
            margin, closeness, False, "jplog"
        )
    known = seed().recall_text("A hammer, steel, 33 cm long, 600 g.")
    unseen = seed().recall_text("A flyswatter, steel, 33 cm long, 600 g.")
    assert unseen.not_in_catalog and unseen.confidence <= NOT_IN_CATALOG_CONFIDENCE < known.confidence


# ------------------------------------------------------------------------------- nouns nobody listed
def test_a_word_said_in_the_plural_is_a_noun_whatever_its_ending():
    assert said_in_plural("binocular", "a pair of binoculars, 600 g")
    assert said_in_plural("box", "two boxes") and said_in_plural("battery", "some batteries")
    assert not said_in_plural("binocular", "a binocular view") and not said_in_plural("box", "boxer")
    res = seed().recall_text("A pair of bifocals, plastic, 14 cm wide, 30 g.")  # -al, but a plural
    assert res.not_in_catalog and res.described.noun == "bifocal"


def test_a_y_after_a_vowel_is_no_adjective_ending():
    assert is_adjective("squishy") and is_adjective("fuzzy")
    assert not is_adjective("trolley") and not is_adjective("key") and not is_adjective("tray")


# ------------------------------------------------------------------------------------------ verdict
def test_one_verdict_line_for_every_face():
    from recall.verdict import verdict

    cases = {
        "An orange of 7 cm diameter.": "not in the catalog",
        "a fuzzy yellow tennis ball, about 6.5 cm across, 58 g": "close match",
        "something small and round": "a guess",
    }
    for text, label in cases.items():
        res = seed().recall_text(text)
        got = verdict(res)
        assert got.label == label, (text, got)
        assert res.to_dict()["verdict"] == got.to_dict()  # --json and POST /recall carry the CLI's line
        assert f"confidence {res.confidence:.2f}" in got.text
    far = seed().recall_text("steel, 3 m long, 90 kg")
    assert far.open_set and not far.not_in_catalog and verdict(far).label == "not a close match"


def test_a_request_or_question_before_the_subject_is_skipped():
    assert subject_phrase("Could you pass the salt shaker, glass, 8 cm tall?") == ("salt", "shaker")
    assert subject_phrase("Where is the ice cream scoop? steel, 20 cm.") == ("ice", "cream", "scoop")
    assert subject_phrase("Looking for my harmonica, it's metal") == ("harmonica",)
    assert subject_phrase("Please get the tea kettle, 2 kg.") == ("tea", "kettle")
    assert subject_phrase("Hand me the hammer, 33 cm") == ("hammer",)
    assert subject_phrase("Hand towel, 50 cm by 30 cm") == ("hand", "towel")  # a noun follows: no request
    assert subject_phrase("A pass key, 5 cm") == ("pass", "key")  # inside the phrase it is a word of it
    res = seed().recall_text("Could you pass the salt shaker, glass, 8 cm tall?")
    assert res.not_in_catalog and res.described.noun == "salt shaker"
    assert seed().recall_text("Hand me the hammer, 33 cm, 600 g.").best.name == "hammer"


def test_a_noun_after_a_subject_of_feature_words_is_the_described_noun():
    from recall.subject import noun_phrase

    assert noun_phrase("Steel, about 15 cm long, 150 g, a nutcracker.") == ("nutcracker",)
    assert noun_phrase("Metal, 5.5 inches long, a fifth of an ounce.") == ("metal",)  # no lexicon noun later
    assert noun_phrase("A plush dinosaur toy, 35 cm, a gift") == ("plush", "dinosaur", "toy")  # a noun first
    res = seed().recall_text("Plastic, 27 cm across, 175 g, a frisbee.")
    assert res.not_in_catalog and res.described.noun == "frisbee"


def test_a_collective_or_kind_word_names_no_missing_object():
    for text in (
        "A piece of clothing, cotton, 70 by 50 cm, 150 g.",
        "Some cutlery, steel, 20 cm long, 50 g.",
    ):
        res = seed().recall_text(text)
        assert not res.not_in_catalog and not res.open_set, text


def test_made_of_a_material_is_no_subject_and_a_colon_ends_a_chunk():
    from recall.subject import noun_phrase

    assert noun_phrase("Made of glass, 8 cm tall: a salt shaker.") == ("salt", "shaker")
    assert subject_phrase("Teapot: ceramic, 900 g") == ("teapot",)
    assert subject_phrase("A bowl made of glass, 12 cm") == ("bowl",)


# ------------------------------------------------------------------------------------------- typos
def test_a_typing_slip_in_a_catalog_or_lexicon_noun_is_read_as_that_noun():
    from recall.typos import MIN_LENGTH, corrected, edits

    heads = seed().names.heads
    assert "screwdriver" in edits("screwdiver") and "screwdiver" not in edits("screwdiver")
    assert corrected("screwdiver", heads) == "screwdriver" and corrected("stappler", heads) == "stapler"
    assert corrected("nutcraker", heads) == "nutcracker"  # a lexicon noun
    assert corrected("flyswatter", heads) is None  # nothing one edit away
    assert corrected("jugg", heads) is None and MIN_LENGTH == 6  # too short to correct
    res = seed().recall_text("A screwdiver, 20 cm long, 80 g.")
    assert not res.not_in_catalog and res.described.noun == "screwdriver"
    res = seed().recall_text("A nutcraker, metal, 15 cm long, 150 g.")
    assert res.not_in_catalog and res.described.noun == "nutcracker"
    # a correction that names no noun (a participle of a catalog name: "sliced") is no correction
    assert seed().recall_text("A bagel slicer, plastic, 25 cm long, 300 g.").not_in_catalog


def test_the_verdict_label_agrees_with_the_confidence():
    from recall.verdict import GUESS_CONFIDENCE, verdict

    texts = ("a tennis ball", "something small and round", "a coffee mug", "a small red toy", "a plastic bottle cap",
             "a fuzzy yellow tennis ball, about 6.5 cm across, 58 g", "a heavy steel tool about a foot long")
    for text in texts:
        res = seed().recall_text(text)
        label = verdict(res).label
        if label in ("close match", "a guess"):
            assert (label == "close match") == (res.confidence >= GUESS_CONFIDENCE), (text, res.confidence, label)
    assert verdict(seed().recall_text("a tennis ball")).label == "close match"  # 0.89 is no guess


def test_grasp_target_says_the_recalls_own_verdict():
    from recall.target import grasp_target
    from recall.verdict import verdict

    res = seed().recall_text("something small and round")
    _record, info = grasp_target(res, lambda name: seed_record(name))
    assert verdict(res).text in info["why"] and "(close match)" not in info["why"]


def seed_record(name: str):
    import csv

    from kb.features import ObjectRecord

    path = Path(__file__).resolve().parents[1] / "kb" / "data" / "seed_catalog.csv"
    with path.open(encoding="utf-8") as f:
        row = next(r for r in csv.DictReader(f) if r["name"] == name)
    values = {k: v for k, v in row.items() if k in ("a_cm", "b_cm", "c_cm", "mass_g") and v}
    return ObjectRecord.create(name, **{k: float(v) for k, v in values.items()})


# ------------------------------------------------------------------ grasp target: stated sides kept
@pytest.mark.parametrize(
    ("stated", "hint", "expected"),
    [
        ({"a_cm": 1.0}, (15.0, 4.2, 1.5), (1.0, 1.0, 1.0)),  # "a spoon 1 cm long": a stays 1, b, c <= a
        ({"b_cm": 40.0, "c_cm": 40.0}, (27.0, 27.0, 27.0), (40.0, 40.0, 40.0)),  # "a bottle 40 cm wide"
        ({"a_cm": 15.0}, (15.0, 4.2, 1.5), (15.0, 4.2, 1.5)),  # boundary: the hint's side equal to a stated
        ({"a_cm": 4.2}, (15.0, 4.2, 1.5), (4.2, 4.2, 1.5)),  # ... b equal to the stated a: kept
        ({"c_cm": 2.0}, (15.0, 4.2, 1.5), (15.0, 4.2, 2.0)),  # a stated c keeps its place
        ({"b_cm": 5.0}, (15.0, 4.2, 1.5), (15.0, 5.0, 1.5)),
        ({}, (1.5, 15.0, 4.2), (15.0, 4.2, 1.5)),  # nothing stated: the hint's sides, sorted
    ],
)
def test_grasp_target_keeps_stated_sides_and_clamps_filled_ones(stated, hint, expected):
    from types import SimpleNamespace

    from kb.features import ObjectRecord
    from recall.target import grasp_target

    hint_object = ObjectRecord.create("spoon", a_cm=hint[0], b_cm=hint[1], c_cm=hint[2], mass_g=50.0)
    best = SimpleNamespace(name="spoon", distance=3.0)
    result = SimpleNamespace(
        best=best, matches=[best], confidence=0.1, open_set=True, not_in_catalog=False, described=None,
        same_kind=[], query={"values": dict(stated)}, closeness=0.5, unknown_noun=None, competitors=1.0,
    )  # fmt: skip
    record, info = grasp_target(result, lambda name: hint_object)
    assert (record.a_cm, record.b_cm, record.c_cm) == expected
    assert record.a_cm >= record.b_cm >= record.c_cm
    assert all(getattr(record, f) == v for f, v in stated.items())  # place and value
