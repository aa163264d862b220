"""The words of measurement labels, in many languages: what :mod:`scrapers.labels` matches labels against.

Kind words (length, width, ... weight), package and shipping words, negations, harmless qualifiers, the
prefixes of German/Dutch/Scandinavian compounds, whole CJK labels and CJK tokens, capacity words and part
words. Every word is folded (:func:`fold`: lower case, NFKD, marks removed) like the labels it is compared
with. The rules that use them are in :mod:`scrapers.labels`.
"""

from __future__ import annotations

import re
import unicodedata


def fold(text: str) -> str:
    if text.isascii():
        return text.lower()  # NFKD leaves ASCII as it is, and it has no combining marks
    decomposed = unicodedata.normalize("NFKD", text.lower().replace("ł", "l"))  # NFKD keeps ł: głębokość/glebokosc
    return "".join(ch for ch in decomposed if not unicodedata.combining(ch))


def _words(kind: str, text: str) -> dict[str, str]:
    return {fold(w): kind for w in text.split()}


KIND_WORDS: dict[str, str] = {
    **_words(
        "length",
        "length len long boy boyu länge laenge longueur longitud largo lunghezza comprimento długość dlugosc dĺžka "
        "délka длина довжина lengte längd længde lengde uzunluk uzunluğu lungime pituus hossz hosszúság μήκος panjang garums ilgis pikkus dolžina dužina duljina дължина אורך الطول طول",
    ),
    **_words(
        "width",
        "width wide breite largeur ancho anchura larghezza largura szerokość šírka šířka ширина ширина "
        "breedte bredd bredde genişlik genişliği lățime latime leveys szélesség πλάτος lebar platums plotis laius širina ширина רוחב العرض عرض",
    ),
    **_words(
        "height",
        "height high tall höhe hoehe hauteur alto altura altezza wysokość výška высота висота hoogte höjd højde "
        "høyde yükseklik yüksekliği înălțime inaltime korkeus magasság ύψος tinggi augstums aukštis kõrgus višina visina височина גובה الارتفاع ارتفاع",
    ),
    **_words(
        "depth",
        "depth deep tiefe profondeur profundidad fondo profondità profundidade głębokość hĺbka hloubka "
        "глубина глибина diepte djup dybde derinlik derinliği adâncime syvyys mélység βάθος dziļums gylis sügavus globina dubina дълбочина עומק العمق عمق",
    ),
    **_words(
        "diameter",
        "diameter dia קוטר القطر durchmesser diamètre diámetro diametro średnica priemer průměr диаметр діаметр "
        "çap çapı doorsnede halkaisija átmérő diametru διάμετρος promjer premer prečnik диаметър diametrs skersmuo "
        "läbimõõt",
    ),
    **_words(
        "thickness",
        "thickness thick dicke stärke épaisseur grosor espesor spessore espessura grubość hrúbka tloušťka "
        "толщина товщина dikte kalınlık kalınlığı tjocklek tykkelse paksuus vastagság grosime πάχος debljina "
        "debelina дебелина biezums storis paksus ketebalan",
    ),
    **_words(
        "dimensions",
        "dimensions dimension dims measurements measures abmessungen abmessung maße masse maasse außenmaße "
        "dimensiones medidas dimensioni misure dimensões wymiary rozmery rozměry размеры габариты габарит "
        "afmetingen afmeting mått mål габаритные габаритный габарити розміри boyutlar boyutları boyut dimensiuni mitat méretek "
        "méret διαστάσεις dimensi ukuran izmēri izmeri matmenys mõõtmed dimenzije размери מידות الأبعاد الابعاد أبعاد ابعاد المقاسات "
        "ölçü ölçüler ölçüleri ölçüsü ebat ebatlar ebatları ebadı dimensioner dimensjoner encombrement ingombro",
    ),
    **_words("size", "size sizes größe groesse grosse taille tamaño tamanho taglia formato format размер velikost"),
    **_words(
        "weight",
        "weight weighs wt mass gewicht poids peso waga masa hmotnosť hmotnost váha вес масса вага vikt vægt vekt "
        "ağırlık ağırlığı greutate paino súly tömeg βάρος berat svars svoris kaal teža težina тегло משקל الوزن وزن ciężar",
    ),
}
PACKAGE_WORDS = {
    fold(w)
    for w in (
        "package packages packaging packed shipping shipment box carton parcel gross verpackung verpackt "
        "versand paket karton brutto emballage emballé colis embalaje embalado paquete envío caja imballo "
        "imballaggio confezione spedizione pacco embalagem pacote caixa opakowanie opakowaniu balenie "
        "balení obal упаковка упаковки упаковке упаковкой коробки коробка брутто verpakking bruto lordo brut "
        "opakowaniem opakowania упаковці упаковки ambalaj ambalaj ambalajlı emballasje förpackning förpackningens "
        "collo colli kargo kargolu gönderi paketli koli kutu przesyłki wysyłki zásilky balíku balenia "
        "csomagolás csomagolással doboz упаковкою посылки отправления obalem obalu hrubá hrubý pakke pakken "
        "pakkens pakning pakningen pakkaus pakkauksen pakkauksineen emballagen emballasjen"
    ).split()
}
NEGATIONS = {
    fold(w) for w in "without ohne sans sin senza sem без bez zonder excl exkl excluding not".split()
}
#: Words that say a value includes what follows: in a label's brackets they keep it the whole product's
#: ("Height (with stand)", "Weight (incl. battery)"); after a value, with a package word, they make it the
#: package's (``scrapers.value_forms.packed_value``).
INCLUDING = {fold(w) for w in "with incl inkl including included inc mit con com avec plus med".split()}
QUALIFIERS = {
    fold(w)
    for w in (
        "item product article artikel produkt produit producto produto prodotto articolo artigo overall physical "
        "total totale gesamt body unit assembled device net netto nett neto нетто устройства товара "
        "изделия прибора the of a de del della di du des la le el do da dos das der die den w in en em na "
        "s с v на inkl incl including included with mit con com avec z approx approximately ca circa "
        "approximate dell dello dei degli van het een des "
        "ungefähr aprox environ общий общая общие nominal real actual main articulo artículo artikels produkts "
        "shade os as pés feet legs produs füße todo conjunto jednostkowym jednostkowe produktu produkcie výrobku vyrobku geräts gerätes изделия товару aproximado aproximada liquido líquido "
        "netto нето ürün urun produsului tuotteen в во предмета предмет изделие товар ürünün "
        "one "  # "One size: 2 x 2 x 2 in": the only size there is
        "about around roughly nearly almost etwa rund aproximadamente circa ongeveer omkring cirka noin "  # "measures about: 7 cm"
        "all alle tous toutes todas todos tutte tutti wszystkie "  # a unit note: "All measurements in cm"
        "i på "  # Nordic prepositions: "Lengde i fot"
        "čistá čistý tuotteen tuote "  # cs net ("Čistá hmotnost"), fi the product's
        "starting at from per piece each pro stück je unit pièce unidad adet ca cca około okolo približne přibližně asi около примерно yaklaşık yaklasik ungefaehr env "
        "chest bust poitrine pecho petto case gehäuse gehause boîtier boitier caja cassa fabric stoff tissu tela "
        "rim brim waist "  # a vessel's own outline: "rim diameter 9 cm" (a mug), "Waist width 65mm" (a cup)
        " l b h w d t x х"
    ).split()
}
OVERALL = {"overall", "assembled", "gesamt", "total", "outer", "exterior", "aussen", "außen"}
# Compounds of German, Dutch and the Scandinavian languages: <prefix><kind word>, e.g. Artikelgewicht,
# Verpackungsgewicht, Produktabmessungen, productafmetingen, förpackningsmått. Only known prefixes count,
# so Schlauchlänge (hose length) or Sitzhöhe (seat height) are not the product's measurements.
_PRODUCT_PREFIXES = (
    "artikel artikels produkt produkts product netto nett gesamt totaal total korpus aussen außen geräte gerät "
    "eigen leer kokonais tuote"
)
_PACKAGE_PREFIXES = (
    "verpackungs verpackung versand paket pakket brutto karton verpakkings verpakking verzend förpacknings "
    "forpaknings emballage frakt bruto pakke pakkaus"
)
COMPOUND_PREFIXES: dict[str, bool] = {
    **{fold(w): False for w in _PRODUCT_PREFIXES.split()},
    **{fold(w): True for w in _PACKAGE_PREFIXES.split()},
}
COMPOUND_SUFFIXES = sorted(
    (
        fold(w)
        for w in "gewicht abmessungen abmessung maße masse höhe breite länge tiefe durchmesser stärke dicke größe "
        "afmetingen afmeting hoogte breedte diepte lengte vikt mått höjd bredd djup längd vægt mål højde bredde "
        "dybde længde vekt paino mitat pituus leveys korkeus syvyys".split()
    ),
    key=len,
    reverse=True,
)
assert all(suffix in KIND_WORDS for suffix in COMPOUND_SUFFIXES)
# Labels of languages written without spaces, matched whole (after removing spaces and punctuation).
CJK_LABELS: dict[str, tuple[str, bool]] = {
    "尺寸": ("dimensions", False),
    "商品尺寸": ("dimensions", False),
    "產品尺寸": ("dimensions", False),
    "产品尺寸": ("dimensions", False),
    "商品大小": ("dimensions", False),
    "規格尺寸": ("dimensions", False),
    "外觀尺寸": ("dimensions", False),
    "外观尺寸": ("dimensions", False),
    "本體尺寸": ("dimensions", False),
    "包裝尺寸": ("dimensions", True),
    "包装尺寸": ("dimensions", True),
    "外箱尺寸": ("dimensions", True),
    "重量": ("weight", False),
    "淨重": ("weight", False),
    "净重": ("weight", False),
    "商品重量": ("weight", False),
    "產品重量": ("weight", False),
    "产品重量": ("weight", False),
    "本體重量": ("weight", False),
    "毛重": ("weight", True),
    "包裝重量": ("weight", True),
    "包装重量": ("weight", True),
    "長": ("length", False),
    "长": ("length", False),
    "長度": ("length", False),
    "长度": ("length", False),
    "寬": ("width", False),
    "宽": ("width", False),
    "寬度": ("width", False),
    "宽度": ("width", False),
    "高": ("height", False),
    "高度": ("height", False),
    "深": ("depth", False),
    "深度": ("depth", False),
    "直徑": ("diameter", False),
    "直径": ("diameter", False),
    "厚度": ("thickness", False),
    "サイズ": ("dimensions", False),
    "寸法": ("dimensions", False),
    "本体サイズ": ("dimensions", False),
    "外形寸法": ("dimensions", False),
    "梱包サイズ": ("dimensions", True),
    "重さ": ("weight", False),
    "本体重量": ("weight", False),
    "크기": ("dimensions", False),
    "무게": ("weight", False),
    "중량": ("weight", False),
    "商品の重量": ("weight", False),
    "商品サイズ": ("dimensions", False),
    "製品サイズ": ("dimensions", False),
    "商品の寸法": ("dimensions", False),
    "梱包重量": ("weight", True),
    "発送重量": ("weight", True),
    "質量": ("weight", False),
    "商品毛重": ("weight", True),
    "商品淨重": ("weight", False),
    "商品净重": ("weight", False),
    "사이즈": ("dimensions", False),
    "제품크기": ("dimensions", False),
    "正味重量": ("weight", False),  # net
    "総重量": ("weight", False),  # total, like "Gesamtgewicht"
    "순중량": ("weight", False),
    "총중량": ("weight", False),
}
# Folded like the labels they are compared with (NFKD splits the dakuten off katakana: サイズ -> サイス).
CJK_LABELS = {re.sub(r"[\W_]+", "", fold(k)): v for k, v in CJK_LABELS.items()}

# Labels written without spaces (zh, ja, ko) are read token by token, longest first, with the same
# whitelist rule as the word labels: every part must be a measurement, package or qualifier token
# (商品の寸法 幅×奥行×高さ, 商品パッケージの寸法, 本体質量, 产品尺寸 长*宽*高).
_CJK_KIND_TOKENS = {
    "dimensions": "寸法 サイズ 尺寸 外形寸法 外寸 크기 사이즈 치수 규격",
    "weight": "重量 重さ 質量 质量 净重 淨重 무게 중량",
    "length": "長さ 长度 長度 長 长 길이 着丈 丈 全長 縦 たて 세로",
    "width": "幅 宽度 寬度 宽 寬 横幅 너비 폭 全幅 横 よこ 가로",
    "height": "高さ 高度 高 높이 全高",
    "depth": "奥行き 奥行 深さ 深度 深 깊이",
    "diameter": "直径 直徑 지름 직경 外径",
    "thickness": "厚さ 厚度 厚 두께 厚み",
}
_CJK_PACKAGE_TOKENS = "梱包 包装 包裝 パッケージ 外箱 発送 配送 出荷 毛重 포장 박스"
_CJK_QUALIFIER_TOKENS = (
    "商品 本体 本體 製品 产品 產品 の 的 外形 外観 外觀 規格 规格 约 約 总 總 整体 整體 实际 實際 单品 單品 "
    "제품 상품 약 全体 完成 正味"
)


def _cjk_token_table() -> dict[str, tuple[str, str | None]]:
    table: dict[str, tuple[str, str | None]] = {}
    for kind, tokens in _CJK_KIND_TOKENS.items():
        for t in tokens.split():
            table[fold(t)] = ("kind", kind)
    for t in _CJK_PACKAGE_TOKENS.split():
        table[fold(t)] = ("package", "weight" if t == "毛重" else None)
    for t in _CJK_QUALIFIER_TOKENS.split():
        table[fold(t)] = ("qualifier", None)
    return table


CJK_TOKENS = _cjk_token_table()
CJK_TOKEN_LENGTHS = sorted({len(t) for t in CJK_TOKENS}, reverse=True)

CAPACITY_WORDS = {
    fold(w)
    for w in (
        "capacity capacities load max maximum min minimum supported supports rated rating volume "
        "fassungsvermögen fassungsvermoegen kapazität kapazitaet füllmenge belastbarkeit tragkraft traglast "
        "nutzinhalt contenance capacité charge capacidad carga capacità portata capacidade suportado "
        "pojemność udźwig объем объём вместимость нагрузка грузоподъемность hacim kapasite taşıma inhoud "
        "draagvermogen"
    ).split()
}
CJK_CAPACITY = ("容量", "耐荷重", "最大", "容积", "承重", "용량")


#: Package words that name shipping rather than the product in its box (gross weight, the parcel sent):
#: whole words, and stems found inside compounds and CJK labels (``Versandgewicht``, ``発送重量``, ``毛重``).
SHIPPING_WORDS = {
    fold(w)
    for w in "shipping shipment ship gross brutto bruto lordo brut kargo kargolu gönderi parcel envío envio "
    "spedizione expédition expedition versand frakt przesyłki wysyłki zásilky доставки посылки отправления hrubá hrubý".split()
}
SHIPPING_STEMS = tuple(fold(w) for w in "versand verzend frakt brutto bruto 発送 配送 出荷 毛重 shipping".split())
#: Whole labels of one short word that is a qualifier elsewhere: Turkish ``En`` (width), ``Eni``.
SHORT_LABELS = {"en": "width", "eni": "width"}
#: Words naming the product's own main body: an unknown word beside them names the object whose body it is
#: (``Body of lamp width``, ``Lamp body width``, ``Depth of fitting from wall``).
BODY_WORDS = {
    fold(w)
    for w in "body fitting corps cuerpo corpo korpus gövde gövdesi gehäuse gehause kompletter".split()
}
#: Words naming a part of a product: a label with one names that part's extent or weight (``Cable length``,
#: ``Lid diameter``, ``Stand height``, ``Wall bracket width``), never the product's.
PART_WORDS = {
    fold(w)
    for w in (
        "cable cord hose lid cap handle stand base bracket bracked bulb blade strap chain battery seat "
        "leg arm armrest screen display drawer shelf door opening inner interior pipe tube wire plug "
        "cushion mattress pillow heel sole shaft spout nozzle filter bowl cup glass jar tray basket wheel "
        "pendant lens ständer standfuß standfuss fuss pied pieds piedistallo "
        "kabel schlauch deckel griff fuß sockel akku câble couvercle poignée pied cable tapa asa pie "
        "cavo coperchio manico piede kablo kapak sap ayak kordon"
    ).split()
}
