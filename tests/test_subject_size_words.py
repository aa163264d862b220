"""Size words are never the subject (blind-test finding: "a ball between 6 and 7 cm" was "not in the
catalog: no 'between'"): a hedge, a range word or a dimension noun ends the subject phrase."""

from __future__ import annotations

import pytest
from recallers import seed

from recall import lexicon as lx
from recall.subject import subject_phrase

RANGE_WORDS = sorted(w for w, tag in lx.FUNCTION_WORDS.items() if tag == "BETW")


@pytest.mark.parametrize(
    "hedge", sorted(h for h in lx.HEDGES if h.replace(".", "").replace(" ", "").isalpha())
)
def test_no_hedge_of_the_lexicon_becomes_the_subject(hedge):
    assert subject_phrase(f"a ball {hedge} 7 cm wide") == ("ball",)


@pytest.mark.parametrize("word", RANGE_WORDS)
def test_no_range_word_becomes_the_subject(word):
    assert subject_phrase(f"a ball {word} 6 to 7 cm") == ("ball",)


@pytest.mark.parametrize(
    ("text", "subject"),
    [
        ("a ball between 6 and 7 cm", ("ball",)),
        ("A ball ~7 cm", ("ball",)),
        ("a ball bigger than an orange", ("ball",)),  # a multi-word hedge
        ("a ball diameter 7 cm", ("ball",)),  # a dimension noun ending its chunk
        ("a box height is 10 cm", ("box",)),  # ... or before a phrase end
        ("a side table", ("side", "table")),  # a dimension noun before a noun is a modifier
        ("a little ball", ("ball",)),
        ("a glass measuring cup", ("glass", "measuring", "cup")),  # a compound, not the verb
    ],
)
def test_size_words_end_the_subject_phrase(text, subject):
    assert subject_phrase(text) == subject


def test_a_ball_between_6_and_7_cm_is_a_ball_of_the_catalog():
    result = seed().recall_text("a ball between 6 and 7 cm")
    assert result.unknown_noun is None and not result.not_in_catalog and not result.open_set
    assert "ball" in result.matches[0].name
    assert result.matches[0].features["a_cm"] == pytest.approx(6.5, abs=0.6)
