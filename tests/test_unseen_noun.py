"""The unseen-noun rule: a subject noun that neither the catalog nor the kinds lexicon knows names an
object the catalog does not have (recall/openset.py :func:`unseen_noun`, RECALL.md "Not in the catalog").
Each condition of the rule is pinned on its own."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st
from recallers import seed

from kb.kinds import ROOT
from recall.engine import NOT_IN_CATALOG_CONFIDENCE
from recall.openset import NOTE_WORDS, PART_NOUNS, PLACEHOLDERS, SHAPE_NOUNS, unseen_noun


# --------------------------------------------------------------------------------------- the rule alone
def test_a_noun_nobody_knows_is_an_unseen_object_of_unknown_kind():
    got = unseen_noun("flyswatter", ("flyswatter",))
    assert got is not None and (got.noun, got.kind, got.in_catalog) == ("flyswatter", ROOT, False)
    assert got.english == "flyswatter"


def test_no_unknown_head_no_unseen_noun():
    assert unseen_noun(None, ()) is None
    assert unseen_noun(None, ("flyswatter",)) is None


def test_each_excluded_class_on_its_own():
    # the same shape of input as the positive case: only the word's class differs
    for word in ("gizmo", "whatsit"):
        assert word in PLACEHOLDERS and unseen_noun(word, (word,)) is None, word
    for word in ("blade", "headband", "handle"):
        assert word in PART_NOUNS and unseen_noun(word, (word,)) is None, word
    for word in ("dim", "wt"):
        assert word in NOTE_WORDS and unseen_noun(word, (word,)) is None, word
    for word in ("loop", "coil"):
        assert word in SHAPE_NOUNS and unseen_noun(word, (word,)) is None, word


def test_a_lexicon_noun_is_not_the_unseen_rules_to_judge():
    assert unseen_noun("toaster", ("toaster",)) is None  # kinds lexicon: electronics
    assert unseen_noun("teapot", ("teapot",)) is None


def test_colours_and_adjective_like_words_are_no_nouns():
    for word in ("beige", "squishy", "metallic", "folded", "ab"):
        assert unseen_noun(word, (word,)) is None, word


def test_the_reported_noun_keeps_a_noun_modifier_but_not_a_feature_word():
    assert unseen_noun("roller", ("lint", "roller")).noun == "lint roller"
    assert unseen_noun("roller", ("lint", "roller")).english == "roller"  # a store search's word
    assert unseen_noun("flyswatter", ("metal", "flyswatter")).noun == "flyswatter"
    assert unseen_noun("flyswatter", ("gizmo", "flyswatter")).noun == "flyswatter"
    assert unseen_noun("flyswatter", ("shiny", "flyswatter")).noun == "flyswatter"


@given(st.text(alphabet="abcdefghijklmnopqrstuvwxyz", min_size=0, max_size=12), st.lists(st.text(max_size=8), max_size=4))
def test_never_fails_and_is_never_in_the_catalog(word, subject):
    got = unseen_noun(word or None, tuple(subject) + ((word,) if word else ()))
    assert got is None or (not got.in_catalog and got.kind == ROOT and got.noun.endswith(word))


# ------------------------------------------------------------------------------------ through the recall
def test_an_unseen_noun_is_reported_not_in_the_catalog_with_the_closest_objects():
    res = seed().recall_text("A flyswatter, metal, about 15 cm long, 150 g.")
    assert res.not_in_catalog and res.open_set
    assert res.described is not None and res.described.noun == "flyswatter" and res.described.kind == ROOT
    assert res.matches and res.confidence <= NOT_IN_CATALOG_CONFIDENCE
    assert res.same_kind == [] and res.same_kind_as is None  # no kind: only the physically closest
    assert res.to_dict()["described"]["noun"] == "flyswatter"


def test_a_part_noun_or_a_placeholder_describes_a_catalog_object():
    for text in (
        "A long steel blade with a handle, about a foot long, 4.5 cm wide at the heel, 200 g.",
        "something small and round, 4 cm, 3 g",
        "dims 8.5 x 3 in, wt 1.5 lbs. steel bottle, holds water",
    ):
        assert not seed().recall_text(text).not_in_catalog, text


def test_a_name_in_the_text_beats_an_unseen_subject():
    # the unseen head is trusted only when the best match is not named in the text
    res = seed().recall_text("A gizmo-free flyswatter, it is a hammer really, 33 cm, 600 g, steel")
    assert res.best.name == "hammer" and res.best.matched_by_name
    assert not res.not_in_catalog


def test_an_unseen_noun_without_any_feature_is_nothing_to_recall():
    res = seed().recall_text("qwerty uiop")
    assert res.matches == [] and not res.not_in_catalog and res.described is None
    assert seed().recall_text("a flyswatter").described is None
    assert seed().recall_text("a flyswatter, 15 cm").not_in_catalog  # one feature is enough
    assert seed().recall_text("a small flyswatter").not_in_catalog  # a vague word is a feature too


def test_features_only_knows_no_nouns():
    res = seed().recall_text("A flyswatter, metal, about 15 cm long, 150 g.", features_only=True)
    assert not res.not_in_catalog and res.described is None
