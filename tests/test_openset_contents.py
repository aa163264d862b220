"""Contents of a container (recall/contents.py): where the catalog names every object of a container noun
by what it holds, a container of other contents is not in the catalog; contents a name has, a container
the catalog also holds plainly, or no "<container> of" at all keep the old rules. Catalogs written here,
each condition pinned on its own."""

from __future__ import annotations

import pytest
from recallers import from_sizes

from recall.contents import foreign_contents
from recall.engine import Recaller
from recall.subject import noun_phrase

BY_CONTENTS = [
    ("cracker box", 21, 16, 7, 411), ("tissue box", 24, 12, 9, 250), ("mustard bottle", 19, 9, 6, 600),
    ("roll of tape", 11, 11, 5, 300), ("hammer", 33, 13, 3, 600), ("cereal box", 30, 20, 7, 500),
]  # fmt: skip
PLAIN = [*BY_CONTENTS, ("small bottle", 11, 3, 3, 120), ("plastic box", 20, 15, 10, 300)]


@pytest.fixture(scope="module")
def catalogs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("contents")
    return from_sizes(tmp / "a.csv", BY_CONTENTS), from_sizes(tmp / "b.csv", PLAIN)


def _contents(recaller: Recaller, text: str) -> str | None:
    import re

    from recall.subject import subject_phrase

    subject = noun_phrase(text)
    m = re.search(rf"\b{subject[-1]}s?\s+of\s+(.*)", text.lower())
    return foreign_contents(text, subject, subject_phrase(m.group(1)) if m else (), recaller.names)


def test_other_contents_of_a_container_held_only_by_its_contents_are_not_in_the_catalog(catalogs):
    by_contents, _ = catalogs
    assert _contents(by_contents, "a box of Cheerios, 28 x 19 x 7 cm, 340 g") == "cheerio box"
    assert _contents(by_contents, "a roll of toilet paper, 11 cm across") == "toilet paper roll"
    assert _contents(by_contents, "a bottle of ketchup, 20 cm tall") == "ketchup bottle"
    result = by_contents.recall_text("a box of Cheerios, 21 x 16 x 7 cm, 411 g", top=3)
    assert result.open_set and result.not_in_catalog  # the cracker box's own sizes: still another box


def test_contents_a_name_holds_stay_in_the_catalog(catalogs):
    by_contents, _ = catalogs
    assert _contents(by_contents, "a box of Kleenex tissues, 24 x 12 x 9 cm") is None  # "tissue box"
    assert _contents(by_contents, "a box of crackers, 21 cm") is None
    # the lexicon's "cornflakes box" has the English name "cereal box", a catalog name
    assert _contents(by_contents, "a box of cornflakes, 30 by 20 by 7 cm") is None
    result = by_contents.recall_text("a box of crackers, 21 x 16 x 7 cm, 411 g", top=3)
    assert result.matches[0].name == "cracker box" and not result.open_set


def test_a_plainly_held_container_or_no_container_keeps_the_old_rules(catalogs):
    by_contents, plain = catalogs
    assert _contents(plain, "a bottle of ketchup, 20 cm tall") is None  # "small bottle": any bottle
    assert _contents(plain, "a box of Cheerios, 28 x 19 x 7 cm") is None  # "plastic box": any box
    assert _contents(by_contents, "a Cheerios box, 28 x 19 x 7 cm") is None  # no "box of"
    assert _contents(by_contents, "a hammer of steel, 33 cm") is None  # no container noun
    assert _contents(by_contents, "a can of Cheerios, 12 cm") is None  # no catalog object of "can"


CANS = [("potted meat can", 10, 10, 6, 370), ("chips can", 24, 8, 8, 205), ("trash can", 60, 38, 28, 4000)]


def test_a_can_after_an_article_is_the_subject_not_a_request():
    """ "can" is a request word ("can you find the hammer"), but never after an article: "a can of WD-40"
    is a can, whose contents the contents rule judges."""
    assert noun_phrase("a can of WD-40, 18 cm tall, 11 oz") == ("can",)
    assert noun_phrase("the can of paint, 1 litre") == ("can",)
    assert noun_phrase("can you find the hammer, 300 g") == ("hammer",)


def test_contents_named_by_a_synonym_or_the_lexicon_stay_in_the_catalog(tmp_path):
    r = from_sizes(tmp_path / "cans.csv", CANS)
    # "potato crisps can" (no lexicon noun) is a synonym of the catalog's "chips can" (kb/data/synonyms.csv)
    assert _contents(r, "a can of potato crisps, 25 cm tall") is None
    # the lexicon's "spam" has the English name "potted meat can", a catalog name on "can"
    assert _contents(r, "a can of Spam, 10 cm long, 12 ounces") is None
    assert not r.recall_text("a can of Spam, 10 x 10 x 6 cm, 370 g").open_set
    # contents no name, synonym or lexicon noun holds: another can
    assert _contents(r, "a can of WD-40, 5 cm across, 18 cm tall, 11 oz") == "wd can"
    assert r.recall_text("a can of WD-40, 24 x 8 x 8 cm, 205 g").open_set
