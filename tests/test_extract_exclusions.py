"""Two classes of the real corpus's development stores: a label that leaves a part out ("Dimensions/weight
without the cable", "Depth Without Handle") is the product's, not the part's, and loses to a label of the
same axis that states the whole product; a net quantity in the product's name is its mass when nothing
else states one (never a pack's, never a vessel's capacity in ounces). Pages here are written here, in
the shapes the real pages use (Bose, GE Appliances, Target, Lavazza, Drinco)."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.labels import classify_label, classify_other


def _page(body: str, title: str = "Thing") -> str:
    return f"<html lang='en'><head><title>{title}</title></head><body><h1>{title}</h1>{body}</body></html>"


def _table(rows: list[tuple[str, str]]) -> str:
    cells = "".join(f"<tr><td>{k}</td><td>{v}</td></tr>" for k, v in rows)
    return f"<table>{cells}</table>"


# ------------------------------------------------------------------------------------ labels that exclude
@pytest.mark.parametrize(
    ("label", "kind", "excludes"),
    [
        ("Dimensions/weight without the cable", "dimensions", "cable"),
        ("Weight without battery", "weight", "battery"),
        ("Gewicht ohne Akku", "weight", "akku"),
        ("Poids sans câble", "weight", "cable"),
        ("Depth Without Handle", "depth", "handle"),
    ],
)  # fmt: skip
def test_a_label_that_leaves_a_part_out_is_the_products(label, kind, excludes):
    info = classify_label(label)
    assert info is not None and info.kind == kind and info.role == "product"
    assert info.excludes == excludes
    assert classify_other(label) is None


@pytest.mark.parametrize("label", ["Cable length", "Battery weight", "Handle height"])
def test_a_part_named_without_a_negation_is_still_a_component(label):
    assert classify_label(label) is None
    assert classify_other(label).role == "component"


def test_a_whole_products_label_excludes_nothing():
    assert classify_label("Overall Depth").excludes is None


def test_the_products_size_stated_without_its_cable_is_read():
    body = _table([("Dimensions/weight without the cable", "18 cm H x 17 cm W x 8.1 cm D (0.24 kg)"),
                   ("Audio cable", "1.2 m")])  # fmt: skip
    record = extract_page(_page(body, "Headphones"), "https://s.example/p")
    assert sorted(record.dims_cm, reverse=True) == [18.0, 17.0, 8.1]
    assert record.mass_g == 240.0


def _fridge(rows):
    return extract_page(_page(_table(rows), "Refrigerator"), "https://s.example/fridge")


def test_an_axis_without_a_part_loses_to_the_whole_products_axis():
    record = _fridge([("Overall Depth", "35.25 in"), ("Depth Without Handle", "32.75 in"),
                      ("Overall Height", "69.25 in"), ("Overall Width", "35.75 in")])  # fmt: skip
    assert sorted(record.dims_cm, reverse=True) == pytest.approx([175.895, 90.805, 89.535])


def test_the_order_of_the_two_labels_does_not_matter():
    record = _fridge([("Depth Without Handle", "32.75 in"), ("Overall Depth", "35.25 in"),
                      ("Overall Height", "69.25 in"), ("Overall Width", "35.75 in")])  # fmt: skip
    assert sorted(record.dims_cm, reverse=True) == pytest.approx([175.895, 90.805, 89.535])


def test_an_axis_without_a_part_is_used_when_nothing_states_the_whole():
    record = _fridge([("Depth Without Handle", "32.75 in"), ("Overall Height", "69.25 in"),
                      ("Overall Width", "35.75 in")])  # fmt: skip
    assert sorted(record.dims_cm, reverse=True) == pytest.approx([175.895, 90.805, 83.185])


def test_the_whole_products_axis_of_the_package_does_not_displace_the_products():
    record = _fridge([("Depth Without Handle", "32.75 in"), ("Overall Height", "69.25 in"),
                      ("Overall Width", "35.75 in"), ("Package Depth", "40 in")])  # fmt: skip
    assert sorted(record.dims_cm, reverse=True) == pytest.approx([175.895, 90.805, 83.185])


# ------------------------------------------------------------------------------------ mass in the name
@pytest.mark.parametrize(
    ("title", "grams"),
    [
        ("Himalayan Salted Dark Chocolate Almonds - 13oz - Good & Gather", 368.54),
        ("Qualità Oro - Perfect Symphony, 250g Dose", 250.0),
        ("Bio Haferflocken 500 g", 500.0),
    ],
)  # fmt: skip
def test_a_net_quantity_in_the_name_is_the_mass_when_nothing_else_states_one(title, grams):
    record = extract_page(_page("<p>Tasty.</p>", title), "https://s.example/p")
    assert record.mass_g == pytest.approx(grams, rel=1e-3)
    assert any(c["feature"] == "mass" and "product name" in (c.get("note") or "") for c in record.candidates)


def test_a_stated_weight_beats_the_names():
    body = _table([("Net weight", "260 g")])
    record = extract_page(_page(body, "Coffee, 250g Dose"), "https://s.example/p")
    assert record.mass_g == 260.0


@pytest.mark.parametrize(
    "title",
    [
        "Coffee Pods 12 x 250g",  # a pack
        "Nutella 2×1 kg",
        "Stainless Steel Vacuum Insulated Water Bottle 32oz",  # a vessel's capacity
        "Travel Mug 16 oz",
    ],
)
def test_no_mass_from_a_packs_or_a_vessels_name(title):
    with pytest.raises(ExtractionError):
        extract_page(_page("<p>Nice.</p>", title), "https://s.example/p")


def test_grams_in_a_vessels_name_are_its_mass():
    record = extract_page(_page("<p>Nice.</p>", "Glass Jar 300 g"), "https://s.example/p")
    assert record.mass_g == 300.0
