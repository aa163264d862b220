"""The kinds vocabulary (kb/kinds.py): hierarchy, every catalog object and lexicon noun placed, store names
in other languages given a kind and an English alias with provenance."""

from __future__ import annotations

import csv
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

from kb.kinds import ROOT, ancestors, assign_kind, kind_of_name, kinds, noun_in, nouns, title_words, words_of

REPO = Path(__file__).resolve().parents[1]
CATALOGS = (REPO / "kb" / "data" / "seed_catalog.csv", REPO / "tests" / "data" / "catalog2" / "catalog.csv")


def test_every_kind_reaches_the_root_and_every_noun_has_a_known_kind():
    table = kinds()
    assert {"fruit", "ball", "container", "cup", "bottle", "can", "tool", "utensil", "toy", "electronics",
            "stationery", "clothing"} <= set(table)  # fmt: skip
    for kind in table:
        assert ancestors(kind)[-1] == ROOT, kind
    for noun in nouns().values():
        assert noun.kind in table and ancestors(noun.kind)[-1] == ROOT


def test_every_catalog_object_has_a_kind():
    for path in CATALOGS:
        with path.open(encoding="utf-8") as fh:
            for row in csv.DictReader(fh):
                aliases = [a for a in (row.get("aliases") or "").split(";") if a]
                assert kind_of_name(row["name"], aliases) is not None, (path.name, row["name"])


def test_kind_of_a_name_uses_its_head_noun_and_plastic_fruit_is_a_toy():
    assert kind_of_name("tomato soup can") == "can"
    assert kind_of_name("bottle of water") == "bottle"
    assert kind_of_name("apple") == "fruit"
    assert kind_of_name("plastic banana") == "toy"
    assert kind_of_name("mini rubix cube") == "game"  # the longest lexicon phrase at the head wins
    assert kind_of_name("wood cube") == "material piece"
    assert kind_of_name("zorblax") is None
    assert kind_of_name("zorblax", ["coffee mug"]) == "cup"  # else an alias


def test_ancestors_walk_up_to_the_root():
    assert ancestors("fruit") == ["fruit", "food", "object"]
    assert ancestors("nonsense") == []


def test_store_names_in_other_languages_get_a_kind_and_an_english_alias():
    cases = {
        "caffettiera moka in alluminio 3 tazze": ("jug", "moka pot", "it"),
        "cafetera italiana de aluminio 6 tazas": ("jug", "moka pot", "es"),
        "théière en fonte": ("jug", "teapot", "fr"),
        "theiere en fonte": ("jug", "teapot", "fr"),  # typed without accents
        "Wasserkocher": ("jug", "electric kettle", "de"),
    }
    for title, (kind, english, lang) in cases.items():
        got = assign_kind(title)
        assert got is not None and (got.kind, got.english, got.lang) == (kind, english, lang), title
        assert got.provenance.startswith("title")


def test_an_english_title_needs_no_alias_and_a_synonym_gets_the_catalog_word():
    got = assign_kind("Stainless steel water bottle 750 ml")
    assert got is not None and got.kind == "bottle" and got.english is None
    got = assign_kind("Heavy duty spanner 10 mm")
    assert got is not None and got.kind == "hand tool" and got.english == "wrench"


def test_breadcrumbs_and_categories_when_the_title_says_nothing():
    got = assign_kind("Modell 4711 Deluxe", breadcrumbs=["Home", "Küche", "Wasserkocher"])
    assert got is not None and got.english == "electric kettle"
    assert got.provenance.startswith("breadcrumb: Wasserkocher")
    got = assign_kind("Modell 4711", categories=["Teekanne"], breadcrumbs=["Home", "Wasserkocher"])
    assert got is not None and got.english == "teapot" and got.provenance.startswith("category: Teekanne")
    assert assign_kind("Modell 4711", breadcrumbs=["Home", "Angebote"]) is None
    assert assign_kind("") is None


@given(st.text(max_size=60))
def test_words_and_nouns_never_fail_on_any_text(text):
    words = words_of(text)
    assert all(w == w.lower() for w in words)
    noun = noun_in(words)
    assert noun is None or noun.kind in kinds()
    got = assign_kind(text)
    assert got is None or got.kind in kinds()


# ------------------------------------------------------------------ titles against the store's filing
def test_brands_and_quoted_model_names_make_no_kind():
    assert title_words("APPLE iMac Pro 27 Retina") == ["imac", "pro", "27", "retina"]
    assert assign_kind("APPLE iMac Pro 27 Retina") is None  # "apple" only as a brand
    assert assign_kind("Apple iMac Pro 27 Retina").kind == "fruit"  # written as a word, it is one
    assert assign_kind("KÄRCHER Hochdruckreiniger »K 3 Full Control«") is None
    assert assign_kind("Hochdruckreiniger »K 3 Remote Control«") is None
    assert assign_kind("Hochdruckreiniger K 3 Remote Control").kind == "electronics"  # unquoted
    assert title_words("Lampe \u201eFull Control\u201c") == ["lampe"]
    # a title all in capitals keeps its words: there is nothing to tell a brand from
    assert assign_kind("STAINLESS STEEL WATER BOTTLE").kind == "bottle"
    assert title_words("AA battery") == ["battery"]


def test_the_category_trail_wins_when_it_disagrees_with_the_title():
    got = assign_kind("Apple crate, pine, 50 x 30 cm", breadcrumbs=["Home", "Garden", "Wasserkocher"])
    assert got.kind == "jug" and got.provenance.startswith("breadcrumb: Wasserkocher")
    assert got.provenance.endswith("over the title's 'apple'")  # the title alone says fruit
    assert assign_kind("Apple crate, pine, 50 x 30 cm").kind == "fruit"
    got = assign_kind("Apple crate, pine, 50 x 30 cm", categories=["Teekanne"], breadcrumbs=["Home", "Wasserkocher"])
    assert got.provenance.startswith("category: Teekanne")


def test_the_title_stays_when_the_trail_agrees_or_is_an_ancestor_or_says_nothing():
    # same kind: the title's (more specific) noun and alias stay
    got = assign_kind("caffettiera moka in alluminio 3 tazze", breadcrumbs=["Casa", "Teiera"])
    assert got.provenance.startswith("title") and got.english == "moka pot"
    # the trail's kind an ancestor of the title's
    title_kind = assign_kind("caffettiera moka").kind
    parent = kinds()[title_kind].parent
    parent_noun = next(n for n in nouns().values() if n.kind == parent)
    got = assign_kind("caffettiera moka", breadcrumbs=[parent_noun.text])
    assert got.provenance.startswith("title")
    # the trail names no noun
    assert assign_kind("caffettiera moka", breadcrumbs=["Home", "Angebote"]).provenance.startswith("title")


def test_a_light_is_no_tealight_and_a_control_no_tv_remote():
    got = assign_kind("Mercedes-Benz Left Side Tailgate Tail Light")
    assert got.kind == "lighting" and got.english is None  # no "tealight" alias for a car's lamp
    got = assign_kind("Tea light candles, unscented")
    assert got.kind == "lighting" and got.english == "tealight"
    assert assign_kind("Robot Limpiacristales, Control por App") is None
    assert assign_kind("Universal remote control").english == "tv remote"
