"""Compound nouns (blind-test findings): a description's compound names a catalog object by its head only
when modifier and head both agree ("a wedding ring" is no "key ring"), and a material word counted by an
article is a head noun ("a glass" is the drinking glass)."""

from __future__ import annotations

import pytest
from recallers import seed

from recall.compounds import compound_agrees, modifier_noun
from recall.subject import counted_head

KEYS = ("bunch of keys", "keys", "key ring", "keychain")


@pytest.mark.parametrize(
    ("words", "expected"),
    [
        (["a", "wedding", "ring"], "wedding"),  # a noun modifier, whatever its ending
        (["a", "salad", "plate"], "salad"),
        (["the", "ring"], None),  # a determiner
        (["ring"], None),  # nothing before the head
        (["an", "old", "mug"], None),  # a word skipped in a subject phrase
        (["a", "plastic", "mug"], None),  # a material
        (["a", "red", "mug"], None),  # a colour
        (["a", "toy", "banana"], None),  # a generic noun
        (["a", "shiny", "mug"], None),  # a feature word
        (["a", "round", "plate"], None),  # an adjective
        (["my", "mug"], None),  # a pronoun
        (["30", "mug"], None),  # a number
    ],
)
def test_modifier_noun_each_condition(words, expected):
    assert modifier_noun(words, len(words) - 1) == expected


@pytest.mark.parametrize(
    ("modifier", "head", "phrases", "expected"),
    [
        ("wedding", "ring", KEYS, False),  # every name with the head is a compound on another noun
        ("key", "ring", KEYS, True),  # the modifier is a word of its names
        ("set", "ring", ("set of keys", "key ring"), True),  # ... of any of them
        ("travel", "mug", ("coffee mug", "plastic mug"), True),  # a name with the head and no noun modifier
        ("travel", "mug", ("coffee mug",), False),
        ("travel", "mug", ("mug",), True),  # the bare head
        ("soup", "spoon", ("teaspoon",), False),  # a compound word on the head
        ("tea", "spoon", ("teaspoon",), True),  # its prefix is the modifier
        ("water", "bottle", ("bottle of water",), True),
        ("beer", "bottle", ("bottle of water",), False),  # head before "of", with a noun after it
        ("steel", "bottle", ("stainless steel bottle",), True),
        ("wedding", "ring", ("ring 2",), True),  # a variant label is no modifier
    ],
)
def test_compound_agrees_each_condition(modifier, head, phrases, expected):
    assert compound_agrees(modifier, head, phrases) is expected


def test_a_wedding_ring_names_no_key_ring():
    result = seed().recall_text("a wedding ring")
    keys = seed().snapshot.names.index("bunch of keys")
    assert keys not in result.evidence.rows()
    assert not result.matches or result.confidence < 0.5


def test_a_key_ring_and_a_ring_still_name_the_keys():
    for text in ("a key ring", "a metal ring"):  # the whole alias; the bare head after a material
        result = seed().recall_text(text)
        assert result.matches[0].name == "bunch of keys", text


def test_a_compound_on_a_compound_names_head_names_no_object_and_the_bare_head_does():
    # every name of the tennis ball with the head "ball" is a compound on "tennis"
    names = seed().snapshot.names
    result = seed().recall_text("a kitchen ball")
    assert names.index("tennis ball") not in result.evidence.rows()
    plain = seed().recall_text("a ball")
    assert names.index("tennis ball") in plain.evidence.rows()


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("a glass", "glass"),
        ("A glass, 10 cm tall", "glass"),
        ("a glass of water", "glass"),
        ("a tall glass", "glass"),
        ("A small glass.", "glass"),
        ("glass, 10 cm tall", None),  # no article: a material
        ("made of glass", None),
        ("the glass", None),  # "the" does not count
        ("a glass bottle", "bottle"),  # the head is the bottle
        ("a glass and steel lamp", None),  # a material joined to another
        ("a glass-topped table", None),
    ],
)
def test_counted_head_each_condition(text, expected):
    assert counted_head(text) == expected


def test_a_glass_is_recalled_from_its_own_head_noun():
    result = seed().recall_text("a glass")
    assert "glass" in result.evidence.heads
    assert result.matches[0].name in {"drinking glass", "wine glass"}
    assert seed().recall_text("a glass of water").matches[0].name in {"drinking glass", "wine glass"}


def test_glass_as_a_material_names_no_glass():
    for text in ("glass, 10 cm tall", "a glass bottle", "made of glass, 300 g"):
        assert "glass" not in seed().recall_text(text).evidence.heads, text
