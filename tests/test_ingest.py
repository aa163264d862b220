"""The ingestion job end to end: demo store over real HTTP on 127.0.0.1 -> a real DuckDB catalog file."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import requests

import kb
from kb.catalog import KnowledgeBase
from scrapers.demo_store import PRODUCTS, DemoStore
from scrapers.ingest import page_identity, run_ingestion
from scrapers.sources import parse_sources

SEED_CSV = Path(kb.__file__).parent / "data" / "seed_catalog.csv"

SOURCES = """
[defaults]
delay_s = 0
read_timeout_s = 1.0
connect_timeout_s = 2
max_retries = 1
backoff_s = 0
max_bytes = 2_000_000

[[stores]]
name = "demo"
base_url = "http://127.0.0.1:1"
sitemaps = ["{base_url}/sitemap.xml"]

[[stores]]
name = "demo-shopify-json"
base_url = "http://127.0.0.1:1"
sitemaps = ["{base_url}/sitemap.xml"]
include = ["^/products/"]
adapter = "shopify"
"""

BROKEN_REASONS = {"http_500", "timeout", "too_large", "robots_disallowed", "absurd_value", "no_product"}


def sources_for(store: DemoStore, include: str | None = None):
    """The two demo stores, or (with ``include``) only the HTML store restricted to matching paths (and
    without the slow, flaky and huge pages, which cost seconds)."""
    text = SOURCES
    if include is not None:
        text = SOURCES.split("[[stores]]")[0] + '[[stores]]\nname = "demo"\nbase_url = "http://127.0.0.1:1"\n'
        text += f'sitemaps = ["{{base_url}}/sitemap.xml"]\ninclude = ["{include}"]\n'
        text += 'exclude = ["slow", "flaky", "huge"]\n'
    return parse_sources(text, origin="test-sources.toml", base_url=store.base_url)


_SEEDED: dict[str, Path] = {}


def seeded(path: Path) -> KnowledgeBase:
    """A catalog at ``path`` holding the seed catalog (imported once per session, then copied)."""
    if "template" not in _SEEDED:
        template = path.parent / "seed-template.duckdb"
        KnowledgeBase.open(template).import_csv(SEED_CSV)
        _SEEDED["template"] = template
    shutil.copy(_SEEDED["template"], path)
    return KnowledgeBase.open(path)


def local(store: DemoStore, path: str) -> str:
    """A demo page's identity in the catalog (its URL without the server's port)."""
    return page_identity(store.url(path))


def rows(kb: KnowledgeBase, sql: str, params=()) -> list[tuple]:
    with kb.connect() as con:
        return con.execute(sql, list(params)).fetchall()


@pytest.fixture(scope="module")
def store():
    with DemoStore(crawl_delay=None, slow_s=2.5) as s:
        yield s


@pytest.fixture(scope="module")
def first_run(store, tmp_path_factory):
    """One ingestion of the demo store into a seeded catalog; tests copy the file before changing it."""
    path = tmp_path_factory.mktemp("ingest") / "catalog.duckdb"
    kb = seeded(path)
    before = rows(kb, "SELECT count(*) FROM objects")[0][0]
    with requests.Session() as session:
        report = run_ingestion(kb, sources_for(store), session=session)
    return path, report, before


def test_first_run_counts(first_run, store):
    path, report, before = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    assert report.status == "ok"
    assert report.pages == len(store.sitemap_paths()) + sum(p.fmt == "shopify" for p in PRODUCTS)
    assert set(report.rejected_reasons) >= BROKEN_REASONS
    assert report.rejected == sum(report.rejected_reasons.values())
    assert (
        report.fetched
        + report.rejected_reasons["http_500"]
        + report.rejected_reasons["timeout"]
        + (report.rejected_reasons["too_large"] + report.rejected_reasons["robots_disallowed"])
        == report.pages
    )
    assert report.new >= 25 and report.new == len(report.new_objects)
    in_seed = {p.name for p in PRODUCTS if p.in_seed}
    assert set(report.updated_objects) == in_seed
    assert rows(kb, "SELECT count(*) FROM objects")[0][0] == before + report.new
    (run,) = rows(
        kb,
        "SELECT id, status, fetched, not_modified, extracted, rejected, new, updated, rejected_reasons, duration_s "
        "FROM ingestion_runs",
    )
    assert run[:8] == (report.run_id, "ok", report.fetched, 0, report.extracted, report.rejected, report.new,
                       report.updated)  # fmt: skip
    assert '"too_large": 1' in run[8] and run[9] > 0


def test_bad_pages_are_recorded_with_their_reason(first_run, store):
    path, report, _ = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    events = {
        url: (stage, reason) for url, stage, reason in rows(kb, "SELECT url, stage, reason FROM page_events")
    }
    expect = {
        "/p/server-error.html": ("fetch", "http_500"),
        "/p/slow-teapot.html": ("fetch", "timeout"),
        "/p/huge-catalogue.html": ("fetch", "too_large"),
        "/private/staff-lamp.html": ("fetch", "robots_disallowed"),
        "/p/giant-mug.html": ("validate", "absurd_value"),
        "/about.html": ("extract", "no_product"),
        "/p/broken-jsonld.html": ("extract", "no_product"),
    }
    for path_, (stage, reason) in expect.items():
        got_stage, got_reason = events[store.url(path_)]
        assert got_stage == stage and got_reason.startswith(reason + ":"), path_
    assert not rows(kb, "SELECT * FROM objects WHERE name IN ('giant mug', 'about us', 'staff desk lamp')")
    (err,) = rows(kb, "SELECT error FROM pages WHERE url = ?", [page_identity(store.url("/p/giant-mug.html"))])
    assert err[0].startswith("absurd_value")
    assert not any(
        page_identity(store.url("/private/")) in u for (u,) in rows(kb, "SELECT url FROM pages WHERE status = 200")
    )


def test_new_objects_carry_the_true_values(first_run):
    path, report, _ = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    catalog = {o.name: o for o in kb.list_objects()}
    checked = 0
    for prod in PRODUCTS:
        if prod.in_seed or prod.name not in report.new_objects:
            continue
        obj = catalog[prod.name]
        assert obj.dims_cm[: len(prod.dims_cm)] == pytest.approx(prod.dims_cm, rel=0.01), prod.handle
        assert obj.mass_g == pytest.approx(prod.mass_g, rel=0.01), prod.handle
        assert obj.source.startswith("http://127.0.0.1/")  # a local server's port is no part of it
        checked += 1
    assert checked >= 25


def test_every_value_is_kept_with_its_source(first_run, store):
    path, report, _ = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    prov = kb.provenance("digital kitchen scale")
    product = {o["feature"]: o for o in prov if o["role"] == "product"}
    package = [o for o in prov if o["role"] == "package"]
    assert product["mass_g"]["source"] == local(store, "/dp/kitchen-scale")
    assert product["mass_g"]["run_id"] == report.run_id and product["mass_g"]["raw_text"]
    assert product["mass_g"]["adapter"]
    assert {o["feature"] for o in package} == {"a_cm", "b_cm", "c_cm", "mass_g"}
    obj = kb.get_object("digital kitchen scale")
    # Package values are kept apart: the catalog holds the product's own (9.25 x 6.3 x 0.79 in; 1.06 lb).
    assert obj.a_cm == pytest.approx(23.495, rel=0.01) and obj.mass_g == pytest.approx(480.8, rel=0.01)


def test_pages_of_one_product_become_one_object(first_run, store):
    path, _, _ = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    towel_pages = rows(
        kb,
        "SELECT url, object_id FROM pages WHERE url LIKE '%linen-tea-towel%' ORDER BY url",
    )
    assert {u for u, _ in towel_pages} == {
        local(store, "/products/linen-tea-towel"),
        local(store, "/products/linen-tea-towel.json"),
        local(store, "/collections/kitchen/products/linen-tea-towel"),
    }
    assert len({oid for _, oid in towel_pages}) == 1 and towel_pages[0][1] is not None
    skillet = rows(kb, "SELECT object_id FROM pages WHERE url LIKE '%cast-iron%' OR url LIKE '%frying-pan%'")
    assert len(skillet) == 3 and len({oid for (oid,) in skillet}) == 1
    # The same GTIN under another title: one object, the other title an alias, both pages its sources.
    assert kb.get_object("pre-seasoned cast iron frying pan").name == "cast iron skillet 26 cm"
    sources = {o["source"] for o in kb.provenance("cast iron skillet 26 cm")}
    assert sources == {local(store, "/p/cast-iron-skillet.html"), local(store, "/p/pre-seasoned-frying-pan.html")}
    assert rows(kb, "SELECT count(*) FROM objects WHERE name LIKE '%linen tea towel%'")[0][0] == 1


def test_seed_objects_are_fused_with_page_values(first_run, store):
    path, report, _ = first_run
    kb = KnowledgeBase.open(path, read_only=True)
    seed = {o.name: o for o in _seed_records()}
    mug = kb.get_object("coffee mug")
    page = next(p for p in PRODUCTS if p.handle == "coffee-mug")
    # Two sources (the seed catalog and the page): the curated value stands, the page's is kept beside it.
    assert page.mass_g != seed["coffee mug"].mass_g
    assert mug.mass_g == pytest.approx(seed["coffee mug"].mass_g)
    assert mug.texture == seed["coffee mug"].texture  # no page states texture: kept
    assert mug.source == seed["coffee mug"].source
    masses = {o["source"]: o["value_num"] for o in kb.provenance("coffee mug") if o["feature"] == "mass_g"}
    assert masses[page_identity(store.url("/p/coffee-mug.html"))] == pytest.approx(page.mass_g)
    assert len(masses) == 2
    (url,) = rows(kb, "SELECT canonical_url FROM objects WHERE name = 'coffee mug'")
    assert url[0] == page_identity(store.url("/p/coffee-mug.html"))
    assert ":" not in url[0].split("//", 1)[1].split("/", 1)[0]  # no port in a local page's identity


def _seed_records():
    from kb.csvio import read_catalog_csv

    return read_catalog_csv(SEED_CSV).records


def _copy_of(first_run, tmp_path):
    """A copy of the first run's catalog, with its objects and observation count before a second run."""
    copy = tmp_path / "again.duckdb"
    shutil.copy(first_run[0], copy)
    kb = KnowledgeBase.open(copy)
    return kb, rows(kb, "SELECT * FROM objects ORDER BY id"), rows(kb, "SELECT count(*) FROM observations")


def test_second_run_changes_nothing(first_run, store, tmp_path):
    first = first_run[1]
    kb, objects_before, obs_before = _copy_of(first_run, tmp_path)
    log_start = len(store.log)
    with requests.Session() as session:
        report = run_ingestion(kb, sources_for(store), session=session)
    assert report.new == report.updated == report.observations_added == 0
    assert report.not_modified >= first.new + first.updated
    assert rows(kb, "SELECT * FROM objects ORDER BY id") == objects_before
    assert rows(kb, "SELECT count(*) FROM observations") == obs_before
    runs = rows(kb, "SELECT id, not_modified, new, updated FROM ingestion_runs ORDER BY id")
    assert len(runs) == 2 and runs[1] == (report.run_id, report.not_modified, 0, 0)
    # The pages were asked with their validators: 304s, not parsed.
    conditional = [e for e in store.log[log_start:] if e.if_none_match and e.status == 304]
    assert len(conditional) == report.not_modified >= first.new


def test_a_second_run_on_another_port_changes_nothing(first_run, tmp_path):
    """The main job starts the demo store on a free port each time: the pages are the same pages."""
    kb, objects_before, obs_before = _copy_of(first_run, tmp_path)
    with DemoStore(crawl_delay=None, slow_s=2.5) as other, requests.Session() as session:
        report = run_ingestion(kb, sources_for(other), session=session)
    assert report.new == report.updated == report.observations_added == 0
    assert rows(kb, "SELECT * FROM objects ORDER BY id") == objects_before
    assert rows(kb, "SELECT count(*) FROM observations") == obs_before


def test_page_identity_drops_only_a_local_servers_port():
    assert page_identity("http://127.0.0.1:53211/p/x.html?a=1") == "http://127.0.0.1/p/x.html?a=1"
    assert page_identity("http://localhost:8000/p") == "http://localhost/p"
    assert page_identity("http://[::1]:8000/p") == "http://[::1]/p"
    assert page_identity("http://127.0.0.1/p") == "http://127.0.0.1/p"
    assert page_identity("https://shop.example:8443/p") == "https://shop.example:8443/p"  # a real store's
    assert page_identity("http://10.0.0.1:8000/p") == "http://10.0.0.1:8000/p"  # not loopback


def test_a_changed_page_adds_its_new_values(tmp_path):
    with DemoStore(crawl_delay=None) as store, requests.Session() as session:
        kb = seeded(tmp_path / "c.duckdb")
        sources = sources_for(store, include="bamboo|tennis")
        run_ingestion(kb, sources, session=session)
        before = kb.get_object("bamboo serving tray")
        store.update_product("bamboo-serving-tray", mass=0.95)
        report = run_ingestion(kb, sources, session=session)
        assert report.updated_objects == ["bamboo serving tray"] and report.new == 0
        masses = [o["value_num"] for o in kb.provenance("bamboo serving tray") if o["feature"] == "mass_g"]
        assert masses == [950.0, 850.0]  # newest first; the old value is kept
        after = kb.get_object("bamboo serving tray")
        # One source, its latest value counts.
        assert before.mass_g == 850.0 and after.mass_g == 950.0 and after.a_cm == before.a_cm


def test_an_extractor_failure_skips_only_that_page(store, tmp_path):
    from scrapers.extract import extract_page

    def flaky_extractor(body, url, content_type):
        if "tennis-ball" in url:
            raise RuntimeError("bug in an adapter")
        return extract_page(body, url, content_type)

    kb = seeded(tmp_path / "e.duckdb")
    with requests.Session() as session:
        report = run_ingestion(
            kb, sources_for(store, "tennis|bamboo|rolling"), session=session, extract=flaky_extractor
        )
    assert report.rejected_reasons == {"extractor_failed": 1}
    assert report.new_objects == ["bamboo serving tray"] and report.updated_objects == ["rolling pin"]


def test_no_database_handle_is_held_while_fetching(store, tmp_path):
    """Another process can open the catalog while pages are being fetched (only the final write locks it)."""
    path = tmp_path / "r.duckdb"
    kb = seeded(path)
    probe = "import duckdb, sys; c = duckdb.connect(sys.argv[1], read_only=True); print(c.execute('select count(*) from objects').fetchone()[0])"
    seen: list[str] = []

    def progress(done: int, total: int, url: str) -> None:
        if done == 10:
            out = subprocess.run(
                [sys.executable, "-c", probe, str(path)], capture_output=True, text=True, timeout=60
            )
            seen.append(out.stdout.strip() or out.stderr)

    with requests.Session() as session:
        run_ingestion(kb, sources_for(store, "^/(p|dp)/"), session=session, progress=progress)
    assert seen and seen[0].isdigit()


@pytest.mark.slow
def test_ingest_demo_in_one_call(tmp_path):
    from scrapers.demo_store import ingest_demo

    kb = seeded(tmp_path / "demo.duckdb")
    report = ingest_demo(kb)
    assert report.new >= 25 and len(report.updated_objects) == sum(p.in_seed for p in PRODUCTS)
    assert report.rejected_reasons["timeout"] == 1 and report.rejected_reasons["too_large"] == 1


def test_two_hosts_are_crawled_at_the_same_time_each_one_request_at_a_time(tmp_path):
    text = """
[defaults]
delay_s = 0.05
max_retries = 0

[[stores]]
name = "a"
base_url = "{a}"
sitemaps = ["{{base_url}}/sitemap.xml"]
include = ["^/(p|dp)/"]
exclude = ["slow", "flaky", "huge"]

[[stores]]
name = "b"
base_url = "{b}"
sitemaps = ["{{base_url}}/sitemap.xml"]
include = ["^/(de|fr|es|it|pt)/"]
"""
    with DemoStore(crawl_delay=None) as a, DemoStore(crawl_delay=None) as b, requests.Session() as session:
        sources = parse_sources(text.format(a=a.base_url, b=b.base_url))
        kb = seeded(tmp_path / "two.duckdb")
        report = run_ingestion(kb, sources, session=session)
        assert report.new >= 15 and report.pages == len(a.log) - 2 + len(b.log) - 2  # minus robots, sitemap
        assert a.max_in_flight == 1 and b.max_in_flight == 1
        a_pages = [e for e in a.log if e.path.startswith(("/p/", "/dp/"))]
        b_pages = [e for e in b.log if e.path.startswith(("/de/", "/fr/"))]
        # Interleaved in time: some page of b was served while a's crawl was under way, and vice versa.
        assert any(a_pages[0].started < e.started < a_pages[-1].started for e in b_pages)


def test_store_names_in_other_languages_get_an_english_alias_with_provenance(tmp_path):
    from recall.engine import Recaller

    with DemoStore(crawl_delay=None) as store, requests.Session() as session:
        kb = seeded(tmp_path / "names.duckdb")
        sources = sources_for(store, include="cafetera|wasserkocher|theiere|moka-alluminio")
        run_ingestion(kb, sources, session=session)
    aliases = dict(rows(kb, "SELECT alias, o.name FROM object_aliases a JOIN objects o ON o.id = a.object_id"))
    assert aliases["moka pot"] in {"caffettiera moka in alluminio 3 tazze", "cafetera italiana de aluminio 6 tazas"}
    assert aliases["electric kettle"].startswith("wasserkocher")
    assert aliases["teapot"].startswith("théière")
    events = rows(kb, "SELECT url, reason FROM page_events WHERE stage = 'naming' ORDER BY url")
    assert any("English alias 'electric kettle' from the title ('wasserkocher', de)" in r for _, r in events)
    # the recall finds them by their English names, and a teapot is no longer "not in the catalog"
    recaller = Recaller.from_db(tmp_path / "names.duckdb")
    assert recaller.recall_text("an electric kettle").best.name.startswith("wasserkocher")
    teapot = recaller.recall_text("a cast iron teapot, 1.2 kg")
    assert teapot.best.name.startswith("théière") and not teapot.not_in_catalog
