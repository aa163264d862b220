"""How the held-back stores write sizes and weights, one written line or table each (data written here,
in the shapes Japanese and Turkish retailers, computer makers' spec pages and bookstores publish): the
product's dimensions and mass within 2 %, nothing where the page states nothing."""

from __future__ import annotations

import pytest

from scrapers.extract import extract_page
from scrapers.labelled_pages import dims_within, within


def page(body, lang="en", title="Thing"):
    return f"<html lang='{lang}'><head><title>{title}</title></head><body><h1>{title}</h1>{body}</body></html>"


CASES = [
 ("rakuten brackets", page("<p>【サイズ】約W30×D20×H10cm<br>【重量】約500g<br>【材質】ステンレス</p>","ja"), (30,20,10), 500),
 ("rakuten black square", page("<p>■サイズ：幅30×奥行20×高さ10cm<br>■重量：約1.2kg</p>","ja"), (30,20,10), 1200),
 ("fullwidth", page("<table><tr><th>サイズ</th><td>幅３０×奥行２０×高さ１０ｃｍ</td></tr><tr><th>重量</th><td>約１．２ｋｇ</td></tr></table>","ja"), (30,20,10), 1200),
 ("yodobashi", page("<table><tr><th>本体寸法（幅×高さ×奥行）</th><td>約200×150×100mm</td></tr><tr><th>本体質量</th><td>約1.2kg</td></tr></table>","ja"), (20,15,10), 1200),
 ("bic", page("<dl><dt>外形寸法</dt><dd>幅×高さ×奥行き 約 300×200×100 mm</dd><dt>質量</dt><dd>約1.5kg</dd></dl>","ja"), (30,20,10), 1500),
 ("muji", page("<div class='spec'><span>サイズ</span><span>約幅37×奥行26×高さ17.5cm</span><span>重量</span><span>約0.9kg</span></div>","ja"), (37,26,17.5), 900),
 ("nitori", page("<ul><li>商品サイズ：幅30×奥行20×高さ10cm</li><li>重量：約1.5kg</li></ul>","ja"), (30,20,10), 1500),
 ("ja diameter", page("<table><tr><th>サイズ</th><td>直径12cm×高さ6.5cm</td></tr><tr><th>重さ</th><td>約230g</td></tr></table>","ja"), (12,12,6.5), 230),
 ("ja W D H mm no x", page("<table><tr><th>外形寸法</th><td>W300×D200×H100mm</td></tr><tr><th>質量</th><td>2.3kg</td></tr></table>","ja"), (30,20,10), 2300),
 ("ja honbai", page("<table><tr><th>本体サイズ</th><td>幅30cm 奥行20cm 高さ10cm</td></tr><tr><th>本体重量</th><td>約1.2kg</td></tr></table>","ja"), (30,20,10), 1200),
 ("ja sep rows", page("<table><tr><th>幅</th><td>30cm</td></tr><tr><th>奥行き</th><td>20cm</td></tr><tr><th>高さ</th><td>10cm</td></tr><tr><th>重量</th><td>1.2kg</td></tr></table>","ja"), (30,20,10), 1200),
 ("ja yahoo text", page("<div>商品詳細<br>サイズ:約 幅30×奥行20×高さ10cm<br>重量:約1.2kg<br>生産国:日本</div>","ja"), (30,20,10), 1200),
 ("ja kg as キロ", page("<p>サイズ 30×20×10cm / 重さ 約1.2キロ</p>","ja"), (30,20,10), 1200),
 ("ja book", page("<table><tr><th>判型</th><td>B6判</td></tr><tr><th>ページ数</th><td>320p</td></tr><tr><th>高さ</th><td>19cm</td></tr></table>","ja"), (19,), None),
 ("ja book honto", page("<p>サイズ：19cm／240p</p>","ja"), (19,), None),
 ("trendyol list", page("<ul><li><span>Boyut/Ebat:</span><span>30 x 20 cm</span></li><li><span>Ağırlık:</span><span>1,5 kg</span></li></ul>","tr"), (30,20), 1500),
 ("hepsi table", page("<table><tr><th>Genişlik</th><td>30 cm</td></tr><tr><th>Yükseklik</th><td>20 cm</td></tr><tr><th>Derinlik</th><td>10,5 cm</td></tr><tr><th>Ağırlık</th><td>2,3 kg</td></tr></table>","tr"), (30,20,10.5), 2300),
 ("tr en boy", page("<ul><li>En: 30 cm</li><li>Boy: 50 cm</li><li>Net Ağırlık: 450 gr</li></ul>","tr"), (50,30), 450),
 ("tr olculer", page("<p>Ölçüler: 30x20x10 cm</p><p>Ağırlık: 1,25 kg</p>","tr"), (30,20,10), 1250),
 ("tr no lang", "<html><body><h1>Tencere</h1><p>Ürün Ölçüleri: 24 x 24 x 12 cm</p><p>Ağırlık: 1,250 kg</p></body></html>", (24,24,12), 1250),
 ("tr cap", page("<ul><li>Çap: 24 cm</li><li>Yükseklik: 12 cm</li><li>Ağırlık: 1,2 kg</li></ul>","tr"), (24,24,12), 1200),
 ("tr boyutlar", page("<table><tr><td>Boyutlar</td><td>45 x 30 x 15 cm</td></tr><tr><td>Ürün Ağırlığı</td><td>3,4 kg</td></tr></table>","tr"), (45,30,15), 3400),
 ("apple", page("<div><h3>Size and Weight</h3><ul><li>Height: 0.44 inch (1.13 cm)</li><li>Width: 11.97 inches (30.41 cm)</li><li>Depth: 8.46 inches (21.5 cm)</li><li>Weight: 2.7 pounds (1.24 kg)</li></ul></div>"), (30.41,21.5,1.13), 1240),
 ("apple dl", page("<div class='techspecs'><p>Height:</p><p>0.44 inch (1.13 cm)</p><p>Width:</p><p>11.97 inches (30.41 cm)</p><p>Depth:</p><p>8.46 inches (21.5 cm)</p><p>Weight:</p><p>2.7 pounds (1.24 kg)</p></div>"), (30.41,21.5,1.13), 1240),
 ("dell", page("<ul><li>Height: 0.58 in. (14.8 mm)</li><li>Width: 11.64 in. (295.7 mm)</li><li>Depth: 7.79 in. (198.7 mm)</li><li>Weight: Starting at 2.59 lb (1.17 kg)</li></ul>"), (29.57,19.87,1.48), 1170),
 ("hp", page("<table><tr><td>Dimensions</td><td>30.3 x 20.6 x 1.79 cm</td></tr><tr><td>Weight</td><td>Starting at 1.3 kg</td></tr></table>"), (30.3,20.6,1.79), 1300),
 ("lenovo psref", page("<table><tr><td>Dimensions (WxDxH)</td><td>312.8 x 221.6 x 14.9 mm (12.32 x 8.72 x 0.59 inches)</td></tr><tr><td>Weight</td><td>Starting at 1.12 kg (2.47 lbs)</td></tr></table>"), (31.28,22.16,1.49), 1120),
 ("apple imperial first in table", page("<table><tr><th>Height</th><td>0.61 inch (1.56 cm)</td></tr><tr><th>Width</th><td>12.31 inches (31.26 cm)</td></tr><tr><th>Depth</th><td>8.71 inches (22.12 cm)</td></tr><tr><th>Weight</th><td>3.0 pounds (1.36 kg)</td></tr></table>"), (31.26,22.12,1.56), 1360),
 ("two configs", page("<div><h3>13-inch model</h3><ul><li>Height: 0.61 inch (1.56 cm)</li><li>Width: 11.97 inches (30.41 cm)</li><li>Depth: 8.46 inches (21.5 cm)</li><li>Weight: 3.0 pounds (1.36 kg)</li></ul><h3>15-inch model</h3><ul><li>Height: 0.61 inch (1.55 cm)</li><li>Width: 13.40 inches (34.04 cm)</li><li>Depth: 9.35 inches (23.76 cm)</li><li>Weight: 3.3 pounds (1.51 kg)</li></ul></div>",title="MacBook Air 13-inch"), (30.41,21.5,1.56), 1360),
 ("starting weight label", page("<ul><li>Starting weight: 2.8 lb (1.27 kg)</li><li>Dimensions (H x W x D): 0.71 x 12.1 x 8.5 in (18 x 307 x 216 mm)</li></ul>"), (30.7,21.6,1.8), 1270),
 ("amazon book", page("<ul><li><span>Publisher : </span><span>Penguin (2020)</span></li><li><span>Paperback : </span><span>320 pages</span></li><li><span>Item Weight : </span><span>450 g</span></li><li><span>Dimensions : </span><span>15.2 x 2.3 x 22.9 cm</span></li></ul>"), (22.9,15.2,2.3), 450),
 ("amazon book in", page("<ul><li>Paperback : 320 pages</li><li>Item Weight : 1.1 pounds</li><li>Dimensions : 6.14 x 0.9 x 9.21 inches</li></ul>"), (23.39,15.6,2.29), 499),
 ("bn", page("<table><tr><th>ISBN-13:</th><td>9780143127741</td></tr><tr><th>Pages:</th><td>320</td></tr><tr><th>Product dimensions:</th><td>5.40(w) x 8.30(h) x 0.90(d)</td></tr></table>", "en-US"), (21.08,13.72,2.29), None),
 ("waterstones", page("<p>Dimensions: 234 x 153 x 29 mm</p><p>Weight: 520 g</p><p>Number of pages: 384</p>"), (23.4,15.3,2.9), 520),
 ("bookdepo", page("<ul><li><label>Dimensions</label><span>129 x 198 x 22mm | 220g</span></li><li><label>Pages</label><span>320</span></li></ul>"), (19.8,12.9,2.2), 220),
 ("book shipping wt", page("<ul><li>Dimensions : 6 x 0.8 x 9 inches</li><li>Shipping Weight: 1.2 pounds</li></ul>"), (22.86,15.24,2.03), None),
 ("product dims label", page("<p>Product dimensions: 15.2 x 2.3 x 22.9 cm</p><p>Item weight: 450 g</p>"), (22.9,15.2,2.3), 450),
 ("asus tilde", page("<table><tr><td>Dimensions (W x D x H)</td><td>31.18 x 22.25 x 1.49 ~ 1.69 cm (12.28\" x 8.76\" x 0.59\" ~ 0.67\")</td></tr><tr><td>Weight</td><td>1.40 kg (3.09 lbs)</td></tr></table>"), (31.18,22.25,1.69), 1400),
 ("surface", page("<ul><li>Dimensions: 11.3\" x 8.2\" x 0.37\" (287 mm x 208 mm x 9.3 mm)</li><li>Weight: Surface Pro 9 i5, i7: 879 g (1.94 lb)</li></ul>"), (28.7,20.8,0.93), 879),
 ("bam", page("<div><p>Dimensions: 5.20 X 8.00 X 0.40 (inches)</p><p>Weight: 0.35 (pounds)</p></div>"), (20.32,13.2,1.02), 158.8),
 ("thalia", page("<dl><dt>Maße (L/B/H)</dt><dd>19/12,5/2,5 cm</dd><dt>Gewicht</dt><dd>250 g</dd><dt>Seitenzahl</dt><dd>320</dd></dl>","de"), (19,12.5,2.5), 250),
 ("ja zencho", page("<table><tr><th>全長</th><td>30cm</td></tr><tr><th>全幅</th><td>20cm</td></tr><tr><th>全高</th><td>10cm</td></tr><tr><th>重量</th><td>500g</td></tr></table>","ja"), (30,20,10), 500),
 ("ja tate yoko", page("<p>サイズ：縦30×横20×厚み5cm</p><p>重さ：約300g</p>","ja"), (30,20,5), 300),
 ("ja atsumi", page("<table><tr><th>厚み</th><td>2cm</td></tr><tr><th>直径</th><td>25cm</td></tr></table>","ja"), (25,25,2), None),
 ("tr en x boy", page("<ul><li>En x Boy: 160 x 230 cm</li><li>Ağırlık: 3,5 kg</li></ul>","tr"), (230,160), 3500),
 ("tr desi", page("<ul><li>Boyut: 30 x 20 x 10 cm</li><li>Desi: 3</li><li>Ağırlık: 1,2 kg</li></ul>","tr"), (30,20,10), 1200),
 ("tr olcu cm", page("<table><tr><td>Ürün Ölçüsü (cm)</td><td>45 x 30 x 15</td></tr><tr><td>Ürün Ağırlığı (kg)</td><td>2,5</td></tr></table>","tr"), (45,30,15), 2500),
 ("apple multi column", page("<table><tr><th></th><th>13-inch</th><th>15-inch</th></tr><tr><td>Height</td><td>1.13 cm</td><td>1.15 cm</td></tr><tr><td>Width</td><td>30.41 cm</td><td>34.04 cm</td></tr><tr><td>Depth</td><td>21.5 cm</td><td>23.76 cm</td></tr><tr><td>Weight</td><td>1.24 kg</td><td>1.51 kg</td></tr></table>", title="MacBook Air 13-inch"), (30.41,21.5,1.13), 1240),
 ("ja book amazon weight", page("<ul><li>本の長さ : 320ページ</li><li>寸法 : 12.8 x 1.8 x 18.8 cm</li><li>重量 : 200 g</li></ul>","ja"), (18.8,12.8,1.8), 200),
 ("yodobashi W x H x D mm", page("<table><tr><th>本体寸法（W×H×D）</th><td>約220×200×155mm</td></tr><tr><th>本体質量</th><td>約1.0kg</td></tr></table>","ja"), (22,20,15.5), 1000),
 ("hp package first", page("<ul><li>Package dimensions: 53 x 29 x 7 cm</li><li>Package weight: 2.7 kg</li><li>Dimensions: 35.8 x 23.4 x 1.9 cm</li><li>Weight: 1.7 kg</li></ul>"), (35.8,23.4,1.9), 1700),
 ("book item weight shipping", page("<ul><li>Item Weight : 1.1 pounds</li><li>Shipping Weight: 1.4 pounds</li><li>Product Dimensions: 6 x 1 x 9 inches</li></ul>"), (22.86,15.24,2.54), 499),
 ("bic hwd", page("<table><tr><th>本体サイズ（H×W×D） mm</th><td>H200×W220×D155</td></tr><tr><th>本体重量</th><td>1.0kg</td></tr></table>","ja"), (22,20,15.5), 1000),
 ("joshin", page("<dl><dt>外形寸法（幅×奥行×高さ）</dt><dd>約220×155×200mm</dd><dt>質量（本体のみ）</dt><dd>約1.0kg</dd></dl>","ja"), (22,20,15.5), 1000),
 ("ja multi mass", page("<p>質量：本体 約1.2kg、充電台 約0.3kg</p><p>外形寸法：幅60×奥行40×高さ35mm</p>","ja"), (6,4,3.5), 1200),
 ("tr ürün boyutları", page("<ul><li>Ürün Boyutları: 30 cm x 20 cm x 10 cm</li><li>Ağırlık (kg): 1,5</li></ul>","tr"), (30,20,10), 1500),
 ("tr book", page("<table><tr><td>Sayfa Sayısı</td><td>320</td></tr><tr><td>Boyut</td><td>13.5 x 21 cm</td></tr><tr><td>Kağıt Cinsi</td><td>2. Hamur</td></tr></table>","tr"), (21,13.5), None),
 ("iphone", page("<ul><li>Width: 2.78 inches (70.6 mm)</li><li>Height: 5.81 inches (147.6 mm)</li><li>Depth: 0.31 inch (7.80 mm)</li><li>Weight: 6.02 ounces (171 grams)</li></ul>"), (14.76,7.06,0.78), 171),
 ("dell heading weight", page("<div><h4>Weight</h4><p>Starting at: 2.59 lb (1.17 kg)</p><h4>Dimensions</h4><p>Height (front): 0.55 in. (13.99 mm)</p><p>Width: 11.63 in. (295.3 mm)</p><p>Depth: 7.86 in. (199.4 mm)</p></div>"), (29.53,19.94,1.399), 1170),
 ("lenovo slash", page("<ul><li>Weight: Starting at 2.48lbs / 1.12kg</li><li>Dimensions: 12.43 x 8.76 x 0.60 inches / 315.6 x 222.5 x 15.36 mm</li></ul>"), (31.56,22.25,1.536), 1120),
 ("kindle ja", page("<table><tr><th>サイズ</th><td>127 x 176.7 x 7.8 mm</td></tr><tr><th>重量</th><td>205 g</td></tr></table>","ja"), (17.67,12.7,0.78), 205),
 ("amazon jp item", page("<div id='prodDetails'><table><tr><th>梱包サイズ</th><td>30 x 20 x 10 cm; 500 g</td></tr><tr><th>商品の重量</th><td>450 g</td></tr><tr><th>製品サイズ</th><td>25 x 15 x 8 cm</td></tr></table></div>","ja"), (25,15,8), 450),
]


@pytest.mark.parametrize(("name", "html", "dims", "mass"), CASES, ids=[c[0] for c in CASES])
def test_the_products_values_within_two_percent(name, html, dims, mass):
    record = extract_page(html, "https://shop.example.test/p")
    assert dims_within(record.dims_cm, dims, 0.02) if dims else record.dims_cm is None, record.dims_cm
    assert (record.mass_g is not None and within(record.mass_g, mass, 0.02)) if mass else record.mass_g is None, (
        record.mass_g
    )


@pytest.mark.parametrize("lang", ["en", "en-GB", "de-DE"])
def test_unitless_lengths_are_inches_only_on_a_declared_us_page(lang):
    from kb.errors import ExtractionError

    body = "<table><tr><th>Product dimensions:</th><td>5.40(w) x 8.30(h) x 0.90(d)</td></tr></table>"
    with pytest.raises(ExtractionError, match="no unit stated"):
        extract_page(page(body, lang), "https://shop.example.test/p")


@pytest.mark.parametrize(("label", "unit"), [("Höhe cm", "cm"), ("Gewicht kg", "kg"), ("本体サイズ（H×W×D） mm", "mm"),
                                            ("Size M", None), ("Weight", None)])
def test_a_unit_word_in_a_label_is_its_unit_but_not_a_garment_size(label, unit):
    from scrapers.labels import classify_label

    assert classify_label(label).unit == unit
