"""A demo storefront on loopback: product pages in every format the extractors read, plus broken pages.

``python -m scrapers.demo_store --port 8765`` (or ``objrecall demo-store``) serves it in the foreground;
tests and benchmarks start :class:`DemoStore` in a background thread on a free port. The products and the
truth about them are in :mod:`scrapers.demo_store.products`. :func:`ingest_demo` serves it and runs the
ingestion job over it in one call (what the main job does).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from scrapers.demo_store.products import BROKEN_PAGES, PRODUCTS, BrokenPage, DemoProduct
from scrapers.demo_store.server import DemoStore

if TYPE_CHECKING:
    from scrapers.ingest import IngestionReport, ProgressFn

__all__ = [
    "BROKEN_PAGES",
    "DEMO_SOURCES",
    "PRODUCTS",
    "BrokenPage",
    "DemoProduct",
    "DemoStore",
    "ingest_demo",
]

#: The sources file that reads the demo store (its base URL is overridden to wherever the store runs).
DEMO_SOURCES = Path(__file__).resolve().parent.parent / "demo_sources.toml"


def ingest_demo(kb, *, progress: ProgressFn | None = None, delay_s: float = 0.0) -> IngestionReport:
    """Serve the demo store on a free port of 127.0.0.1 and ingest it into ``kb`` (a writable
    :class:`kb.catalog.KnowledgeBase`) with :data:`DEMO_SOURCES`; no network beyond loopback."""
    import requests

    from scrapers.ingest import run_ingestion
    from scrapers.sources import load_sources

    with DemoStore(port=0, crawl_delay=delay_s or None) as store, requests.Session() as session:
        sources = load_sources(DEMO_SOURCES, base_url=store.base_url, delay_s=delay_s)
        return run_ingestion(kb, sources, session=session, progress=progress)
