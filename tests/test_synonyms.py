"""Synonyms of catalog names (recall/synonyms.py, kb/data/synonyms.csv, RECALL.md "Synonyms"): a synset
names the catalog's object by each of its nouns, never two objects of one catalog; a closed compound
names the open one and back."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from recallers import CATALOG2_CSV, SEED_CSV, from_sizes

from kb.kinds import words_of
from recall.names import tables_by_rules
from recall.synonyms import MIN_PART, SynonymPhrases, synsets

DATA = Path(__file__).parent / "data"
CATALOGS = [SEED_CSV, CATALOG2_CSV, DATA / "catalog_ycb" / "catalog.csv", DATA / "catalog_yale" / "catalog.csv"]


def _phrases(csv_path: Path) -> dict:
    with csv_path.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.DictReader(fh))
    names = [r["name"] for r in rows]
    aliases = [[a for a in (r.get("aliases") or "").split(";") if a.strip()] for r in rows]
    return tables_by_rules(names, aliases, None, 3).phrases


@pytest.mark.parametrize("catalog", CATALOGS, ids=lambda p: p.parent.name)
def test_no_synset_merges_two_objects_of_a_catalog(catalog):
    """Every synset's nouns that are names or aliases of the catalog name one and the same object (set of
    rows): a synset that names two different objects would merge distinct kinds."""
    phrases = _phrases(catalog)
    for synset in synsets():
        named = {frozenset(phrases[p]) for p in synset if p in phrases}
        assert len(named) <= 1, (catalog.parent.name, sorted(" ".join(p) for p in synset))


def test_a_noun_is_in_one_synset_only():
    seen: dict[tuple[str, ...], frozenset] = {}
    for synset in synsets():
        for noun in synset:
            assert noun not in seen, " ".join(noun)
            seen[noun] = synset


def test_a_synonym_names_the_catalog_object(tmp_path):
    r = from_sizes(tmp_path / "c.csv", [("allen wrench", 9, 1, 0.6, 15), ("trash can", 60, 38, 28, 4000)])
    assert r.names.find("a hex key, 9 cm long").exact == {0: pytest.approx(0.6931, abs=1e-3)}
    assert set(r.names.find("kitchen wastebasket with a lid").exact) == {1}
    assert r.names.find("kitchen wastebasket with a lid").phrases == ("wastebasket",)
    res = r.recall_text("an allen key, 9 cm long, 15 g")
    assert res.matches[0].name == "allen wrench" and not res.open_set
    assert res.fit.reason.endswith("named)")


def test_a_synset_naming_two_objects_names_none(tmp_path):
    """The catalog holds "trash can" and "dustbin" as two objects: the synset cannot say which one a
    "wastebasket" is, so it names neither (each still names itself)."""
    r = from_sizes(tmp_path / "c.csv", [("trash can", 60, 38, 28, 4000), ("dustbin", 30, 30, 30, 900)])
    assert r.names.find("a wastebasket").exact == {}
    assert set(r.names.find("a dustbin").exact) == {1}


def test_closed_compound_names_the_open_one_and_back():
    base = {("head", "band"): {0}, ("toothbrush",): {1}, ("tv", "stand"): {2}, ("pen", "cup"): {3}}
    phrases = SynonymPhrases(base)
    assert phrases[("headband",)] == {0}
    assert phrases[("tooth", "brush")] == {1}
    assert ("pencup",) in phrases  # parts of MIN_PART letters
    assert MIN_PART == 3 and ("tvstand",) not in phrases  # "tv" is shorter than MIN_PART
    assert ("headbands",) not in phrases  # words are singular before the look-up (words_of)
    assert phrases.get(tuple(words_of("headbands"))) == {0}
    with pytest.raises(KeyError):
        phrases[("hat",)]


def test_a_closed_compound_of_a_catalog_name_is_no_unknown_noun(tmp_path):
    r = from_sizes(tmp_path / "c.csv", [("head band", 20, 18, 2, 30), ("mug", 10, 8, 8, 300)])
    assert r.names.unknown_noun("a headband, 20 cm across") is None
    assert r.names.unknown_noun("a flyswatter, 33 cm long") == "flyswatter"
    assert set(r.names.find("a headband, 20 cm across").exact) == {0}


def test_a_synonym_holds_its_own_modifier(tmp_path):
    """The modifier of a synonym the text names the object by ("cross-head" of "cross-head screwdriver")
    is no foreign modifier of that object; a modifier no phrase naming it holds still doubts the match."""
    r = from_sizes(tmp_path / "c.csv", [("phillips screwdriver", 20, 3, 3, 100), ("hammer", 33, 13, 3, 600)])
    named = r.recall_text("a cross-head screwdriver, 30 cm long, 100 g")  # closeness 0.17
    assert named.matches[0].name == "phillips screwdriver" and not named.open_set
    assert named.fit.reason.endswith("named)")
    # the same words without the synonym phrase found: "head" is foreign to the object's own names
    import dataclasses

    from recall.openset_verdict import foreign_modifier_of
    from recall.subject import noun_phrase

    text = "a cross-head screwdriver, 30 cm long, 100 g"
    found = r.names.find(text)
    assert found.phrases == ("cross head screwdriver",)
    assert foreign_modifier_of(r, noun_phrase(text), 0, found) is None
    assert foreign_modifier_of(r, noun_phrase(text), 0, dataclasses.replace(found, phrases=())) == "head"
