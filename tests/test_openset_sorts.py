"""Sorts of a catalog object (issue 23): a compound on the head of an object with a plain name ("a spring
clamp" of the catalog's "medium clamp", "a kitchen timer" of its "timer") is in the catalog, and a noun
before the head of such an object says which sort, not another object; where the catalog names its
objects by their sorts ("soccer ball"), another sort ("volleyball") is still another object. Catalogs
written here, each rule's conditions pinned one at a time."""

from __future__ import annotations

from pathlib import Path

import pytest
from recallers import from_sizes

from kb.kinds import Noun, noun_in
from recall.catalog_kinds import KindIndex, is_qualifier, plain_name, sort_of_catalog_object
from recall.engine import Recaller


def _recaller(tmp_path: Path, rows: list[tuple]) -> Recaller:
    return from_sizes(tmp_path / "catalog.csv", rows)


TOOLS = [
    ("medium clamp", 8.9, 7.7, 2.6, 59), ("timer", 12.2, 11.9, 4.1, 102), ("knife", 21.5, 2.3, 2.1, 31),
    ("spoon", 18.6, 8.3, 2.1, 30), ("skillet", 43, 27, 8, 950), ("sugar box", 17.5, 9, 4, 514),
]  # fmt: skip
BALLS = [("soccer ball", 22, 22, 22, 430), ("tennis ball", 6.7, 6.7, 6.7, 57), ("plastic ball", 7, 7, 7, 20)]


@pytest.fixture(scope="module")
def tools(tmp_path_factory) -> Recaller:
    return _recaller(tmp_path_factory.mktemp("tools"), TOOLS)


@pytest.fixture(scope="module")
def balls(tmp_path_factory) -> Recaller:
    return _recaller(tmp_path_factory.mktemp("balls"), BALLS)


# --------------------------------------------------------------------------------------------- names
@pytest.mark.parametrize("name", ["timer", "small clamp", "medium clamp", "extra large clamp", "adjustable wrench",
                                  "plastic ball", "bouncy ball"])  # fmt: skip
def test_a_name_of_its_head_alone_or_after_qualifiers_is_plain(name):
    assert plain_name(name.split())


@pytest.mark.parametrize("name", ["soccer ball", "frying pan", "dinner plate", "kitchen timer", ""])
def test_a_name_with_a_noun_or_gerund_before_its_head_is_not_plain(name):
    assert not plain_name(name.split())


@pytest.mark.parametrize("word", ["small", "extra", "medium", "tiny", "biggest"])
def test_size_words_only_qualify(word):
    assert is_qualifier(word)


# ------------------------------------------------------------------------------------------ the rule
def _index(names: list[str]) -> KindIndex:
    return KindIndex(names, [()] * len(names))


def test_a_compound_of_the_same_kind_on_a_plain_heads_object_is_a_sort_of_it():
    assert sort_of_catalog_object(noun_in(["spring", "clamp"]), {"clamp"}, _index(["medium clamp"])) == "clamp"


def test_a_compound_of_another_kind_is_not_a_sort():
    egg_cup = noun_in(["egg", "cup"])
    assert egg_cup.kind != noun_in(["cup"]).kind
    assert sort_of_catalog_object(egg_cup, {"cup"}, _index(["cup"])) is None


def test_no_sort_where_the_catalog_names_sorts_of_that_head():
    volleyball = noun_in(["volleyball"])
    assert sort_of_catalog_object(volleyball, {"ball"}, _index(["plastic ball"])) == "ball"
    assert sort_of_catalog_object(volleyball, {"ball"}, _index(["plastic ball", "soccer ball"])) is None


def test_a_closed_compound_ends_with_the_head_of_three_letters_or_more():
    tablespoon = noun_in(["tablespoon"])
    assert sort_of_catalog_object(tablespoon, {"spoon"}, _index(["spoon"])) == "spoon"
    made_up = Noun(("abcxyz",), tablespoon.kind, "en", "abcxyz")
    assert sort_of_catalog_object(made_up, {"yz"}, _index(["yz"])) is None  # a head under 3 letters


def test_the_noun_alone_is_no_sort_of_itself():
    timer = noun_in(["timer"])
    assert sort_of_catalog_object(timer, {"timer"}, _index(["timer"])) is None


def test_a_noun_whose_english_name_is_a_catalog_objects_names_it():
    frying_pan = noun_in(["frying", "pan"])
    assert sort_of_catalog_object(frying_pan, {"skillet"}, _index(["skillet"])) == "skillet"
    assert sort_of_catalog_object(frying_pan, set(), None) is None


def test_a_catalog_object_called_by_a_kind_alone_holds_every_noun_of_that_kind():
    """The Yale "furniture": a side table (kind furniture) is a sort of it; not a noun of another kind,
    nor where the kind's name only heads a longer name ("garden furniture"), nor a kind no object is
    called by alone."""
    side_table = noun_in(["side", "table"])
    assert side_table.kind == "furniture"
    assert sort_of_catalog_object(side_table, {"furniture"}, _index(["furniture", "drawer"])) == "furniture"
    assert sort_of_catalog_object(side_table, {"furniture"}, _index(["garden furniture"])) is None
    assert sort_of_catalog_object(side_table, {"drawer"}, _index(["drawer"])) is None
    hammer = noun_in(["hammer"])
    assert hammer.kind != "furniture"
    assert sort_of_catalog_object(hammer, {"furniture"}, _index(["furniture"])) is None
    assert _index(["furniture", "cup", "small ball", "garden furniture"]).kind_named() == {"furniture", "cup"}


# -------------------------------------------------------------------------------------- in the recall
@pytest.mark.parametrize("text", [
    "a medium spring clamp, plastic, 11.5 by 9 by 2.7 cm, about 60 g",
    "a kitchen timer, 12 x 12 x 4 cm, plastic, about 100 grams",
    "a frying pan, 43 cm long with the handle, about 2 pounds",
])  # fmt: skip
def test_a_sort_of_a_catalog_object_is_recalled_as_it(tools, text):
    res = tools.recall_text(text)
    assert not res.not_in_catalog and not res.open_set, res.fit.reason


def test_a_sort_is_in_the_catalog_only_as_an_object_of_that_head(tools):
    # a spring clamp the size and mass of the sugar box: the best match is no clamp, so it is not in it
    res = tools.recall_text("a spring clamp, 17.5 x 9 x 4 cm, 514 g")
    assert res.matches[0].name == "sugar box"
    assert res.not_in_catalog and res.open_set


def test_a_noun_before_a_plain_named_objects_head_narrows_it(tools):
    res = tools.recall_text("a table knife, stainless, 21.5 cm long, 2 cm wide blade, about 40 g")
    assert res.matches[0].name == "knife" and res.foreign_modifier is None
    assert not res.open_set and "plain" in res.fit.reason  # neither doubted nor named


def test_a_noun_before_a_sort_named_objects_head_still_doubts_it(balls):
    res = balls.recall_text("a cricket ball, hard leather, 7.2 cm across, 160 g")
    assert res.not_in_catalog or res.open_set


def test_another_sort_of_a_head_the_catalog_names_by_sorts_is_not_in_it(balls):
    res = balls.recall_text("a volleyball, soft leather, 21 cm across, 270 g")
    assert res.not_in_catalog and res.open_set


# ------------------------------------------------------------------------------------------ hyphens
@pytest.mark.parametrize("text, phrase", [
    ("cross-head screwdriver, eight inches long", ("cross", "head", "screwdriver")),
    ("the T-shirt, cotton", ("t", "shirt")),
    ("A two-slice toaster, 28 cm", ("slice", "toaster")),  # a number word keeps its hyphen: a count
    ("a box 10-12 cm wide", ("box",)),  # a hyphen between numbers is a range
    ("a mug - blue, 10 cm", ("mug",)),  # a dash ends the chunk
])  # fmt: skip
def test_a_hyphen_between_letters_joins_one_phrases_words(text, phrase):
    from recall.subject import subject_phrase

    assert subject_phrase(text) == phrase


def test_a_hyphenated_modifier_no_longer_hides_the_head(tools):
    res = tools.recall_text("a cross-head spoon, 18.6 cm long, 30 g")
    assert res.described is None or res.described.noun != "cross"


# ----------------------------------------------- an object named by the head alone (issue 23, helper-desc)
def test_a_sort_of_an_object_named_by_its_head_alone_beside_other_sorts():
    # the catalog's "cord" beside its "power cord" is its generic cord: an extension cord is a sort of it;
    # a head only qualified ("plastic ball") beside sorts ("soccer ball") is not (the volleyball above)
    cord = noun_in(["extension", "cord"])
    assert sort_of_catalog_object(cord, {"cord"}, _index(["cord", "power cord"])) == "cord"
    assert sort_of_catalog_object(cord, {"cord"}, _index(["black cord", "power cord"])) is None


def test_a_generic_noun_a_catalog_object_is_named_by_is_no_foreign_thing(tmp_path):
    # "tube" is a generic noun ("a mailing tube" would name a foreign thing of its kind), but this catalog
    # calls an object "tube": a mailing tube is a sort of it, judged by the features
    r = _recaller(tmp_path, [("tube", 60, 7.5, 7.5, 150), ("cup", 9, 8, 8, 300)])
    res = r.recall_text("a cardboard mailing tube, 60 cm long, 7.5 cm diameter, about 150 g")
    assert res.best.name == "tube" and not res.not_in_catalog and not res.open_set, res.fit.reason
    (tmp_path / "other").mkdir()
    other = _recaller(tmp_path / "other", [("cup", 9, 8, 8, 300)])
    assert other.recall_text("a cardboard mailing tube, 60 cm long, 7.5 cm diameter, 150 g").not_in_catalog


def test_a_noun_of_the_kind_a_catalog_head_names_with_the_same_modifier_is_that_object(tools):
    from recall.catalog_kinds import kind_mate

    carton = noun_in(["carton"])
    assert carton.kind == "box"
    index = _index(["sugar box", "timer"])
    assert kind_mate(carton, ("yellow", "sugar", "carton"), index) == "box"
    assert kind_mate(carton, ("timer", "carton"), index) is None  # a catalog word, but of no box
    assert kind_mate(carton, ("carton",), index) is None  # no modifier: another object
    assert kind_mate(carton, ("sugar", "carton"), None) is None
    res = tools.recall_text("the yellow sugar carton, roughly 7 by 3.5 by 1.5 inches, around 500 g, paperboard")
    assert res.best.name == "sugar box" and not res.not_in_catalog and not res.open_set, res.fit.reason
    assert tools.recall_text("a carton, 17.5 x 9 x 4 cm, 514 g").not_in_catalog  # no modifier: not it


def test_a_synonym_of_another_head_is_in_the_catalog_only_where_that_head_is_plain(tmp_path):
    # the lexicon's "cola" is the seed catalog's "soda can": a catalog that names its cans by their sorts
    # ("tomato soup can", "chips can") has no soda can; one with a plain "can" has it as a sort of that
    # can. A synonym that is itself a word of the head ("puzzle cube", "squeeze bottle") is a sort of it.
    from recall.catalog_kinds import names_sort_of

    cola = noun_in(["cola"])
    assert cola.english == "soda can"
    sorts = _recaller(tmp_path, [("tomato soup can", 11.9, 7.1, 6.8, 349), ("chips can", 24, 8.6, 8.4, 205)])
    res = sorts.recall_text("a cola, 12 cm tall, 6.6 cm across, aluminium, 370 g")
    assert res.described.noun == "cola" and res.not_in_catalog
    (tmp_path / "plain").mkdir()
    plain = _recaller(tmp_path / "plain", [("can", 12, 6.6, 6.6, 370), ("chips can", 24, 8.6, 8.4, 205)])
    assert not plain.recall_text("a cola, 12 cm tall, 6.6 cm across, aluminium, 370 g").not_in_catalog
    cube = noun_in(["puzzle", "cube"])
    assert names_sort_of(cube, ("rubik", "cube"), {"cube"}, _index(["rubix cube"]))
    assert not names_sort_of(cola, ("soda", "can"), {"can"}, _index(["chips can"]))
    assert not names_sort_of(cola, ("soda", "can"), {"cup"}, None)  # no catalog can at all
