"""Four classes of the real corpus's development stores (a yoga-mat store, a French gift shop, an electronics
maker's spec grid, a jeweller), each pinned on pages written here in the same shapes:

- a value keyed by the variant it is for (``1-inch: 71"L x 24"W x 1"H``) is that variant's;
- a label over a list of differing values, one per line (``Dimensions :`` / ``- 13,3 x 21,2 cm`` /
  ``- 18 x 30,2 cm``), lists variants: none of them is the product's;
- a label whose brackets name a part (``Size (Main Display)``) is that part's; a unit in a bracketed list
  (``Dimension (HxWxD, mm)``) is the label's unit;
- a sentence's value that a labelled field gives to a part (``Pendant measures 5/16 x 3/4`` beside
  ``Pendant measures: 0.3125" x 0.75"``) is the part's.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.labels import bracket_part, classify_label, classify_other
from scrapers.quantities import unit_hint
from scrapers.spec_pairs import lists_variants
from scrapers.value_forms import keyed_variant


def _page(body: str, title: str = "Thing") -> str:
    return f"<html lang='en'><head><title>{title}</title></head><body><h1>{title}</h1>{body}</body></html>"


def _record(body: str, title: str = "Thing"):
    try:
        return extract_page(_page(body, title), "https://shop.test/p", "text/html")
    except ExtractionError:
        return None


def _dims(body: str, title: str = "Thing"):
    r = _record(body, title)
    return None if r is None or not r.dims else sorted((e["cm"] for e in r.dims), reverse=True)


# ------------------------------------------------------------------------------------- keyed variants
@pytest.mark.parametrize(
    ("value", "keyed"),
    [
        ('1-inch: 71"L x 24"W x 1"H', True),
        ("½-inch: 2.55 lb", True),
        ("Queen: 60 x 80 in", True),
        ("Small: 20 cm", True),
        ("Height: 30 cm", False),  # a measurement label: the product's axis inside a dimensions field
        ("Lens width: 5 cm", False),  # a part's label: classify_other decides, not this rule
        ("Overall: 30 x 20 cm", False),
        ("approx.: 2 kg", False),
        ("Body: 30 cm", False),
        ("30 x 20 cm", False),
        ("10:30", False),  # no letter in the key
        ("One two three four: 3 kg", False),  # four words: a sentence, not a key
        ("One two three: 3 kg", True),
    ],
)  # fmt: skip
def test_a_value_keyed_by_its_variant(value, keyed):
    assert keyed_variant(value) is keyed


def test_keyed_values_under_a_label_are_no_products_size():
    body = "<p><strong>Measurements:</strong> 1-inch: 71\"L x 24\"W x 1\"H</p><p>Material: foam</p>"
    assert _record(body) is None
    assert _dims("<p><strong>Measurements:</strong> 71\"L x 24\"W x 1\"H</p>") == [180.34, 60.96, 2.54]


# --------------------------------------------------------------------------------- lists of variants
def test_a_label_over_differing_values_lists_variants():
    body = "<p>Dimensions :<br/>- 13,3 x 21,2 cm<br/>- 18 x 30,2 cm<br/><br/>Composition : bambou</p>"
    assert _record(body) is None
    assert _dims("<p>Dimensions :<br/>- 13,3 x 21,2 cm<br/><br/>Composition : bambou</p>") == [21.2, 13.3]


def test_one_weight_written_in_two_units_is_not_a_list():
    r = _record("<div><span>Weight</span><p>2 kg</p><p>4.4 lb</p></div>")
    assert r is not None and r.mass_g == 2000.0


@pytest.mark.parametrize(
    ("value", "following", "listed"),
    [
        ("2 kg", "4.4 lb", False),  # the same weight (within 2 %)
        ("2 kg", "2.04 kg", False),  # exactly 2 % apart: still the same
        ("2 kg", "2.05 kg", True),  # just over 2 %
        ("30 x 20 cm", "30 x 20 cm", False),  # the same line twice (a second layout)
        ("30 x 20 cm", "40 x 20 cm", True),
        ("30 x 20 cm", "30 x 20 x 5 cm", True),  # another number of extents
        ("30 x 20 cm", "Height: 40 cm", False),  # the next line is a field of its own
        ("30 x 20 cm", "Colour: red", False),
        ("30 x 20 cm", "made in 2019", False),  # no quantity of the label's kind
    ],
)  # fmt: skip
def test_lists_variants_at_its_boundary(value, following, listed):
    kind = "weight" if "kg" in value else "dimensions"
    assert lists_variants(value, following, classify_label("Weight" if kind == "weight" else "Dimensions")) is listed


# ---------------------------------------------------------------------------------- parts in brackets
@pytest.mark.parametrize(
    ("label", "part"),
    [
        ("Size (Main Display)", "Main Display"),
        ("Dimensions (Pendant)", "Pendant"),
        ("Size (Screen)", "Screen"),
        ("Height (with stand)", None),  # what the product includes
        ("Weight (incl. battery)", None),
        ("Weight (without battery)", None),  # what it leaves out: still the product's
        ("Length (body, cable)", None),  # its body
        ("Size (cm)", None),
        ("Dimension (HxWxD, mm)", None),
    ],
)  # fmt: skip
def test_a_part_named_in_brackets(label, part):
    assert bracket_part(label) == part
    if part:
        assert classify_label(label) is None
        other = classify_other(label)
        assert other is not None and other.role == "component" and other.part == part
    else:
        assert classify_label(label) is not None


def test_a_displays_size_is_not_the_tablets():
    rows = "<table><tr><td>Size (Main Display)</td><td>10.9\" (277.0mm)</td></tr><tr><td>Weight (g)</td><td>523</td></tr></table>"
    r = _record(rows)
    assert r is not None and r.mass_g == 523.0 and not r.dims


@pytest.mark.parametrize(("label", "unit"), [("Dimension (HxWxD, mm)", "mm"), ("Size (mm; W x H x D)", "mm"),
                                             ("Maße (B x H x T, cm)", "cm"), ("Size (Small, Medium)", None)])
def test_a_unit_in_a_bracketed_list(label, unit):
    assert unit_hint(label) == unit


def test_a_spec_grid_with_the_unit_in_a_bracketed_list():
    grid = ("<ul><li><p>Dimension (HxWxD, mm)</p><p>165.8 x 254.3 x 6.5</p></li>"
            "<li><p>Weight (g)</p><p>523</p></li></ul>")
    r = _record(grid)
    assert r is not None and sorted((e["role"], e["cm"]) for e in r.dims) == [
        ("depth", 0.65), ("height", 16.58), ("width", 25.43)]  # the label's order, its unit


# ------------------------------------------------------------------------ a sentence restating a part's
def test_a_sentence_restating_a_parts_labelled_value_is_the_parts():
    body = ("<p>Pendant measures 5/16″ x 3/4″. A gift she will love.</p>"
            "<ul><li>Pendant measures: 0.3125\" x 0.75\"</li><li>Metal: 18k gold</li></ul>")
    assert _dims(body, "Diamond Drop Necklace") is None


def test_a_sentence_with_its_own_value_is_still_the_products():
    body = ("<p>The lamp measures 30 x 20 cm and brightens any room.</p>"
            "<ul><li>Cable length: 150 cm</li></ul>")
    assert _dims(body, "Lamp") == [30.0, 20.0]


@given(st.floats(1, 500), st.floats(1, 500))
def test_lists_variants_is_symmetric(x, y):
    info = classify_label("Weight")
    assert lists_variants(f"{x:.2f} g", f"{y:.2f} g", info) == lists_variants(f"{y:.2f} g", f"{x:.2f} g", info)


# ------------------------------------------------------------- structured data restating the parcel's
def _microdata(weight: str) -> str:
    return (f"<div itemscope itemtype='https://schema.org/Product'><span itemprop='name'>Monitor</span>"
            f"<span itemprop='weight'>{weight}</span></div>")


def test_a_bare_structured_weight_equal_to_the_labelled_shipping_weight_is_the_shipments():
    body = _microdata("6.34 kg") + "<table><tr><td>Versandgewicht</td><td>6,34 kg</td></tr></table>"
    r = _record(body, "Monitor")
    assert r is None or r.mass_g is None
    assert r is None or r.shipping_mass_g == [6340.0]


def test_it_stays_the_products_when_a_labelled_product_weight_agrees():
    body = _microdata("6.34 kg") + ("<table><tr><td>Gewicht</td><td>6,34 kg</td></tr>"
                                    "<tr><td>Versandgewicht</td><td>6,34 kg</td></tr></table>")
    assert _record(body, "Monitor").mass_g == 6340.0


def test_a_structured_weight_equal_to_a_parts_is_still_the_products():
    # only the parcel's or the box's labelled value says a structured weight is not the product's
    body = _microdata("2 kg") + "<table><tr><td>Akkugewicht</td><td>2 kg</td></tr></table>"
    assert _record(body, "Drill").mass_g == 2000.0


def test_a_screens_size_on_a_monitors_page_is_no_extent():
    body = "<table><tr><td>Displaygröße</td><td>23.8\"</td></tr><tr><td>Gewicht</td><td>3 kg</td></tr></table>"
    r = _record(body, "Acer CB242YE 23.8 Full HD IPS Display schwarz")
    assert r is not None and not r.dims and r.mass_g == 3000.0
    # a part named by the title is still the product's otherwise ("Robot Weight" on a robot's page)
    r = _record("<table><tr><td>Robot Weight</td><td>3.2 kg</td></tr></table>", "Robot Vacuum R7")
    assert r is not None and r.mass_g == 3200.0


# ------------------------------------------------------------------ variants in state JSON, placeholders
def _state(obj) -> str:
    import json

    return f"<script>window.__STATE__ = {json.dumps(obj)};</script><p>A rug.</p>"


def test_a_label_with_three_different_values_in_state_json_lists_variants():
    sizes = [{"title": "Size", "value": v} for v in ("2'x3'", "3'x5'", "5'x7'")]
    assert _record(_state({"product": {"name": "Thing", "options": sizes}})) is None


def test_two_values_or_one_repeated_are_not_a_list():
    two = [{"title": "Size", "value": v} for v in ("3'x5'", "3' x 5'", "3'x5'")]  # one size, written thrice
    r = _record(_state({"product": {"name": "Thing", "options": two}}))
    assert r is not None and sorted(e["cm"] for e in r.dims) == [91.44, 152.4]
    pair = [{"title": "Size", "value": v} for v in ("2'x3'", "3'x5'")]
    assert _record(_state({"product": {"name": "Thing", "options": pair}})) is not None


@pytest.mark.parametrize(("size", "refused"), [("1 × 1 × 1 in", True), ("1x1x1 cm", True), ("1.0 x 1.0 x 1.0 in", True),
                                               ("10 x 1 x 1 cm", False), ("1 x 1 x 10 cm", False)])
def test_a_shop_systems_placeholder_size_is_refused(size, refused):
    from scrapers.value_forms import placeholder_size

    assert placeholder_size(f"dimensions_html: {size}") is refused
    r = _record(f"<dl><dt>Dimensions</dt><dd>{size}</dd><dt>Weight</dt><dd>2 kg</dd></dl>")
    assert r is not None and (not r.dims) is refused


# ---------------------------------------------------------------------- a shop system's weight field
class _Obs:
    def __init__(self, source: str, value: float):
        self.source, self.value, self.raw = source, value, f"{source}: {value}"


def _agree(a: float, b: float) -> bool:
    return abs(a - b) <= 0.02 * max(a, b)


def test_a_labelled_product_weight_outranks_a_shop_systems_weight_field():
    from scrapers.restatements import outranked_shop_fields

    shop, label = _Obs("shopify", 150.0), _Obs("spec_table", 56.7)  # Ridge: weight 150 vs "WEIGHT: 2 oz"
    assert outranked_shop_fields([shop, label], _agree) == [(shop, label)]
    woo = _Obs("woocommerce", 560.0)
    assert outranked_shop_fields([woo, _Obs("embedded_json", 500.0)], _agree)[0][0] is woo


@pytest.mark.parametrize("others", [
    [],  # no labelled weight: the field is what there is
    [_Obs("spec_table", 151.0)],  # a labelled weight agrees (within 2 %)
    [_Obs("jsonld", 56.7)],  # structured data is no label
])  # fmt: skip
def test_a_shop_systems_weight_field_stays_when_no_label_disagrees(others):
    from scrapers.restatements import outranked_shop_fields

    assert outranked_shop_fields([_Obs("shopify", 150.0), *others], _agree) == []


def test_a_shop_systems_size_field_is_outranked_by_a_labelled_size_too():
    from scrapers.extract import _dims_agree
    from scrapers.restatements import outranked_shop_fields

    woo, label = _Obs("woocommerce", (9.6, 7.2, 7.2)), _Obs("spec_table", (8.6,))
    assert outranked_shop_fields([woo, label], _dims_agree) == [(woo, label)]
    assert outranked_shop_fields([woo, _Obs("spec_table", (9.6, 7.2))], _dims_agree) == []  # agrees
