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


# A word that is an amount word only as the start of a hedge of several words ("lighter" of "lighter
# than"), counted by an indefinite article and alone in its chunk, is a noun: "a lighter, Bic, 20 g".
@pytest.mark.parametrize(
    ("text", "subject"),
    [
        ("a lighter, Bic, 8 x 2.5 x 1.2 cm, 20 g", ("lighter",)),
        ("A lighter. 20 g", ("lighter",)),
        ("lighter, 20 g", ("g",)),  # no article: the comparative of a list of features, as before
        ("the lighter, 20 g", ("g",)),  # only an indefinite article counts it
        ("a lighter than usual pen, 20 g", ("than", "usual", "pen")),  # not alone in its chunk: as before
        ("a mug, lighter than 300 g", ("mug",)),
        ("a half, 20 g", ("g",)),  # a fraction is an amount whatever counts it
    ],
)
def test_a_counted_hedge_start_alone_is_a_noun(text, subject):
    assert subject_phrase(text) == subject


def test_a_lighter_is_not_in_a_catalog_without_one(tmp_path):
    from recallers import from_sizes

    r = from_sizes(tmp_path / "c.csv", [("allen wrench", 8, 2.5, 1.2, 20), ("mug", 10, 8, 8, 300)])
    res = r.recall_text("a lighter, Bic, 8 x 2.5 x 1.2 cm, 20 g")
    assert res.open_set and res.described.noun == "lighter" and not res.described.in_catalog
    assert not r.recall_text("an allen wrench, 8 x 2.5 x 1.2 cm, 20 g").open_set
