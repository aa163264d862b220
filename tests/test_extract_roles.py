"""Whose value it is: a set versus one item, the package versus the shipment, a part versus the product's
body, a refused candidate versus a refused product value, and the page's own decimal mark. Pages here are
written here (in the shapes stores publish), not real pages."""

from __future__ import annotations

import pytest

from scrapers.extract import extract_page
from scrapers.labels import classify_label, classify_other
from scrapers.page import Page
from scrapers.page_lines import decimal_mark_of_lines
from scrapers.sets import MAX_SET, per_item, set_size
from scrapers.value_forms import axis_segments, metric_figure


def _page(body: str, title: str = "Thing", lang: str | None = "en") -> str:
    attr = f" lang='{lang}'" if lang is not None else ""
    return f"<html{attr}><head><title>{title}</title></head><body><h1>{title}</h1>{body}</body></html>"


def _decision(record, feature: str, value) -> str:
    return next(c["decision"] for c in record.candidates if c["feature"] == feature and c["value"] == value)


# ------------------------------------------------------------------------------------ a set or one item
@pytest.mark.parametrize(
    ("name", "count"),
    [
        ("Stoneware Pasta Bowl Set of 4", 4), ("Pack of 12 Bowls", 12), ("IKEA bowl, 12 pack", 12),
        ("Herren Boxershorts, 6er Pack", 6), ("Blackout Curtains (Pair)", 2), ("A pair of linen curtains", 2),
        ("Mugs 4-Piece Set", 4), ("Kupfer Topf-Set 5-teilig", 5), ("Çay Bardağı 6'lı Set", 6),
        ("マグカップ 4個セット", 4), ("Lot de 6 verres", 6), ("Set di 4 piatti", 4), ("Juego de 3 sartenes", 3),
        ("Set of four mugs", 4), ("Paar Vorhänge", 2),
    ],
)  # fmt: skip
def test_a_set_is_read_from_the_name(name, count):
    assert set_size(name)[0] == count


@pytest.mark.parametrize(
    "name",
    ["Size: 10 Ounce (Pack of 1)", "charmast 20000mAh Portable Charger", 'Samsung 37" LE37B550', "2 in 1 USB cable",
     "Tempur 90 x 200 cm", "THINK! Herren Boots", "1 Stück Vase", None, ""],
)  # fmt: skip
def test_one_item_is_not_a_set(name):
    assert set_size(name) is None


def test_a_set_count_is_bounded():
    assert set_size(f"Screws, {MAX_SET} pcs")[0] == MAX_SET
    assert set_size(f"Screws, {MAX_SET + 1} pcs") is None
    assert set_size("Bowl, 1 pcs") is None and set_size("Bowls, 2 pcs")[0] == 2


def test_a_sets_weight_is_kept_apart_not_reported_as_one_items():
    body = "<table><tr><th>Weight</th><td>2.4 kg</td></tr><tr><th>Dimensions</th><td>15 x 15 x 6 cm</td></tr></table>"
    record = extract_page(_page(body, "Stoneware Bowls, Pack of 12"), "https://s.example/p")
    assert record.mass_g is None and record.set_mass_g == 2400.0 and record.set_count == 12
    assert any("set of 12" in w and "not one item's" in w and "200 g each" in w for w in record.warnings)
    assert any("set of 12" in w and w.startswith("dims:") for w in record.warnings)
    assert record.dims_cm == (15.0, 15.0, 6.0)  # kept, with the warning
    assert _decision(record, "mass", 2400.0).startswith("the set's value")


def test_a_weight_stated_per_item_on_a_set_page_is_the_items():
    body = "<ul><li>Weight per piece: 200 g</li></ul>"
    record = extract_page(_page(body, "Stoneware Bowls, Pack of 12"), "https://s.example/p")
    assert record.mass_g == 200.0 and record.set_mass_g is None and record.set_count == 12
    assert per_item("Gewicht je Stück: 200 g") and not per_item("Item Weight: 1.2 kg")


def test_a_single_item_page_has_no_set():
    record = extract_page(_page("<ul><li>Weight: 2.4 kg</li></ul>", "Stoneware Bowl (Pack of 1)"), "https://s.example/p")
    assert record.mass_g == 2400.0 and record.set_count is None and record.set_mass_g is None


# ------------------------------------------------ a qualifier in a bracket after the value (packaging)
@pytest.mark.parametrize(
    ("value", "packed"),
    [("5.197kg [Eigenmessung inkl. Verpackung & Beilagen]", True), ("2 kg (incl. packaging)", True),
     ("3 kg (with box)", True), ("2 kg (ohne Verpackung)", False), ("2 kg (without packaging)", False),
     ("5.60kg (mit Standfuß)", False), ("1.65 lb / 750 g (Body Only)", False),
     ("2 kg (inkl. Verpackung 2,5 kg)", False),  # a figure inside: another value, not a qualifier
     ("2 kg inkl. Verpackung", False), ("(inkl. Verpackung) 2 kg", False)],  # no bracket after the number
)  # fmt: skip
def test_a_bracket_after_the_value_saying_it_includes_the_packaging(value, packed):
    from scrapers.value_forms import packed_value

    assert packed_value(value) is packed


def test_a_weight_including_the_packaging_is_a_package_value_wherever_the_store_writes_it():
    body = ("<table><tr><td>Breite</td><td>54 cm</td></tr><tr><td>Gewicht</td>"
            "<td>5,2 kg [inkl. Verpackung]</td></tr></table>")  # fmt: skip
    record = extract_page(_page(body, lang="de"), "https://s.example/p")
    assert record.mass_g is None and record.package_mass_g == [5200.0]
    kept = extract_page(_page(body.replace("inkl.", "ohne"), lang="de"), "https://s.example/p")
    assert kept.mass_g == 5200.0 and not kept.package_mass_g

def test_a_set_page_stating_only_the_sets_weight_is_still_a_record():
    record = extract_page(_page("<ul><li>Weight: 2.4 kg</li></ul>", "Mugs, Set of 4"), "https://s.example/p")
    assert record.mass_g is None and record.set_mass_g == 2400.0 and record.dims_cm is None


# --------------------------------------------------------------------------- package versus shipment
def test_shipping_and_package_values_are_kept_apart_from_each_other():
    body = ("<ul><li>Item Weight: 1.1 kg</li><li>Package Weight: 1.4 kg</li><li>Shipping Weight: 1.9 kg</li>"
            "<li>Package Dimensions: 40 x 30 x 20 cm</li><li>Shipping Dimensions: 45 x 35 x 25 cm</li></ul>")  # fmt: skip
    record = extract_page(_page(body), "https://s.example/p")
    assert record.mass_g == 1100.0
    assert record.package_mass_g == [1400.0] and record.shipping_mass_g == [1900.0]
    assert record.package_dims_cm == [(40.0, 30.0, 20.0)] and record.shipping_dims_cm == [(45.0, 35.0, 25.0)]
    roles = {c["value"]: c["role"] for c in record.candidates if c["feature"] == "mass"}
    assert roles == {1100.0: "product", 1400.0: "package", 1900.0: "shipping"}


@pytest.mark.parametrize(
    ("label", "shipping"),
    [("Shipping Weight", True), ("Gross weight", True), ("Bruttogewicht", True), ("Versandgewicht", True),
     ("発送重量", True), ("商品毛重", True), ("Kargo Ağırlığı", True), ("Package Weight", False),
     ("Verpackungsgewicht", False), ("梱包重量", False), ("Item Weight", False), ("Weight without packaging", False)],
)  # fmt: skip
def test_which_package_labels_name_the_shipment(label, shipping):
    assert classify_label(label).shipping is shipping


def test_separate_shipping_axis_fields_are_the_shipments():
    body = "<ul><li>Shipping Length: 45 cm</li><li>Shipping Width: 35 cm</li><li>Weight: 2 kg</li></ul>"
    record = extract_page(_page(body), "https://s.example/p")
    assert record.dims_cm is None and record.shipping_dims_cm == [(45.0, 35.0)]


# -------------------------------------------------------------------- the product's body versus a part
@pytest.mark.parametrize(
    ("label", "kind"),
    [("Body of lamp width", "width"), ("Lamp body width", "width"), ("Depth of fitting from wall", "depth"),
     ("Starting weight", "weight"), ("En", "width"), ("Boy", "length")],
)  # fmt: skip
def test_role_words_anywhere_in_a_label_of_the_products_body(label, kind):
    info = classify_label(label)
    assert info is not None and info.kind == kind and info.role == "product"


@pytest.mark.parametrize(
    ("label", "part"),
    [("Wall bracket width", "wall bracket"), ("Cable length", "cable"), ("Lid diameter", "lid"),
     ("Stand height", "stand"), ("Schlauchlänge", "schlauch"), ("Body cable length", None)],
)  # fmt: skip
def test_a_part_word_names_the_component(label, part):
    assert classify_label(label) is None
    other = classify_other(label)
    assert other.role == "component"
    if part:
        assert other.part == part


def test_a_parts_value_is_explained_with_the_part_it_names():
    body = "<ul><li>Body of lamp width: 34cm</li><li>Wall bracket width: 9.2cm</li><li>Depth of fitting from wall: 22.1cm</li></ul>"
    record = extract_page(_page(body), "https://s.example/p")
    assert sorted((e["role"], e["cm"]) for e in record.dims) == [("depth", 22.1), ("width", 34.0)]
    assert "(wall bracket)" in _decision(record, "dims", [9.2])


# -------------------------------------------------------------- refused candidates versus refused values
def test_an_absurd_candidate_that_lost_to_a_valid_value_does_not_reject_the_page():
    from scrapers.ingest import _validate

    body = ("<table><tr><th>Dimensions</th><td>30 x 20 x 10 cm</td></tr><tr><th>Weight</th><td>2 kg</td></tr>"
            "</table><p>Höhe: 4000 cm</p>")  # fmt: skip
    record = extract_page(_page(body, "Oak Side Table"), "https://s.example/p")
    assert any("absurd" in w for w in record.warnings) and record.refused == {}
    assert any(c["decision"].startswith("refused") for c in record.candidates)
    catalog, _, _ = _validate(record)
    assert catalog.mass_g == 2000.0


def test_a_page_whose_every_product_value_is_absurd_is_rejected():
    from scrapers.ingest import _Rejected, _validate

    body = "<table><tr><th>Height</th><td>4000 cm</td></tr><tr><th>Weight</th><td>2 kg</td></tr></table>"
    record = extract_page(_page(body, "Giant Mug"), "https://s.example/p")
    assert record.dims_cm is None and "absurd" in record.refused["dims"]
    with pytest.raises(_Rejected, match="absurd_value"):
        _validate(record)


# ---------------------------------------------------------------------- the page's own decimal mark
TURKISH = ("<html><head><title>Tencere</title></head><body><h1>Tencere</h1><ul><li>Ağırlık: 1,250 kg</li>"
           "<li>Çap: 24,5 cm</li></ul></body></html>")  # fmt: skip


@pytest.mark.parametrize("url", ["https://www.magaza.com.tr/p/1", "http://127.0.0.1:8123/p/1", "file:///tmp/p.html"])
def test_the_decimal_mark_comes_from_the_page_never_from_the_host(url):
    record = extract_page(TURKISH, url)
    assert record.mass_g == 1250.0 and record.dims_cm == (24.5, 24.5)


def test_a_declared_language_decides_before_number_forms():
    page = "<html lang='en-US'><body><h1>Pot</h1><p>Weight: 1,250 kg</p><p>Width: 24,5 cm</p></body></html>"
    assert Page(page, "https://shop.example.de/p").decimal_comma is False
    assert Page(page.replace("en-US", "tr"), "https://shop.example.com/p").decimal_comma is True


def test_a_jsonld_language_decides_when_the_html_has_none():
    ld = '<script type="application/ld+json">{"@type": "Product", "name": "Pot", "inLanguage": "de-DE"}</script>'
    assert Page(f"<html><head>{ld}</head><body><p>1.250 kg</p></body></html>", "http://127.0.0.1/p").decimal_comma


@pytest.mark.parametrize(
    ("texts", "comma"),
    [(["1,5 kg", "24,5 cm"], True), (["1.5 kg", "24.5 cm"], False), (["1,5 kg", "2.5 kg"], None),
     (["1,250 kg"], None), (["1,5 kg", "1,5 kg", "2.5 kg"], True), ([], None)],
)  # fmt: skip
def test_number_forms_decide_at_the_majority(texts, comma):
    from scrapers.page_lines import Line

    lines = [Line(t, False, i, i) for i, t in enumerate(texts)]
    assert decimal_mark_of_lines(lines) is comma


# ------------------------------------------------------------------- metric beside imperial, axis words
@pytest.mark.parametrize(
    ("value", "metric"),
    [("0.61 inch (1.56 cm)", "1.56 cm"), ("Starting at 2.8 lb (1.27 kg)", "1.27 kg"),
     ("12.32 x 8.72 in (312.8 x 221.6 mm)", "312.8 x 221.6 mm"), ("1.27 kg (2.8 lb)", None),
     ("30 cm (12 in)", None), ("2.8 lb", None), ("0.61 inch (approx.)", None), ("1.5 cm (0.6 in)", None)],
)  # fmt: skip
def test_the_metric_figure_is_preferred_when_both_are_stated(value, metric):
    assert metric_figure(value) == metric


def test_a_computer_makers_spec_sheet_gives_its_metric_figures():
    body = ("<ul><li>Height: 0.44 inch (1.13 cm)</li><li>Width: 11.97 inches (30.41 cm)</li>"
            "<li>Depth: 8.46 inches (21.5 cm)</li><li>Weight: 2.7 pounds (1.24 kg)</li></ul>")  # fmt: skip
    record = extract_page(_page(body, "MacBook Air"), "https://s.example/p")
    assert record.dims_cm == (30.41, 21.5, 1.13) and record.mass_g == 1240.0


def test_axis_words_each_with_a_number_inside_one_value():
    assert axis_segments("幅30cm 奥行20cm 高さ10cm", None, None) == [("width", 30.0), ("depth", 20.0), ("height", 10.0)]
    assert axis_segments("W 30 cm, W 20 cm", None, None) == []  # an axis twice: not one size
    body = "<table><tr><th>本体サイズ</th><td>幅30cm 奥行20cm 高さ10cm</td></tr></table>"
    assert extract_page(_page(body, lang="ja"), "https://s.example/p").dims_cm == (30.0, 20.0, 10.0)


def test_a_size_of_one_length_is_one_unnamed_extent():
    record = extract_page(_page("<p>サイズ：19cm／240p</p>", lang="ja"), "https://s.example/p")
    assert record.dims == [{"role": "extent", "cm": 19.0}]


# ---------------------------------------------------------------- values written without a unit
def _tv(body: str):
    return extract_page(_page(body, "Samsung LE37B550 TV"), "https://s.example/p")


def test_a_headings_unit_reads_the_unitless_values_under_it_and_says_so():
    record = _tv("<h3>Dimensions (mm)</h3><ul><li>Width: 923</li><li>Depth: 253</li><li>Height: 659.4</li></ul>"
                 "<h3>Weight (kg)</h3><ul><li>Net weight: 19.4</li></ul>")  # fmt: skip
    assert record.dims_cm == (92.3, 65.94, 25.3) and record.mass_g == 19400.0
    assert any("heading 'Dimensions (mm)'" in w for w in record.warnings)


def test_a_column_headings_unit_reads_the_row_under_it():
    record = _tv("<table><tr><th>Width (cm)</th><th>Height (cm)</th></tr><tr><td>30</td><td>20</td></tr></table>")
    assert sorted((e["role"], e["cm"]) for e in record.dims) == [("height", 20.0), ("width", 30.0)]


def test_a_unitless_value_with_no_unit_anywhere_is_refused_with_the_reason():
    from kb.errors import ExtractionError

    with pytest.raises(ExtractionError, match="no unit stated"):
        _tv("<h3>Dimensions</h3><ul><li>Width: 92</li><li>Depth: 25</li><li>Weight: 19.4</li></ul>")
    # lengths over the cm limit in cm are millimetres (scrapers/unitless.py), and that sheet's bare weight kg
    record = _tv("<h3>Dimensions</h3><ul><li>Width: 923</li><li>Depth: 253</li><li>Weight: 19.4</li></ul>")
    assert record.dims_cm == (92.3, 25.3) and record.mass_g == 19400.0
    assert any("read as millimetres" in w for w in record.warnings)
    assert any("read as kilograms" in w for w in record.warnings)


def test_a_headings_unit_reaches_only_its_own_block():
    from scrapers.page_lines import Line
    from scrapers.spec_pairs import HEADING_SCOPE, pairs_from_lines

    def unit_after(gap: int):
        texts = ["Dimensions (mm)", *(["Colour black"] * gap), "Width: 923"]
        (pair,) = pairs_from_lines([Line(t, False, i, i) for i, t in enumerate(texts)])
        return pair.info.unit

    assert unit_after(HEADING_SCOPE - 1) == "mm"
    assert unit_after(HEADING_SCOPE) is None


def test_a_mass_headings_unit_is_not_a_lengths():
    record = _tv("<h3>Weight (kg)</h3><ul><li>Width: 92 cm</li><li>Weight: 19.4</li></ul>")
    assert record.dims_cm == (92.0,) and record.mass_g == 19400.0


# ------------------------------------------------------------------------- what ingestion stores
def test_ingestion_stores_packages_but_not_the_shipment_nor_a_sets_mass():
    from scrapers.ingest import _validate

    body = ("<ul><li>Weight: 2.4 kg</li><li>Dimensions: 15 x 15 x 6 cm</li><li>Package Weight: 2.9 kg</li>"
            "<li>Shipping Weight: 3.5 kg</li></ul>")  # fmt: skip
    record = extract_page(_page(body, "Stoneware Bowls, Pack of 12"), "https://s.example/p")
    catalog, packages, _ = _validate(record)
    assert catalog.mass_g is None and record.set_mass_g == 2400.0
    assert [p.get("mass_g") for p in packages] == [2900.0]
    assert record.shipping_mass_g == [3500.0]


# ------------------------------------------------------------------------------ properties
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_WORDS = st.sampled_from(["set", "of", "pack", "4", "12", "1", "pair", "er", "Pack", "(Pack of 1)", "個", "セット",
                          "lot", "de", "6'lı", "bowls", "mug", "x", "-", "pcs", "1001", "teilig", " "])  # fmt: skip


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.text(max_size=80), st.lists(_WORDS, max_size=8).map(" ".join)))
def test_a_set_count_is_two_to_max_or_none_and_named_in_the_text(name):
    found = set_size(name)
    if found is not None:
        count, words = found
        assert 2 <= count <= MAX_SET and words and words.lower() in name.lower()


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=60), st.sampled_from(["in", "inch", "lb", "oz", '"', "cm", "mm", "kg", "g", ""]))
def test_the_metric_figure_is_a_bracketed_part_of_the_value(text, unit):
    value = f"{text} 2.5 {unit} (6.35 cm)"
    metric = metric_figure(value)
    assert metric is None or (metric in value and any(u in metric for u in ("cm", "mm", "kg", "g", "m")))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["幅", "奥行", "高さ", "W", "D", "H", "x"]), st.integers(1, 400)), max_size=5))
def test_axis_segments_name_each_axis_once_or_nothing(parts):
    found = axis_segments(" ".join(f"{a}{n}cm" for a, n in parts), None, None)
    roles = [r for r, _ in found]
    assert len(roles) == len(set(roles)) <= 3 and all(v > 0 for _, v in found)


@pytest.mark.parametrize(("label", "kind"), [("Body of big lamp width", "width"), ("Body of big red lamp width", None)])
def test_at_most_two_unknown_words_beside_a_body_word(label, kind):
    info = classify_label(label)
    assert (info.kind if info else None) == kind


@pytest.mark.parametrize(
    ("value", "read", "said"),
    [("30 x 20 x 10 ~ 15 cm", "30 x 20 x 15 cm", True),  # exactly 1.5 x: narrow, the upper bound
     ("30 x 20 x 10 ~ 15.1 cm", "30 x 20 x 10 ~ 15.1 cm", False),  # wider: left as written
     ("10 ~ 12 cm", "10 ~ 12 cm", False)],  # not inside a size
)  # fmt: skip
def test_a_narrow_range_inside_a_size_gives_its_upper_bound(value, read, said):
    from scrapers.value_forms import written_value

    got, note = written_value(value)
    assert got == read and (note is not None) is said
