"""On-demand lookup (recall.lookup, scrapers.lookup): demo stores over real HTTP on 127.0.0.1 -> a real
DuckDB catalog, and recall again."""

from __future__ import annotations

import json
import shutil
import time
from pathlib import Path

import pytest
import requests
from conftest import SEED_CSV

from kb.catalog import KnowledgeBase
from kb.errors import RecallError
from kb.features import ObjectRecord
from recall.engine import Recaller
from recall.lookup import FIT_CLOSENESS, NOT_FOUND, fits, lookup_reason, recall_with_lookup, search_terms
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import SEARCH_ONLY_PRODUCTS, P
from scrapers.sources import parse_sources

TEAPOT = "A glazed ceramic teapot about 22 cm wide and 14 cm tall, it weighs around 900 grams."
TEAPOT_NAME = "glazed ceramic teapot 1.2 l"
HIPPO = "a purple velvet hippo 40 cm long"


def sources(*stores: DemoStore, search: str = "{base_url}/search?q={query}"):
    text = "[defaults]\ndelay_s = 0\nread_timeout_s = 5\nmax_retries = 1\n"
    for i, store in enumerate(stores):
        text += f'[[stores]]\nname = "store{i}"\nbase_url = "{store.base_url}"\nsearch = "{search}"\n'
    return parse_sources(text, origin="lookup-sources.toml")


_TEMPLATE: dict[str, Path] = {}


@pytest.fixture
def db(tmp_path_factory, tmp_path) -> Path:
    """A copy of a seeded catalog (imported once per module)."""
    if "seed" not in _TEMPLATE:
        template = tmp_path_factory.mktemp("seed") / "seed.duckdb"
        KnowledgeBase.open(template).import_csv(SEED_CSV)
        _TEMPLATE["seed"] = template
    path = tmp_path / "catalog.duckdb"
    shutil.copy(_TEMPLATE["seed"], path)
    return path


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None) as s:
        yield s


def dump(db: Path) -> dict[str, list[tuple]]:
    with KnowledgeBase.open(db).connect() as con:
        return {
            t: con.execute(f"SELECT * FROM {t} ORDER BY ALL").fetchall()
            for t in ("objects", "object_aliases", "observations", "pages", "ingestion_runs", "page_events")
        }


def test_an_object_only_the_store_sells_is_recalled_after_a_lookup(db, store):
    before = Recaller.from_db(db).recall_text(TEAPOT)
    assert before.best.name != TEAPOT_NAME and lookup_reason(before) is not None
    result = recall_with_lookup(db, TEAPOT, sources=sources(store))
    assert result.looked_up and result.found
    assert result.result.best.name == TEAPOT_NAME and not result.result.open_set
    assert result.after.confidence > result.before.confidence
    assert result.stores.new_objects == [TEAPOT_NAME]
    assert TEAPOT_NAME in result.message and "store0" in result.stores.answered
    added = [c for c in result.stores.candidates if c.outcome == "added"]
    assert [c.name for c in added] == [TEAPOT_NAME]
    # provenance: a lookup run recording the query and the description; provisional observations
    with KnowledgeBase.open(db).connect() as con:
        (sources_col,) = con.execute("SELECT sources FROM ingestion_runs").fetchone()
        adapters = {a for (a,) in con.execute("SELECT DISTINCT adapter FROM observations WHERE run_id = 1").fetchall()}
    assert sources_col.startswith("lookup ")
    meta = json.loads(sources_col[len("lookup ") :])
    assert meta["description"] == TEAPOT and meta["query"][0] == "glazed ceramic teapot"
    assert adapters == {"lookup:jsonld"}
    obj = KnowledgeBase.open(db).get_object(TEAPOT_NAME)
    assert (obj.a_cm, obj.b_cm, obj.c_cm, obj.mass_g) == (22.0, 15.0, 14.0, 900.0)


def test_an_object_neither_has_is_not_found_in_the_catalog_or_the_stores(db, store):
    before = dump(db)
    result = recall_with_lookup(db, HIPPO, sources=sources(store))
    assert result.looked_up and not result.found
    assert result.message.startswith(NOT_FOUND)
    assert result.stores.stores[0].status == "no_results"
    assert result.stores.stores[0].queries == ["purple velvet hippo", "hippo"]
    assert dump(db) == before


def test_the_same_lookup_twice_changes_nothing(db, store):
    first = recall_with_lookup(db, TEAPOT, sources=sources(store))
    assert first.found
    after_first = dump(db)
    again = recall_with_lookup(db, TEAPOT, sources=sources(store))
    assert not again.looked_up and again.result.best.name == TEAPOT_NAME  # recalled from the catalog now
    forced = recall_with_lookup(db, TEAPOT, sources=sources(store), force=True)
    assert forced.looked_up and forced.found and forced.why == "forced"
    assert [(c.outcome, c.name) for c in forced.stores.candidates] == [("known", TEAPOT_NAME)]
    assert dump(db) == after_first


def test_a_result_that_does_not_fit_is_read_but_not_added(db, store):
    text = "a teapot, about 22 cm wide and 14 cm tall, about 900 g, ceramic"
    result = recall_with_lookup(db, text, sources=sources(store))
    by_name = {c.name: c for c in result.stores.candidates}
    assert by_name["cast iron teapot 0.9 l"].outcome == "does_not_fit"
    assert by_name[TEAPOT_NAME].outcome == "added"
    assert result.stores.new_objects == [TEAPOT_NAME]
    names = {o.name for o in KnowledgeBase.open(db).list_objects()}
    assert "cast iron teapot 0.9 l" not in names


@pytest.mark.parametrize(
    ("kind", "reason"),
    [("slow", "timeout"), ("http_500", "http_500"), ("robots", "robots_disallowed")],
)
def test_a_failing_store_is_skipped_with_its_reason_within_the_budget(db, store, kind, reason):
    options = {"disallow_search": True} if kind == "robots" else {"search_fault": kind}
    with DemoStore(crawl_delay=None, slow_s=20.0, **options) as bad:
        t0 = time.monotonic()
        result = recall_with_lookup(db, TEAPOT, sources=sources(bad, store), budget_s=4.0)
        elapsed = time.monotonic() - t0
    skipped, good = result.stores.stores
    assert skipped.status == "skipped" and reason in skipped.reason
    assert f"({bad.base_url}/" in skipped.reason  # the address asked, so a user sees which store is down
    assert good.status == "answered" and result.found and result.result.best.name == TEAPOT_NAME
    assert elapsed < 20.0  # did not wait for the slow store's answer
    assert result.stores.fetch_s <= 4.0  # the stores' part ended by its deadline


def test_no_store_answering_says_so(db):
    with DemoStore(crawl_delay=None, search_fault="http_500") as bad:
        result = recall_with_lookup(db, TEAPOT, sources=sources(bad), budget_s=3.0)
    assert not result.found and result.message.startswith(NOT_FOUND) and "no store answered" in result.message


def test_sources_without_a_search_say_so(db, store):
    plain = parse_sources(f'[[stores]]\nname = "s"\nbase_url = "{store.base_url}"\n')
    result = recall_with_lookup(db, TEAPOT, sources=plain)
    assert not result.found and "has a search" in result.message


def test_the_page_budget_counts_search_and_product_pages(db, store):
    one = recall_with_lookup(db, TEAPOT, sources=sources(store), max_pages=1)
    assert not one.found and one.stores.stores[0].reason == "page budget used up"
    assert one.stores.requests == 2  # robots.txt and the search page
    two = recall_with_lookup(db, TEAPOT, sources=sources(store), max_pages=2)
    assert two.found and two.stores.stores[0].product_pages


def test_absurd_values_from_a_store_are_refused(db):
    giant = P("giant-teapot", "jsonld", "en", "Glazed Ceramic Teapot XXL", (22.0, 15.0, 1400.0), "m", 900, "g",
              "other", "glazed ceramic")  # fmt: skip
    with DemoStore(crawl_delay=None, search_only=(giant,)) as shop:
        before = dump(db)
        result = recall_with_lookup(db, TEAPOT, sources=sources(shop))
    (cand,) = result.stores.candidates
    assert cand.outcome == "rejected" and cand.reason.startswith("absurd_value")
    assert not result.found and dump(db) == before


def test_a_lookup_never_moves_curated_values(db, store):
    curated = KnowledgeBase.open(db).get_object("coffee mug")
    text = "a coffee mug, 12 cm wide, 9.5 cm tall, about 350 g"
    result = recall_with_lookup(db, text, sources=sources(store), force=True)
    assert result.stores.updated_objects == ["coffee mug"]
    assert KnowledgeBase.open(db).get_object("coffee mug").features() == curated.features()
    adapters = {row["adapter"] for row in KnowledgeBase.open(db).provenance("coffee mug")}
    assert "lookup:jsonld" in adapters


def test_a_confident_recall_is_not_looked_up(db, store):
    result = recall_with_lookup(db, "a tennis ball, 6.7 cm across, 58 g", sources=sources(store))
    assert not result.looked_up and result.stores is None and result.found
    assert result.result.best.name == "tennis ball"


def test_lookup_reason_at_the_confidence_threshold():
    res = Recaller.from_csv(SEED_CSV).recall_text("a tennis ball, 6.7 cm across, 58 g")
    assert lookup_reason(res, threshold=res.confidence) is None
    assert "below" in lookup_reason(res, threshold=res.confidence + 1e-9)


def test_search_terms_go_from_the_subject_phrase_to_its_noun():
    res = Recaller.from_csv(SEED_CSV).recall_text(TEAPOT)
    assert search_terms(res) == ("glazed ceramic teapot", "teapot")
    for nothing in ("it weighs 5 grams", "it weighs 5 g", "something about 20 cm tall"):
        assert search_terms(Recaller.from_csv(SEED_CSV).recall_text(nothing)) == ()


def test_fit_at_the_closeness_boundary():
    text = "it weighs exactly 1000 g"
    edge = 1000 * (1 - FIT_CLOSENESS)
    assert fits(text, ObjectRecord.create("thing a", mass_g=edge))[0]
    assert not fits(text, ObjectRecord.create("thing b", mass_g=edge - 10))[0]


def test_absurd_budgets_are_refused(db, store):
    for kw in ({"budget_s": 0}, {"budget_s": 601}, {"max_pages": 0}, {"max_pages": 201}):
        with pytest.raises(RecallError):
            recall_with_lookup(db, TEAPOT, sources=sources(store), **kw)


def test_the_search_only_products_are_in_no_sitemap(store):
    sitemap = requests.get(store.url("/sitemap.xml"), timeout=5).text
    for prod in SEARCH_ONLY_PRODUCTS:
        assert prod.path not in sitemap
        assert requests.get(store.url(prod.path), timeout=5).status_code == 200


def test_results_pages_are_followed_until_a_store_has_listed_its_search_results(db, store):
    from kb.catalog import KnowledgeBase as KB
    from scrapers.lookup import search_stores

    text = '[[stores]]\nname = "s"\nbase_url = "' + store.base_url + '"\nsearch = "{base_url}/search?q={query}"\n'
    plan = parse_sources(text + "search_results = 5\ndelay_s = 0\n")
    with requests.Session() as session:
        report = search_stores(KB.open(db), plan, ["steel"], description="steel", fits=lambda r: (False, "no"),
                               session=session, deadline=time.monotonic() + 20)  # fmt: skip
    (answer,) = report.stores
    assert len(answer.search_pages) == 2 and answer.search_pages[1].endswith("page=2")
    assert len(answer.product_pages) == 5
    assert {c.outcome for c in report.candidates} == {"does_not_fit"} and report.run_id is None


def test_a_crawl_delay_longer_than_the_time_left_skips_the_store(db, store):
    with DemoStore(crawl_delay=5) as patient:
        t0 = time.monotonic()
        result = recall_with_lookup(db, TEAPOT, sources=sources(patient, store), budget_s=3.0)
        elapsed = time.monotonic() - t0
    patient_answer = result.stores.stores[0]
    assert patient_answer.status == "skipped" and "delay between requests (5 s)" in patient_answer.reason
    assert result.found and elapsed < 5.0
