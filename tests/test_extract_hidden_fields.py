"""Weights a page states only in hidden ``<meta>`` fields, and heading units over values that name things.

Pages here are small HTML written here, each mirroring a layout class of several real stores: a shop
system's postage weight in Open Graph's ``product:weight`` (PrestaShop) or a microdata ``<meta
itemprop="weight">`` in the buybox (Shopware: one development store labels it ``Versandgewicht`` on the
page, another shows it nowhere and it is the monitor's packed weight that a third store lists as
``Gewicht inkl. Verpackung``); and a variant table whose header states the unit of a column (``Gewicht
(kg)``) over rows that begin with a model's name."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.spec_pairs import figures_only

OG = ('<meta property="product:weight:value" content="1.1"><meta property="product:weight:units" content="KG">'
      '<meta property="product:shipping_weight:value" content="2.0">'
      '<meta property="product:shipping_weight:units" content="kg">')  # fmt: skip


def page(head: str, body: str) -> str:
    return f"<html lang='en'><head><title>Graphics Card</title>{head}</head><body><h1>Graphics Card</h1>{body}</body></html>"


SIZE_ROW = "<table><tr><th>Dimensions</th><td>24.2 x 12.9 x 3.8 cm</td></tr></table>"


def mass_decision(record, value: float) -> str:
    return next(c["decision"] for c in record.candidates if c["feature"] == "mass" and c["value"] == value)


def test_an_open_graph_weight_no_shown_line_states_is_not_the_products():
    record = extract_page(page(OG, SIZE_ROW), "https://shop.example/card")
    assert record.dims_cm == (24.2, 12.9, 3.8)
    assert record.mass_g is None
    assert mass_decision(record, 1100.0).startswith("not the product's: stated only in a hidden meta field")
    assert record.package_mass_g == [pytest.approx(2000.0)]  # the declared shipping weight stays a package's
    assert any("only hidden meta fields state one" in w for w in record.warnings)


def test_an_open_graph_weight_a_shown_row_agrees_with_is_the_products():
    body = SIZE_ROW + "<p>Weight: 1.1 kg</p>"
    record = extract_page(page(OG, body), "https://shop.example/card")
    assert record.mass_g == pytest.approx(1100.0)
    assert mass_decision(record, 1100.0).startswith("chosen")


def test_a_shown_row_that_disagrees_wins_over_the_hidden_weight():
    record = extract_page(page(OG, SIZE_ROW + "<p>Weight: 0.7 kg</p>"), "https://shop.example/card")
    assert record.mass_g == pytest.approx(700.0)


def test_a_hidden_weight_alone_is_no_product_value():
    # the page states nothing else: no product value (the fallback readers ran and found none)
    record = extract_page(page(OG, "<p>A fast card.</p>"), "https://shop.example/card")
    assert record.mass_g is None and record.dims_cm is None
    assert record.package_mass_g == [pytest.approx(2000.0)]
    bare = page(OG.split('<meta property="product:shipping', 1)[0], "<p>A fast card.</p>")
    with pytest.raises(ExtractionError, match="only hidden meta fields state one"):
        extract_page(bare, "https://shop.example/card")


def microdata(weight: str) -> str:
    return (f'<div itemscope itemtype="https://schema.org/Product"><h1 itemprop="name">Monitor 24</h1>{weight}'
            f"{SIZE_ROW}</div>")


@pytest.mark.parametrize("weight, hidden", [
    ('<meta itemprop="weight" content="6.5 kg">', True),
    ('<span itemprop="weight">6.5 kg</span>', False),
    ('<div itemprop="weight" itemscope itemtype="https://schema.org/QuantitativeValue">'
     '<meta itemprop="value" content="6.5"><meta itemprop="unitCode" content="KGM"></div>', True),
    ('<div itemprop="weight" itemscope itemtype="https://schema.org/QuantitativeValue">'
     '<span itemprop="value">6.5</span><meta itemprop="unitCode" content="KGM"></div>', False),
])  # fmt: skip
def test_a_microdata_weight_in_a_meta_element_is_hidden(weight, hidden):
    record = extract_page(page("", microdata(weight)), "https://shop.example/monitor")
    assert record.mass_g == (None if hidden else pytest.approx(6500.0))


def test_a_hidden_microdata_weight_a_shown_row_states_is_the_products():
    body = microdata('<meta itemprop="weight" content="5 kg">') + "<p>Gewicht: 5 kg</p>"
    assert extract_page(page("", body), "https://shop.example/monitor").mass_g == pytest.approx(5000.0)


VARIANT_TABLE = ("<html lang='de'><body><h1>Deckenventilator</h1><p>Gesamthöhe: 36 cm</p><table><tr><th>Modell</th>"
                 "<th>Luftdurchsatz<br>(m³/h)</th><th>Gewicht<br>(kg)</th></tr><tr><td>{first}</td><td>6480</td>"
                 "<td>6,8</td></tr><tr><td>Eco Genuino 152 NT</td><td>12720</td><td>7,0</td></tr></table></body></html>")  # fmt: skip


def test_a_heading_unit_never_completes_a_cell_that_names_a_model():
    # the header row's last label pairs with the first row's first cell, a model's name holding a figure
    record = extract_page(VARIANT_TABLE.format(first="Eco Genuino 122 NT"), "https://shop.example/fan")
    assert record.mass_g is None
    assert not [c for c in record.candidates if c["feature"] == "mass"]


def test_a_heading_unit_still_completes_a_bare_figure():
    record = extract_page(VARIANT_TABLE.format(first="122"), "https://shop.example/fan")
    assert record.mass_g == pytest.approx(122000.0)


@pytest.mark.parametrize("value, figures", [
    ("923", True), ("19,4", True), ("ca. 30 x 20", True), ("5.20(w) x 8.00(h) x 0.40(d)", True),
    ("approx. 12 cm", True), ("Set Size(WXDXH) with Stand: 923 x 253 x 659.4", True),
    ("Eco Genuino 122 NT", False), ("Modell 122", False), ("122 NT", False),
])  # fmt: skip
def test_figures_only(value, figures):
    assert figures_only(value) is figures
