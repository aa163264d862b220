""""No invented value" on every development page of the real-page corpus (``scrapers.corpus.load_corpus``:
``tests/data/real_pages`` with its cache, and the shared batches; skipped when none is present), judged
by ``scrapers.verdicts.invented``: no extent or mass that the label gives another thing (another product,
a size chart, a package, a set, a site-wide block) and none the page states nowhere. Held-out stores are
not read here (``benchmarks/corpus_bench.py --held-out`` counts them in aggregate)."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.corpus import load_corpus
from scrapers.extract import extract_page
from scrapers.verdicts import invented, page_numbers

DEV = [p for p in load_corpus() if not p.held_out]
pytestmark = pytest.mark.skipif(not DEV, reason="no corpus page is present (cache and shared batches absent)")


@pytest.mark.parametrize("page", DEV, ids=lambda p: p.id)
def test_no_value_is_invented(page):
    body = page.path.read_bytes()
    try:
        record = extract_page(body, page.url or f"https://example.test/{page.id}", "text/html")
    except ExtractionError:
        return  # nothing extracted: nothing invented
    assert invented(record, page.truth, page_numbers(body.decode("utf-8", errors="replace"))) == []
