"""Extract one product record from one page: run every adapter, then fuse what they observed.

Entry points: :func:`extract_page` (a body as fetched), :func:`extract_file` (a saved page: ``.html`` or
``.json``). Both return a :class:`~scrapers.records.ProductRecord` in catalog units or raise
:class:`~kb.errors.ExtractionError` with the reason; nothing else escapes, whatever the input.

Fusion, the choice between the adapters' observations, is :func:`scrapers.chooser.fuse` (documented in
``scrapers/EXTRACTION.md`` §3), re-exported here.
"""

from __future__ import annotations

from pathlib import Path

from kb.errors import ExtractionError
from kb.files import read_input_file

# Importing an adapter module registers its adapters (in priority order, whatever the import order).
from scrapers.adapters import (  # noqa: F401
    ADAPTERS,
    Observation,
    embedded_json,
    jsonld,
    microdata,
    shopify,
    spec_table,
    text,
    woocommerce,
)
from scrapers.chooser import AGREE_TOLERANCE, _close, _dims_agree, fuse  # noqa: F401 - tests read the agreement rule here
from scrapers.page import MAX_LINES, Page
from scrapers.records import ProductRecord
from scrapers.trail import category_trail

__all__ = ["ADAPTERS", "AGREE_TOLERANCE", "MAX_PAGE_BYTES", "extract_file", "extract_page", "fuse"]

#: Larger saved pages are refused (the fetcher caps downloads the same way).
MAX_PAGE_BYTES = 50 * 1024 * 1024


def extract_page(body: str | bytes, url: str, content_type: str | None = None) -> ProductRecord:
    """The product record of one page. Raises :class:`ExtractionError` (with the reason) when the page
    holds no product dimensions or mass; never raises anything else."""
    try:
        if body is None or not isinstance(body, (str, bytes, bytearray, memoryview)):
            raise ExtractionError(f"{url}: no page body")
        if len(body) > MAX_PAGE_BYTES:
            raise ExtractionError(f"{url}: page too large ({len(body)} bytes)")
        page = Page(body, str(url or ""), content_type)
        if not page.text.strip():
            raise ExtractionError(f"{url}: empty page")
        if not page.is_json and page.tree is None:
            raise ExtractionError(f"{url}: not an HTML page")
        if page.is_json and page.json is None:
            raise ExtractionError(f"{url}: malformed JSON")
        observations: list[Observation] = []
        for adp in ADAPTERS:
            if adp.fallback and _has_dims_and_mass(observations):
                continue
            try:
                found = adp.func(page)
            except Exception as err:  # noqa: BLE001 - one broken adapter must not lose the others' values
                observations.append(
                    Observation("warning", f"adapter {adp.name} failed: {type(err).__name__}: {err}")
                )
                continue
            for o in found:
                o.source = adp.name
            observations.extend(found)
        if page.truncated:
            observations.append(
                Observation("warning", f"page has over {MAX_LINES} text lines; only the first were read")
            )
        record = fuse(observations, str(url or ""))
        trail = category_trail(page)
        record.breadcrumbs, record.categories = trail.breadcrumbs, trail.categories
        return record
    except ExtractionError:
        raise
    except Exception as err:  # noqa: BLE001 - the contract: ExtractionError or a record, never a crash
        raise ExtractionError(f"{url}: could not read the page ({type(err).__name__}: {err})") from None


def _has_dims_and_mass(observations: list[Observation]) -> bool:
    found = {
        o.feature for o in observations
        if not o.package and o.role == "product" and o.feature in ("dims", "mass") and not o.off_main
    }
    return len(found) == 2


def extract_file(path: str | Path) -> ProductRecord:
    """The product record of a saved page (HTML, or JSON when the name ends in ``.json``)."""
    path = Path(path)
    try:
        if path.stat().st_size > MAX_PAGE_BYTES:
            raise ExtractionError(f"{path}: page too large ({path.stat().st_size} bytes)")
        body = read_input_file(path, MAX_PAGE_BYTES)
    except OSError as err:
        raise ExtractionError(f"{path}: cannot read the file ({err.strerror or err})") from None
    content_type = "application/json" if path.suffix.lower() == ".json" else "text/html"
    return extract_page(body, path.resolve().as_uri(), content_type)
