"""Two loopback stores on different ports that list the same path in one run (a blind tester's attack on
issue 25): a loopback server's port is not part of a page's identity, so the second page is the same
identity. The run must not fail as a whole: the later page is skipped with its reason, the others are
written. Real HTTP on loopback, a real DuckDB file."""

from __future__ import annotations

import requests
from hostile_store import HostileStore, product_page

from kb.catalog import KnowledgeBase
from scrapers.ingest import run_ingestion
from scrapers.sources import parse_sources


def _sources(stores: dict[str, HostileStore]) -> str:
    text = "[defaults]\ndelay_s = 0\nmax_retries = 1\nbackoff_s = 0\n"
    for name, store in stores.items():
        text += f'[[stores]]\nname = "{name}"\nbase_url = "{store.base_url}"\nurls = ["{{base_url}}/p/0.html"]\n'
    return text


def test_the_same_path_on_two_loopback_ports_is_skipped_once_not_a_failed_run(tmp_path):
    kb = KnowledgeBase.open(tmp_path / "catalog.duckdb")
    a = {"/p/0.html": product_page("Blue Mug", "9 x 9 x 10 cm", "320 g").encode()}
    b = {"/p/0.html": product_page("Red Bowl", "15 x 15 x 6 cm", "410 g").encode()}
    with HostileStore(a) as one, HostileStore(b) as two, requests.Session() as session:
        report = run_ingestion(kb, parse_sources(_sources({"one": one, "two": two})), session=session)
    assert report.status == "ok_with_errors" and report.run_id is not None
    (event,) = [e for e in report.errors if e["reason"].startswith("duplicate_page")]
    assert event["stage"] == "discover" and "http://127.0.0.1/p/0.html" in event["reason"]
    with kb.connect() as con:
        names = [r[0] for r in con.execute("SELECT name FROM objects").fetchall()]
    assert len(names) == 1 and names[0] in ("blue mug", "red bowl")  # the first one listed, once
