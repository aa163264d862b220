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

Stage 1 is :mod:`scrapers.discovery`, stages 2-4 live here; planning stages 5-7 (which rows the run adds or changes) is
:mod:`scrapers.write_set`, executing them in one transaction :mod:`scrapers.catalog_write`, and the fusion
rule :mod:`scrapers.fusion`. A page's identity (:func:`page_identity`) is its URL (or same-host canonical
URL) without a local server's port, so the demo store on another port serves the same pages.

Stages 1-4 run with no database connection open. Stages 5-7 run in **one** short write transaction, with
set-based statements over Arrow batches (no row-by-row round trips): readers wait at most that long, and a
crash or a kill at any moment leaves the catalog as it was before the run or as it is after it. A page whose
values equal what its source said last time adds no rows, so a second run over unchanged pages changes
nothing in the catalog.
"""

from __future__ import annotations

import hashlib
from collections import Counter
from collections.abc import Callable
from contextlib import AbstractContextManager, nullcontext
from typing import Any

import requests

from kb.errors import ExtractionError, FetchError, ImpossibleValues, IngestionError, InvalidFeature
from kb.features import (
    DIMENSIONS,
    NUMERIC_FEATURES,
    ObjectRecord,
    normalize_category,
    normalize_name,
)
from scrapers.catalog_write import PAUSE_ENV, write
from scrapers.crawl import (
    MAX_CRAWLING,
    MAX_WORKING,
    crawl_stores,
)
from scrapers.discovery import discover_urls
from scrapers.fetcher import Clock, PoliteFetcher, SystemClock, Validators, fetch_error_kind
from scrapers.normalize import impossible_value
from scrapers.outcomes import LOCAL_HOSTS, IngestionReport, PageOutcome, page_identity
from scrapers.records import ProductRecord
from scrapers.sources import Sources, StoreSource
from scrapers.write_set import naive

__all__ = [
    "LOCAL_HOSTS",
    "PAUSE_ENV",
    "IngestionReport",
    "PageOutcome",
    "ProgressFn",
    "page_identity",
    "previous_pages",
    "process_page",
    "run_ingestion",
    "write_run",
]

#: progress(done, total, url): called after each page (and once with done=0 when the total is known).
ProgressFn = Callable[[int, int, str], None]
Extractor = Callable[[bytes, str, "str | None"], ProductRecord]

class _Rejected(Exception):
    def __init__(self, reason: str, detail: str):
        self.reason = reason
        self.detail = detail
        super().__init__(f"{reason}: {detail}")


# ---------------------------------------------------------------------------------------------- validate
def _validate(record: ProductRecord) -> tuple[ObjectRecord, list[dict[str, float]], list[str]]:
    """The catalog record a page supports, its package values and warnings; raises _Rejected."""
    warnings: list[str] = []
    name = normalize_name(record.name or "")
    if not name and record.refused.get("name"):
        raise _Rejected("invalid_name", f"the page's name is refused: {record.refused['name']}")
    if not name:
        raise _Rejected("no_name", "the page names no product")
    impossible = [reason for reason in record.refused.values() if impossible_value(reason)]
    if impossible:
        # Every value the page states for one of the product's features is impossible (a mug 40 m tall, a
        # plate weighing -600 g): none of its numbers can be trusted. An impossible candidate that lost to a
        # valid value (a misread alternative, another block's number) is only an --explain row and a warning.
        raise _Rejected(impossible_value(impossible[0]), impossible[0])
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
        raise _Rejected(impossible_value(err.reason) or "invalid_value", str(err)) from None
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
    *,
    until: float | None = None,
    work: AbstractContextManager | None = None,
) -> PageOutcome:
    """Fetch, extract and validate one page. ``work`` (a :class:`~scrapers.crawl.WorkSlots`) is held
    while the page is extracted and validated, not while it is fetched."""
    with_work = work or nullcontext()
    page = PageOutcome(url=url, store=store.name)
    good_before = prev is not None and prev.get("error") is None and prev.get("object_id") is not None
    validators = Validators(prev.get("etag"), prev.get("last_modified")) if good_before else None
    try:
        result = fetcher.fetch(url, validators=validators, policy=store.policy, until=until)
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
    with with_work:
        return _extract_page(page, body, result, extract)


def _extract_page(page: PageOutcome, body: bytes, result, extract: Extractor) -> PageOutcome:
    """Stages 3-4 for a fetched body: ``page`` filled in as extracted or rejected."""
    try:
        record = extract(body, result.final_url, result.content_type)
    except ImpossibleValues as err:  # every value refused: the same reasons as _validate's
        kind = impossible_value(err.refusal) or "invalid_value"
        page.outcome, page.stage, page.reason, page.detail = "rejected", "extract", kind, str(err)
        return page
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


# ---------------------------------------------------------------------------------------------- the job
def run_ingestion(
    kb,
    sources: Sources,
    *,
    session: requests.Session,
    clock: Clock | None = None,
    progress: ProgressFn | None = None,
    extract: Extractor | None = None,
    max_crawling: int = MAX_CRAWLING,
    max_working: int = MAX_WORKING,
) -> IngestionReport:
    """Run the whole job (see the module docstring) and return its report.

    ``kb`` is a :class:`kb.catalog.KnowledgeBase` opened for writing. The network (``session``) and the
    clock are passed in. Up to ``max_crawling`` stores are crawled at the same time, each on its own thread
    under its own budget, and up to ``max_working`` of them parse a page at once (:mod:`scrapers.crawl`:
    a store waiting on the network holds no work slot; each host still one request at a time, with its
    delay). Pages that fail are recorded and skipped; only a failure of the run as a whole
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

    def process(fetcher, store, url, prev, *, until, work):
        return _process_page(fetcher, store, url, prev, extract, until=until, work=work)

    outcomes, events = crawl_stores(
        fetcher,
        sources.stores,
        previous,
        discover=discover_urls,
        process=process,
        clock=clock,
        progress=progress,
        max_crawling=max_crawling,
        max_working=max_working,
    )
    outcomes = _without_duplicate_pages(outcomes, events)
    report.pages = len(outcomes)
    report.fetched = sum(1 for p in outcomes if p.status is not None and 200 <= p.status < 300)
    report.not_modified = sum(1 for p in outcomes if p.outcome == "not_modified")
    report.extracted = sum(1 for p in outcomes if p.record is not None)
    rejected = [p for p in outcomes if p.outcome == "rejected"]
    report.rejected = len(rejected)
    report.rejected_reasons = dict(sorted(Counter(p.reason for p in rejected).items()))
    report.errors = [{"url": u, "stage": s, "reason": r} for u, s, r in events]
    for p in outcomes:
        report.warnings.extend(f"{p.url}: {w}" for w in p.warnings)
    report.status = run_status(report, events)
    report.duration_s = clock.monotonic() - t0  # the write adds its own time (real clock) in _write
    write_run(kb, outcomes, report, events, clock)
    return report


def _without_duplicate_pages(outcomes: list[PageOutcome], events: list[tuple[str, str, str]]) -> list[PageOutcome]:
    """``outcomes`` with one page per identity (:func:`~scrapers.outcomes.page_identity`): two loopback
    stores on different ports can list the same path, which is one page identity. The later one is
    skipped with its reason in ``events`` (stage ``discover``), so the others are written."""
    first: dict[str, PageOutcome] = {}
    out = []
    for p in outcomes:
        seen = first.setdefault(p.key, p)
        if seen is p:
            out.append(p)
        else:
            events.append((p.url, "discover", f"duplicate_page: the same page identity ({p.key}) as {seen.url} of "
                                               f"store {seen.store!r}; skipped"))
    return out


def run_status(report: IngestionReport, events: list[tuple[str, str, str]]) -> str:
    """The run's status: ``failed`` when nothing was read (no page fetched or confirmed unchanged) because
    of failures (an unreadable sitemap or robots.txt, every page's fetch failing: a store that is down),
    ``ok_with_errors`` when some were read despite failures, else ``ok`` (also a run whose stores list no
    page at all and nothing failed). ``objrecall ingest`` exits non-zero on ``failed``
    (:data:`EXIT_CODES`)."""
    failures = bool(events) or report.rejected > 0
    if report.fetched + report.not_modified == 0 and failures:
        return "failed"
    return "ok_with_errors" if events else "ok"


#: ``objrecall ingest``'s exit code per run status (1 and 2 are the CLI's own: an error before the run,
#: such as a malformed sources file or a database that cannot be written, and a usage error).
EXIT_CODES = {"ok": 0, "ok_with_errors": 0, "failed": 3}


#: The stages for other jobs that read pages one by one (the on-demand lookup, scrapers.lookup).
previous_pages = _previous_pages
process_page = _process_page


def write_run(
    kb, outcomes: list[PageOutcome], report: IngestionReport, events: list[tuple[str, str, str]], clock: Clock
) -> None:
    """Stages 5-7 for pages already fetched, extracted and validated: one short write transaction that
    records ``report`` as a run (its ``run_id``, counts and ``write_s`` are filled in). Raises
    :class:`~kb.errors.IngestionError`, leaving the catalog unchanged, when it cannot be written."""
    now = naive(clock.now())
    try:
        write(kb, outcomes, report, events, now)
    except IngestionError:
        raise
    except Exception as err:
        raise IngestionError(f"the run could not be written; the catalog is unchanged ({err})") from None
