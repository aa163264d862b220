"""The scoreboard on the 12 real storefront pages in ../shared/storefront-pages (skipped when absent).

The pages are read from where they are (never copied into the repository); the goal is dimensions and
mass within 1 % on at least 10 of 12.
"""

from __future__ import annotations

import pytest

from scrapers.extract import extract_page
from scrapers.labelled_pages import judge, load_labels, package_matches

PAGES = load_labels()
pytestmark = pytest.mark.skipif(not PAGES, reason="../shared/storefront-pages is absent")


@pytest.fixture(scope="module")
def results():
    out = {}
    for page in PAGES:
        record = extract_page(page.path.read_bytes(), page.url, "text/html")
        out[page.truth["file"]] = (record, page.truth)
    return out


def test_at_least_ten_of_twelve_real_pages_right(results):
    verdicts = {name: judge(record, truth) for name, (record, truth) in results.items()}
    wrong = {name: v.problems for name, v in verdicts.items() if not v.right}
    right = len(verdicts) - len(wrong)
    assert len(verdicts) >= 12
    assert right >= 10, f"{right}/{len(verdicts)} right; wrong: {wrong}"


def test_package_values_kept_apart_on_real_pages(results):
    matched = [name for name, (record, truth) in results.items() if package_matches(record, truth)]
    assert len(matched) >= 10, f"package values matched on {len(matched)} pages only"


def test_ikea_lists_every_package_and_no_product_mass(results):
    record, _ = results["peb-0666abebc0.html"]
    assert record.mass_g is None
    assert len(record.package_dims_cm) == 3 and len(record.package_mass_g) == 3


def test_other_fridge_in_similar_products_is_ignored(results):
    record, _ = results["peb-a8a8fc6a31.html"]
    assert record.dims_cm == (184.0, 60.0, 54.0)
    assert not any("180" in w for w in record.warnings)
