"""Count words: one table (kb.measures.words.COUNT_WORDS) that the set reader (scrapers.sets) uses, every word
of it read as its count in each language's set wording."""

from __future__ import annotations

import pytest

from kb.measures.words import COUNT_WORDS, NUMBER_WORDS, count_words
from scrapers import sets
from scrapers.sets import set_size

#: A product name selling a set, per language, with {w} the count word.
SET_NAMES = {
    "en": "Stoneware mugs, set of {w}",
    "de": "Kaffeetassen, {w} Stück",
    "fr": "Bols en grès, lot de {w}",
    "es": "Tazas, juego de {w}",
    "it": "Tazze, confezione da {w}",
}


def test_every_language_has_a_set_wording():
    assert set(SET_NAMES) == set(COUNT_WORDS)


@pytest.mark.parametrize(
    ("lang", "word", "count"),
    [(lang, word, count) for lang, table in COUNT_WORDS.items() for word, count in table.items()],
)
def test_every_count_word_reads_as_its_count(lang: str, word: str, count: int):
    assert set_size(SET_NAMES[lang].format(w=word)) == (count, SET_NAMES[lang].format(w=word).split(", ")[-1])


def test_capitalised_words_count_too():
    assert set_size("Mugs, Set of Seven")[0] == 7 and set_size("Tassen, Fünf Stück")[0] == 5


@pytest.mark.parametrize("word", ["one", "zero", "couple", "neuf", "a"])
def test_words_that_are_no_count_of_two_or_more_give_no_set(word: str):
    assert set_size(f"Stoneware mugs, set of {word}") is None


def test_english_counts_are_the_number_words_from_two_up():
    assert COUNT_WORDS["en"] == {w: v for w, v in NUMBER_WORDS.items() if v >= 2 and w != "couple"}
    assert (
        COUNT_WORDS["en"]["twelve"] == 12
        and COUNT_WORDS["en"]["dozen"] == 12
        and "one" not in COUNT_WORDS["en"]
    )


def test_one_merged_table_without_conflicts_is_what_the_set_reader_uses():
    merged = count_words()
    assert merged["six"] == 6  # English and French share it
    assert sets._COUNT_WORDS == merged
    tables = [k for k, v in vars(sets).items() if isinstance(v, dict) and not k.startswith("__")]
    assert tables == ["_COUNT_WORDS"], "scrapers.sets keeps no word table of its own"
