"""A compound's modifier picks its head's sense (recall/synonyms.py ``senses``, ``SynonymPhrases.sense_rows``;
RECALL.md "Synonyms"): of the senses of a head noun in the synonym table and the kinds lexicon, the one
sense whose words hold the modifier wins; a modifier in no sense's words, in two senses' words or stating a
feature leaves the default reading."""

from __future__ import annotations

from pathlib import Path

from recallers import from_sizes

from kb.kinds import words_of
from recall.synonyms import SynonymPhrases, senses, synsets

YCB = Path(__file__).parent / "data" / "catalog_ycb" / "catalog.csv"


def _index(words: str) -> int:
    return next(i for i, s in enumerate(synsets()) if tuple(words.split()) in s)


def test_the_senses_of_a_head_noun():
    """The senses of "flipper": the spatula's synset (its nouns "egg flipper", "pancake flipper", its gloss's "kitchen
    turner") and the lexicon's swim fin (sports equipment); "turner" has one sense only: the lexicon's
    turner is the spatula (its English name a noun of that synset)."""
    flipper = {s.synset: s.words for s in senses()["flipper"]}
    assert set(flipper) == {_index("spatula"), None}
    assert {"kitchen", "pancake", "egg"} <= flipper[_index("spatula")]
    assert "flat" not in flipper[_index("spatula")]  # "with a flat blade": the blade's, not the turner's
    assert {"sport", "equipment"} <= flipper[None] and "kitchen" not in flipper[None]
    assert "turner" not in senses()
    assert all(len(ss) > 1 for ss in senses().values())


def test_the_modifier_picks_the_sense():
    phrases = SynonymPhrases({("spatula",): {0}, ("sink", "hose"): {1}})
    assert phrases[("kitchen", "flipper")] == {0}  # "kitchen" is only the spatula synset's
    assert phrases.get(("kitchen", "hose")) == {1}  # "kitchen sprayer": the sink hose's
    assert ("swim", "flipper") not in phrases  # in no sense's words: the default (the lexicon's swim fin)
    assert ("garden", "hose") not in phrases  # the lexicon's hose (a garden tool): the default
    assert ("kitchen", "flipper", "blade") not in phrases  # two-word compounds only


def test_a_modifier_of_two_senses_or_stating_a_feature_leaves_the_default():
    phrases = SynonymPhrases({tuple(words_of("phillips screwdriver")): {0}, ("windex", "bottle"): {1}})
    # "head" is in both screwdriver synsets ("cross-head", "flat-head"): which one it is not said
    assert ("cross", "screwdriver") in phrases and ("flat", "screwdriver") not in phrases
    assert ("head", "screwdriver") not in phrases
    # "glass" is in the glass cleaner's words ("glass cleaner bottle"), but a material says what a bottle
    # is made of, not which bottle
    assert ("cleaner", "bottle") in phrases and ("glass", "bottle") not in phrases


def test_a_sense_the_catalog_lacks_names_nothing():
    phrases = SynonymPhrases({("hammer",): {0}})
    assert ("kitchen", "flipper") not in phrases


def test_a_kitchen_flipper_is_the_spatula_of_a_real_catalog(tmp_path):
    """YCB (real sizes and masses) holds a spatula and no swim fin: "kitchen flipper" was "no 'flipper'
    in the catalog" (the lexicon's flipper is sports equipment)."""
    from recall.engine import Recaller

    r = Recaller.from_csv(YCB)
    res = r.recall_text("a kitchen flipper, nylon, 33 cm long, 50 g")
    assert res.matches[0].name == "spatula" and not res.open_set
    assert res.fit.reason.endswith("named)")
    assert r.recall_text("a swim flipper, rubber, 60 cm long, 700 g").open_set
    small = from_sizes(tmp_path / "c.csv", [("spatula", 33, 8, 3, 50), ("flipper", 60, 20, 3, 700)])
    assert small.recall_text("a kitchen flipper, 33 cm long").matches[0].name == "spatula"
    assert small.recall_text("a swim flipper, 60 cm long").matches[0].name == "flipper"
