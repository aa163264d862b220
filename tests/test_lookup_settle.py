"""When a store's search stops reading results (scrapers.lookup, issue 22): a page that fits with a score
at most SETTLED_ERROR settles it; a looser fit (a sibling of the described product) reads the next batch,
whose closer fit wins; a results page is asked for only when its products are wanted. The store is the
demo store on 127.0.0.1 with products written here; the catalog a real DuckDB file; the fit the real one."""

from __future__ import annotations

import pytest
from conftest import SEED_CSV

from kb.catalog import KnowledgeBase
from kb.features import ObjectRecord
from recall.lookup import fits, recall_with_lookup
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import P
from scrapers.demo_store.search import PAGE_SIZE
from scrapers.lookup import MAX_RESULT_BATCHES, SETTLED_ERROR
from scrapers.sources import parse_sources

TEXT = "a camping lantern weighing 1000 g"


def gadget(letter: str, mass_g: float):
    return P(f"camping-lantern-{letter}", "jsonld", "en", f"Camping Lantern {letter.upper()}", (20.0, 10.0, 5.0), "cm",
             mass_g, "g", "plastic", "plastic")  # fmt: skip


@pytest.fixture
def db(tmp_path):
    path = tmp_path / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(SEED_CSV)
    return path


def test_the_fit_score_is_the_mean_error_over_what_the_page_states():
    assert fits(TEXT, ObjectRecord.create("camping lantern a", mass_g=950))[2] == SETTLED_ERROR  # 50 / 1000
    assert fits(TEXT, ObjectRecord.create("camping lantern a", mass_g=949))[2] > SETTLED_ERROR
    assert MAX_RESULT_BATCHES >= 2


@pytest.mark.parametrize(("sibling_g", "settled"), [(950, True), (949, False)])
def test_a_loose_fit_reads_the_next_results_and_the_closer_fit_wins(db, sibling_g, settled):
    # results, by title: A (the sibling), B, C, D (3 kg: no fit) on the first page, E (1000 g) on the second
    products = (gadget("a", sibling_g), *(gadget(x, 3000) for x in "bcd"), gadget("e", 1000))
    with DemoStore(crawl_delay=None, search_only=products) as store:
        text = (f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\n'
                f'search = "{{base_url}}/search?q={{query}}"\nsearch_results = {PAGE_SIZE}\n')  # fmt: skip
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        out = recall_with_lookup(db, TEXT, sources=sources)
    assert out.looked_up and out.found, out.message
    (answer,) = out.stores.stores
    if settled:  # the sibling is within SETTLED_ERROR: one batch, one results page
        assert len(answer.search_pages) == 1 and len(answer.product_pages) == PAGE_SIZE
        assert out.stores.new_objects == ["camping lantern a"] and out.result.best.name == "camping lantern a"
    else:  # the next batch, on the next results page, holds the closer fit
        assert len(answer.search_pages) == 2 and len(answer.product_pages) == PAGE_SIZE + 1
        assert sorted(out.stores.new_objects) == ["camping lantern a", "camping lantern e"]
        assert out.result.best.name == "camping lantern e"


# --- the next search words when no page of the first fits ----------------------------------------------

FEEDER = "a smart bird feeder, about 600 g"


def feeder(handle: str, title: str, mass_g: float):
    return P(handle, "jsonld", "en", title, (23.0, 15.0, 15.0), "cm", mass_g, "g", "plastic", "plastic")


@pytest.mark.parametrize("mount_g", [600, 50])
def test_the_next_search_words_are_asked_only_when_no_page_of_the_first_fits(db, mount_g):
    # "smart bird feeder" (every word, as this store searches) lists only the camera mount; "bird feeder"
    # lists the feeder as well: asked when the mount (50 g) does not fit, not when it (600 g) does
    products = (feeder("smart-bird-feeder-mount", "Smart Bird Feeder Camera Mount", mount_g),
                feeder("bird-feeder-pro", "Bird Feeder Pro", 600))  # fmt: skip
    with DemoStore(crawl_delay=None, search_only=products) as store:
        text = (f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\n'
                f'search = "{{base_url}}/search?q={{query}}"\nsearch_results = 3\n')  # fmt: skip
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        out = recall_with_lookup(db, FEEDER, sources=sources)
    (answer,) = out.stores.stores
    assert out.looked_up and out.found, out.message
    assert out.stores.query[:2] == ("smart bird feeder", "bird feeder")
    if mount_g == 600:
        assert answer.queries == ["smart bird feeder"] and len(answer.product_pages) == 1
        assert out.result.best.name == "smart bird feeder camera mount"
    else:  # the mount read once, not again for the second words
        assert answer.queries == ["smart bird feeder", "bird feeder"] and len(answer.product_pages) == 2
        assert out.result.best.name == "bird feeder pro"
