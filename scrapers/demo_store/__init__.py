"""A demo storefront on loopback: product pages in every format the extractors read, plus broken pages.

``python -m scrapers.demo_store --port 8765`` (or ``objrecall demo-store``) serves it in the foreground;
tests and benchmarks start :class:`DemoStore` in a background thread on a free port. The products and the
truth about them are in :mod:`scrapers.demo_store.products`.
"""

from scrapers.demo_store.products import BROKEN_PAGES, PRODUCTS, BrokenPage, DemoProduct
from scrapers.demo_store.server import DemoStore

__all__ = ["BROKEN_PAGES", "PRODUCTS", "BrokenPage", "DemoProduct", "DemoStore"]
