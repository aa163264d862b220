"""Whose value a spec row states, from the other rows and the page's name (scrapers/pair_roles.py), on
small pages written here: a value said to be one part's alone on a kit's page (``750 g (Body Only)`` on a
camera-with-lens page), and an adjustable product's two bounds of one axis (``Min. height`` / ``Max.
height``), the classes of two development pages (a camera kit, an office chair)."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.value_forms import only_part


def _read(rows: str, title: str):
    html = (f"<html lang='en'><head><title>{title}</title></head><body><h1>{title}</h1><p>Good.</p>"
            f"<table>{rows}</table></body></html>")  # fmt: skip
    try:
        record = extract_page(html, "https://shop.example/p/1", "text/html")
    except ExtractionError:
        return None
    return record


def _row(label: str, value: str) -> str:
    return f"<tr><th>{label}</th><td>{value}</td></tr>"


KIT = "Reflex DSLR Camera with 24-120mm Lens"


@pytest.mark.parametrize(
    ("title", "mass"),
    [(KIT, None), ("Reflex DSLR Camera Kit", None), ("Reflex DSLR Camera Body + Lens", None),
     ("Reflex DSLR Camera Body", pytest.approx(748.43, rel=1e-3))],  # the part sold alone: the product's (1.65 lb read first)
)  # fmt: skip
def test_a_part_only_weight_is_the_parts_on_a_kits_page(title, mass):
    record = _read(_row("Weight", "1.65 lb / 750 g (Body Only)"), title)
    assert (record.mass_g if record else None) == mass


@pytest.mark.parametrize(
    ("value", "part"),
    [("750 g (Body Only)", "body"), ("750 g (nur Gehäuse)", "gehäuse"), ("750 g (boîtier seul)", "boîtier"),
     ("750 g (body)", None), ("750 g (only 2 left)", None), ("750 g", None), ("750 g (with battery)", None)],
)  # fmt: skip
def test_only_part_names_the_part_a_bracket_restricts_the_value_to(value, part):
    assert only_part(value, KIT) == part


def test_no_part_without_a_kit_name():
    assert only_part("750 g (Body Only)", "Reflex DSLR Camera Body") is None
    assert only_part("750 g (Body Only)", None) is None


ROWS = _row("Width", "62 cm") + _row("Depth", "60 cm")


def test_an_adjustable_products_lowest_setting_is_its_extent():
    record = _read(ROWS + _row("Min. height", "129 cm") + _row("Max. height", "140 cm"), "Office chair")
    assert record.dims_cm == (129.0, 62.0, 60.0)
    assert any("adjustable" in w and "lowest" in w for w in record.warnings)


@pytest.mark.parametrize(
    "rows",
    [_row("Max. height", "140 cm"),  # one bound alone: a capacity's
     _row("Min. height", "129 cm"),
     _row("Min. seat height", "46 cm") + _row("Max. seat height", "57 cm")],  # the seat's bounds: a part's
)  # fmt: skip
def test_one_bound_or_a_parts_bounds_are_not_the_products(rows):
    record = _read(ROWS + rows, "Office chair")
    assert record.dims_cm == (62.0, 60.0)


# --- lengths written with no unit anywhere (scrapers/unitless.py) -------------


def _de(rows: str):
    html = (f"<html lang='de'><head><title>Monitor 24 Zoll</title></head><body><h1>Monitor 24 Zoll</h1>"
            f"<table>{rows}</table></body></html>")  # fmt: skip
    try:
        return extract_page(html, "https://shop.example/p/1", "text/html").dims_cm
    except ExtractionError:
        return None


@pytest.mark.parametrize(
    ("width", "dims"),
    [("540,00", (54.0, 37.9, 23.3)),  # 540 cm would be over the 500 cm limit: millimetres
     ("500,00", None),  # within the limit in cm: which unit is not said, unread
     ("6000,00", None)],  # 600 cm even in mm: not a size of a household object either way
)  # fmt: skip
def test_unitless_lengths_over_the_cm_limit_are_millimetres(width, dims):
    rows = _row("Breite", width) + _row("Höhe", "379,00") + _row("Länge", "233,00")
    assert _de(rows) == dims


def test_a_package_rows_unit_is_no_heading_for_the_product_rows():
    # "Verpackung - Höhe in cm" over its own value is a row's label, not a heading saying cm for the rows below
    rows = _row("Verpackung - Höhe in cm", "49,00") + _row("Breite", "54,00") + _row("Höhe", "37,90")
    assert _de(rows) is None
    rows = "<tr><th colspan=2>Maße in cm</th></tr>" + _row("Breite", "54,00") + _row("Höhe", "37,90")
    assert _de(rows) == (54.0, 37.9)
