"""Label and value in sibling elements with filler between them (scrapers/spec_pairs.py ``_filler``), and
several label/value pairs in one line.

Pages written here, each mirroring a layout class many stores use: a spec row whose label is followed by
an info icon or a tooltip's ``?`` before the value's element, and a value split over elements with
``approx.`` before the number and the unit in its own element."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.adapters.spec_table import AXIS_GROUP_GAP
from scrapers.extract import extract_page
from scrapers.spec_pairs import MAX_FILLER_LINES, _filler


def page(body: str) -> str:
    return f"<html lang='en'><head><title>Lamp</title></head><body><h1>Lamp</h1>{body}</body></html>"


def mass_of(body: str):
    try:
        return extract_page(page(body), "https://shop.test/p", "text/html").mass_g
    except ExtractionError:
        return None


def test_an_info_icon_between_label_and_value():
    # layout class: <span>Weight</span><span class=tip>i</span><p>3.2 kg</p> in a grid row
    assert mass_of("<div class='row'><span>Weight</span><span class='tip'>i</span><p>3.2 kg</p></div>") == 3200.0


def test_a_value_split_over_elements_after_approx():
    # layout class: <dd><span>approx.</span> <b>3.2</b> <i>kg</i></dd>
    assert mass_of("<dl><dt>Weight</dt><dd><span>approx.</span> <b>3.2</b> <i>kg</i></dd></dl>") == 3200.0


def test_at_most_three_filler_lines_between_label_and_value():
    assert MAX_FILLER_LINES == 3
    fill3 = "<span>i</span><span>?</span><span>info</span>"
    assert mass_of(f"<div><span>Weight</span>{fill3}<p>3.2 kg</p></div>") == 3200.0
    assert mass_of(f"<div><span>Weight</span>{fill3}<span>more</span><p>3.2 kg</p></div>") is None


def test_filler_is_short_digitless_and_names_no_measurement():
    assert _filler("?") and _filler("i") and _filler("approx.") and _filler("a" * 12)
    assert not _filler("a" * 13)
    assert not _filler("ca. 3")  # a digit: a value, not filler
    assert not _filler("Height")  # a label: the next row
    assert not _filler("Cable length")  # a part's label: another row


@pytest.mark.parametrize("between", ["<span>Height</span>", "<span>" + "a" * 13 + "</span>"])
def test_a_label_or_a_longer_text_between_ends_the_search(between):
    assert mass_of(f"<div><span>Weight</span>{between}<p>3.2 kg</p></div>") is None


@pytest.mark.parametrize("sep", ["; ", ", ", " | "])
def test_several_pairs_on_one_line_keep_each_values_unit(sep):
    # layout class: one bullet or cell listing the axes, "Height: 30 cm; Width: 20 cm; Depth: 10 cm"
    from scrapers.spec_pairs import split_inline

    text = sep.join(["Height: 30 cm", "Width: 20 cm", "Depth: 10 cm"])
    assert [v for _, v, _ in split_inline(text)] == ["30 cm", "20 cm", "10 cm"]
    record = extract_page(page(f"<ul><li>{text}</li></ul>"), "https://shop.test/p", "text/html")
    assert sorted(e["cm"] for e in record.dims) == [10.0, 20.0, 30.0]


def dims_of(body: str):
    try:
        return sorted(e["cm"] for e in extract_page(page(body), "https://shop.test/p", "text/html").dims)
    except ExtractionError:
        return None


def test_a_unit_in_a_column_header_gives_the_unit_of_the_values_under_it():
    # layout class: a spec table whose header row states the unit per column, values as bare numbers
    table = ("<table><tr><th>Dimension</th><th>{unit}</th><th>inch</th></tr>"
             "<tr><td>Width</td><td>30</td><td>11.8</td></tr><tr><td>Height</td><td>20</td><td>7.9</td></tr></table>")
    assert dims_of(table.format(unit="cm")) == [20.0, 30.0]
    assert dims_of(table.format(unit="(mm)")) == [2.0, 3.0]
    assert mass_of("<table><tr><th>Weight</th><th>kg</th></tr><tr><td>Weight</td><td>2.5</td></tr></table>") == 2500.0
    # the header's first cell must name a measurement, and the unit must be the cell right after it
    assert dims_of(table.format(unit="cm").replace("Dimension", "Model")) is None
    assert dims_of(table.format(unit="metric").replace("metric</th>", "metric</th><th>cm</th>")) is None


def _record(body: str):
    return extract_page(page(body), "https://shop.test/p", "text/html")


_PACKAGE = (
    "<h2>Package details</h2><div class='package-details'><p><span>Width:</span><span>8 \"</span></p>"
    "<p><span>Height:</span><span>4 \"</span></p><p><span>Length:</span><span>10 ½ \"</span></p></div>"
)


def test_a_lone_product_axis_beside_a_package_of_three_axes_is_the_products_size():
    # layout class (IKEA and others): "Product size" with one axis, "Package details" with three
    body = "<h2>Product size</h2><dl><div><dt>Diameter:</dt><dd>5 \"</dd></div></dl>" + _PACKAGE
    rec = _record(body)
    assert rec.dims_cm == (12.7, 12.7)  # a diameter: two equal extents
    assert rec.package_dims_cm == [(26.67, 20.32, 10.16)]


def test_a_product_row_of_two_axes_still_wins_over_its_own_lone_axis():
    body = (
        "<dl><dt>Diameter:</dt><dd>5 \"</dd></dl>" + "<p>Text without a number.</p>" * (AXIS_GROUP_GAP + 1)
        + "<dl><dt>Width:</dt><dd>12 cm</dd><dt>Height:</dt><dd>9 cm</dd></dl>" + _PACKAGE
    )
    assert _record(body).dims_cm == (12.0, 9.0)


@pytest.mark.parametrize(
    "value",
    ["72 cm bei Größe S", "70 cm in size M", "68 cm en taille 38", "71 cm (talla M)", "69 cm in der Grösse 40"],
)
def test_a_value_stated_for_one_size_is_a_variants_not_the_products(value):
    # layout class (clothing stores): the length of one size of a garment sold in all sizes
    body = f"<dl><dt>Length</dt><dd>{value}</dd><dt>Weight</dt><dd>180 g</dd></dl>"
    rec = _record(body)
    assert rec.dims_cm is None and rec.mass_g == 180.0


@pytest.mark.parametrize("value", ["72 cm", "Size: 72 cm", "72 cm, sized for adults"])
def test_a_plain_length_stays_the_products(value):
    body = f"<dl><dt>Length</dt><dd>{value}</dd><dt>Weight</dt><dd>180 g</dd></dl>"
    assert _record(body).dims_cm == (72.0,)
