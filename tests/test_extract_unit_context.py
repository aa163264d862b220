"""Three classes of the real corpus's development stores, pinned on pages written here in the same shapes:

- a number without a unit in a page's state JSON (``"width": "24"``, ``"sizes": "16x16"``: an icon's pixels
  as often as a size) is a measurement only with its unit in a sibling key (a nutrition store's page read
  its icons as 86 x 61 cm);
- an element whose class names the product's own specification (``pdp-product-specs``) is not another
  product's block because its id says ``FindSimilar`` (an electronics distributor's spec table).
"""

from __future__ import annotations

import json

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.page_lines import _container_kind
from scrapers.spec_pairs import has_unit


def _page(body: str, title: str = "Thing") -> str:
    return f"<html lang='en-US'><head><title>{title}</title></head><body><h1>{title}</h1>{body}</body></html>"


def _state(obj: dict) -> str:
    return f"<script>window.__STATE__ = {json.dumps(obj)};</script><p>A fine thing.</p>"


def _record(body: str, title: str = "Thing"):
    try:
        return extract_page(_page(body, title), "https://shop.test/p", "text/html")
    except ExtractionError:
        return None


@pytest.mark.parametrize("obj", [
    {"product": {"name": "Thing", "image": {"width": "24", "height": "24"}}},
    {"product": {"name": "Thing", "icon": {"sizes": "16x16"}}},
    {"product": {"name": "Thing", "width": 34, "height": 24}},
])  # fmt: skip
def test_a_number_without_a_unit_in_state_json_is_no_size(obj):
    r = _record(_state(obj))
    assert r is None or not r.dims


@pytest.mark.parametrize("obj", [
    {"product": {"name": "Thing", "width": "24", "widthUnit": "cm", "height": "12", "heightUnit": "cm"}},
    {"product": {"name": "Thing", "width": "24 cm", "height": "12 cm"}},
])  # fmt: skip
def test_with_its_unit_it_is_read(obj):
    r = _record(_state(obj))
    assert r is not None and sorted(e["cm"] for e in r.dims) == [12.0, 24.0]


@pytest.mark.parametrize(("text", "unit"), [("20\"W x 4\"D", True), ("24", False), ("16x16", False),
                                            ("1,5 kg", True), ("30 x 20 cm", True), ("made in 2019", False)])
def test_has_unit(text, unit):
    assert has_unit(text) is unit


def test_a_size_of_a_mass_alone_is_not_read_as_the_weight():
    # "Größe: 1KG" is as often a variant picker's (a coffee store) as a grocer's net weight ("Size: 275g"),
    # and a "Product size" heading can pair with a capacity's "220 lb" below it: a size label never gives a mass
    r = _record("<dl><dt>Product size</dt><dd>Tested for:</dd><dd>220 lb</dd></dl>")
    assert r is None or r.mass_g is None


@pytest.mark.parametrize(("ident", "classes", "foreign"), [
    ("FindSimilarPnl", "card pdp-section pdp-product-specs", False),
    ("FindSimilarPnl", "card pdp-section", True),
    (None, "similar-products-spec", True),  # one token says both: another product's specification
    (None, "related-products product-grid", True),
])  # fmt: skip
def test_the_products_own_spec_class_outranks_a_foreign_id(ident, classes, foreign):
    assert _container_kind(ident, classes)[0] is foreign


def test_a_spec_table_in_such_a_block_is_read():
    body = ("<div id='FindSimilarPnl' class='card pdp-product-specs'><table>"
            "<tr><td>Weight:</td><td>402 g</td></tr></table></div>")
    r = _record(body)
    assert r is not None and r.mass_g == 402.0


@pytest.mark.parametrize("text", ["43'' H X 27'' W X 28'' D", '43" H X 27" W X 28" D', "43'' H x 27'' W x 28'' D"])
def test_an_upper_case_times_sign_after_an_inch_mark_and_an_axis_letter(text):
    # a furniture store's "Overall Dimensions: 43'' H X 27'' W X 28'' D" gave 43 inches only
    from scrapers.sizes import parse_dims

    (d,) = parse_dims(text, None)
    assert d.values_cm == (109.22, 68.58, 71.12) and d.roles == ("height", "width", "depth")


def test_a_word_before_an_upper_case_x_is_still_no_unit():
    from kb.measures.text import clean_text

    assert clean_text("max 5 X 3") == "max 5 x 3" and clean_text("Size XL X 2") == "Size XL X 2"


@pytest.mark.parametrize(("row", "dims"), [
    ("<dt>Format</dt><dd>13,7 x 21,5 cm</dd>", [21.5, 13.7]),  # a German bookshop's "Format"
    ("<dt>One size</dt><dd>2” x 2” x 2”</dd>", [5.08, 5.08, 5.08]),  # the only size there is
])  # fmt: skip
def test_format_and_one_size_label_the_products_size(row, dims):
    r = _record(f"<dl>{row}</dl>")
    assert r is not None and sorted((e["cm"] for e in r.dims), reverse=True) == dims


def test_a_format_without_a_length_is_no_size():
    assert _record("<dl><dt>Format</dt><dd>16:9</dd></dl>") is None


def test_state_shipped_as_a_json_string_literal_is_read():
    # a large US retailer: window.__DATA__ = JSON.parse("{\"product\": {... \"<B>Weight:</B> 8.5 Pounds\"}}")
    inner = json.dumps({"product": {"name": "Thing", "bullets": ["<B>Number of Pieces:</B> 1", "<B>Weight:</B> 8.5 Pounds"]}})
    script = f"<script>function f(o) {{ return o; }}\nwindow.__DATA__ = JSON.parse({json.dumps(inner)});</script>"
    r = _record(script + "<p>A pan.</p>")
    assert r is not None and r.mass_g == pytest.approx(3855.5, rel=1e-3)


@pytest.mark.parametrize("literal", ['"not json"', '"{broken"', "'single quoted'"])
def test_a_json_parse_of_something_else_is_skipped(literal):
    r = _record(f"<script>var x = JSON.parse({literal});</script><dl><dt>Weight</dt><dd>2 kg</dd></dl>")
    assert r is not None and r.mass_g == 2000.0


@pytest.mark.parametrize(("text", "grams"), [("Vekt: 4 000 kg", 4_000_000.0), ("1 250 g", 1250.0),
                                             ("3 500,5 kg", 3_500_500.0), ("2 x 500 g", 500.0)])
def test_thousands_grouped_with_spaces_before_a_unit(text, grams):
    # French, Nordic and Slavic stores write "4 000 kg" (a narrow no-break space, NFKC writes a space)
    from scrapers.quantities import parse_mass

    assert parse_mass(text) == pytest.approx(grams)


def test_spaced_groups_without_a_unit_are_left_alone():
    from kb.measures.text import clean_text

    assert clean_text("price 1 000 EUR") == "price 1 000 EUR" and clean_text("12 34 cm") == "12 34 cm"


def test_a_nordic_label_with_a_preposition_and_its_unit():
    from scrapers.labels import classify_label

    info = classify_label("Lengde i fot")
    assert info is not None and info.kind == "length" and info.role == "product" and info.unit == "fot"


@pytest.mark.parametrize(("sentence", "height", "mass"), [
    ("Il mesure 89 cm de haut et pèse à peine 8 kg.", 89.0, 8000.0),  # a French barbecue store's copy
    ("The vase is 30 cm tall and glazed by hand.", 30.0, None),
    ("Das Regal ist 120 cm hoch und wiegt knapp 12 kg.", 120.0, 12000.0),
])  # fmt: skip
def test_one_axis_after_a_measuring_verb_and_hedged_weights(sentence, height, mass):
    r = _record(f"<p>{sentence}</p>")
    assert r is not None and [(e["role"], e["cm"]) for e in r.dims] == [("height", height)] and r.mass_g == mass


def test_one_axis_phrase_without_a_measuring_verb_is_no_size():
    # "a 5 cm thick base" names a part's extent in passing
    assert _record("<p>Our lamp has a 5 cm thick base and glows warmly all night.</p>") is None


@pytest.mark.parametrize(("entry", "grams"), [
    ({"name": "Weight", "displayValue": "2 kg"}, 2000.0),
    ({"label": "Weight", "values": ["2 kg"]}, 2000.0),
    ({"key": "Weight", "formattedValue": "2 kg"}, 2000.0),
    ({"label": "Weight", "values": ["2 kg", "3 kg"]}, None),  # several values: options, not the product's
])  # fmt: skip
def test_a_state_entrys_value_under_other_keys(entry, grams):
    r = _record(_state({"product": {"name": "Thing", "specs": [entry]}}))
    assert (r.mass_g if r is not None else None) == grams
