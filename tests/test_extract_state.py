"""Values that live only in the page's embedded state (script tags holding the store's product data):
JSON and JavaScript object literals, measurement keys, and whose object it is."""

from __future__ import annotations

import json

import pytest

from scrapers.adapters.embedded_json import _key_label, _names_product
from scrapers.extract import extract_page

TITLE = "Stoneware Pasta Bowl Set Sage"


def _page(script: str, title: str = TITLE) -> str:
    return (f"<html lang='en'><head><title>{title}</title></head><body><h1>{title}</h1><p>Lovely.</p>"
            f"<script>{script}</script></body></html>")  # fmt: skip


def _state(product: dict, *others: dict) -> str:
    return "window.__STATE__ = " + json.dumps({"page": {"product": product, "recommended": list(others)}}) + ";"


def test_measurement_keys_of_the_product_object_are_read():
    product = {"name": TITLE, "itemWeight": "1.2 kg", "width": {"value": 30, "unit": "cm"},
               "height": 8, "heightUnit": "cm"}  # fmt: skip
    record = extract_page(_page(_state(product)), "https://s.example/p")
    assert record.mass_g == 1200.0
    assert sorted((e["role"], e["cm"]) for e in record.dims) == [("height", 8.0), ("width", 30.0)]
    assert record.adapter == "embedded_json"


def test_a_number_without_a_unit_is_not_a_measurement():
    record = extract_page(_page(_state({"name": TITLE, "weight": 3, "width": "30 cm"})), "https://s.example/p")
    assert record.mass_g is None and record.dims_cm == (30.0,)


def test_other_products_in_the_state_are_not_the_product():
    other = {"name": "Walnut Serving Board Large", "weight": "2.5 kg", "dimensions": "60 x 30 x 2 cm"}
    record = extract_page(_page(_state({"name": TITLE, "weight": "1.2 kg"}, other)), "https://s.example/p")
    assert record.mass_g == 1200.0 and record.dims_cm is None
    assert not any("2500" in w or "60" in w for w in record.warnings)


def test_a_javascript_object_literal_is_read():
    script = "var product = {name: '" + TITLE + "', netWeight: '450 g', depth: '22 cm',};"
    record = extract_page(_page(script), "https://s.example/p")
    assert record.mass_g == 450.0 and record.dims_cm == (22.0,)


def test_an_escaped_inch_mark_inside_state_json():
    script = 'var p = {"name": "' + TITLE + '", "dimensions": "20\\"W x 4\\"D x 16\\"H"};'
    record = extract_page(_page(script), "https://s.example/p")
    assert record.dims_cm == pytest.approx((50.8, 40.64, 10.16))


@pytest.mark.parametrize(
    ("key", "label"),
    [("itemWeight", "item Weight"), ("product_width", "product width"), ("net-weight", "net weight"), ("Höhe", "Höhe")],
)
def test_keys_become_label_words(key, label):
    assert _key_label(key) == label


def test_a_name_is_the_products_when_most_of_its_words_are_in_the_title():
    title = frozenset(w.lower() for w in TITLE.split())
    assert _names_product("Pasta Bowl Set", title)
    assert _names_product("Stoneware Pasta Bowl Set Grey", title)  # 4 of 5 words: 80 %
    assert not _names_product("Stoneware Mug Grey Large Matte", title)  # 1 of 5
    assert not _names_product("Bowl Cover Lid Glass Large", title)


@pytest.mark.parametrize("encoding", ["shift_jis", "euc-jp"])
def test_an_undeclared_japanese_encoding_is_detected(encoding):
    page = ("<html><head><title>木製テーブル</title></head><body><h1>木製テーブル</h1>"
            "<p>シンプルなデザインの木製テーブルです。毎日の食卓にどうぞ。</p>"
            "<table><tr><th>サイズ</th><td>幅30×奥行20×高さ10cm</td></tr><tr><th>重量</th><td>約1.2kg</td></tr>"
            "</table></body></html>")  # fmt: skip
    record = extract_page(page.encode(encoding), "https://shop.example.jp/p", "text/html")
    assert record.name == "木製テーブル"
    assert record.dims_cm == (30.0, 20.0, 10.0) and record.mass_g == 1200.0


def test_an_undeclared_western_page_still_reads_its_umlauts():
    page = ("<html><body><h1>Küchenwaage</h1><p>Die Waage für Ihre Küche, präzise und flach.</p>"
            "<p>Gewicht</p><p>4,7 kg</p><p>Höhe: 10 cm</p><p>Breite: 5 cm</p></body></html>")  # fmt: skip
    record = extract_page(page.encode("cp1252"), "https://shop.example.de/x")
    assert record.mass_g == pytest.approx(4700.0) and record.dims_cm == (10.0, 5.0)
