"""The label vocabulary language by language (issue 21): for each store language of the next stores (French,
Spanish, Italian, Polish, Dutch, Portuguese, Swedish, Danish, Norwegian, Finnish, Czech, Japanese, Korean)
the words of the whole concept, not one page's word: width, height, depth, length, diameter, thickness,
weight, net, gross, package and dimensions, as a store writes them on a label (from general knowledge of
the languages; labels written here). Words added here: fr ``Encombrement``, it ``Ingombro`` (overall size),
pl ``Ciężar``, nl ``Doorsnede``, ``Brutogewicht``, sv ``Tjocklek``, ``Dimensioner``, da/no ``Tykkelse``,
``Dimensioner``/``Dimensjoner``, ``Pakkens mål``, ``Pakkevekt``, ``med`` (with), fi ``Halkaisija``,
``Paksuus``, ``Pakkauksen``, Finnish compounds (``Nettopaino``, ``Bruttopaino``, ``Kokonaispaino``), cs
``Čistá``/``Hrubá hmotnost``, ``s obalem``, ja ``正味重量``, ``総重量``, ``外径``, ko ``가로``, ``세로``, ``직경``,
``순중량``, ``총중량``, ``규격``.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from scrapers.extract import extract_page
from scrapers.labels import classify_label, classify_other

W, H, D, L, DI, T, WT, DM = "width", "height", "depth", "length", "diameter", "thickness", "weight", "dimensions"

#: (language, label, kind or None for no measurement of the product, package value)
LABELS = [
    ('fr', 'Largeur', 'width', False),
    ('fr', 'Hauteur', 'height', False),
    ('fr', 'Profondeur', 'depth', False),
    ('fr', 'Longueur', 'length', False),
    ('fr', 'Diamètre', 'diameter', False),
    ('fr', 'Épaisseur', 'thickness', False),
    ('fr', 'Poids', 'weight', False),
    ('fr', 'Poids net', 'weight', False),
    ('fr', 'Poids brut', 'weight', True),
    ('fr', 'Poids du colis', 'weight', True),
    ('fr', "Dimensions de l'emballage", 'dimensions', True),
    ('fr', 'Dimensions', 'dimensions', False),
    ('fr', 'Encombrement', 'dimensions', False),
    ('fr', "Poids de l'article", 'weight', False),
    ('fr', 'Dimensions du produit', 'dimensions', False),
    ('fr', 'Poids avec emballage', 'weight', True),
    ('es', 'Ancho', 'width', False),
    ('es', 'Alto', 'height', False),
    ('es', 'Fondo', 'depth', False),
    ('es', 'Largo', 'length', False),
    ('es', 'Diámetro', 'diameter', False),
    ('es', 'Grosor', 'thickness', False),
    ('es', 'Espesor', 'thickness', False),
    ('es', 'Peso', 'weight', False),
    ('es', 'Peso neto', 'weight', False),
    ('es', 'Peso bruto', 'weight', True),
    ('es', 'Peso del paquete', 'weight', True),
    ('es', 'Dimensiones del embalaje', 'dimensions', True),
    ('es', 'Medidas', 'dimensions', False),
    ('es', 'Dimensiones', 'dimensions', False),
    ('es', 'Profundidad', 'depth', False),
    ('es', 'Longitud', 'length', False),
    ('es', 'Anchura', 'width', False),
    ('es', 'Altura', 'height', False),
    ('it', 'Larghezza', 'width', False),
    ('it', 'Altezza', 'height', False),
    ('it', 'Profondità', 'depth', False),
    ('it', 'Lunghezza', 'length', False),
    ('it', 'Diametro', 'diameter', False),
    ('it', 'Spessore', 'thickness', False),
    ('it', 'Peso', 'weight', False),
    ('it', 'Peso netto', 'weight', False),
    ('it', 'Peso lordo', 'weight', True),
    ('it', 'Peso della confezione', 'weight', True),
    ('it', 'Dimensioni imballo', 'dimensions', True),
    ('it', 'Dimensioni', 'dimensions', False),
    ('it', 'Misure', 'dimensions', False),
    ('it', 'Ingombro', 'dimensions', False),
    ('it', 'Peso imballo', 'weight', True),
    ('pl', 'Szerokość', 'width', False),
    ('pl', 'Wysokość', 'height', False),
    ('pl', 'Głębokość', 'depth', False),
    ('pl', 'Długość', 'length', False),
    ('pl', 'Średnica', 'diameter', False),
    ('pl', 'Grubość', 'thickness', False),
    ('pl', 'Waga', 'weight', False),
    ('pl', 'Masa', 'weight', False),
    ('pl', 'Ciężar', 'weight', False),
    ('pl', 'Waga netto', 'weight', False),
    ('pl', 'Waga brutto', 'weight', True),
    ('pl', 'Waga z opakowaniem', 'weight', True),
    ('pl', 'Wymiary opakowania', 'dimensions', True),
    ('pl', 'Wymiary', 'dimensions', False),
    ('pl', 'Wymiary produktu', 'dimensions', False),
    ('pl', 'Masa netto', 'weight', False),
    ('nl', 'Breedte', 'width', False),
    ('nl', 'Hoogte', 'height', False),
    ('nl', 'Diepte', 'depth', False),
    ('nl', 'Lengte', 'length', False),
    ('nl', 'Diameter', 'diameter', False),
    ('nl', 'Doorsnede', 'diameter', False),
    ('nl', 'Dikte', 'thickness', False),
    ('nl', 'Gewicht', 'weight', False),
    ('nl', 'Nettogewicht', 'weight', False),
    ('nl', 'Brutogewicht', 'weight', True),
    ('nl', 'Verpakkingsgewicht', 'weight', True),
    ('nl', 'Afmetingen verpakking', 'dimensions', True),
    ('nl', 'Afmetingen', 'dimensions', False),
    ('nl', 'Productgewicht', 'weight', False),
    ('nl', 'Gewicht (netto)', 'weight', False),
    ('nl', 'Verpakking afmetingen', 'dimensions', True),
    ('nl', 'Productafmetingen', 'dimensions', False),
    ('nl', 'Totaalgewicht', 'weight', False),
    ('pt', 'Largura', 'width', False),
    ('pt', 'Altura', 'height', False),
    ('pt', 'Profundidade', 'depth', False),
    ('pt', 'Comprimento', 'length', False),
    ('pt', 'Diâmetro', 'diameter', False),
    ('pt', 'Espessura', 'thickness', False),
    ('pt', 'Peso', 'weight', False),
    ('pt', 'Peso líquido', 'weight', False),
    ('pt', 'Peso bruto', 'weight', True),
    ('pt', 'Peso da embalagem', 'weight', True),
    ('pt', 'Dimensões da embalagem', 'dimensions', True),
    ('pt', 'Dimensões', 'dimensions', False),
    ('pt', 'Medidas', 'dimensions', False),
    ('pt', 'Peso do produto', 'weight', False),
    ('sv', 'Bredd', 'width', False),
    ('sv', 'Höjd', 'height', False),
    ('sv', 'Djup', 'depth', False),
    ('sv', 'Längd', 'length', False),
    ('sv', 'Diameter', 'diameter', False),
    ('sv', 'Tjocklek', 'thickness', False),
    ('sv', 'Vikt', 'weight', False),
    ('sv', 'Nettovikt', 'weight', False),
    ('sv', 'Bruttovikt', 'weight', True),
    ('sv', 'Förpackningsvikt', 'weight', True),
    ('sv', 'Mått', 'dimensions', False),
    ('sv', 'Dimensioner', 'dimensions', False),
    ('sv', 'Produktvikt', 'weight', False),
    ('sv', 'Förpackningens mått', 'dimensions', True),
    ('sv', 'Totalvikt', 'weight', False),
    ('da', 'Bredde', 'width', False),
    ('da', 'Højde', 'height', False),
    ('da', 'Dybde', 'depth', False),
    ('da', 'Længde', 'length', False),
    ('da', 'Diameter', 'diameter', False),
    ('da', 'Tykkelse', 'thickness', False),
    ('da', 'Vægt', 'weight', False),
    ('da', 'Nettovægt', 'weight', False),
    ('da', 'Bruttovægt', 'weight', True),
    ('da', 'Emballagevægt', 'weight', True),
    ('da', 'Mål', 'dimensions', False),
    ('da', 'Dimensioner', 'dimensions', False),
    ('da', 'Produktvægt', 'weight', False),
    ('da', 'Pakkens mål', 'dimensions', True),
    ('da', 'Vægt inkl. emballage', 'weight', True),
    ('no', 'Bredde', 'width', False),
    ('no', 'Høyde', 'height', False),
    ('no', 'Dybde', 'depth', False),
    ('no', 'Lengde', 'length', False),
    ('no', 'Diameter', 'diameter', False),
    ('no', 'Tykkelse', 'thickness', False),
    ('no', 'Vekt', 'weight', False),
    ('no', 'Nettovekt', 'weight', False),
    ('no', 'Bruttovekt', 'weight', True),
    ('no', 'Mål', 'dimensions', False),
    ('no', 'Dimensjoner', 'dimensions', False),
    ('no', 'Produktvekt', 'weight', False),
    ('no', 'Vekt med emballasje', 'weight', True),
    ('no', 'Pakkevekt', 'weight', True),
    ('fi', 'Leveys', 'width', False),
    ('fi', 'Korkeus', 'height', False),
    ('fi', 'Syvyys', 'depth', False),
    ('fi', 'Pituus', 'length', False),
    ('fi', 'Halkaisija', 'diameter', False),
    ('fi', 'Paksuus', 'thickness', False),
    ('fi', 'Paino', 'weight', False),
    ('fi', 'Nettopaino', 'weight', False),
    ('fi', 'Bruttopaino', 'weight', True),
    ('fi', 'Pakkauksen paino', 'weight', True),
    ('fi', 'Mitat', 'dimensions', False),
    ('fi', 'Pakkauksen mitat', 'dimensions', True),
    ('fi', 'Tuotteen paino', 'weight', False),
    ('fi', 'Kokonaispaino', 'weight', False),
    ('fi', 'Tuotteen mitat', 'dimensions', False),
    ('cs', 'Šířka', 'width', False),
    ('cs', 'Výška', 'height', False),
    ('cs', 'Hloubka', 'depth', False),
    ('cs', 'Délka', 'length', False),
    ('cs', 'Průměr', 'diameter', False),
    ('cs', 'Tloušťka', 'thickness', False),
    ('cs', 'Hmotnost', 'weight', False),
    ('cs', 'Váha', 'weight', False),
    ('cs', 'Hmotnost netto', 'weight', False),
    ('cs', 'Hmotnost brutto', 'weight', True),
    ('cs', 'Hmotnost s obalem', 'weight', True),
    ('cs', 'Rozměry balení', 'dimensions', True),
    ('cs', 'Rozměry', 'dimensions', False),
    ('cs', 'Čistá hmotnost', 'weight', False),
    ('cs', 'Hmotnost výrobku', 'weight', False),
    ('cs', 'Rozměry výrobku', 'dimensions', False),
    ('cs', 'Hrubá hmotnost', 'weight', True),
    ('ja', '幅', 'width', False),
    ('ja', '高さ', 'height', False),
    ('ja', '奥行き', 'depth', False),
    ('ja', '長さ', 'length', False),
    ('ja', '直径', 'diameter', False),
    ('ja', '厚さ', 'thickness', False),
    ('ja', '重量', 'weight', False),
    ('ja', '重さ', 'weight', False),
    ('ja', '質量', 'weight', False),
    ('ja', '正味重量', 'weight', False),
    ('ja', '総重量', 'weight', False),
    ('ja', '梱包重量', 'weight', True),
    ('ja', '梱包サイズ', 'dimensions', True),
    ('ja', '寸法', 'dimensions', False),
    ('ja', '外形寸法', 'dimensions', False),
    ('ja', '外径', 'diameter', False),
    ('ja', '本体重量', 'weight', False),
    ('ja', '商品サイズ', 'dimensions', False),
    ('ja', 'パッケージサイズ', 'dimensions', True),
    ('ja', '内容量', None, False),
    ('ko', '가로', 'width', False),
    ('ko', '세로', 'length', False),
    ('ko', '높이', 'height', False),
    ('ko', '깊이', 'depth', False),
    ('ko', '폭', 'width', False),
    ('ko', '너비', 'width', False),
    ('ko', '길이', 'length', False),
    ('ko', '지름', 'diameter', False),
    ('ko', '직경', 'diameter', False),
    ('ko', '두께', 'thickness', False),
    ('ko', '무게', 'weight', False),
    ('ko', '중량', 'weight', False),
    ('ko', '순중량', 'weight', False),
    ('ko', '총중량', 'weight', False),
    ('ko', '포장 무게', 'weight', True),
    ('ko', '포장 크기', 'dimensions', True),
    ('ko', '크기', 'dimensions', False),
    ('ko', '사이즈', 'dimensions', False),
    ('ko', '제품 크기', 'dimensions', False),
    ('ko', '제품 무게', 'weight', False),
    ('ko', '치수', 'dimensions', False),
    ('ko', '규격', 'dimensions', False),
    ('ko', '제품 규격', 'dimensions', False),
    ('ko', '박스 크기', 'dimensions', True),
]


@pytest.mark.parametrize(("lang", "label", "kind", "package"), LABELS)
def test_each_languages_label_names_its_measurement(lang, label, kind, package):
    info = classify_label(label)
    assert (None if info is None else (info.kind, info.package)) == (None if kind is None else (kind, package))


WORD_LABELS = [row for row in LABELS if row[2] is not None and row[0] not in ("ja", "ko")]


@given(st.sampled_from(WORD_LABELS), st.sampled_from(["Cable", "Kabel", "Handle", "Deckel"]))
def test_a_part_word_makes_any_languages_label_a_parts(row, part):
    _, label, _, _ = row
    assert classify_label(f"{part} {label}") is None
    other = classify_other(f"{part} {label}")
    assert other is None or other.role in ("component", "capacity")


@given(st.sampled_from(WORD_LABELS), st.sampled_from([":", " :", "：", " (cm)", " [kg]"]))
def test_punctuation_and_a_unit_after_a_label_keep_its_kind(row, tail):
    _, label, kind, package = row
    info = classify_label(label + tail)
    assert info is not None and (info.kind, info.package) == (kind, package)


def _page(lang: str, rows: list[tuple[str, str]]) -> str:
    cells = "".join(f"<tr><th>{a}</th><td>{b}</td></tr>" for a, b in rows)
    return f"<html lang='{lang}'><head><title>Lampe</title></head><body><h1>Lampe</h1><table>{cells}</table></body></html>"


@pytest.mark.parametrize(("lang", "rows", "dims", "mass", "package_mass"), [
    ("fi", [("Halkaisija", "30 cm"), ("Korkeus", "45 cm"), ("Nettopaino", "1,2 kg"), ("Bruttopaino", "1,6 kg")],
     (45.0, 30.0, 30.0), 1200.0, [1600.0]),
    ("ko", [("가로", "30cm"), ("세로", "20cm"), ("높이", "10cm"), ("순중량", "500g")], (30.0, 20.0, 10.0), 500.0, []),
    ("no", [("Tykkelse", "2 cm"), ("Bredde", "60 cm"), ("Vekt", "3 kg"), ("Vekt med emballasje", "3,5 kg")],
     (60.0, 2.0), 3000.0, [3500.0]),
    ("cs", [("Průměr", "25 cm"), ("Čistá hmotnost", "800 g"), ("Hmotnost s obalem", "950 g")], (25.0, 25.0), 800.0, [950.0]),
    ("nl", [("Doorsnede", "12 cm"), ("Nettogewicht", "400 g"), ("Brutogewicht", "450 g")], (12.0, 12.0), 400.0, [450.0]),
])  # fmt: skip
def test_a_spec_table_in_each_language_reads_the_products_values(lang, rows, dims, mass, package_mass):
    record = extract_page(_page(lang, rows), "https://shop.example/p")
    assert record.dims_cm == dims and record.mass_g == mass
    assert list(record.package_mass_g or []) + list(record.shipping_mass_g or []) == package_mass
