"""The demo's own catalog (seed + the demo storefront's products, ingested as `objrecall demo` does)
against the demo's own sample descriptions and the store names it ingests (bugs a blind tester found)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
import requests

from kb.catalog import KnowledgeBase
from recall.engine import Recaller
from scrapers.demo_store import DemoStore
from scrapers.ingest import run_ingestion
from scrapers.sources import parse_sources

REPO = Path(__file__).resolve().parents[1]
SEED_CSV = REPO / "kb" / "data" / "seed_catalog.csv"
DEMO_DESCRIPTIONS = REPO / "kb" / "data" / "demo_descriptions.csv"


@pytest.fixture(scope="module")
def demo(tmp_path_factory) -> Recaller:
    path = tmp_path_factory.mktemp("demo") / "demo.duckdb"
    kb = KnowledgeBase.open(path)
    kb.import_csv(SEED_CSV)
    with DemoStore(crawl_delay=None) as store, requests.Session() as session:
        text = '[[stores]]\nname = "demo"\nbase_url = "http://127.0.0.1:1"\n'
        text += 'sitemaps = ["{base_url}/sitemap.xml"]\nexclude = ["slow", "flaky", "huge"]\n'
        run_ingestion(kb, parse_sources(text, origin="test.toml", base_url=store.base_url), session=session)
    return Recaller.from_db(path)


def test_no_demo_sample_description_is_wrongly_flagged_not_in_the_catalog(demo):
    with DEMO_DESCRIPTIONS.open(encoding="utf-8") as f:
        texts = [row["description"] for row in csv.DictReader(f)]
    flagged = [t for t in texts if demo.recall_text(t).not_in_catalog]
    assert flagged == ["An orange of 7 cm diameter."]  # the paper's orange: no orange in the catalog
    pan = demo.recall_text("a heavy cast iron pan, roughly 26 cm across and a bit over two kilograms.")
    assert not pan.open_set and ("pan" in pan.best.name or "skillet" in pan.best.name)


@pytest.mark.parametrize("word", ["wasserkocher", "caffettiera", "théière", "sartén", "cafetera"])
def test_a_word_of_an_ingested_name_finds_it_even_when_the_lexicon_does_not_know_it(demo, word):
    res = demo.recall_text(f"a {word}")
    assert res.matches and word in res.best.name.split()[0], (word, [m.name for m in res.matches[:3]])
    assert res.unknown_noun is None and not res.not_in_catalog  # accents kept: no "'th' is no catalog noun"


def test_an_empty_result_is_never_a_close_match(demo):
    from recall.verdict import verdict

    res = demo.recall_text("qwerty uiop")
    assert not res.matches and verdict(res).label != "close match"
    assert res.to_dict()["verdict"]["label"] == "not a close match"
