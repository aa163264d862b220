"""The label vocabulary (scrapers/labels.py) and normalisation rules (scrapers/normalize.py)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.features import MATERIALS, SHAPES
from scrapers.labels import classify_label
from scrapers.normalize import check_dims, check_mass, material_from_text, shape_from_dims, shape_from_name


@pytest.mark.parametrize(
    ("label", "kind", "package", "unit"),
    [
        ("Item Dimensions LxWxH", "dimensions", False, None),
        ("Product Dimensions :", "dimensions", False, None),
        ("Artikelabmessungen L x B x H", "dimensions", False, None),
        ("Artikelgewicht", "weight", False, None),
        ("Item Package Dimensions L x W x H", "dimensions", True, None),
        ("Package Weight", "weight", True, None),
        ("Shipping Weight", "weight", True, None),
        ("Masse der Verpackung (LxBxH)", "dimensions", True, None),
        ("Gewicht inkl. Verpackung", "weight", True, None),
        ("Versandgewicht", "weight", True, None),
        ("Breite", "width", False, None),
        ("Höhe", "height", False, None),
        ("Profundidade:", "depth", False, None),
        ("Peso del producto", "weight", False, None),
        ("Peso del artículo", "weight", False, None),
        ("Peso con imballo", "weight", True, None),
        ("Peso bruto", "weight", True, None),
        ("Poids net", "weight", False, None),
        ("Dimensions du colis", "dimensions", True, None),
        ("Dimensioni prodotto", "dimensions", False, None),
        ("Výška [mm]:", "height", False, "mm"),
        ("Hmotnosť [kg]:", "weight", False, "kg"),
        ("Grubość (w mm):", "thickness", False, "mm"),
        ("Wysokość produktu", "height", False, None),
        ("Габариты устройства (ВхШхГ), см:", "dimensions", False, "см"),
        ("Вес без упаковки (нетто), кг:", "weight", False, "кг"),  # "without packaging": the product
        ("Размеры упаковки", "dimensions", True, None),
        ("尺寸：", "dimensions", False, None),
        ("重量：", "weight", False, None),
        ("包裝尺寸", "dimensions", True, None),
        ("Product size", "size", False, None),
        ("Width x Height x Depth", "dimensions", False, None),
        ("Product Depth (in.)", "depth", False, "in."),
        ("Weight & Dimensions", "dimensions", False, None),
        ("Productafmetingen", "dimensions", False, None),
        ("Verpakkingsafmetingen", "dimensions", True, None),
        ("Förpackningsmått", "dimensions", True, None),
        ("Ürün Ağırlığı", "weight", False, None),
        ("Greutate", "weight", False, None),
        ("Svars", "weight", False, None),  # lv
        ("Mõõtmed", "dimensions", False, None),  # et
        ("Težina", "weight", False, None),  # hr
        ("Тегло", "weight", False, None),  # bg
        ("משקל", "weight", False, None),  # he
        ("الوزن", "weight", False, None),  # ar
        ("商品の重量", "weight", False, None),
        ("Altura com os pés", "height", False, None),
        ("梱包サイズ", "dimensions", True, None),  # katakana with a dakuten (ズ) folds like the table
        ("本体サイズ", "dimensions", False, None),
        ("Вес в упаковке, г", "weight", True, "г"),
        ("Длина предмета", "length", False, None),
        ("Dimensioni del collo", "dimensions", True, None),
        ("Kargo Ağırlığı", "weight", True, None),
        ("Boyutlar", "dimensions", False, None),
        ("Rozměry (Š x V x H)", "dimensions", False, None),
        ("Hmotnost balení", "weight", True, None),
        ("Waga produktu z opakowaniem jednostkowym", "weight", True, None),
        ("Overall Height - Top to Bottom", "height", False, None),
        ("Overall Depth - Front to Back", "depth", False, None),
        ("Profundidad", "depth", False, None),
        ("Dimensioni dell'articolo Lunghezza x Larghezza x Altezza", "dimensions", False, None),
        ("Peso dell'articolo", "weight", False, None),
        ("Gewicht van het artikel", "weight", False, None),
        ("Förpackningens mått", "dimensions", True, None),
        ("Tömeg", "weight", False, None),
        ("商品の寸法 幅 × 奥行 × 高さ", "dimensions", False, None),  # zh/ja read token by token
        ("商品パッケージの寸法", "dimensions", True, None),
        ("产品尺寸 长*宽*高", "dimensions", False, None),
        ("本体質量", "weight", False, None),
        ("本体サイズ W×D×H", "dimensions", False, None),
    ],
)
def test_measurement_labels(label, kind, package, unit):
    info = classify_label(label)
    assert info is not None, label
    assert (info.kind, info.package, info.unit) == (kind, package, unit)


@pytest.mark.parametrize(
    "label",
    [
        "Schlauchlänge",  # hose length: a component
        "Peso suportado por cada lado",  # supported load
        "Peso Suportado",
        "Durchmesser Stiftspitze",  # tip diameter
        "Min Height",
        "Overall Max Height",
        "Chain Length",
        "Body Height - Top to Bottom",
        "Shelf Height - Top to Bottom",
        "電源コード長さ",  # cord length
        "高さ調節",  # height adjustment
        "耐荷重",  # load capacity
        "Peso máximo soportado",
        "Maximum Weight Recommendation",
        "Мощность замораживания, кг/сутки:",
        "容量：",
        "Package(s): 1",
        "Item model number",
        "Screen size",
        "Weight capacity",
        "",
        "x" * 300,
    ],
)
def test_non_measurement_labels(label):
    assert classify_label(label) is None


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.text(max_size=120), st.none(), st.integers(), st.binary(max_size=50)))
def test_classify_label_never_raises(label):
    info = classify_label(label)
    assert info is None or info.kind


@pytest.mark.parametrize(
    ("dims", "shape"),
    [
        ((15.4, 7.9, 1.5), "thin"),  # calculator (paper, table)
        ((15.5, 9.0, 1.8), "thin"),  # cardboard box
        ((16.0, 3.5, 2.0), "long"),  # TV remote
        ((21.5, 7.2, 7.2), "prism"),  # water bottle
        ((6.0, 3.0, 1.5), "prism"),  # wood wedge
        ((3.0, 3.0, 3.0), "compact"),  # rubik cube
        ((7.2, 7.2, 2.0), "compact"),  # wood disk
        ((2.0, 7.2, 7.2), "compact"),  # any order
        ((40.0, 5.0), "long"),
        ((40.0, 30.0), None),
        ((12.0,), None),
        (None, None),
    ],
)
def test_shape_rule(dims, shape):
    assert shape_from_dims(dims) == shape


def test_radial_from_name_and_every_shape_is_a_catalog_word():
    assert shape_from_name("Tennis ball, pack of 3") == "radial"
    assert shape_from_name("Balle de tennis") == "radial"
    assert shape_from_name("Ballpoint pen") is None
    assert {shape_from_dims(d) for d in [(1, 1, 0.1), (10, 1, 1), (3, 1.5, 1.5), (2, 2, 2)]} <= set(SHAPES)


@pytest.mark.parametrize(
    ("text", "material"),
    [
        ("Edelstahl", "metal"),
        ("Acier inoxydable", "metal"),
        ("Plástico", "plastic"),
        ("Particleboard, Thick oak veneer", "wood"),
        ("MDF", "wood"),
        ("不鏽鋼", "metal"),
        ("100% cotton", "fabric"),
        ("Borosilicate glass", "glass"),
        ("Porcelain", "other"),
        ("Buchenholz", "wood"),  # a compound named by its last part
        ("陶器", "other"),
        ("ポリプロピレン", "plastic"),
        ("Bakır", "metal"),
        ("чугун", "metal"),
        ("nerezová ocel", "metal"),
        ("Madera de acacia", "wood"),
        ("glasses", None),
        ("Molas", None),
        ("", None),
        (None, None),
    ],
)
def test_material_words(text, material):
    assert material_from_text(text) == material
    assert material is None or material in MATERIALS


def test_limits():
    assert check_dims((10.0, 5.0, 1.0)) is None
    assert "absurd" in check_dims((600.0, 5.0))
    assert check_dims((1.0, 2.0, 3.0, 4.0)) is not None
    assert check_mass(500.0) is None
    assert "absurd" in check_mass(900_000.0)
    assert check_mass(0.0) is not None
