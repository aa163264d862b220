"""Which configuration of the product a field states (a monitor store's layout class, many German shops):
``Gewicht mit Ständer`` / ``Höhe mit Standfuß`` (with the stand: the whole product as sold) wins over a field
of the same axis that says nothing (``Gewicht``), which wins over one that leaves a part out (``Gewicht ohne
Ständer``). A package's fields between the product's do not break the product's row of axes.
Pages written here in the shapes of the real pages (otto, csv-direct)."""

from __future__ import annotations

import pytest

from scrapers.extract import extract_page
from scrapers.labels import classify_label, classify_other


def _page(rows: list[tuple[str, str]]) -> str:
    cells = "".join(f"<tr><td>{k}</td><td>{v}</td></tr>" for k, v in rows)
    return f"<html lang='de'><head><title>Monitor</title></head><body><h1>Monitor</h1><table>{cells}</table></body></html>"


def _record(rows):
    return extract_page(_page(rows), "https://shop.test/p", "text/html")


@pytest.mark.parametrize(
    ("label", "configuration", "includes"),
    [
        ("Gewicht mit Ständer", 2, "stander"),
        ("Höhe mit Standfuß", 2, "standfuß"),
        ("Height including stand", 2, "stand"),
        ("Weight (incl. battery)", 2, "battery"),
        ("Weight (with stand)", 2, "stand"),
        ("Gewicht", 1, None),
        ("Weight (kg)", 1, None),
        ("Gewicht ohne Ständer", 0, None),
        ("Weight (without battery)", 0, None),
    ],
)  # fmt: skip
def test_a_labels_configuration(label, configuration, includes):
    info = classify_label(label)
    assert info is not None and info.role == "product" and classify_other(label) is None
    assert info.configuration == configuration and info.includes == includes


def test_with_packaging_stays_the_packages():
    info = classify_label("Breite mit Verpackung")
    assert info is not None and info.package and info.configuration == 1


def test_a_weight_with_the_stand_beats_a_plain_weight_and_one_without():
    assert _record([("Gewicht", "2,9 kg"), ("Gewicht mit Standfuß", "3,5 kg")]).mass_g == 3500.0
    assert _record([("Gewicht ohne Ständer", "4,2 kg"), ("Gewicht mit Ständer", "6,3 kg")]).mass_g == 6300.0
    assert _record([("Gewicht ohne Ständer", "4,2 kg"), ("Gewicht", "6,3 kg")]).mass_g == 6300.0
    assert _record([("Gewicht ohne Ständer", "4,2 kg")]).mass_g == 4200.0  # alone, it is what there is


def test_axes_with_the_stand_replace_the_plain_ones_across_package_fields():
    rows = [("Breite", "51,3 cm"), ("Höhe", "30,9 cm"), ("Tiefe", "5,21 cm"),
            ("Breite mit Verpackung", "56,5 cm"), ("Höhe mit Verpackung", "44 cm"),
            ("Höhe mit Standfuß", "37,3 cm"), ("Tiefe mit Verpackung", "12,3 cm"), ("Tiefe mit Standfuß", "19,94 cm"),
            ("Gewicht", "2,9 kg")]  # fmt: skip
    r = _record(rows)
    assert sorted((e["role"], e["cm"]) for e in r.dims) == [("depth", 19.94), ("height", 37.3), ("width", 51.3)]
    assert r.package_dims_cm == [(56.5, 44.0, 12.3)]


def test_a_package_field_between_keeps_the_product_row():
    r = _record([("Breite", "30 cm"), ("Breite mit Verpackung", "35 cm"), ("Höhe", "20 cm"), ("Höhe mit Verpackung", "25 cm")])
    assert sorted(e["cm"] for e in r.dims) == [20.0, 30.0]


@pytest.mark.parametrize(("text", "cm"), [
    ("539.5 x 355.5 (505.5) x 171 mm", (53.95, 35.55, 17.1)),  # the height at the stand's highest position
    ("30 (35) x 20 x 10 cm", (30.0, 20.0, 10.0)),
    ("30 x 20 x 10 (cm)", (30.0, 20.0, 10.0)),  # a bracketed unit is still the unit
])  # fmt: skip
def test_a_bracketed_alternative_figure_inside_a_size_is_left_out(text, cm):
    from scrapers.sizes import parse_dims

    assert parse_dims(text, None)[0].values_cm == cm


@pytest.mark.parametrize("label", ["Depth with Door Open 90", "Altura com os pés: 61 cm", "Weight with 2 batteries"])
def test_only_a_part_can_be_included(label):
    # a state ("door open 90") or a number after "with" is no part: the label is not the product's
    info = classify_label(label)
    assert info is None or info.includes is None and info.configuration != 2
