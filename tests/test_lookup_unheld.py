"""A described noun no catalog row holds (recall.unheld, issue 22): a generic noun after a noun the catalog's
names never use ("an RF development kit") is not in the catalog, so the open-set verdict says so and the
store lookup is asked; a category word after a place word ("an office gadget") still names a kind. The
store is the demo store on 127.0.0.1 with a product written here; the catalog a real DuckDB file."""

from __future__ import annotations

import pytest
from conftest import SEED_CSV

from kb.catalog import KnowledgeBase
from recall.engine import Recaller
from recall.lookup import lookup_reason, recall_with_lookup
from recall.names import GENERIC_NOUNS
from recall.unheld import COLLECTIONS, unheld_pair
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import P
from scrapers.sources import parse_sources

VOCABULARY = frozenset({"tennis", "ball", "stapler", "mailing", "tube"})
PHRASES = {("tennis", "ball"): [0], ("stapler",): [1], ("tube",): [2]}
KIT = "an RF development kit from Analog Devices, about 400 g"
KIT_TITLE = "DC2645A RF Development Kit"


def pair(*words: str, phrases=PHRASES) -> str | None:
    return unheld_pair(words, VOCABULARY, phrases, GENERIC_NOUNS)


def test_a_collection_after_a_noun_the_catalog_lacks_is_an_object_it_lacks():
    assert COLLECTIONS <= GENERIC_NOUNS
    assert pair("rf", "development", "kit") == "development kit"
    assert pair("chess", "set") == "chess set"
    assert pair("plush", "dinosaur", "toy") == "dinosaur toy"  # a lexicon generic noun, as before


@pytest.mark.parametrize(
    "words",
    [
        ("office", "gadget"),  # a category word outside the lexicon and no collection: still a kind
        ("tennis", "kit"),  # the word before it is a catalog word
        ("tool", "set"),  # ... or itself generic
        ("something", "kit"),  # ... or a placeholder
        ("red", "kit"),  # ... or no noun (a colour)
        ("plastic", "kit"),  # (a material)
        ("kit",),  # no word before it
        ("development", "stapler"),  # no generic noun
    ],
)
def test_no_unheld_pair(words):
    assert pair(*words) is None


def test_a_generic_noun_a_catalog_object_is_called_by_alone_is_a_sort_of_it():
    assert pair("sewing", "kit") == "sewing kit"
    assert pair("sewing", "kit", phrases={**PHRASES, ("kit",): [3]}) is None


@pytest.fixture(scope="module")
def recaller():
    return Recaller.from_csv(SEED_CSV)


def test_the_open_set_verdict_and_the_lookup_read_the_same_noun(recaller):
    result = recaller.recall_text(KIT)
    assert result.not_in_catalog and result.open_set
    assert result.described.noun == "development kit" and not result.described.in_catalog
    assert "development kit" in lookup_reason(result)
    gadget = recaller.recall_text("A heavy metal office gadget, maybe 18 cm long, 6 cm wide and 5 cm tall, 300 g.")
    assert gadget.best.name == "stapler" and not gadget.not_in_catalog and not gadget.open_set


@pytest.fixture
def db(tmp_path):
    path = tmp_path / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(SEED_CSV)
    return path


def test_the_kit_only_a_store_sells_is_looked_up_and_recalled(db, tmp_path):
    kit = P("rf-development-kit", "jsonld", "en", KIT_TITLE, (17.0, 12.0, 4.0), "cm", 402, "g", "other",
            "circuit board in a plastic case")  # fmt: skip
    with DemoStore(crawl_delay=None, search_only=(kit,)) as store:
        text = f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\nsearch = "{{base_url}}/search?q={{query}}"\n'
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        out = recall_with_lookup(db, KIT, sources=sources)
    assert out.looked_up and out.found, out.message
    assert out.stores.new_objects == [out.result.best.name] and "development kit" in out.result.best.name
    assert not out.result.open_set and out.result.best.features["mass_g"] == 402
