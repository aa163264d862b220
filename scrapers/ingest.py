"""The ingestion job: storefront pages -> catalog objects, with provenance, idempotently and crash-safely.

Stages (see ``scrapers/INGESTION.md`` for the whole story):

1. **discover**: each store's sitemaps (or the Sitemap lines of its robots.txt) and listed URLs, filtered by
   the store's include/exclude patterns, at most ``max_pages``;
2. **fetch** politely (:class:`~scrapers.fetcher.PoliteFetcher`), sending the validators stored for the page
   last time: a 304, or a 200 whose body hashes the same as last time, is *not modified* and not parsed;
3. **extract** (:func:`scrapers.extract.extract_page`) a :class:`~scrapers.records.ProductRecord`;
4. **validate** with the catalog's own rules (:class:`kb.features.ObjectRecord`): absurd or malformed values
   reject the page with a reason;
5. **de-duplicate**: pages sharing a canonical URL, a GTIN or a normalised name are one product, and a
   product is matched to a catalog object by canonical URL, then GTIN, then name or alias;
6. **upsert with provenance**: every value observed is kept in ``observations`` (source = the page's
   canonical URL); the object's catalog values are fused from all its observations by the rule in
   :mod:`scrapers.fusion`;
7. a row in ``ingestion_runs`` with the counts, ``pages`` rows (validators for the next run) and a
   ``page_events`` row per rejected page, with its reason.

Stages 1-4 run with no database connection open. Stages 5-7 run in **one** short write transaction, with
set-based statements over Arrow batches (no row-by-row round trips): readers wait at most that long, and a
crash or a kill at any moment leaves the catalog as it was before the run or as it is after it. A page whose
values equal what its source said last time adds no rows, so a second run over unchanged pages changes
nothing in the catalog.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import sys
import threading
import time
from collections import Counter
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, field
from datetime import datetime
from typing import Any
from urllib.parse import urlsplit

import requests

from kb.catalog import bulk_execute
from kb.errors import ExtractionError, FetchError, IngestionError, InvalidFeature
from kb.features import (
    DIMENSIONS,
    FEATURES,
    NUMERIC_FEATURES,
    ObjectRecord,
    normalize_category,
    normalize_name,
)
from scrapers.fetcher import Clock, PoliteFetcher, SystemClock, Validators, fetch_error_kind
from scrapers.fusion import Observation, fuse
from scrapers.records import ProductRecord
from scrapers.sources import Sources, StoreSource

__all__ = [
    "LOCAL_HOSTS",
    "IngestionReport",
    "PageOutcome",
    "ProgressFn",
    "discover_urls",
    "page_identity",
    "previous_pages",
    "process_page",
    "run_ingestion",
    "write_run",
]

#: progress(done, total, url): called after each page (and once with done=0 when the total is known).
ProgressFn = Callable[[int, int, str], None]
Extractor = Callable[[bytes, str, "str | None"], ProductRecord]

#: Testing hook: seconds to sleep inside the write transaction, after every statement and before COMMIT,
#: so a test can kill the process while the transaction is open (see tests/test_ingest_crash.py).
PAUSE_ENV = "OBJRECALL_INGEST_PAUSE_BEFORE_COMMIT"
MAX_SITEMAPS = 50
#: Hosts crawled at the same time (each host still gets one request at a time).
DEFAULT_MAX_HOSTS = 4
_SHOPIFY_PRODUCT = re.compile(r"^/products/[^/.]+/?$")


@dataclass
class PageOutcome:
    """What happened to one page in this run (kept in memory until the write transaction)."""

    url: str
    store: str
    outcome: str = "pending"  # extracted | not_modified | rejected
    stage: str | None = None  # fetch | extract | validate (where a rejected page stopped)
    reason: str | None = None  # short key, counted in rejected_reasons
    detail: str | None = None
    status: int | None = None
    final_url: str | None = None
    etag: str | None = None
    last_modified: str | None = None
    content_sha256: str | None = None
    fetched_at: datetime | None = None
    record: ProductRecord | None = None
    clean: ObjectRecord | None = None
    packages: list[dict[str, float]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def source(self) -> str:
        """The page's identity as a source: its canonical URL when on the same host, else the final URL
        (:func:`page_identity`: a local server's port is not part of it)."""
        final = self.final_url or self.url
        canonical = self.record.canonical_url if self.record is not None else None
        if canonical and urlsplit(canonical).netloc == urlsplit(final).netloc:
            return page_identity(canonical)
        return page_identity(final)

    @property
    def key(self) -> str:
        """The page's row in the ``pages`` table (its URL as listed, without a local server's port)."""
        return page_identity(self.url)


#: Hosts of servers on this machine: their port changes from run to run (the demo store picks a free one).
LOCAL_HOSTS = frozenset({"localhost", "127.0.0.1", "::1", "[::1]"})


def page_identity(url: str) -> str:
    """``url`` as a page's identity: a loopback server's port removed (``http://127.0.0.1:53211/p/x`` ->
    ``http://127.0.0.1/p/x``), anything else unchanged. A page served by a local server on another port
    next run is the same page; a real store's port is part of its address and kept."""
    parts = urlsplit(url)
    host = (parts.hostname or "").lower()
    if parts.port is None or not (host in LOCAL_HOSTS or host.startswith("127.")):
        return url
    netloc = f"[{host}]" if ":" in host else host
    if parts.username or parts.password:
        return url
    return parts._replace(netloc=netloc).geturl()


@dataclass
class IngestionReport:
    """The counts of one run (also stored as a row of ``ingestion_runs``)."""

    run_id: int | None
    status: str
    sources: str
    started_at: datetime
    finished_at: datetime | None = None
    duration_s: float = 0.0
    pages: int = 0
    fetched: int = 0
    not_modified: int = 0
    extracted: int = 0
    rejected: int = 0
    rejected_reasons: dict[str, int] = field(default_factory=dict)
    new: int = 0
    updated: int = 0
    unchanged: int = 0
    observations_added: int = 0
    aliases_added: int = 0
    new_objects: list[str] = field(default_factory=list)
    updated_objects: list[str] = field(default_factory=list)
    errors: list[dict[str, str]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    write_s: float = 0.0

    @property
    def pages_per_s(self) -> float:
        return self.pages / self.duration_s if self.duration_s > 0 else 0.0

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["pages_per_s"] = round(self.pages_per_s, 2)
        return d


class _Rejected(Exception):
    def __init__(self, reason: str, detail: str):
        self.reason = reason
        self.detail = detail
        super().__init__(f"{reason}: {detail}")


# ---------------------------------------------------------------------------------------------- discover
def _sitemap_locs(body: bytes) -> tuple[str, list[str]]:
    """(root kind, <loc> texts) of a sitemap or sitemap index; entities and network access disabled."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, recover=False, huge_tree=False)
    root = etree.fromstring(body, parser=parser)
    kind = etree.QName(root).localname
    locs = [el.text.strip() for el in root.iter() if etree.QName(el).localname == "loc" and el.text]
    return kind, locs


def discover_urls(
    fetcher: PoliteFetcher, store: StoreSource, events: list[tuple[str, str, str]]
) -> list[str]:
    """The page URLs to fetch for ``store``, in order, de-duplicated, filtered and capped.

    Problems (an unreadable sitemap) are appended to ``events`` as (url, stage, reason) and skipped.
    """
    urls: list[str] = list(store.urls)
    sitemaps = list(store.sitemaps)
    if not sitemaps and not urls:
        try:
            sitemaps = fetcher.sitemaps(store.base_url + "/", store.policy)
        except FetchError as err:
            events.append(
                (store.base_url + "/robots.txt", "discover", f"{fetch_error_kind(err)}: {err.reason}")
            )
    seen_maps: set[str] = set()
    while sitemaps and len(seen_maps) < MAX_SITEMAPS:
        sitemap = sitemaps.pop(0)
        if sitemap in seen_maps:
            continue
        seen_maps.add(sitemap)
        try:
            result = fetcher.fetch(sitemap, policy=store.policy)
            kind, locs = _sitemap_locs(result.body or b"")
        except FetchError as err:
            events.append((sitemap, "discover", f"{fetch_error_kind(err)}: {err.reason}"))
            continue
        except Exception as err:  # noqa: BLE001 - lxml's XMLSyntaxError and friends: a bad sitemap is skipped
            events.append((sitemap, "discover", f"bad_sitemap: {type(err).__name__}: {err}"))
            continue
        if kind == "sitemapindex":
            sitemaps.extend(locs)
        else:
            urls.extend(locs)
    out: list[str] = []
    seen: set[str] = set()
    for url in urls:
        if store.adapter == "shopify" and _SHOPIFY_PRODUCT.match(urlsplit(url).path):
            url = url.rstrip("/") + ".json"
        if url in seen or not store.wants(url):
            continue
        seen.add(url)
        out.append(url)
        if len(out) >= store.max_pages:
            break
    return out


# ---------------------------------------------------------------------------------------------- validate
def _validate(record: ProductRecord) -> tuple[ObjectRecord, list[dict[str, float]], list[str]]:
    """The catalog record a page supports, its package values and warnings; raises _Rejected."""
    warnings: list[str] = []
    name = normalize_name(record.name or "")
    if not name:
        raise _Rejected("no_name", "the page names no product")
    absurd = [w for w in record.warnings if "absurd" in w.lower() and "package" not in w.lower()]
    if absurd:
        # The page states an impossible value for the product: none of its numbers can be trusted.
        raise _Rejected("absurd_value", absurd[0])
    dims = tuple(record.dims_cm or ())
    if not dims and record.mass_g is None:
        raise _Rejected("no_measurements", "no product dimensions or mass")
    if len(dims) > 3:
        raise _Rejected("invalid_value", f"{len(dims)} dimensions")
    categories: dict[str, str | None] = {}
    for feat in ("material", "shape"):
        try:
            categories[feat] = normalize_category(feat, getattr(record, feat))
        except InvalidFeature as err:
            warnings.append(f"{feat} dropped: {err}")
    try:
        clean = ObjectRecord.create(
            name,
            **dict(zip(DIMENSIONS, dims, strict=False)),
            mass_g=record.mass_g,
            **categories,
        )
    except InvalidFeature as err:
        kind = "absurd_value" if "absurd" in err.reason else "invalid_value"
        raise _Rejected(kind, str(err)) from None
    packages: list[dict[str, float]] = []
    n = max(len(record.package_dims_cm), len(record.package_mass_g))
    for i in range(n):
        pdims = record.package_dims_cm[i] if i < len(record.package_dims_cm) else ()
        pmass = record.package_mass_g[i] if i < len(record.package_mass_g) else None
        try:
            values = ObjectRecord.create(
                "package", **dict(zip(DIMENSIONS, pdims, strict=False)), mass_g=pmass
            )
        except InvalidFeature as err:
            warnings.append(f"package {i + 1} dropped: {err}")
            continue
        packages.append({f: v for f, v in values.known_features().items() if f in NUMERIC_FEATURES})
    return clean, packages, warnings


# ---------------------------------------------------------------------------------------------- fetch + extract
def _default_extractor() -> Extractor:
    from scrapers.extract import extract_page

    return extract_page


class PreviousPages(dict):
    """The ``pages`` rows by page identity; looked up by any URL of the page (a local server's port
    does not matter: :func:`page_identity`)."""

    def __getitem__(self, url: str) -> dict[str, Any]:
        return super().__getitem__(page_identity(url))

    def __contains__(self, url: object) -> bool:
        return isinstance(url, str) and super().__contains__(page_identity(url))

    def get(self, url: str, default: Any = None) -> Any:
        return super().get(page_identity(url), default)


def _previous_pages(kb) -> PreviousPages:
    with kb.connect() as con:
        cur = con.execute("SELECT url, etag, last_modified, content_sha256, object_id, error FROM pages")
        cols = [d[0] for d in cur.description]
        return PreviousPages({row[0]: dict(zip(cols, row, strict=True)) for row in cur.fetchall()})


def _process_page(
    fetcher: PoliteFetcher,
    store: StoreSource,
    url: str,
    prev: dict[str, Any] | None,
    extract: Extractor,
) -> PageOutcome:
    page = PageOutcome(url=url, store=store.name)
    good_before = prev is not None and prev.get("error") is None and prev.get("object_id") is not None
    validators = Validators(prev.get("etag"), prev.get("last_modified")) if good_before else None
    try:
        result = fetcher.fetch(url, validators=validators, policy=store.policy)
    except FetchError as err:
        page.outcome, page.stage, page.reason, page.detail = (
            "rejected",
            "fetch",
            fetch_error_kind(err),
            err.reason,
        )
        return page
    page.status, page.final_url, page.fetched_at = result.status, result.final_url, result.fetched_at
    page.etag, page.last_modified = result.etag, result.last_modified
    if result.not_modified:
        page.outcome = "not_modified"
        return page
    body = result.body or b""
    page.content_sha256 = hashlib.sha256(body).hexdigest()
    if good_before and prev.get("content_sha256") == page.content_sha256:
        page.outcome = "not_modified"  # same bytes as last time: nothing to parse
        return page
    try:
        record = extract(body, result.final_url, result.content_type)
    except ExtractionError as err:
        page.outcome, page.stage, page.reason, page.detail = "rejected", "extract", "no_product", str(err)
        return page
    except Exception as err:  # noqa: BLE001 - an extractor bug must not stop the run
        page.outcome, page.stage, page.reason = "rejected", "extract", "extractor_failed"
        page.detail = f"{type(err).__name__}: {err}"
        return page
    page.record = record
    try:
        page.clean, page.packages, page.warnings = _validate(record)
    except _Rejected as rej:
        page.outcome, page.stage, page.reason, page.detail = "rejected", "validate", rej.reason, rej.detail
        return page
    page.outcome = "extracted"
    return page


# ---------------------------------------------------------------------------------------------- de-duplicate
def _group_pages(pages: list[PageOutcome]) -> list[list[PageOutcome]]:
    """Pages of one product together: union of shared canonical URL, GTIN or normalised name."""
    parent = list(range(len(pages)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict[tuple[str, str], int] = {}
    for i, page in enumerate(pages):
        keys = [("url", page.source), ("name", page.clean.name)]
        if page.record.gtin:
            keys.append(("gtin", page.record.gtin.lstrip("0")))
        for key in keys:
            if key in owner:
                parent[find(i)] = find(owner[key])
            else:
                owner[key] = i
    groups: dict[int, list[PageOutcome]] = {}
    for i, page in enumerate(pages):
        groups.setdefault(find(i), []).append(page)
    return list(groups.values())


def _observations_of(page: PageOutcome) -> list[dict[str, Any]]:
    """The observation rows one page contributes (without object id, run id)."""
    rec, raw = page.clean, page.record.raw
    rows = []
    for feat, value in rec.known_features().items():
        numeric = feat in NUMERIC_FEATURES
        text = (
            raw.get("dims") if feat in DIMENSIONS else raw.get("mass") if feat == "mass_g" else raw.get(feat)
        )
        rows.append(
            {
                "feature": feat,
                "value_num": float(value) if numeric else None,
                "value_text": None if numeric else str(value),
                "role": "product",
                "raw_text": (text or str(value))[:500],
            }
        )
    for i, pkg in enumerate(page.packages, start=1):
        for feat, value in pkg.items():
            text = raw.get("package_dims") if feat in DIMENSIONS else raw.get("package_mass")
            rows.append(
                {
                    "feature": feat,
                    "value_num": float(value),
                    "value_text": None,
                    "role": "package",
                    "raw_text": (f"package {i}: " + (text or f"{value:g}"))[:500],
                }
            )
    for row in rows:
        row.update(source=page.source, adapter=page.record.adapter, fetched_at=page.fetched_at)
    return rows


def _signature(rows: Iterable[dict[str, Any]]) -> tuple:
    return tuple(
        sorted(
            (
                r["feature"],
                r["role"],
                None if r["value_num"] is None else round(float(r["value_num"]), 6),
                r["value_text"],
            )
            for r in rows
        )
    )


# ---------------------------------------------------------------------------------------------- write
def _bulk(con, view: str, columns: list[str], rows: list[dict[str, Any]], sql: str) -> None:
    """Run ``sql`` once over ``rows`` exposed as the relation ``view`` (see kb.catalog.bulk_execute)."""
    bulk_execute(con, view, columns, rows, sql)


def _warm_up_arrow() -> None:
    """Register one Arrow table on a throwaway in-memory database: DuckDB and pyarrow import what they need
    for that (pandas and friends, seconds on a cold, busy machine) now, not while we hold the write lock."""
    import duckdb
    import pyarrow as pa

    con = duckdb.connect()
    try:
        con.register("warm_up", pa.table({"x": [1]}))
        con.execute("SELECT count(*) FROM warm_up").fetchone()
    finally:
        con.close()


def _naive(ts: datetime | None) -> datetime | None:
    return ts.replace(tzinfo=None) if ts is not None and ts.tzinfo is not None else ts


def _write(
    kb, outcomes: list[PageOutcome], report: IngestionReport, events: list[tuple[str, str, str]], now
) -> None:
    """Stages 5-7 in one write transaction (see the module docstring)."""
    extracted = [p for p in outcomes if p.outcome == "extracted"]
    groups = _group_pages(extracted)
    pause = float(os.environ.get(PAUSE_ENV, "0") or 0)
    _warm_up_arrow()
    with kb.connect(write=True) as con:
        t0 = time.monotonic()
        con.begin()
        try:
            run_id = con.execute(
                "INSERT INTO ingestion_runs (started_at, status, sources) VALUES (?, 'running', ?) RETURNING id",
                [_naive(report.started_at), report.sources],
            ).fetchone()[0]
            report.run_id = run_id
            object_cols = ["id", "name", *FEATURES, "source", "gtin", "canonical_url", "updated_at"]
            existing = {
                row[0]: dict(zip(object_cols, row, strict=True))
                for row in con.execute(f"SELECT {', '.join(object_cols)} FROM objects").fetchall()
            }
            by_name = {o["name"]: oid for oid, o in existing.items()}
            by_url = {o["canonical_url"]: oid for oid, o in existing.items() if o["canonical_url"]}
            by_gtin = {o["gtin"].lstrip("0"): oid for oid, o in existing.items() if o["gtin"]}
            for alias, oid in con.execute("SELECT alias, object_id FROM object_aliases").fetchall():
                by_name.setdefault(alias, oid)

            # Match each product (group of pages) to an object, or plan a new one.
            matched: dict[int, list[PageOutcome]] = {}
            fresh: list[list[PageOutcome]] = []
            for group in groups:
                oid = None
                for look in (
                    lambda p: by_url.get(p.source),
                    lambda p: by_gtin.get((p.record.gtin or "").lstrip("0")) if p.record.gtin else None,
                    lambda p: by_name.get(p.clean.name),
                ):
                    oid = next((o for o in map(look, group) if o is not None), None)
                    if oid is not None:
                        break
                if oid is None:
                    fresh.append(group)
                else:
                    matched.setdefault(oid, []).extend(group)

            # Existing observations of the matched objects, for idempotency and fusion.
            old_obs: dict[int, list[dict[str, Any]]] = {}
            if matched:
                cur = con.execute(
                    "SELECT id, object_id, feature, value_num, value_text, role, source, adapter, fetched_at, "
                    "run_id FROM observations WHERE list_contains(?, object_id)",
                    [list(matched)],
                )
                cols = [d[0] for d in cur.description]
                for row in cur.fetchall():
                    rec = dict(zip(cols, row, strict=True))
                    old_obs.setdefault(rec["object_id"], []).append(rec)

            # New objects: values fused from their pages alone.
            new_rows, new_obs_by_name = [], {}
            for group in fresh:
                first = group[0]
                rows = _dedupe_rows(r for p in group for r in _observations_of(p))
                fused = fuse(_as_observations(rows))
                values = _catalog_values(fused.values, {}, report.warnings, first.clean.name)
                report.warnings.extend(f"{first.clean.name}: {w}" for w in fused.warnings)
                new_rows.append(
                    {
                        "name": first.clean.name,
                        **values,
                        "source": first.source,
                        "gtin": next((p.record.gtin for p in group if p.record.gtin), None),
                        "canonical_url": first.source,
                        "created_at": now,
                        "updated_at": now,
                    }
                )
                new_obs_by_name[first.clean.name] = rows
            cols = ["name", *FEATURES, "source", "gtin", "canonical_url", "created_at", "updated_at"]
            _bulk(
                con,
                "ingest_new_objects",
                cols,
                new_rows,
                f"INSERT INTO objects ({', '.join(cols)}) SELECT {', '.join(cols)} FROM ingest_new_objects",
            )
            ids: dict[str, int] = {}
            if new_obs_by_name:
                ids = dict(
                    con.execute(
                        "SELECT name, id FROM objects WHERE list_contains(?, name)", [list(new_obs_by_name)]
                    ).fetchall()
                )
            obs_rows: list[dict[str, Any]] = []
            object_of_page: dict[str, int] = {}
            for group in fresh:
                oid = ids[group[0].clean.name]
                for p in group:
                    object_of_page[p.url] = oid
                obs_rows.extend({**r, "object_id": oid} for r in new_obs_by_name[group[0].clean.name])
                report.new_objects.append(group[0].clean.name)

            # Matched objects: keep only pages that say something new, then fuse everything.
            update_rows = []
            for oid, group in matched.items():
                obj = existing[oid]
                for p in group:
                    object_of_page[p.url] = oid
                history = old_obs.get(oid, [])
                last_run_of: dict[str, Any] = {}
                for h in history:
                    if h["source"] not in last_run_of or (h["run_id"] or -1) > (
                        last_run_of[h["source"]] or -1
                    ):
                        last_run_of[h["source"]] = h["run_id"]
                latest_sig = {
                    src: _signature(h for h in history if h["source"] == src and h["run_id"] == rid)
                    for src, rid in last_run_of.items()
                }
                added = []
                for rows_of_source in _rows_by_source(
                    _dedupe_rows(r for p in group for r in _observations_of(p))
                ):
                    src = rows_of_source[0]["source"]
                    if latest_sig.get(src) != _signature(rows_of_source):
                        added.extend(rows_of_source)
                if not added:
                    report.unchanged += 1
                    continue
                # Curated values that never got an observation row become one now (rule 2's "curated source").
                observed = {h["feature"] for h in history if h["role"] == "product"}
                baseline = [
                    {
                        "feature": f,
                        "value_num": float(obj[f]) if f in NUMERIC_FEATURES else None,
                        "value_text": None if f in NUMERIC_FEATURES else str(obj[f]),
                        "role": "product",
                        "source": obj["source"] or "catalog",
                        "adapter": "catalog",
                        "fetched_at": obj["updated_at"],
                        "raw_text": f"catalog value before ingestion run {run_id}",
                    }
                    for f in FEATURES
                    if obj[f] is not None and f not in observed and f in {r["feature"] for r in added}
                ]
                added = baseline + added
                obs_rows.extend({**r, "object_id": oid} for r in added)
                fused = fuse(_as_observations([*history, *added]))
                report.warnings.extend(f"{obj['name']}: {w}" for w in fused.warnings)
                values = _catalog_values(fused.values, obj, report.warnings, obj["name"])
                first = group[0]
                update_rows.append(
                    {
                        "id": oid,
                        **values,
                        "gtin": obj["gtin"] or next((p.record.gtin for p in group if p.record.gtin), None),
                        "canonical_url": obj["canonical_url"] or first.source,
                        "updated_at": now,
                    }
                )
                report.updated_objects.append(obj["name"])
            # Other names a product goes by (a second store's title matched by URL or GTIN) become aliases.
            alias_rows = []
            taken = set(by_name) | set(ids)
            owners = [(ids[g[0].clean.name], g) for g in fresh] + list(matched.items())
            for oid, group in owners:
                for p in group:
                    if p.clean.name not in taken:
                        taken.add(p.clean.name)
                        alias_rows.append({"alias": p.clean.name, "object_id": oid})
            _bulk(
                con,
                "ingest_aliases",
                ["alias", "object_id"],
                alias_rows,
                "INSERT INTO object_aliases (alias, object_id) SELECT alias, object_id FROM ingest_aliases",
            )
            report.aliases_added = len(alias_rows)
            sets = ", ".join(f"{c} = u.{c}" for c in [*FEATURES, "gtin", "canonical_url", "updated_at"])
            _bulk(
                con,
                "ingest_updates",
                ["id", *FEATURES, "gtin", "canonical_url", "updated_at"],
                update_rows,
                f"UPDATE objects SET {sets} FROM ingest_updates u WHERE objects.id = u.id",
            )
            obs_cols = [
                "object_id",
                "feature",
                "value_num",
                "value_text",
                "role",
                "source",
                "adapter",
                "fetched_at",
                "raw_text",
                "run_id",
            ]
            for r in obs_rows:
                r["run_id"] = run_id
                r["fetched_at"] = _naive(r["fetched_at"]) or now
            _bulk(
                con,
                "ingest_observations",
                obs_cols,
                obs_rows,
                f"INSERT INTO observations ({', '.join(obs_cols)}) SELECT {', '.join(obs_cols)} FROM ingest_observations",
            )

            # Pages: validators for next time (not-modified pages keep their object and hash).
            page_rows = []
            for p in outcomes:
                row = {
                    "url": p.key,
                    "canonical_url": p.source if p.record is not None else None,
                    "etag": p.etag,
                    "last_modified": p.last_modified,
                    "content_sha256": p.content_sha256,
                    "status": p.status,
                    "fetched_at": _naive(p.fetched_at) or now,
                    "object_id": object_of_page.get(p.url),
                    "error": f"{p.reason}: {p.detail}" if p.outcome == "rejected" else None,
                    "run_id": run_id,
                }
                page_rows.append(row)
            not_modified = [
                r for r, p in zip(page_rows, outcomes, strict=True) if p.outcome == "not_modified"
            ]
            others = [r for r, p in zip(page_rows, outcomes, strict=True) if p.outcome != "not_modified"]
            _bulk(
                con,
                "ingest_seen",
                ["url", "status", "fetched_at", "run_id", "etag", "last_modified"],
                not_modified,
                "UPDATE pages SET status = s.status, fetched_at = s.fetched_at, run_id = s.run_id, "
                "etag = coalesce(s.etag, pages.etag), last_modified = coalesce(s.last_modified, pages.last_modified) "
                "FROM ingest_seen s WHERE pages.url = s.url",
            )
            page_cols = list(others[0]) if others else []
            _bulk(
                con,
                "ingest_pages",
                ["url"],
                others,
                "DELETE FROM pages WHERE url IN (SELECT url FROM ingest_pages)",
            )
            _bulk(
                con,
                "ingest_pages",
                page_cols,
                others,
                f"INSERT INTO pages ({', '.join(page_cols)}) SELECT {', '.join(page_cols)} FROM ingest_pages",
            )
            event_rows = [
                {
                    "run_id": run_id,
                    "url": p.url,
                    "stage": p.stage,
                    "reason": f"{p.reason}: {p.detail}",
                    "occurred_at": _naive(p.fetched_at) or now,
                }
                for p in outcomes
                if p.outcome == "rejected"
            ] + [
                {"run_id": run_id, "url": url, "stage": stage, "reason": reason, "occurred_at": now}
                for url, stage, reason in events
            ]
            _bulk(
                con,
                "ingest_events",
                ["run_id", "url", "stage", "reason", "occurred_at"],
                event_rows,
                "INSERT INTO page_events (run_id, url, stage, reason, occurred_at) "
                "SELECT run_id, url, stage, reason, occurred_at FROM ingest_events",
            )
            report.new = len(report.new_objects)
            report.updated = len(report.updated_objects)
            report.observations_added = len(obs_rows)
            report.finished_at = now
            report.duration_s += time.monotonic() - t0
            con.execute(
                "UPDATE ingestion_runs SET finished_at = ?, status = ?, fetched = ?, not_modified = ?, "
                "extracted = ?, rejected = ?, new = ?, updated = ?, rejected_reasons = ?, errors = ?, "
                "duration_s = ? WHERE id = ?",
                [
                    _naive(now),
                    report.status,
                    report.fetched,
                    report.not_modified,
                    report.extracted,
                    report.rejected,
                    report.new,
                    report.updated,
                    json.dumps(report.rejected_reasons, sort_keys=True),
                    json.dumps(report.errors[:100]),
                    report.duration_s,
                    run_id,
                ],
            )
            if pause > 0:
                print("ingest: write transaction open, pausing before commit", file=sys.stderr, flush=True)
                time.sleep(pause)
            con.commit()
        except BaseException:
            con.rollback()
            raise
        report.write_s = time.monotonic() - t0


def _dedupe_rows(rows: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    """Drop exact repeats (the same source stating the same value twice, e.g. a duplicate route)."""
    seen, out = set(), []
    for r in rows:
        key = (r["source"], r["feature"], r["role"], r["value_num"], r["value_text"])
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def _rows_by_source(rows: list[dict[str, Any]]) -> list[list[dict[str, Any]]]:
    groups: dict[str, list[dict[str, Any]]] = {}
    for r in rows:
        groups.setdefault(r["source"], []).append(r)
    return list(groups.values())


def _as_observations(rows: Iterable[dict[str, Any]]) -> list[Observation]:
    out = []
    for r in rows:
        value = r["value_num"] if r["value_num"] is not None else r["value_text"]
        if value is None:
            continue
        out.append(
            Observation(
                feature=r["feature"],
                value=value,
                source=r["source"],
                role=r["role"],
                fetched_at=_naive(r.get("fetched_at")),
                id=r.get("id") or 0,
                adapter=r.get("adapter"),
            )
        )
    return out


def _catalog_values(
    fused: dict[str, Any], current: dict[str, Any], warnings: list[str], name: str
) -> dict[str, Any]:
    """Fused values over the current ones, checked and sorted by the catalog's rules. A fused value the
    catalog refuses (it cannot happen with validated observations, but old rows may predate a rule) keeps
    the current value, with a warning."""
    merged = {f: fused.get(f, current.get(f)) for f in FEATURES}
    try:
        return ObjectRecord.create("x", **merged).features()
    except InvalidFeature as err:
        warnings.append(f"{name}: fused {err}; kept the catalog's values")
        return ObjectRecord.create("x", **{f: current.get(f) for f in FEATURES}).features()


# ---------------------------------------------------------------------------------------------- the job
def _fetch_all(
    fetcher: PoliteFetcher,
    plan: list[tuple[StoreSource, str]],
    previous: dict[str, dict[str, Any]],
    extract: Extractor,
    progress: ProgressFn | None,
    max_hosts: int,
) -> list[PageOutcome]:
    """Fetch and extract every planned page: hosts in parallel (up to ``max_hosts``), each host's pages in
    order, one at a time (the fetcher also enforces that). Outcomes come back in plan order."""
    by_host: dict[str, list[int]] = {}
    for i, (_, url) in enumerate(plan):
        by_host.setdefault(urlsplit(url).netloc, []).append(i)
    outcomes: list[PageOutcome | None] = [None] * len(plan)
    lock = threading.Lock()
    done = 0

    def crawl(indices: list[int]) -> None:
        nonlocal done
        for i in indices:
            store, url = plan[i]
            outcomes[i] = _process_page(fetcher, store, url, previous.get(url), extract)
            with lock:
                done += 1
                if progress:
                    progress(done, len(plan), url)

    workers = max(1, min(max_hosts, len(by_host)))
    if workers == 1:
        for indices in by_host.values():
            crawl(indices)
    else:
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="ingest-host") as pool:
            list(pool.map(crawl, by_host.values()))  # re-raises a worker's unexpected error
    return [o for o in outcomes if o is not None]


def run_ingestion(
    kb,
    sources: Sources,
    *,
    session: requests.Session,
    clock: Clock | None = None,
    progress: ProgressFn | None = None,
    extract: Extractor | None = None,
    max_hosts: int = DEFAULT_MAX_HOSTS,
) -> IngestionReport:
    """Run the whole job (see the module docstring) and return its report.

    ``kb`` is a :class:`kb.catalog.KnowledgeBase` opened for writing. The network (``session``) and the
    clock are passed in. Up to ``max_hosts`` hosts are crawled at the same time (each still one request at a
    time, with its delay). Pages that fail are recorded and skipped; only a failure of the run as a whole
    (the database cannot be written) raises :class:`~kb.errors.IngestionError`, and then the catalog is
    left exactly as it was.
    """
    clock = clock or SystemClock()
    extract = extract or _default_extractor()
    t0 = clock.monotonic()
    report = IngestionReport(run_id=None, status="ok", sources=sources.describe(), started_at=clock.now())
    fetcher = PoliteFetcher(session, clock=clock)
    try:
        previous = _previous_pages(kb)
    except Exception as err:
        raise IngestionError(f"cannot read the catalog's pages table: {err}") from None
    events: list[tuple[str, str, str]] = []
    plan: list[tuple[StoreSource, str]] = []
    for store in sources.stores:
        for url in discover_urls(fetcher, store, events):
            plan.append((store, url))
    # The same URL listed by two stores is fetched once.
    plan = list({url: (store, url) for store, url in reversed(plan)}.values())[::-1]
    report.pages = len(plan)
    if progress:
        progress(0, len(plan), "")
    outcomes = _fetch_all(fetcher, plan, previous, extract, progress, max_hosts)
    report.fetched = sum(1 for p in outcomes if p.status is not None and 200 <= p.status < 300)
    report.not_modified = sum(1 for p in outcomes if p.outcome == "not_modified")
    report.extracted = sum(1 for p in outcomes if p.record is not None)
    rejected = [p for p in outcomes if p.outcome == "rejected"]
    report.rejected = len(rejected)
    report.rejected_reasons = dict(sorted(Counter(p.reason for p in rejected).items()))
    report.errors = [{"url": u, "stage": s, "reason": r} for u, s, r in events]
    for p in outcomes:
        report.warnings.extend(f"{p.url}: {w}" for w in p.warnings)
    if events:
        report.status = "ok_with_errors"
    report.duration_s = clock.monotonic() - t0  # the write adds its own time (real clock) in _write
    write_run(kb, outcomes, report, events, clock)
    return report


#: The stages for other jobs that read pages one by one (the on-demand lookup, scrapers.lookup).
previous_pages = _previous_pages
process_page = _process_page


def write_run(
    kb, outcomes: list[PageOutcome], report: IngestionReport, events: list[tuple[str, str, str]], clock: Clock
) -> None:
    """Stages 5-7 for pages already fetched, extracted and validated: one short write transaction that
    records ``report`` as a run (its ``run_id``, counts and ``write_s`` are filled in). Raises
    :class:`~kb.errors.IngestionError`, leaving the catalog unchanged, when it cannot be written."""
    now = _naive(clock.now())
    try:
        _write(kb, outcomes, report, events, now)
    except IngestionError:
        raise
    except Exception as err:
        raise IngestionError(f"the run could not be written; the catalog is unchanged ({err})") from None
