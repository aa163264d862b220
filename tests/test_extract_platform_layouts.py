"""Layouts of store platforms that a reader must handle, on small pages **written here** (issue 21, round
3), from how the platforms render products, not copied from any store's page: page state (Next.js
``__NEXT_DATA__``, ``window.__INITIAL_STATE__``, Mercado Libre's preloaded state, Shopware's properties)
with measurement keys in any nesting and key language, units in keys of their own or in the key's name,
spec lists written as two-item lists, package objects; and spec tables whose unit is in a header.
Each rule is pinned at its boundary."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.errors import ExtractionError
from scrapers.adapters.state_units import is_unit_key, unit_for, unit_keys, value_object
from scrapers.extract import extract_page
from scrapers.label_vocabulary import fold
from scrapers.quantities import unit_hint

TITLE = "Oak Storage Box Natural"


def _page(body: str, lang: str = "en") -> str:
    return (f"<html lang='{lang}'><head><title>{TITLE}</title></head><body><h1>{TITLE}</h1>"
            f"<p>A lovely box.</p>{body}</body></html>")  # fmt: skip


def _state(obj: dict, lang: str = "en", prefix: str = "window.__INITIAL_STATE__ = ") -> str:
    return _page(f"<script>{prefix}{json.dumps(obj)};</script>", lang)


def _read(html: str):
    try:
        record = extract_page(html, "https://shop.example/p/1", "text/html")
    except ExtractionError:
        return None, None
    return (tuple(sorted(record.dims_cm, reverse=True)) if record.dims_cm else None), record.mass_g


def _product(lang: str = "en", **keys) -> str:
    return _state({"product": {"name": TITLE, **keys}}, lang)


# --- units in keys of their own -------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("lang", "keys"),
    [
        # Next.js / headless: one unit key for a dimensions object, a value object for the weight
        ("en", {"dimensions": {"width": 30, "height": 20, "depth": 10, "unit": "cm"},
                "weight": {"value": 3.2, "unit": "kg"}}),
        # the unit one level up, beside the key holding the measurements
        ("en", {"dimensions": {"width": 30, "height": 20, "depth": 10}, "dimensionUnit": "cm",
                "weight": 3.2, "weightUnit": "kg"}),
        # German keys, transliterated umlauts, Einheit/Wert
        ("de", {"abmessungen": {"breite": 30, "hoehe": 20, "tiefe": 10, "einheit": "cm"},
                "gewicht": {"wert": 3.2, "einheit": "kg"}}),
        # Spanish: unidad_medida for the lengths, unidad_peso for the weight
        ("es", {"ancho": 30, "alto": 20, "largo": 10, "unidad_medida": "cm", "peso": 3.2, "unidad_peso": "kg"}),
        # Italian value objects
        ("it", {"larghezza": {"valore": 30, "unita": "cm"}, "altezza": {"valore": 20, "unita": "cm"},
                "profondita": {"valore": 10, "unita": "cm"}, "peso": {"valore": 3.2, "unita": "kg"}}),
        # Polish keys written without diacritics (głębokość -> glebokosc)
        ("pl", {"szerokosc": "30 cm", "wysokosc": "20 cm", "glebokosc": "10 cm", "waga": "3,2 kg"}),
        # the unit in the key's name
        ("en", {"width_cm": 30, "height_cm": 20, "depth_cm": 10, "weight_kg": 3.2}),
        ("en", {"widthCm": 30, "heightCm": 20, "lengthCm": 10, "weightInGrams": 3200}),
        # unit codes and unit objects
        ("en", {"width": {"amount": 30, "unitOfMeasure": "CM"}, "height": {"amount": 20, "unitCode": "CMT"},
                "depth": {"amount": 10, "uom": {"symbol": "cm"}}, "weight": {"amount": 3.2, "unitOfMeasure": "KG"}}),
    ],
)  # fmt: skip
def test_state_measurements_with_their_unit_in_another_key(lang, keys):
    assert _read(_product(lang, **keys)) == ((30.0, 20.0, 10.0), 3200.0)


def test_a_unit_of_the_other_family_is_not_taken():
    # "unit": "cm" beside a bare weight says nothing of the weight's unit
    assert _read(_product(width=30, weight=3.2, unit="cm")) == ((30.0,), None)


def test_two_units_of_a_family_and_none_naming_the_key_give_none():
    units = unit_keys({"unit": "cm", "displayUnit": "in"})
    assert unit_for("width", "length", units) == "cm"  # the plain unit key is the object's unit
    units = unit_keys({"frontUnit": "cm", "backUnit": "in"})
    assert unit_for("width", "length", units) is None
    assert unit_for("frontWidth", "length", units) == "cm"


def test_a_parents_unit_reaches_only_an_object_held_by_a_measurement_key():
    # an image's pixels under "image" never take the product's dimension unit
    assert _read(_product(image={"width": 800, "height": 600}, dimensionUnit="cm", weight="1 kg")) == (None, 1000.0)
    assert _read(_product(size={"width": 80, "height": 60}, dimensionUnit="cm")) == ((80.0, 60.0), None)


def test_a_number_whose_key_names_no_unit_is_refused():
    assert _read(_product(width_px=800, weight="1 kg")) == (None, 1000.0)
    assert value_object({"value": 3.2}) is None
    assert value_object({"value": 3.2, "unit": "kg"}) == "3.2 kg"
    assert value_object({"value": 3.2, "unit": "kg", "displayUnit": "lb"}) is None  # which one is not said


@pytest.mark.parametrize(
    ("key", "is_unit"),
    [("unit", True), ("weightUnit", True), ("unidad_peso", True), ("einheit", True), ("unitOfMeasure", True),
     ("dimension_unit_of_measure", True), ("weight", False), ("units_sold", True), ("community", False)],
)  # fmt: skip
def test_unit_keys_are_named_by_a_unit_word(key, is_unit):
    assert is_unit_key(key) is is_unit


@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=1, max_value=400), st.sampled_from(["cm", "mm", "in", "CMT", "INH"]))
def test_a_value_object_reads_like_the_string_it_stands_for(number, unit):
    as_object = _read(_product(width={"value": number, "unit": unit}, weight="1 kg"))
    as_string = _read(_product(width=f"{number} {unit}", weight="1 kg"))
    assert as_object == as_string


# --- whose value -------------------------------------------------------------------------------------------


def test_values_under_a_package_key_are_package_values():
    # a big US retailer's state: the package's size and weight, in their own unit keys
    html = _product(package_dimensions={"depth": 9, "height": 4.1, "width": 7, "dimension_unit_of_measure": "INCH",
                                        "weight": 0.9, "weight_unit_of_measure": "POUND"})  # fmt: skip
    record = extract_page(html, "https://shop.example/p/1", "text/html")
    assert record.dims_cm is None and record.mass_g is None
    assert record.package_mass_g == [pytest.approx(408.233, rel=1e-3)]
    assert record.package_dims_cm == [pytest.approx((22.86, 17.78, 10.414), rel=1e-3)]


def test_a_product_key_beside_the_package_key_stays_the_products():
    html = _product(weight={"value": 0.7, "unit": "lb"}, package_dimensions={"weight": 0.9, "weight_unit": "lb"})
    assert _read(html)[1] == pytest.approx(317.515, rel=1e-3)


# --- label/value entries -------------------------------------------------------------------------------


def test_marketplace_attributes_with_value_name_and_value_struct():
    state = {"item": {"title": TITLE, "attributes": [
        {"id": "WEIGHT", "name": "Peso", "value_name": "3,2 kg"},
        {"id": "WIDTH", "name": "Ancho", "value_struct": {"number": 30, "unit": "cm"}}]}}  # fmt: skip
    assert _read(_state(state, "es", "window.__PRELOADED_STATE__ = ")) == ((30.0,), 3200.0)


def test_a_label_in_a_group_object_and_the_value_in_the_name():
    # Shopware's properties: {"group": {"name": "Gewicht"}, "name": "3,2 kg"}
    props = [{"group": {"name": "Gewicht"}, "name": "3,2 kg"}, {"group": {"name": "Breite"}, "name": "30 cm"},
             {"group": {"name": "Farbe"}, "name": "Natur 2"}]  # fmt: skip
    assert _read(_product("de", properties=props)) == ((30.0,), 3200.0)


def test_an_entry_whose_label_key_is_feature():
    feats = [{"feature": "Weight", "value": "3.2 kg"}, {"feature": "Width", "value": "30 cm"}]
    assert _read(_product(features=feats)) == ((30.0,), 3200.0)


def test_spec_lists_written_as_two_item_lists():
    assert _read(_product(specifications=[["Weight", "3.2 kg"], ["Width", "30 cm"]])) == ((30.0,), 3200.0)
    # a pair whose first item is no measurement label is not a spec
    assert _read(_product(specifications=[["Colour", "3 cm"], ["Weight", "1 kg"]])) == (None, 1000.0)


def test_fold_reads_the_polish_l_as_l():
    assert fold("Głębokość") == "glebokosc" and fold("Długość") == "dlugosc"


# --- tables whose unit is in a header -----------------------------------------------------------------------


def test_a_header_row_of_labels_with_units_pairs_each_label_once():
    # the last header label was also paired with the first value under the header (Weight (kg) -> 30)
    html = _page("<table><tr><th>Width (cm)</th><th>Height (cm)</th><th>Depth (cm)</th><th>Weight (kg)</th></tr>"
                 "<tr><td>30</td><td>20</td><td>10</td><td>3.2</td></tr></table>")  # fmt: skip
    assert _read(html) == ((30.0, 20.0, 10.0), 3200.0)


@pytest.mark.parametrize(
    ("label", "unit"),
    [("Dimensions (inches)", "inches"), ("Dimensions (inch)", "inch"), ("Dimensions (in)", "in"),
     ("Grubość (w mm)", "mm"), ("Maße in cm", "cm"), ("Weight (kg)", "kg")],
)  # fmt: skip
def test_a_unit_word_in_brackets_is_read_whole(label, unit):
    # "(inches)" was read as the prefix "in" and the word "ches"
    assert unit_hint(label) == unit


def test_a_heading_in_inches_gives_the_unit_of_the_rows_below():
    html = _page("<h3>Dimensions (inches)</h3><ul><li>Width: 12</li><li>Height: 8</li><li>Depth: 4</li></ul>", "en-GB")
    assert _read(html)[0] == pytest.approx((30.48, 20.32, 10.16))


@pytest.mark.parametrize("note", ["All measurements in cm", "Measurements in cm", "Alle Maße in cm"])
def test_a_note_stating_the_unit_of_all_measurements(note):
    html = _page(f"<h3>Specifications</h3><p>{note}</p><table><tr><td>Width</td><td>30</td></tr>"
                 "<tr><td>Height</td><td>20</td></tr><tr><td>Depth</td><td>10</td></tr></table>", "en-GB")  # fmt: skip
    assert _read(html)[0] == (30.0, 20.0, 10.0)


@pytest.mark.parametrize(("head", "dims"), [("Value (cm)", (30.0, 20.0, 10.0)), ("Wert [cm]", (30.0, 20.0, 10.0)),
                                            ("Value", None), ("Colour (cm)", None)])  # fmt: skip
def test_a_value_column_heading_with_a_unit(head, dims):
    html = _page(f"<table><thead><tr><th>Property</th><th>{head}</th></tr></thead><tbody><tr><td>Width</td><td>30</td>"
                 "</tr><tr><td>Height</td><td>20</td></tr><tr><td>Depth</td><td>10</td></tr></tbody></table>", "en-GB")  # fmt: skip
    assert _read(html)[0] == dims
