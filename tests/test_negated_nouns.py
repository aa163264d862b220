"""Negated nouns (blind-test finding): a noun phrase the description negates ("not a mug") is no name and
no subject, with the parser's negation scope for values (PARSER.md, "Negated values")."""

from __future__ import annotations

import pytest
from recallers import seed

from recall.subject import negated_spans, negated_words, subject_phrase


@pytest.mark.parametrize(
    ("text", "negated"),
    [
        ("not a mug , a glass", "mug"),  # an article after the negation starts the phrase ...
        ("it is not a coffee mug but a glass", "coffee mug"),  # ... to "but"
        ("it isnt really the cup", "cup"),  # gap words before the article
        ("no mug", "mug"),  # determiner-like negations need no article
        ("a jar without a lid", "lid"),
        ("neither a mug nor a cup", "mug cup"),
        ("not heavy ceramic mug", ""),  # no article: the negation is the adjective's
        ("a non slip mat", ""),  # "non" negates a word, not a phrase
        ("hardly a mug", ""),
        ("not a mug and a glass", "mug"),  # "and" ends it
        ("not a 10 cm mug", ""),  # a number ends it (the value's own negation is the parser's)
        ("not quite the cup", "cup"),
    ],
)
def test_negated_words_each_condition(text, negated):
    words = text.split()
    assert " ".join(words[i] for i in sorted(negated_words(words))) == negated


def test_negated_spans_are_character_spans_of_the_text():
    text = "Not a mug, it's a glass"
    assert [text[a:b] for a, b in negated_spans(text)] == ["mug"]
    text = "It isn’t a Coffee Mug."
    assert [text[a:b] for a, b in negated_spans(text)] == ["Coffee", "Mug"]


@pytest.mark.parametrize(
    ("text", "subject"),
    [
        ("not a mug, a glass", ("glass",)),
        ("it is not a mug but a glass", ("glass",)),
        ("Not a mug. A glass.", ("glass",)),  # every phrase of the first sentence negated: the next one
        ("a mug, not a glass", ("mug",)),
        ("a jar without a lid", ("jar",)),
        ("a mug with no handle", ("mug",)),
        ("not very heavy ceramic mug", ("heavy", "ceramic", "mug")),
    ],
)
def test_a_negated_phrase_is_no_subject(text, subject):
    assert subject_phrase(text) == subject


def test_not_a_mug_names_no_mug():
    names = seed().snapshot.names
    result = seed().recall_text("not a mug")
    assert names.index("coffee mug") not in result.evidence.rows()
    assert not result.matches or result.confidence < 0.5


def test_not_a_mug_a_glass_is_a_glass():
    names = seed().snapshot.names
    for text in ("not a mug, a glass", "It is not a mug but a glass.", "Not a mug. A glass."):
        result = seed().recall_text(text)
        assert names.index("coffee mug") not in result.evidence.rows(), text
        assert result.matches[0].name in {"drinking glass", "wine glass"}, text


def test_the_named_object_before_a_negated_one_is_still_named():
    result = seed().recall_text("a mug, not a glass")
    assert result.matches[0].name == "coffee mug"
    assert "mug" in result.named or "mug" in result.evidence.heads
