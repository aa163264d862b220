"""Ingestion of a hostile loopback store (pages equivalent to a blind tester's): impossible values are
rejected with their reason, never stored without their sign or as a partial read."""

from __future__ import annotations

import pytest
import requests
from hostile_store import HostileStore, sources

from kb.catalog import KnowledgeBase
from scrapers.ingest import run_ingestion


@pytest.fixture(scope="module")
def ingested(tmp_path_factory):
    path = tmp_path_factory.mktemp("hostile") / "catalog.duckdb"
    kb = KnowledgeBase.open(path)
    with HostileStore() as store, requests.Session() as session:
        report = run_ingestion(kb, sources(store), session=session)
    with kb.connect() as con:
        names = {row[0] for row in con.execute("SELECT name FROM objects").fetchall()}
        events = {
            url.rsplit("/", 1)[-1]: (stage, reason)
            for url, stage, reason in con.execute("SELECT url, stage, reason FROM page_events").fetchall()
        }
    return report, names, events


def test_a_page_with_negative_values_is_rejected_with_the_reason(ingested):
    _, names, events = ingested
    assert "negative plate" not in names
    _, reason = events["negative"]
    assert reason.startswith("invalid_value") and "not positive" in reason
    assert "-600 g" in reason or "-27 cm" in reason


def test_a_good_page_beside_them_is_stored(ingested):
    _, names, _ = ingested
    assert "plain mug" in names


def test_a_page_whose_size_is_absurd_in_every_field_is_rejected_as_absurd(ingested):
    _, names, events = ingested
    assert "giant teacup" not in names
    _, reason = events["absurd"]
    assert reason.startswith("absurd_value") and "5000 cm" in reason


@pytest.mark.parametrize("page", ["longname", "nul", "notutf8"])
def test_a_page_whose_name_breaks_the_name_rules_is_rejected_with_the_reason(ingested, page):
    _, _, events = ingested
    assert events[page][1].startswith("invalid_name: the page's name is refused")


def test_no_stored_name_breaks_the_name_rules_and_markup_never_enters_one(ingested):
    _, names, _ = ingested
    assert "hostile mug" in names
    assert all(len(n) <= 200 and "\ufffd" not in n and "<" not in n and "alert" not in n for n in names)
