"""The parser's category words: material, shape (and the shape cues of the dimension rules), rigidity,
texture, fragility, mass hints and colours, each word -> its canonical value of :mod:`kb.features`.

Data only, part of the parser's lexicon (:mod:`recall.lexicon` re-exports every table; ``recall/PARSER.md``
prints them with the rules that use them). Split from :mod:`recall.lexicon` (no behaviour change).
"""

from __future__ import annotations

__all__ = [
    "BALL_COMPOUND_HEADS",
    "BALL_SUFFIX",
    "CAN_PRECEDERS",
    "COLOUR_WORDS",
    "CUBE_WORDS",
    "CYLINDER_WORDS",
    "DISC_WORDS",
    "FLAT_WORDS",
    "FRAGILITY_WORDS",
    "MASS_HINT_WORDS",
    "MATERIAL_WORDS",
    "MEDIUM_WORDS",
    "NEGATED_FRAGILITY",
    "RIGIDITY_WORDS",
    "ROUND_WORDS",
    "SHAPE_WORDS",
    "SPHERE_WORDS",
    "TEXTURE_WORDS",
    "VESSEL_WORDS",
]

#: Material words -> :data:`kb.features.MATERIALS`.
MATERIAL_WORDS: dict[str, str] = {
    "metal": "metal", "metallic": "metal", "metals": "metal", "steel": "metal", "stainless": "metal",
    "aluminum": "metal", "aluminium": "metal", "iron": "metal", "tin": "metal", "copper": "metal",
    "brass": "metal", "bronze": "metal", "chrome": "metal", "silver": "metal", "zinc": "metal",
    "titanium": "metal", "cast-iron": "metal", "nickel": "metal", "wire": "metal", "foil": "metal",
    "wood": "wood", "wooden": "wood", "woody": "wood", "timber": "wood", "bamboo": "wood", "oak": "wood",
    "pine": "wood", "plywood": "wood", "beech": "wood", "maple": "wood", "birch": "wood", "balsa": "wood",
    "mdf": "wood", "cork": "wood", "walnut": "wood", "hardwood": "wood",
    "paper": "paper", "papery": "paper", "cardboard": "paper", "carton": "paper", "paperboard": "paper",
    "card stock": "paper", "cardstock": "paper", "corrugated": "paper", "tissue": "paper",
    "fabric": "fabric", "cloth": "fabric", "cotton": "fabric", "textile": "fabric", "felt": "fabric",
    "wool": "fabric", "woolen": "fabric", "woollen": "fabric", "polyester": "fabric", "denim": "fabric",
    "linen": "fabric", "silk": "fabric", "canvas": "fabric", "fleece": "fabric", "knitted": "fabric",
    "microfiber": "fabric", "microfibre": "fabric", "terry": "fabric",
    "glass": "glass", "glassy": "glass", "crystal": "glass",
    "plastic": "plastic", "plastics": "plastic", "polycarbonate": "plastic", "acrylic": "plastic",
    "pvc": "plastic", "vinyl": "plastic", "polypropylene": "plastic", "polyethylene": "plastic",
    "nylon": "plastic", "abs": "plastic", "styrofoam": "plastic", "melamine": "plastic",
    "rubber": "rubber", "silicone": "rubber", "latex": "rubber", "neoprene": "rubber",
    "ceramic": "other", "ceramics": "other", "porcelain": "other", "stone": "other", "clay": "other",
    "marble": "other", "terracotta": "other", "granite": "other", "foam": "other", "sponge": "other",
    "wax": "other", "soap": "other", "stoneware": "other", "earthenware": "other", "concrete": "other",
    "chalk": "other", "graphite": "other", "leather": "other", "leathery": "other",
}  # fmt: skip


#: Shape words -> :data:`kb.features.SHAPES`, with a priority: when several shape words occur, the
#: highest priority wins (geometric adjectives 3 > object-kind nouns 2 > vague words 1), ties go to the
#: first. "long" as a shape only counts when it is not part of a dimension ("15 cm long").
SHAPE_WORDS: dict[str, tuple[str, int]] = {
    "flat": ("thin", 3), "thin": ("thin", 1), "card": ("thin", 2), "sheet": ("thin", 2),
    "slim": ("thin", 2), "plate": ("thin", 2), "flattened": ("thin", 3), "sheet-like": ("thin", 3),
    "slab": ("thin", 2), "wafer": ("thin", 2), "pad": ("thin", 1), "envelope": ("thin", 2),
    "booklet": ("thin", 2), "notebook": ("thin", 2), "book": ("thin", 1), "tablet": ("thin", 1),
    "phone": ("thin", 1), "smartphone": ("thin", 1), "wallet": ("thin", 1), "coaster": ("thin", 2),
    "cube": ("compact", 3), "cubic": ("compact", 3), "cubical": ("compact", 3), "cube-shaped": ("compact", 3),
    "block": ("prism", 2), "chunky": ("compact", 2), "compact": ("compact", 3), "lump": ("compact", 2),
    "nugget": ("compact", 2), "squat": ("compact", 2), "stubby": ("compact", 2),
    "cylindrical": ("prism", 3), "cylinder": ("prism", 3), "prism": ("prism", 3), "prismatic": ("prism", 3),
    "rectangular": ("prism", 2), "box": ("prism", 1), "boxy": ("prism", 2), "cuboid": ("prism", 3),
    "can": ("prism", 1), "bottle": ("prism", 1), "jar": ("prism", 1),
    "tube": ("prism", 2), "tubular": ("prism", 3), "mug": ("prism", 1), "cup": ("prism", 1),
    "canister": ("prism", 1), "roll": ("prism", 1), "brick": ("prism", 2),
    "wedge": ("prism", 2), "triangular": ("prism", 3), "hexagonal": ("prism", 3),
    "long": ("long", 2), "elongated": ("long", 3), "stick": ("long", 2), "rod": ("long", 2),
    "rod-shaped": ("long", 3), "stick-like": ("long", 3), "pen": ("long", 2), "pencil": ("long", 2),
    "straw": ("long", 2), "skinny": ("long", 2), "slender": ("long", 3), "bar": ("long", 1), "spoon": ("long", 2), "fork": ("long", 2), "knife": ("long", 2),
    "brush": ("long", 1), "screwdriver": ("long", 2), "wand": ("long", 2), "baton": ("long", 2),
    "marker": ("long", 2), "remote": ("long", 1), "ruler": ("long", 2), "chopstick": ("long", 2),
    "curved": ("long", 1),
    "round": ("radial", 2), "ball": ("radial", 3), "sphere": ("radial", 3), "spherical": ("radial", 3),
    "globe": ("radial", 2), "orb": ("radial", 2), "ball-shaped": ("radial", 3), "circular": ("radial", 2),
    "disc": ("compact", 2), "disk": ("compact", 2), "disc-shaped": ("compact", 3),
    "dome": ("radial", 2), "egg": ("radial", 2), "oval": ("radial", 1), "orange": ("radial", 1),
    "apple": ("radial", 1), "cap": ("compact", 1), "knob": ("radial", 1),
    "coin": ("thin", 2), "puck": ("radial", 2), "doughnut": ("radial", 2), "donut": ("radial", 2),
    "hot water bottle": ("thin", 2),
}  # fmt: skip


#: Shape cues used by the dimension rules (see PARSER.md): a single stated extent of a cube or a ball
#: is all three dimensions; a diameter alone of a cylinder fills b = c, of a disc a = b.
CUBE_WORDS: frozenset[str] = frozenset({"cube", "cubic", "cubical", "cube-shaped", "dice", "die"})


SPHERE_WORDS: frozenset[str] = frozenset(
    {"ball", "sphere", "spherical", "globe", "orb", "ball-shaped", "marble", "orange", "apple", "bead",
     "balls", "marbles", "grapefruit", "melon", "peach", "plum", "tomato", "lime", "lemon"}
)  # fmt: skip


#: A compound ending in "ball" ("softball", "baseball", "basketball", "racquetball") is a ball too, unless
#: one of these nouns follows it ("baseball cap", "softball bat"): then it only names what the thing is for.
BALL_SUFFIX = "ball"


BALL_COMPOUND_HEADS: frozenset[str] = frozenset(
    {"cap", "caps", "hat", "bat", "bats", "glove", "gloves", "mitt", "card", "cards", "player", "field",
     "court", "game", "bearing", "bearings", "pump", "jersey", "shoe", "shoes", "boot", "boots"}
)  # fmt: skip


#: Words that make an object flat (its width is a width, never a diameter copied into the thickness).
FLAT_WORDS: frozenset[str] = frozenset(
    {"flat", "flattened", "sheet", "card", "slab", "pad", "bag", "pouch", "envelope", "wallet", "mat",
     "hot water bottle", "floppy", "sheet-like", "folded"}
)  # fmt: skip


CYLINDER_WORDS: frozenset[str] = frozenset(
    {"cylindrical", "cylinder", "can", "tube", "tubular", "bottle", "jar", "mug", "cup", "canister", "rod",
     "stick", "pen", "pencil", "straw", "roll", "pipe", "candle", "tumbler", "thermos", "flask",
     "marker", "baton", "dowel", "vase", "spool"}
)  # fmt: skip


DISC_WORDS: frozenset[str] = frozenset(
    {"disc", "disk", "disc-shaped", "coin", "plate", "lid", "cap", "coaster", "puck", "flat", "frisbee",
     "saucer", "ring", "wheel", "doughnut", "donut", "cd", "dvd", "button", "record", "pancake", "dime",
     "penny", "quarter", "nickel", "medal", "token", "tealight"}
)  # fmt: skip


#: Words that make a width of a round object its diameter, besides the sphere/cylinder/disc words.
#: Round vessels: round cues too, but not after "the"/"its"/"at", where they name a part ("2 inches wide
#: at the bowl" of a spoon, "the bowl is 8 cm across" of a wine glass).
VESSEL_WORDS: frozenset[str] = frozenset({"bowl", "pot", "saucepan", "wok", "bucket", "pail", "basin"})


ROUND_WORDS: frozenset[str] = (
    frozenset({"round", "circular", "cylindrical", "rounded", "tealight"}) | VESSEL_WORDS
)


#: "can" is a container (a cylinder cue) only after one of these words or before "of".
CAN_PRECEDERS: frozenset[str] = frozenset(
    {"a", "the", "tin", "soda", "food", "metal", "aluminum", "aluminium", "beer", "tuna", "soup", "paint",
     "small", "large", "short", "tall", "empty", "steel", "drink", "coke", "pop", "flat", "squat"}
)  # fmt: skip


RIGIDITY_WORDS: dict[str, str] = {
    "rigid": "rigid", "hard": "rigid", "firm": "rigid", "stiff": "rigid", "solid": "rigid",
    "inflexible": "rigid", "unbendable": "rigid", "non-flexible": "rigid",
    "squeezable": "squeezable", "soft": "squeezable", "squishy": "squeezable", "spongy": "squeezable",
    "compressible": "squeezable", "squashy": "squeezable", "cushy": "squeezable", "springy": "squeezable",
    "elastic": "squeezable", "stretchy": "squeezable", "pliable": "squeezable", "deformable": "squeezable",
    "squeezy": "squeezable", "malleable": "squeezable", "bouncy": "squeezable",
    "floppy": "floppy", "flexible": "floppy", "limp": "floppy", "bendy": "floppy", "bendable": "floppy",
    "flimsy": "floppy", "droopy": "floppy", "foldable": "floppy", "drapey": "floppy", "saggy": "floppy",
}  # fmt: skip


TEXTURE_WORDS: dict[str, str] = {
    "smooth": "smooth", "glossy": "smooth", "polished": "smooth", "shiny": "smooth", "slick": "smooth",
    "sleek": "smooth", "silky": "smooth", "slippery": "smooth", "glazed": "smooth", "satin": "smooth",
    "rough": "rough", "coarse": "rough", "porous": "rough", "prickly": "rough", "spiky": "rough",
    "scaly": "rough", "thorny": "rough", "fuzzy": "rough", "furry": "rough", "hairy": "rough",
    "bumpy": "rough", "grainy": "rough", "gritty": "rough", "scratchy": "rough", "textured": "rough",
    "unfinished": "rough", "unpolished": "rough", "raw": "rough", "splintery": "rough", "felted": "rough",
    "grippy": "grippy", "rubbery": "grippy", "tacky": "grippy", "sticky": "grippy", "non-slip": "grippy",
    "nonslip": "grippy", "knurled": "grippy", "ridged": "grippy", "ribbed": "grippy", "grooved": "grippy",
    "matte": "medium", "matt": "medium", "semi-smooth": "medium", "satiny": "medium",
}  # fmt: skip


FRAGILITY_WORDS: dict[str, str] = {
    "fragile": "fragile", "delicate": "fragile", "breakable": "fragile", "brittle": "fragile",
    "shatterable": "fragile", "crushable": "fragile", "easily-broken": "fragile",
    "sturdy": "sturdy", "robust": "sturdy", "durable": "sturdy", "tough": "sturdy", "strong": "sturdy",
    "unbreakable": "sturdy", "shatterproof": "sturdy", "shatter-proof": "sturdy", "indestructible": "sturdy",
    "rugged": "sturdy", "heavy-duty": "sturdy", "resilient": "sturdy",
}  # fmt: skip


#: A negated fragility word flips ("not fragile" -> sturdy); other negated category words are dropped.
NEGATED_FRAGILITY: dict[str, str] = {"fragile": "sturdy", "sturdy": "fragile", "medium": "medium"}


#: Words that qualify a category feature as *medium* when they precede its word ("medium texture",
#: "moderately fragile", "somewhat rough" stays rough).
MEDIUM_WORDS: frozenset[str] = frozenset({"medium", "moderately", "moderate", "average", "normal"})


#: Mass hints (tag MH): a weak signal, not a mass. The recall engine decides whether to use it.
MASS_HINT_WORDS: dict[str, str] = {
    "light": "light", "lightweight": "light", "light-weight": "light", "featherweight": "light",
    "weightless": "light", "feather-light": "light",
    "heavy": "heavy", "hefty": "heavy", "weighty": "heavy", "heavyweight": "heavy", "dense": "heavy",
}  # fmt: skip


#: "light" followed by one of these is a colour, not a weight ("light blue").
COLOUR_WORDS: frozenset[str] = frozenset(
    {"blue", "green", "red", "brown", "grey", "gray", "yellow", "pink", "purple", "orange", "colored",
     "coloured", "wood", "tan", "beige", "tone", "shade", "color", "colour"}
)  # fmt: skip
