"""The multilingual label vocabulary of spec tables: which label names which measurement.

:func:`classify_label` reads a label as stores write it (``Item Dimensions LxWxH``, ``Artikelgewicht``,
``Masse der Verpackung (LxBxH)``, ``Hmotnosť [kg]``, ``Вес без упаковки (нетто), кг``, ``重量``) and
returns what it measures, whether it is about the package, and a unit the label states.

The rule is a whitelist, for precision: after removing a unit in brackets or after a comma and an
order hint (``L x W x H``, ``ВхШхГ``), every word of the label must be a measurement word, a package
word, a negation, or a harmless qualifier (``item``, ``product``, ``overall``, ``net``, ``de``, ...).
So ``Schlauchlänge`` (hose length), ``Peso suportado`` (supported load), ``Max Height``, ``Chain Length``
and ``Durchmesser Stiftspitze`` (tip diameter) are not the product's measurements. A package word
(``Verpackung``, ``embalagem``, ``shipping``, ``упаковка``, ``包裝``...) marks a package value unless a
negation (``without``, ``ohne``, ``sin``, ``без``...) precedes it: ``Вес без упаковки`` is the product.

Languages: en, de, fr, es, it, pt, nl, pl, cs, sk, ru/uk/kk, bg, sl/hr/sr, ro, hu, el, tr, lv, lt, et, fi,
sv/da/no, id, he, ar, zh (traditional and simplified), ja, ko.
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass
from functools import lru_cache

from scrapers.quantities import clean_text, length_unit, mass_unit, unit_hint

__all__ = ["AXES", "KINDS", "LabelInfo", "classify_label"]

#: Single-axis kinds (one length each); "dimensions" is a combined A x B x C value, "size" too but never
#: a mass (``Size: 10 Ounce (Pack of 1)`` is a net content), "weight" is a mass.
AXES: tuple[str, ...] = ("length", "width", "height", "depth", "diameter", "thickness")
KINDS: tuple[str, ...] = (*AXES, "dimensions", "size", "weight")


def _fold(text: str) -> str:
    decomposed = unicodedata.normalize("NFKD", text.lower())
    return "".join(ch for ch in decomposed if not unicodedata.combining(ch))


def _words(kind: str, text: str) -> dict[str, str]:
    return {_fold(w): kind for w in text.split()}


_KIND_WORDS: dict[str, str] = {
    **_words(
        "length",
        "length len long länge laenge longueur longitud largo lunghezza comprimento długość dlugosc dĺžka "
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
        "çap çapı",
    ),
    **_words(
        "thickness",
        "thickness thick dicke stärke épaisseur grosor espesor spessore espessura grubość hrúbka tloušťka "
        "толщина товщина dikte kalınlık kalınlığı",
    ),
    **_words(
        "dimensions",
        "dimensions dimension dims measurements measures abmessungen abmessung maße masse maasse außenmaße "
        "dimensiones medidas dimensioni misure dimensões wymiary rozmery rozměry размеры габариты габарит "
        "afmetingen afmeting mått mål габаритные габаритный габарити розміри boyutlar boyutları boyut dimensiuni mitat méretek "
        "méret διαστάσεις dimensi ukuran izmēri izmeri matmenys mõõtmed dimenzije размери מידות الأبعاد الابعاد أبعاد ابعاد المقاسات "
        "ölçü ölçüler ölçüleri ölçüsü ebat ebatlar ebatları ebadı",
    ),
    **_words("size", "size sizes größe groesse grosse taille tamaño tamanho taglia formato размер velikost"),
    **_words(
        "weight",
        "weight weighs wt mass gewicht poids peso waga masa hmotnosť hmotnost váha вес масса вага vikt vægt vekt "
        "ağırlık ağırlığı greutate paino súly tömeg βάρος berat svars svoris kaal teža težina тегло משקל الوزن وزن",
    ),
}
_PACKAGE_WORDS = {
    _fold(w)
    for w in (
        "package packages packaging packed shipping shipment box carton parcel gross verpackung verpackt "
        "versand paket karton brutto emballage emballé colis embalaje embalado paquete envío caja imballo "
        "imballaggio confezione spedizione pacco embalagem pacote caixa opakowanie opakowaniu balenie "
        "balení obal упаковка упаковки упаковке упаковкой коробки коробка брутто verpakking bruto lordo brut "
        "opakowaniem opakowania упаковці упаковки ambalaj ambalaj ambalajlı emballasje förpackning förpackningens "
        "collo colli kargo kargolu gönderi paketli koli kutu przesyłki wysyłki zásilky balíku balenia "
        "csomagolás csomagolással doboz упаковкою посылки отправления"
    ).split()
}
_NEGATIONS = {
    _fold(w) for w in "without ohne sans sin senza sem без bez zonder excl exkl excluding not".split()
}
_QUALIFIERS = {
    _fold(w)
    for w in (
        "item product article artikel produkt produit producto produto prodotto articolo artigo overall physical "
        "total totale gesamt body unit assembled device net netto nett neto нетто устройства товара "
        "изделия прибора the of a de del della di du des la le el do da dos das der die den w in en em na "
        "s с v на inkl incl including included with mit con com avec z approx approximately ca circa "
        "approximate dell dello dei degli van het een des "
        "ungefähr aprox environ общий общая общие nominal real actual main articulo artículo artikels produkts "
        "shade os as pés feet legs produs füße todo conjunto jednostkowym jednostkowe produktu produkcie výrobku vyrobku geräts gerätes изделия товару aproximado aproximada liquido líquido "
        "netto нето ürün urun produsului tuotteen в во предмета предмет изделие товар ürünün "
        "ca cca około okolo približne přibližně asi около примерно yaklaşık yaklasik ungefaehr env "
        "chest bust poitrine pecho petto "
        " l b h w d t x х"
    ).split()
}
_OVERALL = {"overall", "assembled", "gesamt", "total", "outer", "exterior", "aussen", "außen"}
# Compounds of German, Dutch and the Scandinavian languages: <prefix><kind word>, e.g. Artikelgewicht,
# Verpackungsgewicht, Produktabmessungen, productafmetingen, förpackningsmått. Only known prefixes count,
# so Schlauchlänge (hose length) or Sitzhöhe (seat height) are not the product's measurements.
_PRODUCT_PREFIXES = (
    "artikel artikels produkt produkts product netto nett gesamt totaal total korpus aussen außen geräte gerät "
    "eigen leer"
)
_PACKAGE_PREFIXES = (
    "verpackungs verpackung versand paket pakket brutto karton verpakkings verpakking verzend förpacknings "
    "forpaknings emballage frakt"
)
_COMPOUND_PREFIXES: dict[str, bool] = {
    **{_fold(w): False for w in _PRODUCT_PREFIXES.split()},
    **{_fold(w): True for w in _PACKAGE_PREFIXES.split()},
}
_COMPOUND_SUFFIXES = sorted(
    (
        _fold(w)
        for w in "gewicht abmessungen abmessung maße masse höhe breite länge tiefe durchmesser stärke dicke größe "
        "afmetingen afmeting hoogte breedte diepte lengte vikt mått höjd bredd djup längd vægt mål højde bredde "
        "dybde længde vekt".split()
    ),
    key=len,
    reverse=True,
)
assert all(suffix in _KIND_WORDS for suffix in _COMPOUND_SUFFIXES)
# Labels of languages written without spaces, matched whole (after removing spaces and punctuation).
_CJK_LABELS: dict[str, tuple[str, bool]] = {
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
}
# Folded like the labels they are compared with (NFKD splits the dakuten off katakana: サイズ -> サイス).
_CJK_LABELS = {re.sub(r"[\W_]+", "", _fold(k)): v for k, v in _CJK_LABELS.items()}
# Wayfair's "Overall Height - Top to Bottom", "Overall Depth - Front to Back": the direction is not a word
# of the label, but only an overall value is the product's ("Body Height - Top to Bottom" is a lamp shade's).
_DIRECTION = re.compile(
    r"^((?:overall|assembled|product|item)\b.*?)\s*[-–—]\s*(?:top|side|front|left|back|end)\s+to\s+"
    r"(?:bottom|side|back|right|front|end)\s*$",
    re.IGNORECASE,
)
_ORDER_HINT = re.compile(r"\b[a-zа-я](?:\s*[x×хX*/]\s*[a-zа-я]\b){1,2}", re.IGNORECASE)
_ORDER_WORD = re.compile(r"[a-zа-я](?:[xх][a-zа-я]){1,2}")
_BRACKETS = re.compile(r"[\[(（][^\])）]{0,30}[\])）]")
_MAX_WORDS = 8


@dataclass(frozen=True)
class LabelInfo:
    """What a label measures: ``kind`` (one of :data:`KINDS`), ``package`` (a package or shipping value),
    ``unit`` (a unit the label states, e.g. ``mm`` from ``Výška [mm]``, else None)."""

    kind: str
    package: bool = False
    unit: str | None = None
    #: For a dimensions label, the axes it names in order (``Dimensions (H x W x D)`` -> height, width,
    #: depth; ``Largo x Ancho x Alto``); () when it names none or is ambiguous (``L x L x H``).
    order: tuple[str, ...] = ()


#: Axis letters of order hints (en, de: B = Breite, T = Tiefe; ru: В высота, Ш ширина, Г глубина, Д длина).
_ORDER_LETTERS = {
    "l": "length", "w": "width", "b": "width", "h": "height", "d": "depth", "t": "depth",
    "в": "height", "ш": "width", "г": "depth", "д": "length",
}  # fmt: skip


def _order_of(text: str, kinds: list[str]) -> tuple[str, ...]:
    """The axes a dimensions label names in order (see :attr:`LabelInfo.order`)."""
    m = _ORDER_HINT.search(text) or _ORDER_WORD.search(text.lower())
    if m:
        letters = re.sub(r"\s+", "", m.group(0))[::2]  # "H x W x D", "ВхШхГ", "B/H/T": every other char
        roles = tuple(_ORDER_LETTERS.get(ch.lower(), "") for ch in letters)
    else:
        roles = tuple(k for k in kinds if k in AXES)
    if len(roles) < 2 or "" in roles or len(set(roles)) < len(roles):
        return ()
    return roles


def classify_label(label: object) -> LabelInfo | None:
    """The measurement ``label`` names, or None when it names none (or something else, like a load)."""
    if isinstance(label, str):
        return _classify_cached(label) if len(label) <= 200 else None
    try:
        return _classify(label)
    except Exception:  # noqa: BLE001
        return None


@lru_cache(maxsize=16384)
def _classify_cached(label: str) -> LabelInfo | None:
    try:
        return _classify(label)
    except Exception:  # noqa: BLE001 - a label we cannot read is simply not a measurement label
        return None


def _classify(label: object) -> LabelInfo | None:
    text = clean_text(label)
    if not text or len(text) > 80 or text[0].isdigit():
        return None  # a label does not start with a number ("1 kg" is a value)
    unit = unit_hint(text)
    original = text
    text = text.rstrip(" :：-–—=").strip()
    text = _DIRECTION.sub(r"\1", _BRACKETS.sub(" ", text).strip()).strip()
    text = _ORDER_HINT.sub(" ", text)
    folded = _fold(text)
    squashed = re.sub(r"[\W_]+", "", folded)
    if squashed in _CJK_LABELS:
        kind, package = _CJK_LABELS[squashed]
        return LabelInfo(kind, package, unit)
    if any(_is_cjk(ch) for ch in squashed):
        return _classify_cjk(squashed, unit)
    words = [w for w in re.split(r"[\W_]+", folded) if w]
    if not words or len(words) > _MAX_WORDS:
        return None
    kinds: list[str] = []
    package = False
    negated = False
    for word in words:
        if word in _KIND_WORDS:
            kinds.append(_KIND_WORDS[word])
        elif word in _PACKAGE_WORDS:
            package = package or not negated
        elif word in _NEGATIONS:
            negated = True
        elif word in _QUALIFIERS or length_unit(word) is not None or mass_unit(word) is not None:
            continue
        elif _ORDER_WORD.fullmatch(word):
            continue  # "LxWxH", "ВхШхГ" written as one word
        else:
            compound = _split_compound(word)
            if compound is None:
                return None
            kind, is_package = compound
            kinds.append(kind)
            package = package or (is_package and not negated)
    if not kinds:
        if set(words) <= _OVERALL:
            return LabelInfo("size", package, unit)  # Wayfair's "Overall: 15.5'' H x 12'' W x 12'' D"
        return None
    # "Item Package Dimensions", "Product size": the most specific kind wins; weight beats dimensions
    # only when no axis or dimension word is present.
    if len({k for k in kinds if k in AXES}) >= 2:
        # "Width x Height x Depth", "Largo x Ancho x Alto"
        return LabelInfo("dimensions", package, unit, _order_of(original, kinds))
    for kind in (*AXES, "dimensions", "size", "weight"):
        if kind in kinds:
            if kind in ("dimensions", "size") and "weight" in kinds:
                return LabelInfo("dimensions", package, unit)  # "Weight & Dimensions"
            order = _order_of(original, kinds) if kind in ("dimensions", "size") else ()
            return LabelInfo(kind, package, unit, order)
    return None


# Labels written without spaces (zh, ja, ko) are read token by token, longest first, with the same
# whitelist rule as the word labels: every part must be a measurement, package or qualifier token
# (商品の寸法 幅×奥行×高さ, 商品パッケージの寸法, 本体質量, 产品尺寸 长*宽*高).
_CJK_KIND_TOKENS = {
    "dimensions": "寸法 サイズ 尺寸 外形寸法 外寸 크기 사이즈 치수",
    "weight": "重量 重さ 質量 质量 净重 淨重 무게 중량",
    "length": "長さ 长度 長度 長 长 길이",
    "width": "幅 宽度 寬度 宽 寬 横幅 너비 폭",
    "height": "高さ 高度 高 높이",
    "depth": "奥行き 奥行 深さ 深度 深 깊이",
    "diameter": "直径 直徑 지름",
    "thickness": "厚さ 厚度 厚 두께",
}
_CJK_PACKAGE_TOKENS = "梱包 包装 包裝 パッケージ 外箱 発送 配送 出荷 毛重 포장 박스"
_CJK_QUALIFIER_TOKENS = (
    "商品 本体 本體 製品 产品 產品 の 的 外形 外観 外觀 規格 规格 约 約 总 總 整体 整體 实际 實際 单品 單品 "
    "제품 상품 약 全体 完成"
)


def _cjk_token_table() -> dict[str, tuple[str, str | None]]:
    table: dict[str, tuple[str, str | None]] = {}
    for kind, tokens in _CJK_KIND_TOKENS.items():
        for t in tokens.split():
            table[_fold(t)] = ("kind", kind)
    for t in _CJK_PACKAGE_TOKENS.split():
        table[_fold(t)] = ("package", "weight" if t == "毛重" else None)
    for t in _CJK_QUALIFIER_TOKENS.split():
        table[_fold(t)] = ("qualifier", None)
    return table


_CJK_TOKENS = _cjk_token_table()
_CJK_TOKEN_LENGTHS = sorted({len(t) for t in _CJK_TOKENS}, reverse=True)


def _is_cjk(ch: str) -> bool:
    return (
        "\u3040" <= ch <= "\u30ff"
        or "\u4e00" <= ch <= "\u9fff"
        or "\uac00" <= ch <= "\ud7af"
        or "\u1100" <= ch <= "\u11ff"
    )


def _classify_cjk(squashed: str, unit: str | None) -> LabelInfo | None:
    kinds: list[str] = []
    package = False
    i = 0
    while i < len(squashed):
        for n in _CJK_TOKEN_LENGTHS:
            hit = _CJK_TOKENS.get(squashed[i : i + n])
            if hit is not None:
                break
        else:
            if squashed[i].isascii() and squashed[i].isalpha():  # "W×D×H" order letters
                i += 1
                continue
            return None
        role, value = hit
        if role == "kind":
            kinds.append(value)
        elif role == "package":
            package = True
            if value:
                kinds.append(value)
        i += n
    if not kinds:
        return None
    if len({k for k in kinds if k in AXES}) >= 2 or "dimensions" in kinds:
        return LabelInfo("dimensions", package, unit)
    return LabelInfo(kinds[0], package, unit)


def _split_compound(word: str) -> tuple[str, bool] | None:
    for suffix in _COMPOUND_SUFFIXES:
        if word.endswith(suffix) and len(word) > len(suffix):
            prefix = word[: -len(suffix)].rstrip("-")
            if prefix in _COMPOUND_PREFIXES:
                return _KIND_WORDS[suffix], _COMPOUND_PREFIXES[prefix]
    return None
