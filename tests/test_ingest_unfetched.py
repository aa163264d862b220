"""A page that could not be fetched this run (its deadline passed, its store's budget was spent) keeps its
``pages`` row as it was (object, hash, validators) and gets only its error: nothing was learnt about it
(a blind tester found the row's object and hash cleared). Real HTTP on loopback, a real DuckDB file."""

from __future__ import annotations

import requests
from hostile_stores import PageStore, sources_text

from kb.catalog import KnowledgeBase
from scrapers.ingest import run_ingestion
from scrapers.sources import parse_sources

COLS = "object_id, content_sha256, etag, last_modified, canonical_url"


def _row(kb, url: str):
    with kb.connect() as con:
        return con.execute(f"SELECT {COLS}, error FROM pages WHERE url = ?", [url]).fetchone()


def test_a_timed_out_page_keeps_its_row_and_gets_its_error(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "catalog.duckdb")
    with PageStore(drip_s=3.0) as store, requests.Session() as session:
        sources = parse_sources(sources_text({"s": store}, deadline_s=1.0))
        run_ingestion(kb, sources, session=session)
        key = "http://127.0.0.1/p/drip"
        before = _row(kb, key)
        assert before is not None and before[0] is not None and before[1] is not None and before[-1] is None
        store.mode = "hostile"
        run_ingestion(kb, sources, session=session)
        after = _row(kb, key)
        assert after[:-1] == before[:-1]  # object, hash, validators, canonical URL: as they were
        assert after[-1].startswith("timeout: page took longer than 1 s")
        store.mode = "good"
        third = run_ingestion(kb, sources, session=session)  # fetched in full again (an error last time)
    assert _row(kb, key)[-1] is None and third.rejected == 0
