"""From page values to catalog features: units, order, limits, shape and material.

* Dimensions are cm, sorted largest first (``a >= b >= c``); mass is grams. Values outside
  ``kb.features`` limits (0 < dim <= MAX_DIM_CM, 0 < mass <= MAX_MASS_G) are refused with a reason.
* Shape rule (:func:`shape_from_dims`), when the page does not say. With ``a >= b >= c`` in cm:

  ========================  ========  ========================================================
  test (first match wins)   shape     examples from the paper's table
  ========================  ========  ========================================================
  name says ball/sphere...  radial    tennis ball 6.4 x 6.4 x 6.4 (dimensions cannot tell it
                                      from a cube)
  c <= 0.25 b               thin      calculator 15.4 x 7.9 x 1.5, cardboard box 15.5 x 9 x 1.8
  a >= 4 b                  long      TV remote 16 x 3.5 x 2
  a >= 1.8 b                prism     water bottle 21.5 x 7.2 x 7.2, wedge 6 x 3 x 1.5
  otherwise                 compact   rubik cube 3 x 3 x 3, wood disk 7.2 x 7.2 x 2
  ========================  ========  ========================================================

  With two dimensions only ``long`` (a >= 4 b) can be decided; with one, nothing.
* Material (:func:`material_from_text`): the first word of the stated material that names one of
  ``kb.features.MATERIALS`` (``Edelstahl`` -> metal, ``Plástico`` -> plastic, ``oak veneer`` -> wood);
  ``None`` when no word is known (an unknown material is not guessed).
"""

from __future__ import annotations

import re
import unicodedata

from kb.features import MATERIALS, MAX_DIM_CM, MAX_MASS_G, SHAPES

__all__ = [
    "THIN_RATIO",
    "LONG_RATIO",
    "PRISM_RATIO",
    "check_dims",
    "check_mass",
    "impossible_value",
    "material_from_text",
    "shape_from_dims",
    "shape_from_name",
    "sort_desc",
]

THIN_RATIO = 0.25
LONG_RATIO = 4.0
PRISM_RATIO = 1.8

_RADIAL_WORDS = re.compile(
    r"\b(?:ball|balls|sphere|spherical|globe|orb|kugel|ball|balle|boule|pelota|bola|palla|sfera|esfera|мяч|шар)\b",
    re.IGNORECASE,
)


def sort_desc(values) -> tuple[float, ...]:
    return tuple(sorted((float(v) for v in values), reverse=True))


def check_dims(values) -> str | None:
    """Why these dimensions (cm) cannot be the catalog's, or None when they can."""
    if not values or len(values) > 3:
        return f"{len(values or ())} dimensions (expected 1 to 3)"
    for v in values:
        if not (v > 0):
            return f"dimension {v:g} cm is not positive"
        if v > MAX_DIM_CM:
            return f"dimension {v:g} cm is absurd for a household object (over {MAX_DIM_CM:g} cm)"
    return None


def check_mass(value: float) -> str | None:
    """Why this mass (g) cannot be the catalog's, or None when it can."""
    if not (value > 0):
        return f"mass {value:g} g is not positive"
    if value > MAX_MASS_G:
        return f"mass {value:g} g is absurd for a household object (over {MAX_MASS_G:g} g)"
    return None


def impossible_value(reason: str) -> str | None:
    """The kind of a refusal of :func:`check_dims` or :func:`check_mass` (or the catalog's) that says the
    value cannot be: ``absurd_value`` ("... is absurd ...") or ``invalid_value`` ("... is not positive");
    None for another reason (a count of dimensions)."""
    if "absurd" in reason:
        return "absurd_value"
    return "invalid_value" if "not positive" in reason else None


def shape_from_name(name: str | None) -> str | None:
    """``radial`` when the name says ball/sphere/globe (in several languages), else None."""
    if name and _RADIAL_WORDS.search(name):
        return "radial"
    return None


def shape_from_dims(dims_cm) -> str | None:
    """The shape class the dimensions imply (see the module doc), or None when they cannot tell."""
    if not dims_cm:
        return None
    dims = sort_desc(dims_cm)
    if len(dims) == 3:
        a, b, c = dims
        if c <= THIN_RATIO * b:
            return "thin"
        if a >= LONG_RATIO * b:
            return "long"
        if a >= PRISM_RATIO * b:
            return "prism"
        return "compact"
    if len(dims) == 2 and dims[0] >= LONG_RATIO * dims[1]:
        return "long"
    return None


def _fold(text: str) -> str:
    return "".join(c for c in unicodedata.normalize("NFKD", text.lower()) if not unicodedata.combining(c))


def _is_cjk(ch: str) -> bool:
    return (
        "\u3040" <= ch <= "\u30ff"
        or "\u4e00" <= ch <= "\u9fff"
        or "\uac00" <= ch <= "\ud7af"
        or "\u1100" <= ch <= "\u11ff"
    )


_MATERIAL_WORDS: dict[str, str] = {}
for _material, _words in {
    "metal": "metal metallic metall metalen metalico metallo metalowy steel stainless iron aluminium aluminum "
    "brass copper chrome zinc titanium fonte aluminio alluminio stahl edelstahl eisen acier inox fer acero hierro acciaio ferro aco "
    "metalu stal металл сталь алюминий kov oceľ 不鏽鋼 不锈钢 金屬 金属 鋼 鋁 "
    "ocel nerez nerezová nerezova чугун чугунный нержавеющая стальной алюминиевый медь латунь bakır bakir "
    "çelik celik paslanmaz alüminyum aluminyum döküm pirinç ステンレス 鉄 アルミ 铝合金 铸铁 铜 "
    "aço inoxidável acero cobre rame ottone 알루미늄 스테인리스 스텐 주철 cromargan",
    "plastic": "plastic plastics plastik kunststoff plastique plastico plastica pvc abs polypropylene "
    "polyethylene polycarbonate acrylic polystyrene melamine tworzywo пластик пластмасса plast 塑膠 塑料 "
    "plastik polipropilen polypropylen полипропилен プラスチック ポリプロピレン 樹脂 树脂 tritan 플라스틱",
    "wood": "wood wooden oak pine beech birch walnut bamboo teak mdf particleboard plywood veneer holz eiche "
    "buche kiefer bois chene hetre cork kork liege corcho sughero cortica madera roble legno madeira eucalipto drewno дерево древесина drevo 木 木頭 竹 "
    "acacia acacie akazie mango ash maple cherry rattan seagrass seegras wicker ahşap ahsap dřevo drewniany "
    "деревянный бук дуб сосна bambus bambou bambú bambù 木製 木制 天然木 원목 나무",
    "glass": "glass glas verre vidrio vetro vidro szklo стекло sklo 玻璃 borosilicate borosilikat cam ガラス 유리",
    "paper": "paper cardboard paperboard papier pappe karton carton papel carta cartone papelao бумага картон 紙 纸 "
    "kağıt kagit 和紙",
    "fabric": "fabric cotton polyester linen wool textile nylon velvet felt stoff baumwolle leinen tissu coton "
    "tela algodon tessuto cotone tecido algodao tkanina ткань хлопок látka 布 棉 "
    "leather leder cuir cuero pelle couro kumaş pamuk jute hemp lin",
    "rubber": "rubber silicone latex gummi kautschuk caoutchouc goma caucho gomma borracha guma резина "
    "силикон 橡膠 橡胶 矽膠 硅胶",
    "other": "ceramic ceramics porcelain stoneware earthenware terracotta stone marble granite keramik porzellan ceramique porcelaine ceramica "
    "porcelana marmol керамика фарфор 陶瓷 "
    "marble marmor marbre mármore marmo slate concrete beton seramik porselen mermer keramika porcelán "
    "ceramika porcelana kamień kamen камень мрамор 陶器 磁器 陶磁器 石 大理石 陶 瓷",
}.items():
    for _w in _words.split():
        _MATERIAL_WORDS[_fold(_w)] = _material
assert set(_MATERIAL_WORDS.values()) <= set(MATERIALS)
assert {"thin", "long", "prism", "compact", "radial"} <= set(SHAPES)


# German and Dutch compounds end in their material: Buchenholz, Borosilikatglas, Hartplastik.
_COMPOUND_MATERIALS = ("holz", "hout", "stahl", "staal", "glas", "kunststoff", "plastik", "keramik", "leder")
_CJK_MATERIAL_WORDS = {w: m for w, m in _MATERIAL_WORDS.items() if any(_is_cjk(ch) for ch in w)}


def material_from_text(text: str | None) -> str | None:
    """The catalog material the first known word of ``text`` names (a compound like ``Buchenholz`` by
    its last part), or None."""
    if not text:
        return None
    folded = _fold(str(text))
    words = re.findall(r"[^\W\d_]+", folded)
    for word in words:
        if word in _MATERIAL_WORDS:
            return _MATERIAL_WORDS[word]
    for word in words:
        for suffix in _COMPOUND_MATERIALS:
            if word.endswith(suffix) and len(word) > len(suffix) + 2:
                return _MATERIAL_WORDS[suffix]
    if any(_is_cjk(ch) for ch in folded):  # CJK: no spaces between words; the earliest known word wins
        hits = [(folded.find(w), -len(w), m) for w, m in _CJK_MATERIAL_WORDS.items() if w in folded]
        if hits:
            return min(hits)[2]
    return None
