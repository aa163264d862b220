"""Unit words, by the pint unit they name and the language that writes them (data only).

Language ``""`` holds what every language writes: symbols, abbreviations, inch and foot marks and the
UN/CEFACT codes schema.org uses (CMT MMT MTR INH FOT GRM KGM LBR ONZ). Other keys are ISO 639-1 codes.
The description parser reads ``""`` and ``"en"`` (descriptions are English: ``once``, ``pies`` and
``libra`` are English words there); the extractor reads every language. Words are lower case with their
accents; a lookup also finds them written without accents. A word names one unit only (a test checks).
"""

from __future__ import annotations

#: pint unit name -> the kind of quantity it measures. Volume is contents (the parser turns it into grams;
#: the extractor never reads a volume as a size or a mass).
KINDS: dict[str, str] = {
    "millimeter": "length", "centimeter": "length", "meter": "length", "inch": "length", "foot": "length",
    "milligram": "mass", "gram": "mass", "kilogram": "mass", "pound": "mass", "ounce": "mass",
    "milliliter": "volume", "centiliter": "volume", "deciliter": "volume", "liter": "volume",
    "fluid_ounce": "volume", "gallon": "volume", "cup": "volume",
}  # fmt: skip

#: The pint units of the imperial system; the others are metric. One quantity is never written in both
#: ("1 kg 2 lb" is two quantities).
IMPERIAL: frozenset[str] = frozenset(
    {"inch", "foot", "pound", "ounce", "fluid_ounce", "gallon", "cup", "yard", "mile", "stone"}
)

#: pint unit name -> language -> the words (space-separated; ``_`` stands for a space inside a word).
ALIASES: dict[str, dict[str, str]] = {
    "millimeter": {
        "": "mm mmt mms",
        "en": "millimeter millimeters millimetre millimetres",
        "fr": "millimètre millimètres", "es": "milímetro milímetros",
        "it": "millimetri millimetro", "pl": "milimetr milimetrów", "cs": "milimetrů", "tr": "milimetre",
        "ru": "мм", "zh": "毫米 公釐", "ja": "ミリ ミリメートル", "ar": "مم ملم", "he": 'מ"מ',
    },
    "centimeter": {
        "": "cm cmt cms",
        "en": "centimeter centimeters centimetre centimetres centimter centimters centimeteres",
        "de": "zentimeter", "fr": "centimètre centimètres", "es": "centímetro centímetros",
        "it": "centimetri centimetro", "pl": "centymetr centymetrów", "cs": "centimetrů",
        "tr": "santim santimetre", "ru": "см сантиметр сантиметров", "zh": "公分 厘米 釐米",
        "ja": "センチ センチメートル", "ar": "سم سنتيمتر", "he": 'ס"מ',
    },
    "meter": {
        "": "m mtr",
        "en": "meter meters metre metres",
        "fr": "mètre mètres", "es": "metro metros", "it": "metri", "ru": "м метр метра метров",
        "zh": "米 公尺", "ja": "メートル",
    },
    "inch": {
        "": "in inh \" '' ″ ”",
        "en": "inch inches",
        "de": "zoll", "es": "pulgada pulgadas", "fr": "pouce pouces", "it": "pollice pollici",
        "pt": "polegada polegadas", "ru": "дюйм дюйма дюймов", "zh": "吋 英寸",
    },
    "foot": {
        "": "ft fot ' ′ ’",
        "en": "foot feet",
        "de": "fuß", "es": "pies", "fr": "pieds", "it": "piedi", "pt": "pés",
    },
    "milligram": {
        "": "mg mgm",
        "en": "milligram milligrams", "de": "milligramm", "ru": "мг",
    },
    "gram": {
        "": "g grm gr gm gms",
        "en": "gram grams gramme grammes",
        "de": "gramm", "fr": "gramme grammes", "es": "gramo gramos", "it": "grammo grammi",
        "pt": "grama gramas", "pl": "gramów gramy gramu", "cs": "gramů", "ru": "г гр грамм грамма граммов",
        "zh": "克 公克", "ja": "グラム", "ar": "جم غ غرام جرام", "he": "גרם",
    },
    "kilogram": {
        "": "kg kgm kgs",
        "en": "kilo kilos kilogram kilograms kilogramme kilogrammes",
        "de": "kilogramm", "fr": "kilogramme kilogrammes", "es": "kilogramo kilogramos",
        "it": "chilogrammo chilogrammi", "pt": "quilograma quilogramas quilo quilos",
        "pl": "kilogramów kilogramy", "cs": "kilogramů", "ru": "килограмм килограмма килограммов кило кг кгр",
        "zh": "公斤 千克", "ja": "キログラム キロ", "ar": "كجم كغ كيلو كيلوغرام", "he": 'קילו ק"ג',
    },
    "pound": {
        "": "lb lbs lbr",
        "en": "pound pounds",
        "de": "pfund", "es": "libra libras", "fr": "livre livres", "ru": "фунт",
    },
    "ounce": {
        "": "oz onz ozs",
        "en": "ounce ounces",
        "de": "unze unzen", "es": "onza onzas", "fr": "once onces", "it": "oncia oncie",
    },
    "milliliter": {
        "": "ml mls cc",
        "en": "milliliter milliliters millilitre millilitres", "ru": "мл", "zh": "毫升",
    },
    "centiliter": {"": "cl"},
    "deciliter": {"": "dl"},
    "liter": {
        "": "l ltr",
        "en": "liter liters litre litres", "es": "litro litros", "it": "litri", "ru": "литр л",
        "zh": "公升 升",
    },
    "fluid_ounce": {"en": "fl_oz fluid_ounce fluid_ounces"},
    "gallon": {"en": "gallon gallons"},
    "cup": {"en": "cup cups"},
}

#: The languages the description parser reads units in.
PARSER_LANGUAGES: frozenset[str] = frozenset({"", "en"})

#: Units a description is written in that no storefront page states a household object's size or mass in
#: (pint unit name -> kind, then language -> words as in :data:`ALIASES`). Only the description parser reads
#: them (:func:`kb.measures.units.description_units`), so that "a 40 tonne mug" or "a 3 km long pencil" is
#: refused as absurd instead of read as if no size were given; the extractor does not (a page's "range
#: 10 km" or "load 2 t" is no size of the product). Factors by pint, as the others'.
DESCRIPTION_KINDS: dict[str, str] = {
    "micrometer": "length", "kilometer": "length", "yard": "length", "mile": "length",
    "tonne": "mass", "stone": "mass",
}  # fmt: skip
DESCRIPTION_ALIASES: dict[str, dict[str, str]] = {
    "micrometer": {"": "µm μm", "en": "micrometer micrometers micrometre micrometres micron microns"},
    "kilometer": {"": "km kms", "en": "kilometer kilometers kilometre kilometres"},
    "yard": {"": "yd yds", "en": "yard yards"},
    "mile": {"": "mi", "en": "mile miles"},
    "tonne": {"": "t", "en": "tonne tonnes ton tons metric_ton metric_tons"},
    "stone": {"en": "stone stones"},
}
#: Unit words of other languages that are English words too: a description (English) keeps them as words
#: ("once", "pies"; "libra", "metro"); every other language's unit word is read in a description as well
#: ("300 Gramm", "12 Zentimeter", "2 kilogramos").
ENGLISH_HOMOGRAPHS: frozenset[str] = frozenset({"once", "onces", "pies", "libra", "libras", "metro", "metros"})
