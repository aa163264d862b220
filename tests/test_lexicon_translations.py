"""Descriptions in other languages (issue 23): the household words of five languages read in English
(``kb/data/translations.csv``, :mod:`recall.translations`), and a description whose content words are
mostly read by no table is no close match (:mod:`recall.openset_words`)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from recallers import seed

from kb.kinds import singular
from recall.openset_words import MIN_UNREAD, UNREAD_CONFIDENCE, unread_words
from recall.translations import LANGUAGES, english_reading, english_words, table


@pytest.mark.parametrize(
    ("text", "language", "english"),
    [
        ("une tasse en céramique", "fr", "a cup made of ceramic"),
        ("eine Tasse aus Keramik, 9 cm hoch, 300 g", "de", "a cup made of ceramic, 9 cm tall, 300 g"),
        ("una taza de cerámica, 9 cm de alto", "es", "a cup of ceramic, 9 cm tall"),
        ("una ciotola di legno, 500 g", "it", "a bowl wooden, 500 g"),
        ("een kom van hout, ongeveer 20 cm breed", "nl", "a bowl of wood, about 20 cm wide"),
        ("une brosse à dents, 19 cm", "fr", "a toothbrush, 19 cm"),  # the longest phrase first
        ("KERAMIK", "de", "ceramic"),  # case and accents ignored
    ],
)
def test_each_language_reads_in_english(text, language, english):
    r = english_reading(text)
    assert (r.language, r.text) == (language, english)


@pytest.mark.parametrize(
    "text",
    ["a large bowl of wax, die 3 cm", "a casserole dish, 2 kg", "A big D cell, 6 cm long", "a vase, 20 cm"],
)
def test_english_text_is_unchanged(text):
    # words that are English too ("large", "die", "of", "casserole", "vase") are no evidence of a language
    assert english_reading(text).text == text and english_reading(text).language is None


def test_an_english_word_of_a_language_is_read_so_only_with_two_words_of_it():
    # French "large" is wide: read so when two words are French and no English ("une", "tasse"), not on one
    assert english_reading("une tasse large de 10 cm").text == "a cup wide of 10 cm"
    assert english_reading("a tasse, 10 cm large").text == "a cup, 10 cm large"


def test_every_english_reading_is_a_word_the_recall_reads():
    english = english_words()
    for lang in LANGUAGES:
        for target in table()[lang].values():
            assert all(w in english or singular(w) in english for w in target.split()), (lang, target)


_ENGLISH = sorted(w for w in english_words() if w.isalpha())


@settings(max_examples=60, deadline=None)
@given(st.lists(st.sampled_from(_ENGLISH) | st.from_regex(r"[0-9]{1,3} ?(cm|g)", fullmatch=True), max_size=8))
def test_english_words_alone_are_never_translated(words):
    text = " ".join(words)
    assert english_reading(text).text == text


def test_recall_of_a_french_and_a_german_cup():
    for text in ("une tasse en céramique", "eine Tasse aus Keramik, 9 cm hoch, 300 g"):
        r = seed().recall_text(text, top=3)
        assert r.matches[0].name == "coffee mug" and not r.open_set and r.read_as and r.translated
        assert r.text == text and r.to_dict()["read_as"] == r.read_as


def test_a_language_no_table_holds_is_no_close_match():
    r = seed().recall_text("uma caneca de cerâmica branca, 9 cm de altura", top=3)
    assert r.open_set and r.unread == ("uma", "caneca", "branca") and r.confidence <= UNREAD_CONFIDENCE
    assert "not read" in r.fit.reason and "caneca" in r.fit.reason


@pytest.mark.parametrize(
    ("text", "fires"),
    [
        ("upright, noisy, about 7 kg", False),  # two words not read: below MIN_UNREAD
        ("qwerty uiop asdf, 7 kg", True),  # three, every content word
        ("qwerty uiop asdf mug ceramic plastic", False),  # three of six: not more than half
        ("qwerty uiop asdf mug ceramic", True),  # three of five
    ],
)
def test_unread_boundaries(text, fires):
    assert MIN_UNREAD == 3
    assert bool(unread_words(text)) == fires


def test_a_word_the_catalog_names_hold_is_kept_not_translated():
    from recall.translations import english_reading

    assert english_reading("una sartén").text != "una sartén"  # translated without the catalog's word
    assert "sartén" in english_reading("una sartén", frozenset({"sartén"})).text
