"""Partial sizes: a page that states fewer than three extents gives exactly those, with their roles, and
the catalog axes are filled by the one rule in :func:`kb.features.axes_from_extents`; every candidate the
adapters propose is shown with the chooser's decision (``extract --json --explain``)."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from kb.errors import InvalidFeature
from kb.features import EXTENT_ROLES, axes_from_extents
from scrapers.extract import extract_page


def _page(body: str, lang: str = "en") -> str:
    return f"<html lang='{lang}'><head><title>Thing</title></head><body><h1>Thing</h1>{body}</body></html>"


def _roles(record) -> list[tuple[str, float]]:
    return [(e["role"], e["cm"]) for e in record.dims]


# ----------------------------------------------------------------------------------------- the axes rule
def test_a_diameter_alone_fills_two_axes_and_nothing_else():
    assert axes_from_extents([("diameter", 45.0)]) == (45.0, 45.0)


def test_a_diameter_and_a_height_fill_three_axes():
    assert axes_from_extents([("diameter", 7.2), ("height", 21.5)]) == (21.5, 7.2, 7.2)


@pytest.mark.parametrize("other", ["length", "width", "depth"])
def test_a_diameter_beside_a_horizontal_extent_fills_one_axis(other):
    assert axes_from_extents([("diameter", 20.0), (other, 30.0)]) == (30.0, 20.0)


def test_a_diameter_beside_two_extents_fills_one_axis_at_most_three():
    assert axes_from_extents([("diameter", 20.0), ("height", 30.0), ("thickness", 2.0)]) == (30.0, 20.0, 2.0)


def test_a_diameter_beside_three_extents_is_a_part_and_dropped():
    extents = [("length", 40.0), ("width", 30.0), ("height", 10.0), ("diameter", 26.0)]
    assert axes_from_extents(extents) == (40.0, 30.0, 10.0)


@pytest.mark.parametrize("role", [r for r in EXTENT_ROLES if r != "diameter"])
def test_one_stated_extent_fills_one_axis(role):
    assert axes_from_extents([(role, 70.0)]) == (70.0,)


def test_absurd_extents_are_refused_with_the_reason():
    with pytest.raises(InvalidFeature, match="unknown"):
        axes_from_extents([("girth", 3.0)])
    with pytest.raises(InvalidFeature, match="positive"):
        axes_from_extents([("height", 0.0)])
    with pytest.raises(InvalidFeature, match="1 to 3"):
        axes_from_extents([("length", 1.0), ("width", 1.0), ("height", 1.0), ("depth", 1.0)])
    with pytest.raises(InvalidFeature, match="1 to 3"):
        axes_from_extents([])


@given(st.lists(st.tuples(st.sampled_from(EXTENT_ROLES), st.floats(0.1, 500)), min_size=1, max_size=3))
def test_axes_are_sorted_and_hold_only_stated_values(extents):
    axes = axes_from_extents(extents)
    assert list(axes) == sorted(axes, reverse=True)
    stated = {v for _, v in extents}
    assert set(axes) <= stated  # nothing invented
    assert len(extents) <= len(axes) <= 3


# ------------------------------------------------------------------------------------------ pages
def test_a_page_stating_only_a_diameter_gives_that_diameter():
    record = extract_page(_page("<table><tr><th>Diameter</th><td>45 cm</td></tr></table>"), "https://s.example/p")
    assert _roles(record) == [("diameter", 45.0)]
    assert record.dims_cm == (45.0, 45.0)


def test_a_page_stating_only_a_height_gives_one_axis():
    record = extract_page(_page("<dl><dt>Height</dt><dd>30 cm</dd><dt>Weight</dt><dd>2 kg</dd></dl>"), "https://s.example/p")
    assert _roles(record) == [("height", 30.0)]
    assert record.dims_cm == (30.0,)


def test_height_and_diameter_keep_both_roles():
    body = "<ul><li>Height: 21.5 cm</li><li>Diameter: 7.2 cm</li></ul>"
    record = extract_page(_page(body), "https://s.example/p")
    assert sorted(_roles(record)) == [("diameter", 7.2), ("height", 21.5)]
    assert record.dims_cm == (21.5, 7.2, 7.2)


def test_garment_measurements_give_the_two_stated_extents():
    body = "<table><tr><th>Length</th><td>70 cm</td></tr><tr><th>Width</th><td>52 cm</td></tr></table>"
    record = extract_page(_page(body), "https://s.example/p")
    assert sorted(_roles(record)) == [("length", 70.0), ("width", 52.0)]
    assert record.dims_cm == (70.0, 52.0)


def test_lettered_inch_sizes_keep_their_roles():
    body = '<ul><li>Dimensions: 20"w x 4"d x 16"h</li></ul>'
    record = extract_page(_page(body), "https://s.example/p")
    assert _roles(record) == [("width", 50.8), ("height", 40.64), ("depth", 10.16)]
    assert record.dims_cm == pytest.approx((50.8, 40.64, 10.16))


def test_jsonld_with_one_axis_is_a_partial_size():
    ld = {"@context": "https://schema.org", "@type": "Product", "name": "Shade",
          "height": {"@type": "QuantitativeValue", "value": 45, "unitCode": "CMT"}}  # fmt: skip
    body = f"<script type='application/ld+json'>{json.dumps(ld)}</script>"
    record = extract_page(_page(body), "https://s.example/p")
    assert _roles(record) == [("height", 45.0)]
    assert record.dims_cm == (45.0,)


# ---------------------------------------------------------------------------------- explain
def test_every_candidate_is_shown_with_its_decision():
    body = ("<table><tr><th>Weight</th><td>2 kg</td></tr><tr><th>Dimensions</th><td>30 x 20 x 10 cm</td></tr>"
            "<tr><th>Package weight</th><td>2.5 kg</td></tr></table><p>It weighs about 3 kg.</p>")  # fmt: skip
    record = extract_page(_page(body), "https://s.example/p")
    by_value = {(c["feature"], c["role"], json.dumps(c["value"])): c["decision"] for c in record.candidates}
    assert by_value[("mass", "product", "2000.0")].startswith("chosen")
    assert by_value[("dims", "product", "[30.0, 20.0, 10.0]")].startswith("chosen")
    assert by_value[("mass", "package", "2500.0")].startswith("package value")
    assert record.package_mass_g == [2500.0]


def test_a_disagreeing_value_is_an_alternative_not_the_choice():
    body = ("<table><tr><th>Weight</th><td>2 kg</td></tr></table>"
            "<script type='application/ld+json'>{\"@type\": \"Product\", \"name\": \"T\", \"weight\": \"3 kg\"}</script>")
    record = extract_page(_page(body), "https://s.example/p")
    decisions = {c["value"]: c["decision"] for c in record.candidates if c["feature"] == "mass"}
    assert decisions[3000.0].startswith("chosen") and decisions[2000.0].startswith("alternative")


def test_extract_json_gives_stated_extents_and_explain(tmp_path):
    from kb.service.cli import app

    page = tmp_path / "shade.html"
    page.write_text(_page("<table><tr><th>Diameter</th><td>45 cm</td></tr></table>"), encoding="utf-8")
    result = CliRunner().invoke(app, ["extract", str(page), "--json", "--explain"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["dims_cm"] == [45.0, 45.0]
    assert data["dims"] == [{"role": "diameter", "cm": 45.0}]
    assert data["candidates"][0]["decision"].startswith("chosen")
    plain = CliRunner().invoke(app, ["extract", str(page), "--json"])
    assert "candidates" not in json.loads(plain.output)


# ---------------------------------------------------------------------------------- ranges
def _height(value: str):
    body = f"<table><tr><th>Height</th><td>{value}</td></tr><tr><th>Width</th><td>20 cm</td></tr></table>"
    return extract_page(_page(body), "https://s.example/p")


@pytest.mark.parametrize(
    ("value", "height", "bound"),
    [
        ("30-32 cm", 32.0, "upper"),
        ("adjustable from 90 to 110 cm", 110.0, "upper"),
        ("40 - 60 cm", 60.0, "upper"),  # exactly 1.5 x: still narrow
        ("40 - 60.1 cm", 40.0, "lower"),  # just wider: the object's own extent
        ('15.5" - 116.5"', 39.37, "lower"),  # a pendant's hanging reach
    ],
)
def test_a_range_of_one_axis_gives_a_bound_and_says_which(value, height, bound):
    record = _height(value)
    assert max(record.dims_cm) == pytest.approx(height)
    assert any("range" in w and f"{bound} bound" in w for w in record.warnings), record.warnings


# ------------------------------------------------------------------------ whose block is it
def test_a_spec_block_with_a_layout_word_in_its_class_is_read():
    body = ("<section class='tab-specs accordion banner-margin-small'><div>Weight</div><div>23.98 oz. (680.00 g)"
            "</div></section>")  # fmt: skip
    assert extract_page(_page(body), "https://s.example/p").mass_g == 680.0  # the metric figure of the two


@pytest.mark.parametrize("classes", ["banner-margin-small", "product-slider", "similar-specs", "comparison-details"])
def test_other_products_blocks_stay_out(classes):
    body = ("<table><tr><th>Weight</th><td>2 kg</td></tr></table>"
            f"<div class='{classes}'><table><tr><th>Weight</th><td>9 kg</td></tr></table></div>")
    record = extract_page(_page(body), "https://s.example/p")
    assert record.mass_g == 2000.0
    assert not any("9000" in w or "9 kg" in w for w in record.warnings)


# ------------------------------------------------------------------ parts, clauses, hedges
@pytest.mark.parametrize("label", ["Cable length", "Power cord length", "Hose length", "Lid diameter", "Stand height"])
def test_a_parts_extent_is_not_the_products(label):
    body = f"<ul><li>{label}: 75 cm</li><li>Weight: 1.1 kg</li></ul>"
    record = extract_page(_page(body), "https://s.example/p")
    assert record.dims == [] and record.mass_g == 1100.0


def test_labels_after_a_value_on_one_line_are_still_read():
    record = extract_page(_page("<p>Weight: 2 kg Height: 30 cm</p>"), "https://s.example/p")
    assert record.mass_g == 2000.0 and _roles(record) == [("height", 30.0)]


def test_garment_measurements_in_one_sentence_give_each_extent():
    record = extract_page(_page("<p>Length 70 cm, chest width 52 cm, in size L</p>"), "https://s.example/p")
    assert sorted(_roles(record)) == [("length", 70.0), ("width", 52.0)]


def test_a_hedge_between_axis_word_and_number_is_skipped():
    body = "<div>商品サイズ（cm）</div><div>幅約45×奥行約30×高さ約12</div><div>重量</div><div>約850g</div>"
    record = extract_page(_page(body, "ja"), "https://s.example/p")
    assert _roles(record) == [("width", 45.0), ("depth", 30.0), ("height", 12.0)]
    assert record.mass_g == 850.0


# ------------------------------------------------------------------------ header rows
def test_a_header_row_of_labels_pairs_with_the_first_row_under_it():
    body = ("<table><tr><th>Width</th><th>Height</th><th>Depth</th><th>Weight</th></tr>"
            "<tr><td>30 cm</td><td>20 cm</td><td>10 cm</td><td>2 kg</td></tr>"
            "<tr><td>40 cm</td><td>25 cm</td><td>12 cm</td><td>3 kg</td></tr></table>")  # fmt: skip
    record = extract_page(_page(body), "https://s.example/p")
    assert _roles(record) == [("width", 30.0), ("height", 20.0), ("depth", 10.0)]
    assert record.mass_g == 2000.0
    assert not any("40" in w or "3000" in w for w in record.warnings)


def test_a_header_row_needs_as_many_values_as_labels():
    body = "<div>Dimensions</div><div>Width</div><div>30 cm</div><div>Height</div><div>20 cm</div>"
    record = extract_page(_page(body), "https://s.example/p")
    assert sorted(_roles(record)) == [("height", 20.0), ("width", 30.0)]


@pytest.mark.parametrize(
    ("label", "kind"),
    [("Ürün Ölçüleri", "dimensions"), ("Ebat", "dimensions"), ("Çap", "diameter"), ("Kalınlık", "thickness"),
     ("外寸", "dimensions"), ("Physical dimensions", "dimensions")],
)
def test_more_label_words(label, kind):
    from scrapers.labels import classify_label

    assert classify_label(label).kind == kind


@pytest.mark.parametrize(
    ("label", "order"),
    [
        ("Dimensions (H x W x D)", ("height", "width", "depth")),
        ("Item Dimensions LxWxH", ("length", "width", "height")),
        ("Габариты (ВхШхГ), см", ("height", "width", "depth")),
        ("Abmessungen (B/H/T)", ("width", "height", "depth")),
        ("Largo x Ancho x Alto", ("length", "width", "height")),
        ("Dimensions de l'article L x L x H", ()),  # ambiguous: no roles
        ("Product Dimensions", ()),
    ],
)
def test_a_dimensions_label_names_the_order_of_its_axes(label, order):
    from scrapers.labels import classify_label

    assert classify_label(label).order == order


def test_the_label_order_gives_a_combined_value_its_roles():
    body = "<table><tr><th>Dimensions (H x W x D)</th><td>17.9 x 359.3 x 235.6 mm</td></tr></table>"
    record = extract_page(_page(body), "https://s.example/p")
    assert _roles(record) == [("width", 35.93), ("depth", 23.56), ("height", 1.79)]


# ------------------------------------------------------- parts and capacities are candidates too
def test_parts_and_capacities_are_listed_but_never_chosen():
    body = ("<ul><li>Capacity: 1.7 L</li><li>Cable length: 75 cm</li><li>Weight: 1.1 kg</li>"
            "<li>Max load: 5 kg</li></ul><table><tr><th>Fassungsvermögen</th><td>8 kg</td></tr></table>")  # fmt: skip
    record = extract_page(_page(body), "https://s.example/p")
    assert record.dims == [] and record.mass_g == 1100.0
    roles = {(c["feature"], c["role"], json.dumps(c["value"])) for c in record.candidates}
    assert ("dims", "component", "[75.0]") in roles
    assert ("mass", "capacity", "5000.0") in roles and ("mass", "capacity", "8000.0") in roles
    assert all(c["decision"].startswith("not the product's") for c in record.candidates if c["role"] != "product")


def test_a_page_with_only_a_parts_value_states_nothing_of_the_product():
    from kb.errors import ExtractionError

    with pytest.raises(ExtractionError, match="no product dimensions or mass"):
        extract_page(_page("<ul><li>Cable length: 75 cm</li><li>Battery weight: 148 g</li></ul>"), "https://s.example/p")


@pytest.mark.parametrize(
    ("label", "role"),
    [("Cable length", "component"), ("Battery Weight", "component"), ("Schlauchlänge", "component"),
     ("Fassungsvermögen", "capacity"), ("Max Height", "capacity"), ("耐荷重", "capacity"),
     ("Weight", None), ("Colour", None), ("Weight: 1.1 kg", None)],
)
def test_whose_label_it_is(label, role):
    from scrapers.labels import classify_other

    info = classify_other(label)
    assert (info.role if info else None) == role


@pytest.mark.parametrize(
    ("value", "extents", "axes"),
    [
        ("<li>Diameter 30cm x Height 15cm</li>", [("diameter", 30.0), ("height", 15.0)], (30.0, 30.0, 15.0)),
        ("<li>Width: 30 cm x Height 20 cm</li>", [("width", 30.0), ("height", 20.0)], (30.0, 20.0)),
        ("<li>Size: Width 30 cm x Height 20 cm x Depth 10 cm</li>",
         [("width", 30.0), ("height", 20.0), ("depth", 10.0)], (30.0, 20.0, 10.0)),
    ],
)
def test_axis_words_inside_one_value_keep_their_roles(value, extents, axes):
    record = extract_page(_page(f"<ul>{value}</ul>"), "https://s.example/p")
    assert sorted(_roles(record)) == sorted(extents)
    assert record.dims_cm == axes


@pytest.mark.parametrize(("label", "role"), [("Case diameter", "diameter"), ("Fabric width", "width")])
def test_a_case_or_fabric_extent_is_the_products(label, role):
    record = extract_page(_page(f"<ul><li>{label}: 42 mm</li></ul>"), "https://s.example/p")
    assert _roles(record) == [(role, 4.2)]


# ------------------------------------------------------------------------ size variants
def test_the_selected_variants_size_beats_the_size_table_of_all_variants():
    body = ("<select name='size'><option>Mattress 3' x 6'3\" (90 x 190 x 22 cm)</option>"
            "<option selected>Mattress 2'6\" x 6'6\" (75 x 200 x 22 cm)</option></select>"
            "<table><tr><th>Size</th><td>3' x 6'3\"</td></tr><tr><th>Size</th><td>4'6\" x 6'3\"</td></tr></table>")
    record = extract_page(_page(body), "https://s.example/p")
    assert record.dims_cm == (200.0, 75.0, 22.0)
    assert any("selected variant" in w for w in record.warnings)


def test_a_selected_option_without_a_size_adds_nothing():
    body = "<select><option selected>Blue</option></select><ul><li>Dimensions: 30 x 20 x 10 cm</li></ul>"
    assert extract_page(_page(body), "https://s.example/p").dims_cm == (30.0, 20.0, 10.0)
