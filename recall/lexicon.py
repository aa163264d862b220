"""The parser's domain lexicon: every word it knows, the tag it gets, and the feature value it means.

This module is data only, written to be read (``recall/PARSER.md`` prints the same tables with the rules
that use them). The tagger of :mod:`recall.tags` is an NLTK ``UnigramTagger`` whose model is built from
these tables (:func:`tag_model`); a ``RegexpTagger`` tags what is not listed (digits, fractions, other
words). Category values are always canonical words of :mod:`kb.features` (checked by a test).

Tags (the parser's own small tagset, not Penn Treebank):

======= ==========================================================================
tag     meaning
======= ==========================================================================
CD      a number in digits: ``15``, ``7.5``, ``7,5`` (decimal comma), ``1,000``
NW      a number word: ``one`` ... ``ninety``, ``dozen``, ``couple``
NMAG    a magnitude word: ``hundred``, ``thousand``
FRC     a fraction: ``1/2``, ``½``, ``half``, ``quarter(s)``, ``third(s)``
A       ``a`` / ``an`` (part of "a dozen", "half a liter", "one and a half")
AND     ``and``
OF      ``of``
IN      ``in`` as a preposition ("in diameter"); after a number and not before a dimension noun it is
        retagged ULEN (inches)
ULEN    a length unit; UMASS a mass unit; UVOL a volume unit (contents)
DIM     a dimension adjective or phrase (long, wide, on each side); DIMN a dimension noun (length,
        diameter): roles in :data:`DIMENSION_WORDS`
HA/HL/HU/HX  hedges: about / at least / at most / exact (:data:`HEDGES`)
HS      a trailing hedge: "or so", "or thereabouts"
UAND    ``and`` joining a unit to a fraction: "an inch and a half" (set in context)
RTO     a range connector: ``to``, ``-``, ``or``; BETW ``between``/``from``
BY      a multiplication sign of "10 x 5 x 2 cm", "three by four"
BE      a linking word between a dimension noun and its value: is, are, measures, ``:``, ``=``
MAT/SHP/RIG/TEX/FRA  category words (material, shape, rigidity, texture, fragility)
MH      a mass hint word (light, heavy)
FILL    a container-contents word (filled, full, contains)
NEG     a negation (not, non, isn't, doesn't, never, without): of a category word or of a value
SEP     sentence punctuation; CM a comma or parenthesis
W       any other word
======= ==========================================================================
"""

from __future__ import annotations

from types import MappingProxyType

from kb.measures import words as _words
from kb.measures.numbers import VULGAR_FRACTIONS
from kb.measures.units import description_aliases_of
from recall import lexicon_categories as _categories

# --------------------------------------------------------------------------------------------- numbers
#: Number words (tag NW), magnitude words (tag NMAG) and fraction words (tag FRC): the number
#: grammar's (:mod:`kb.measures.words`).
NUMBER_WORDS, MAGNITUDE_WORDS, FRACTION_WORDS = _words.NUMBER_WORDS, _words.MAGNITUDE_WORDS, _words.FRACTION_WORDS
#: Fraction words that are also ordinals or nouns ("the top quarter", "the third"): numbers only after a
#: number, "a"/"an" or "and" ("three eighths", "an eighth", "two and a quarter").
ORDINAL_FRACTIONS: frozenset[str] = frozenset(FRACTION_WORDS) - {"half", "halves"}
#: Unicode vulgar fractions (tag FRC), alone ("½") or after digits ("7½").
UNICODE_FRACTIONS = VULGAR_FRACTIONS

# ----------------------------------------------------------------------------------------------- units
#: Unit words -> pint unit names: the description parser's words of the one unit table
#: (:func:`kb.measures.units.description_units`: every language's but the English homographs, and the
#: description-only units, "t", "km", "stone"); the factors are computed once with pint.
LENGTH_UNITS: dict[str, str] = description_aliases_of("length")
MASS_UNITS: dict[str, str] = description_aliases_of("mass")
VOLUME_UNITS: dict[str, str] = description_aliases_of("volume")
#: Unit words that are other words first (a container, a material): a unit only right after a number.
UNIT_NOUNS: dict[str, str] = {"cup": "UVOL", "stone": "UMASS", "stones": "UMASS"}
#: Density assumed for contents (g per ml): "filled with half a liter of water" weighs at least 500 g.
CONTENTS_DENSITY_G_PER_ML = 1.0

# ------------------------------------------------------------------------------------------ dimensions
#: Dimension words (tag DIM, nouns DIMN) -> role. Roles: ``length`` and ``height`` (usually the largest,
#: a), ``width`` (b),
#: ``depth`` (b, or c when alone with a width), ``thickness`` (usually the smallest, c), ``diameter``
#: (two equal dims), ``radius`` (doubled to a diameter), ``circumference`` (divided by pi to a diameter),
#: ``across`` (a diameter for a round thing, else
#: a width), ``side`` (a cube: all three equal), ``size`` (an unlabelled extent).
DIMENSION_WORDS: dict[str, str] = {
    "long": "length", "length": "length", "lengthwise": "length", "lengths": "length",
    "tall": "height", "height": "height", "high": "height", "heigth": "height",
    "wide": "width", "width": "width", "across": "across", "broad": "width", "breadth": "width",
    "thick": "thickness", "thickness": "thickness", "deep": "depth", "depth": "depth",
    "diameter": "diameter", "diam": "diameter", "dia": "diameter", "diametre": "diameter",
    "radius": "radius",
    "circumference": "circumference", "circ": "circumference", "girth": "circumference",
    "around": "circumference",  # only after a length ("30 cm around"): a hedge elsewhere (recall.tags)
    "side": "side", "sides": "side", "edge": "side", "edges": "side", "on each side": "side",
    "each side": "side", "per side": "side", "a side": "side", "on a side": "side", "each way": "side",
    "on all sides": "side", "all sides": "side", "in every direction": "side",
    "in size": "size", "big": "size", "large": "size",
    "front to back": "depth", "back to front": "depth", "side to side": "width", "top to bottom": "height",
    "end to end": "length", "tip to tip": "length",
    "overall": "overall", "in total": "overall", "including the handle": "overall",
    "with the handle": "overall", "including handle": "overall", "with handle": "overall",
    "handle included": "overall",
    "square": "square",
}  # fmt: skip
#: Dimension roles whose value is a straight extent (sorted into a >= b >= c with the others). ``overall``
#: ("12 cm including the handle", "13 inches overall") is the whole object's largest extent.
LINEAR_ROLES: tuple[str, ...] = ("length", "overall", "height", "width", "depth", "thickness")
#: Single letters that label the numbers of a tuple ("L 20 x W 10 x H 5 cm", "20L x 10W x 5H cm").
TUPLE_LABELS: dict[str, str] = {"l": "length", "w": "width", "h": "height", "d": "depth"}
#: Of those, the ones that need a number right before them to count (so "a large bottle" states no
#: dimension): they only form a DIM chunk as "<number> <unit> big".
WEAK_DIMENSION_WORDS: frozenset[str] = frozenset({"big", "large", "in size"})
#: Dimension words that count only right after a quantity with a length unit ("9 cm square": two equal
#: sides; "10 square" or "a square box" state nothing).
UNIT_ONLY_DIMENSION_WORDS: frozenset[str] = frozenset({"square"})
#: Dimension words that are nouns: "in" before one of them is a preposition ("7 in diameter" means a
#: value with its unit left out), before any other word after a number it is the unit inch ("4 in long").
DIMENSION_NOUNS: frozenset[str] = frozenset(
    {"length", "lengths", "height", "heigth", "width", "breadth", "thickness", "depth", "diameter", "diam",
     "dia", "diametre", "radius", "circumference", "circ", "girth", "side", "sides", "edge", "edges", "size", "in size"}
)  # fmt: skip

# ---------------------------------------------------------------------------------------------- hedges
#: Hedge words -> qualifier, by tag: HA about, HL at_least, HU at_most, HX exact. "nearly"/"almost" mean
#: "close to, a little under"; they are read as *about* so that a close value is not ruled out.
HEDGES: dict[str, str] = {
    "about": "about", "around": "about", "roughly": "about", "approximately": "about", "approx": "about",
    "approx.": "about", "ca": "about", "circa": "about", "nearly": "about", "almost": "about",
    "close to": "about", "some": "about", "maybe": "about", "perhaps": "about", "probably": "about",
    "~": "about", "≈": "about", "estimated": "about", "guess": "about", "like": "about",
    "more or less": "about", "give or take": "about", "somewhere around": "about",
    "more than": "at_least", "over": "at_least", "at least": "at_least", "a bit over": "at_least",
    "a bit more than": "at_least", "just over": "at_least", "a little over": "at_least",
    "a little more than": "at_least", "slightly more than": "at_least", "slightly over": "at_least",
    "above": "at_least", "greater than": "at_least", "no less than": "at_least", "not less than": "at_least",
    "upwards of": "at_least", "well over": "at_least", "in excess of": "at_least", "minimum": "at_least",
    "less than": "at_most", "under": "at_most", "at most": "at_most", "just under": "at_most",
    "a bit under": "at_most", "a bit less than": "at_most", "a little under": "at_most",
    "a little less than": "at_most", "slightly less than": "at_most", "slightly under": "at_most",
    "below": "at_most", "up to": "at_most", "no more than": "at_most", "not more than": "at_most",
    "maximum": "at_most", "well under": "at_most", "smaller than": "at_most", "shorter than": "at_most",
    "lighter than": "at_most", "longer than": "at_least", "bigger than": "at_least",
    "heavier than": "at_least", "wider than": "at_least", "thicker than": "at_least",
    "exactly": "exact", "precisely": "exact", "just": "exact", "measured": "exact",
}  # fmt: skip
#: Hedges that follow the quantity (tag HS).
TRAILING_HEDGES: dict[str, str] = {
    "or so": "about",
    "or thereabouts": "about",
    "ish": "about",
    "odd": "about",
}
HEDGE_TAGS: dict[str, str] = {"about": "HA", "at_least": "HL", "at_most": "HU", "exact": "HX"}

# ------------------------------------------------------------------------------------------ categories
#: The category tables (material, shape, rigidity, texture, fragility, mass hints, colours), re-exported
#: from :mod:`recall.lexicon_categories`.
MATERIAL_WORDS = _categories.MATERIAL_WORDS
SHAPE_WORDS = _categories.SHAPE_WORDS
CUBE_WORDS = _categories.CUBE_WORDS
SPHERE_WORDS = _categories.SPHERE_WORDS
BALL_SUFFIX = _categories.BALL_SUFFIX
BALL_COMPOUND_HEADS = _categories.BALL_COMPOUND_HEADS
FLAT_WORDS = _categories.FLAT_WORDS
CYLINDER_WORDS = _categories.CYLINDER_WORDS
DISC_WORDS = _categories.DISC_WORDS
VESSEL_WORDS = _categories.VESSEL_WORDS
ROUND_WORDS = _categories.ROUND_WORDS
CAN_PRECEDERS = _categories.CAN_PRECEDERS
RIGIDITY_WORDS = _categories.RIGIDITY_WORDS
TEXTURE_WORDS = _categories.TEXTURE_WORDS
FRAGILITY_WORDS = _categories.FRAGILITY_WORDS
NEGATED_FRAGILITY = _categories.NEGATED_FRAGILITY
MEDIUM_WORDS = _categories.MEDIUM_WORDS
MASS_HINT_WORDS = _categories.MASS_HINT_WORDS
COLOUR_WORDS = _categories.COLOUR_WORDS




#: Contents words (tag FILL): a volume after one of these in the same sentence counts as contents whose
#: mass (at :data:`CONTENTS_DENSITY_G_PER_ML`) is a lower bound on the object's mass.
FILL_WORDS: frozenset[str] = frozenset(
    {"filled", "full", "fill", "contains", "containing", "contain", "holding", "holds", "with"}
)
#: Of the FILL words, those that only count when the volume is followed by "of <something>"
#: ("with 500 ml of water"), since "a bottle with 750 ml capacity" or "holds 1 l" state a capacity.
WEAK_FILL_WORDS: frozenset[str] = frozenset({"with", "holding"})
#: Words that mark a volume as a capacity rather than contents.
CAPACITY_WORDS: frozenset[str] = frozenset({"capacity", "holds", "empty", "can hold", "could hold"})

NEGATIONS: frozenset[str] = frozenset(
    {"not", "non", "isn't", "isnt", "aren't", "wasn't", "weren't", "doesn't", "don't", "didn't", "never", "no",
     "without", "nor", "neither", "hardly"}
)  # fmt: skip
#: The negations that also negate a value right after them ("not 10 cm", "isn't over 500 g", "without the
#: 2 cm lid"); "hardly 10 cm" is barely 10 cm, a value still stated.
VALUE_NEGATIONS: frozenset[str] = NEGATIONS - {"hardly"}
#: Words that may stand between a value negation and its value ("does not weigh 300 g", "is not really
#: 10 cm"); tokens tagged BE ("is", "the", ":") may too. At most two of them.
NEGATION_GAP_WORDS: frozenset[str] = frozenset({"weigh", "weighs", "really", "actually"})
#: Negations that negate the noun right after them ("no handle", "without a lid", "neither a mug nor a
#: cup"); the others negate a noun phrase only through an article ("not *a* mug", "isn't *the* cup"; "not
#: heavy" negates the adjective): the noun-phrase scope of ``recall.subject.negated_words``.
NOUN_NEGATIONS: frozenset[str] = frozenset({"no", "without", "neither", "nor"})
#: Articles: after a value negation they start a negated noun phrase ("not a mug").
ARTICLES: frozenset[str] = frozenset({"a", "an", "the"})
#: A word between a negation and its value that turns the negation into a bound or a hedge: "not quite
#: 10 cm" is a little under 10 (about, like "nearly"), "not even 10 cm" is at most 10.
NEGATED_HEDGE_WORDS: dict[str, str] = {"quite": "about", "even": "at_most"}

# ------------------------------------------------------------------------------------ other small words
FUNCTION_WORDS: dict[str, str] = {
    "a": "A", "an": "A", "and": "AND", "&": "AND", "of": "OF", "in": "IN",
    "to": "RTO", "-": "RTO", "–": "RTO", "—": "RTO", "or": "RTO", "between": "BETW", "from": "BETW",
    "x": "BY", "×": "BY", "by": "BY", "*": "BY",
    "is": "BE", "are": "BE", "was": "BE", "be": "BE", "measures": "BE", "measure": "BE",
    "measuring": "BE", "measured at": "BE", ":": "BE", "=": "BE", "its": "BE",
    "the": "BE", "has": "BE", "with": "BE", "at": "BE",
    ".": "SEP", "!": "SEP", "?": "SEP", ";": "SEP", ",": "CM", "(": "CM", ")": "CM",
}  # fmt: skip

#: Nouns that name a part or an accessory: a material or shape word right before one of them
#: ("rubber grip", "plastic bag", "long stem") describes the part, not the object (see PARSER.md).
PART_NOUNS: frozenset[str] = frozenset(
    {"grip", "grips", "handle", "handles", "bag", "bags", "lid", "lids", "cap", "caps", "cover", "sleeve",
     "strap", "straps", "cord", "base", "tip", "tips", "label", "wrapper", "wrapping", "packaging",
     "stand", "coating", "trim", "insert", "bristles", "feet", "seal", "stopper", "spout", "nozzle",
     "stem", "hinge", "clasp", "zip", "zipper", "sole", "wheels", "legs", "knob", "rim", "lining",
     "liner", "inside", "interior", "window", "opener", "holder"}
)  # fmt: skip
#: Prepositions that open a phrase about a part or a container ("with a rubber grip", "in a plastic bag"):
#: material and shape words inside such a phrase rank below the words about the object itself.
PART_PREPOSITIONS: frozenset[str] = frozenset({"with", "in", "inside", "on", "plus", "into", "has", "have"})
#: Nouns that a shape noun before them only modifies ("bottle opener", "pen holder", "can opener").
MODIFIED_HEADS: frozenset[str] = frozenset(
    {"opener", "openers", "holder", "holders", "rack", "stand", "brush", "cleaner", "warmer", "sleeve",
     "cover", "stopper", "top", "bag", "clip", "end", "ends", "mark", "hook", "shelf", "cap", "lid",
     "sharpener", "case", "organizer", "organiser", "tray"}
)  # fmt: skip
#: Shape nouns that, before "of", only measure out a substance ("a bar of soap", "a bar of chocolate"):
#: they say nothing about the shape.
MEASURE_NOUNS: frozenset[str] = frozenset({"bar", "bars"})
#: Shape nouns that, before "of", are a container or a portion ("a tube of toothpaste", "a box of
#: tissues", "a block of wood"): still the object's shape, with the lowest priority.
CONTAINER_NOUNS: frozenset[str] = frozenset(
    {"tube", "box", "roll", "stick", "block", "slab", "sheet", "can", "jar", "bottle", "cup", "pad"}
)  # fmt: skip
#: Words that say the material is the object's own ("a plastic body", "the body is aluminium").
BODY_WORDS: frozenset[str] = frozenset({"body", "bodied", "casing", "housing", "shell", "frame", "barrel"})

#: Long round things whose thickness is a diameter ("a pencil 19 cm long and 7 mm thick": b = c = 0.7).
ROD_WORDS: frozenset[str] = CYLINDER_WORDS - {"jar", "mug", "cup", "tumbler", "vase", "candle"} | frozenset(
    {"banana", "pin", "carrot", "cucumber", "zucchini", "courgette", "sausage", "baguette", "crayon", "cigar",
     "chopstick", "chopsticks", "skewer", "wand", "chalk", "dowel", "cable", "broomstick", "flute"}
)  # fmt: skip
#: A tolerance after a value ("430 g +/- 20 g"): the tolerance is not a second value or a range.
TOLERANCE_WORDS: frozenset[str] = frozenset({"+/-", "+-", "±", "plus or minus", "plus minus", "give or take"})

#: A quantity right after one of these is another object's ("my 2 kg dumbbell") ...
POSSESSIVES: frozenset[str] = frozenset({"my", "your", "our", "their", "his", "her", "mum's", "dad's"})
#: ... and surely so when its sentence compares or places the two ("next to my 2 kg dumbbell").
COMPARISON_WORDS: frozenset[str] = frozenset(
    {"next", "beside", "besides", "than", "compared", "comparison", "heavier", "lighter", "bigger", "smaller",
     "larger", "taller", "shorter", "longer", "wider", "thinner", "thicker", "near", "behind", "versus", "vs"}
)  # fmt: skip

#: Compound nouns whose first word is not what the object is made of (merged, tagged W).
COMPOUND_NOUNS: frozenset[str] = frozenset({"paper clip", "paper clips", "glass cleaner"})

#: Multi-word expressions merged into one token before tagging (longest match first).
MULTIWORD: tuple[str, ...] = tuple(
    sorted(
        {w for table in (HEDGES, TRAILING_HEDGES, DIMENSION_WORDS, VOLUME_UNITS, MATERIAL_WORDS, SHAPE_WORDS,
                         FUNCTION_WORDS) for w in table if " " in w}
        | {"can hold", "could hold", "plus or minus", "plus minus"} | COMPOUND_NOUNS | FLAT_WORDS,
        key=lambda w: (-len(w.split()), w),
    )
)  # fmt: skip


def tag_model() -> dict[str, str]:
    """The UnigramTagger model: lower-case token -> tag. Later tables win over earlier ones, so the
    order below is the tie-break for words listed twice (e.g. "in": unit/preposition -> IN, fixed in
    context by the parser; "long": DIM, reread as a shape outside a dimension; "glass": MAT)."""
    model: dict[str, str] = {}
    for table, tag in (
        (SHAPE_WORDS, "SHP"),
        (FUNCTION_WORDS, None),
        (NUMBER_WORDS, "NW"),
        (MAGNITUDE_WORDS, "NMAG"),
        (FRACTION_WORDS, "FRC"),
        (UNICODE_FRACTIONS, "FRC"),
        (LENGTH_UNITS, "ULEN"),
        (MASS_UNITS, "UMASS"),
        (VOLUME_UNITS, "UVOL"),
        (DIMENSION_WORDS, "DIM"),
        (DIMENSION_NOUNS, "DIMN"),
        (MATERIAL_WORDS, "MAT"),
        (RIGIDITY_WORDS, "RIG"),
        (TEXTURE_WORDS, "TEX"),
        (FRAGILITY_WORDS, "FRA"),
        (MASS_HINT_WORDS, "MH"),
        (TRAILING_HEDGES, "HS"),
    ):
        for word in table:
            model[word] = tag if tag is not None else FUNCTION_WORDS[word]
    for word, qualifier in HEDGES.items():
        model[word] = HEDGE_TAGS[qualifier]
    for word in FILL_WORDS - {"with", "holding", "holds"}:
        model[word] = "FILL"
    for word in NEGATIONS:
        model[word] = "NEG"
    model["in"] = "IN"  # "in diameter"; retagged ULEN after a number when no dimension noun follows
    model["glass"] = "MAT"  # a material more often than a drinking glass
    model["orange"] = "SHP"  # the fruit; as a colour it states nothing we use
    model["cup"] = "SHP"  # a container, not the volume unit (a volume only after a number: retagged)
    model["cups"] = "UVOL"
    model["can"] = "SHP"
    model["over"] = "HL"
    return model


#: Read-only views of the tables, for documentation and tests.
TABLES = MappingProxyType(
    {
        "material": MATERIAL_WORDS,
        "shape": {w: s for w, (s, _p) in SHAPE_WORDS.items()},
        "rigidity": RIGIDITY_WORDS,
        "texture": TEXTURE_WORDS,
        "fragility": FRAGILITY_WORDS,
    }
)
