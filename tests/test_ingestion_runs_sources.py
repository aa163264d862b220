"""``ingestion_runs.sources`` says which sources file and stores a run read, never the file's path on the
server (a blind test read /work/.../demo_sources.toml through ``POST /sql``); old rows are rewritten by
migration 0004."""

from __future__ import annotations

import json

import duckdb
import requests
from hostile_store import HostileStore

from kb import migrate
from kb.catalog import KnowledgeBase
from scrapers.ingest import run_ingestion
from scrapers.sources import file_name, load_sources

SOURCES = """[defaults]
delay_s = 0
max_retries = 0
[[stores]]
name = "hostile"
base_url = "http://127.0.0.1:1"
sitemaps = ["{base_url}/sitemap.xml"]
"""


def test_a_run_records_the_sources_file_name_and_store_names_not_its_path(tmp_path):
    path = tmp_path / "deep" / "stores.toml"
    path.parent.mkdir()
    path.write_text(SOURCES)
    kb = KnowledgeBase.open(tmp_path / "c.duckdb")
    with HostileStore() as store, requests.Session() as session:
        report = run_ingestion(kb, load_sources(path, base_url=store.base_url), session=session)
    with kb.connect() as con:
        (stored,) = con.execute("SELECT sources FROM ingestion_runs").fetchone()
    assert stored == report.sources == "stores.toml: hostile"
    assert str(tmp_path) not in stored


def test_file_name_keeps_only_the_last_path_component():
    assert file_name("/srv/app/stores.toml") == "stores.toml"
    assert file_name("C:\\app\\stores.toml") == "stores.toml"
    assert file_name("stores.toml") == "stores.toml" and file_name("<sources>") == "<sources>"


OLD_ROWS = {
    "/work/blind/p/scrapers/demo_sources.toml: demo, demo-shopify-json": "demo_sources.toml: demo, demo-shopify-json",
    "C:\\srv\\stores.toml: shop": "stores.toml: shop",
    "test-sources.toml: demo": "test-sources.toml: demo",
    "lookup " + json.dumps({"query": ["mug"], "stores": ["https://shop.example/a"]}): None,  # unchanged
}


def test_migration_0004_rewrites_old_rows_and_leaves_the_others(tmp_path):
    db = tmp_path / "old.duckdb"
    migrate.upgrade(db, "0003_grasp_validations")
    with duckdb.connect(str(db)) as con:
        for old in OLD_ROWS:
            con.execute("INSERT INTO ingestion_runs (status, sources) VALUES ('ok', ?)", [old])
        con.execute("INSERT INTO ingestion_runs (status, sources) VALUES ('ok', NULL)")
    migrate.upgrade(db)
    assert migrate.current_revision(db) == "0004_sources_file_name"
    with duckdb.connect(str(db), read_only=True) as con:
        got = [r[0] for r in con.execute("SELECT sources FROM ingestion_runs ORDER BY id").fetchall()]
    assert got == [new or old for old, new in OLD_ROWS.items()] + [None]
    migrate.downgrade(db, "0003_grasp_validations")  # the paths are gone for good: rows stay as they are
    with duckdb.connect(str(db), read_only=True) as con:
        assert con.execute("SELECT count(*) FROM ingestion_runs WHERE sources LIKE '%/%'").fetchone() == (1,)
