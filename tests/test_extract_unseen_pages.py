"""Pages written here in the shapes of the stores the held-back real pages come from (two Japanese
retailers, Turkish stores, computer makers' spec pages, bookstores): each page's dimensions and mass
within 2 % of its label, package and shipping values kept apart, and the traps each page names. Data
written here, not evidence of generality: the real pages (``test_extract_real_*``) are."""

from __future__ import annotations

from pathlib import Path

import pytest

from scrapers.extract import extract_page
from scrapers.labelled_pages import dims_within, load_labels, package_matches, within

FOLDER = Path(__file__).parent / "fixtures" / "pages" / "unseen"
PAGES = load_labels(FOLDER)


@pytest.fixture(scope="module")
def records():
    return {p.truth["file"]: (extract_page(p.path.read_bytes(), p.url, "text/html"), p.truth) for p in PAGES}


def test_the_folder_is_there():
    assert len(PAGES) == 18


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.truth["file"])
def test_dimensions_and_mass_within_two_percent(records, page):
    record, truth = records[page.truth["file"]]
    want_dims, want_mass = truth["dims_cm"], truth["mass_g"]
    assert dims_within(record.dims_cm, want_dims, 0.02) if want_dims else record.dims_cm is None, record.dims_cm
    assert (record.mass_g is not None and within(record.mass_g, want_mass, 0.02)) if want_mass else (
        record.mass_g is None
    ), record.mass_g
    assert len(record.dims) == len(want_dims or []) or any(e["role"] == "diameter" for e in record.dims)
    assert package_matches(record, truth)
    if "set_mass_g" in truth:
        assert record.set_mass_g == pytest.approx(truth["set_mass_g"])


def test_a_pair_whose_weight_is_stated_per_curtain_keeps_it(records):
    record, _ = records["nitori_jp_curtain.html"]
    assert record.set_count == 2 and record.mass_g == 800.0


def test_the_locale_unit_and_the_heading_unit_are_said(records):
    record, _ = records["bn_book.html"]
    assert any("locale (en-US)" in w for w in record.warnings)


def test_parts_and_capacities_are_never_the_products(records):
    for name in ("yodobashi_jp_kettle.html", "n11_tr_lamp.html", "hepsiburada_tr_pan.html", "dell_laptop_specs.html"):
        record, _ = records[name]
        others = [c for c in record.candidates if c["role"] in ("component", "capacity")]
        assert others and all(c["decision"].startswith("not the product's") for c in others), name
