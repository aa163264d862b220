"""Stage 2 of the description parser (the paper's Fig. 2): tokens to tags.

``nltk.tag.UnigramTagger`` whose model is the lexicon (:func:`recall.lexicon.tag_model`), backed off to a
``RegexpTagger`` (digits ``CD``, ``½`` ``FRC``, ``twenty-one`` ``NW``, anything else ``W``); its answer
per word is cached. Then one linear pass, :func:`fix_tags`, fixes the tags that depend on the
neighbours ("in" an inch or a preposition, "x" a multiplication sign or a word, a tolerance dropped,
tuple labels, ...; the list is in ``recall/PARSER.md``).
"""

from __future__ import annotations

import re

from kb.measures.numbers import DIGITS_PATTERN
from kb.measures.units import description_units, is_smaller_unit
from recall import lexicon as lx
from recall.tokens import FRACTION_CHARS, Token
from recall.toolkit import RegexpTagger, UnigramTagger

__all__ = ["CATEGORY_TAGS", "NUMBER_TAGS", "UNIT_TAGS", "Tagger", "fix_tags"]

#: Most words remembered by a tagger's cache (new words past this are tagged, not remembered).
TAG_CACHE_SIZE = 100_000
NUMBER_TAGS = frozenset({"CD", "NW", "NMAG", "FRC"})
UNIT_TAGS = frozenset({"ULEN", "UMASS", "UVOL"})
CATEGORY_TAGS = {"MAT": "material", "SHP": "shape", "RIG": "rigidity", "TEX": "texture", "FRA": "fragility"}
_ABBREVIATIONS = frozenset(
    {"in", "ft", "oz", "lb", "lbs", "approx", "ca", "cm", "mm", "dia", "diam", "no", "vs", "e", "g", "i",
     "kg", "ml", "fl", "m", "l", "gm", "gms", "dl", "cl", "st", "mr", "dr"}
)  # fmt: skip
_SYMBOL_UNITS = frozenset({'"', "''", "”", "″", "'", "′", "’"})


class Tagger:
    """The lexicon's unigram tagger with its regexp fallback; :meth:`tag` is thread-safe."""

    def __init__(self) -> None:
        fallback = RegexpTagger(
            [
                (r"^(?:" + DIGITS_PATTERN + r")$", "CD"),
                (r"^[" + FRACTION_CHARS + r"]$", "FRC"),
                (r"^(?:twenty|thirty|forty|fourty|fifty|sixty|seventy|eighty|ninety)-"
                 r"(?:one|two|three|four|five|six|seven|eight|nine)$", "NW"),
                (r".*", "W"),
            ]
        )  # fmt: skip
        self.model = lx.tag_model()
        self._unigram = UnigramTagger(model=self.model, backoff=fallback)
        # word -> tag: the unigram tagger looks at one word only, so its answer for a word never changes
        self.cache: dict[str, str] = {}

    def tag(self, tokens: list[Token]) -> list[Token]:
        """Tag the tokens (in place) from the lexicon, then fix the tags that depend on the neighbours;
        returns the tokens kept (a tolerance and some joining hyphens and dots are dropped)."""
        cache = self.cache
        missing = list({t.low for t in tokens if t.low not in cache})
        fresh: dict[str, str] = {}
        if missing:
            fresh = {w: (tag or "W") for w, tag in self._unigram.tag(missing)}
            if len(cache) < TAG_CACHE_SIZE:
                cache.update(fresh)  # one dict update: safe for concurrent parses
        for tok in tokens:
            tag = cache.get(tok.low)
            tok.tag = tag if tag is not None else fresh[tok.low]
        return fix_tags(tokens)


def fix_tags(tokens: list[Token]) -> list[Token]:
    """Tags that depend on the neighbours; one linear pass (two for dropped hyphens). Returns the tokens
    kept: a tolerance with its number and unit, a joining hyphen, a minus sign (marked on its number) and
    an abbreviation's dot are dropped."""
    out: list[Token] = []
    n = len(tokens)
    _tuple_labels(tokens)
    imperial = _imperial_text(tokens)
    letters_w = any(t.low == "w" and t.tag != "LBL" for t in tokens)
    skip_to = -1
    for i, tok in enumerate(tokens):
        prev = out[-1] if out else None
        nxt = tokens[i + 1] if i + 1 < n else None
        prev_num = prev is not None and prev.tag in NUMBER_TAGS
        if i < skip_to:
            continue  # the tolerance's own number and unit are dropped
        if tok.low in lx.TOLERANCE_WORDS:
            end = _tolerance_end(tokens, i, prev, prev_num)
            if end is not None:
                skip_to = end  # "430 g +/- 20 g": a tolerance, not a range or a second value: dropped
                continue
        if _sign(tok, prev, nxt):
            nxt.negative = True  # "-10 kg", "minus 5 cm": the number is negative; the sign is dropped
            nxt.word = tok.word + " " * (nxt.start - tok.end) + nxt.word
            nxt.start = tok.start
            continue
        if _letter_extent(tokens, i, out, prev_num, letters_w):
            out.append(tok)
            continue
        if _dropped(tok, prev, nxt, prev_num):
            continue
        tag = _unit_tag(tok, prev, nxt, prev_num, out, imperial)
        if tag is None:
            tag = _connector_tag(tokens, i, tok, prev, nxt, out)
        if tag is None:
            tag = _word_tag(tokens, i, tok, prev, nxt, prev_num)
        if tag in UNIT_TAGS and prev_num and _smaller_unit_after(out, tok):
            tag = "USUB"
        tok.tag = tag
        out.append(tok)
    return out


def _tolerance_end(tokens: list[Token], i: int, prev: Token | None, prev_num: bool) -> int | None:
    """For a tolerance word at ``i`` between a value and a number ("430 g +/- 20 g"), the index after its
    own number and unit; else None."""
    n = len(tokens)
    if prev is None or not (prev_num or prev.tag in UNIT_TAGS):
        return None
    if i + 1 >= n or tokens[i + 1].tag not in NUMBER_TAGS:
        return None
    j = i + 1
    while j < n and tokens[j].tag in NUMBER_TAGS:
        j += 1
    if j < n and tokens[j].tag in UNIT_TAGS | {"IN"}:
        j += 1
    return j


def _letter_extent(tokens: list[Token], i: int, out: list[Token], prev_num: bool, letters_w: bool) -> bool:
    """Retag (DIMN) and return True for a single letter L/W/H/D naming one extent: "L 48 cm, dia 28 cm",
    "L=8cm D=3cm", "L 30 W 20 H 10 cm" (D is a depth next to a W, else a diameter)."""
    tok = tokens[i]
    n = len(tokens)
    chained = len(out) >= 2 and out[-2].tag == "DIMN" and len(out[-2].word) == 1  # "L 30 W 20"
    if len(tok.low) != 1 or tok.low not in lx.TUPLE_LABELS or tok.tag == "LBL":
        return False
    if prev_num and not chained:
        return False
    k = i + 1
    if k < n and tokens[k].low in ("=", ":"):
        k += 1
    after = tokens[k + 1] if k + 1 < n else None
    if after is not None and after.low == "," and k + 2 < n:
        after = tokens[k + 2]
    if (
        after is not None
        and tokens[k].tag == "CD"
        and (after.tag in ("ULEN", "IN") or (len(after.low) == 1 and after.low in lx.TUPLE_LABELS))
    ):
        role = lx.TUPLE_LABELS[tok.low]
        tok.low = "diameter" if role == "depth" and not letters_w else role
        tok.tag = "DIMN"
        return True
    return False


_MINUS = frozenset({"-", "−", "minus"})
_PROPER_FRACTION = re.compile(r"(\d+)/(\d+)")


def _sign(tok: Token, prev: Token | None, nxt: Token | None) -> bool:
    """True for a minus sign: "minus" before a number, or ``-``/``−`` glued to the number after it and
    not glued to a number or word before it ("-10 kg", "from -3 to 4", "size:-5 cm"; not "2-3 cm",
    "12-1/2", "X-5")."""
    if tok.low not in _MINUS or nxt is None or nxt.tag not in NUMBER_TAGS:
        return False
    if tok.low == "minus":
        return True
    if nxt.start != tok.end:
        return False  # "- 10 cm": a dash, a list bullet
    return prev is None or prev.end != tok.start or not prev.word[-1:].isalnum()


def _mixed_fraction(prev: Token | None, nxt: Token | None) -> bool:
    """True for the hyphen of a mixed number written "12-1/2" or "3-½": an integer glued to a proper
    fraction (a range "1/2-3/4" or "2-3" has no whole number before a fraction)."""
    if prev is None or nxt is None or prev.tag != "CD" or not prev.word.isdigit():
        return False
    if nxt.low in lx.UNICODE_FRACTIONS:
        return True
    m = _PROPER_FRACTION.fullmatch(nxt.low)
    return m is not None and 0 < int(m.group(1)) < int(m.group(2))


def _dropped(tok: Token, prev: Token | None, nxt: Token | None, prev_num: bool) -> bool:
    """True for a hyphen that joins ("5-cm-long", "10-ish", the mixed number "12-1/2") and the dot of an
    abbreviation before a lower-case word ("approx. 5 cm", "3 in. long"): neither is a range nor a
    sentence end."""
    if tok.tag == "RTO" and tok.low in ("-", "–", "—"):
        if prev is not None and nxt is not None and prev.end == tok.start == nxt.start - 1:
            if _mixed_fraction(prev, nxt):
                return True
        nxt_unit = nxt is not None and nxt.tag in (UNIT_TAGS | {"DIM", "DIMN", "HS", "IN"})
        if (prev_num and nxt_unit) or (
            prev is not None and prev.tag in UNIT_TAGS and nxt is not None and nxt.tag in ("DIM", "DIMN")
        ):
            return True
    if tok.low == "." and prev is not None and prev.low in _ABBREVIATIONS:
        if nxt is not None and not nxt.word[:1].isupper():
            return True
    return False


def _unit_tag(
    tok: Token, prev: Token | None, nxt: Token | None, prev_num: bool, out: list[Token], imperial: bool
) -> str | None:
    """The tag of "in", a unit symbol or a unit word in context; None when the token is none of them."""
    tag = tok.tag
    if tag == "IN" and prev_num:
        if nxt is None or nxt.low not in lx.DIMENSION_NOUNS or imperial:
            return "ULEN"  # "4 in long", "3 in." ; "7 in diameter" stays a preposition, unless the
            # other units are imperial: "1.68 in diameter, 1.62 oz"
        return tag
    if tok.low in _SYMBOL_UNITS:
        return "ULEN" if prev_num else "CM"
    if tag not in UNIT_TAGS:
        return None
    if prev is not None and prev.tag in ("HS", "LBL") and len(out) >= 2 and (out[-2].tag in NUMBER_TAGS):
        return tag  # "250-ish grams", "5H cm"
    if not prev_num and not _number_before_of(out):
        before_a = out[-2] if len(out) >= 2 else None
        if prev is not None and prev.tag == "A" and len(tok.low) > 2:
            if before_a is None or (before_a.tag not in NUMBER_TAGS and before_a.tag != "OF"):
                prev.tag = "NW"  # "a liter of water", "about a foot long": "a" is one; not "half a liter"
        elif not (prev is not None and prev.tag == "A"):
            return "W"  # "cm" with no number, "m" in "I m", a "cup" of coffee
        return tag
    return None


def _connector_tag(
    tokens: list[Token], i: int, tok: Token, prev: Token | None, nxt: Token | None, out: list[Token]
) -> str | None:
    """The tag of ``x``/``by``/``to``/``or``/``-`` (they only join numbers), ``between``/``from`` (only
    before one) and ``and`` after a unit before a fraction; None for any other token."""
    tag = tok.tag
    if tag in ("BY", "RTO"):
        nxt_num = nxt is not None and (nxt.tag in NUMBER_TAGS or nxt.tag in ("A", "HA", "HL", "HU"))
        prev_ok = prev is not None and (prev.tag in NUMBER_TAGS or prev.tag in UNIT_TAGS)
        if tag == "BY" and not prev_ok and prev is not None and len(out) >= 2:
            # "7.5 cm long by 5 by 5", "20L x 10W": a labelled value before the sign
            before = out[-2].tag
            prev_ok = (
                prev.tag in ("DIM", "DIMN") and (before in UNIT_TAGS or before in NUMBER_TAGS)
            ) or (prev.tag == "LBL" and before in NUMBER_TAGS)
        if tag == "BY" and not nxt_num and nxt is not None and nxt.tag == "LBL":
            nxt_num = True  # "x W 10"
        return tag if nxt_num and prev_ok else "W"
    if tag == "BETW":
        return "W" if nxt is None or nxt.tag not in NUMBER_TAGS else tag
    if tag == "AND" and prev is not None and prev.tag in UNIT_TAGS and nxt is not None:
        after = tokens[i + 2] if i + 2 < len(tokens) else None
        if nxt.low in lx.FRACTION_WORDS or (
            nxt.tag == "A" and after is not None and after.low in lx.FRACTION_WORDS
        ):
            return "UAND"  # "an inch and a half", "a pound and a quarter"
        return tag
    return None


def _word_tag(
    tokens: list[Token], i: int, tok: Token, prev: Token | None, nxt: Token | None, prev_num: bool
) -> str:
    """The tag of a word whose meaning depends on its neighbours ("cup", "can", "light", "quarter", a
    dimension word before its hedged value); the lexicon's tag otherwise."""
    tag = tok.tag
    if prev_num and tok.low in lx.UNIT_NOUNS:
        return lx.UNIT_NOUNS[tok.low]  # "1 cup of water", "a 40 stone mug"; "a stone mortar" keeps its material
    if tok.low == "can" and tag == "SHP":
        if not (
            (prev is not None and prev.low in lx.CAN_PRECEDERS) or (nxt is not None and nxt.low == "of")
        ):
            return "W"  # "it can hold": a verb
        return tag
    if (
        tag == "DIM"
        and nxt is not None
        and nxt.tag == "HA"
        and i + 2 < len(tokens)
        and tokens[i + 2].tag in NUMBER_TAGS
        and not (
            prev_num or (prev is not None and (prev.tag in UNIT_TAGS or prev.low in ("a", "an", "as")))
        )
        and lx.DIMENSION_WORDS.get(tok.low) in lx.LINEAR_ROLES
    ):
        return "DIMN"  # "it is long about 32 cm", "thick maybe 1.5 cm": the word before its value
    if tok.low == "around" and prev is not None and prev.tag == "ULEN" and not _value_follows(tokens, i):
        return "DIM"  # "30 cm around": a circumference; "around 30 cm" stays a hedge
    if tag == "MH" and tok.low == "light" and nxt is not None and nxt.low in lx.COLOUR_WORDS:
        return "W"
    if tag == "SHP" and nxt is not None and _colour_before_noun(tok, nxt):
        return "W"  # "an orange mug", "an apple green mug": a colour, no shape (nor fruit)
    if tag == "FRC" and tok.low in lx.ORDINAL_FRACTIONS:
        if not (prev_num or (prev is not None and prev.tag in ("A", "AND"))):
            return "W"  # "the top quarter", "third" or "fifth" as an ordinal
    return tag


def _colour_before_noun(tok: Token, nxt: Token) -> bool:
    """Whether a shape word is a colour here: a colour word ("orange") before a noun (a shape noun or a
    kinds-lexicon noun: "an orange *mug*"), or any shape word before a colour word ("*apple* green",
    "*lemon* yellow"). "An orange of 7 cm", "an orange, 200 g", "an orange that weighs..." stay the fruit."""
    from kb.kinds import noun_in

    if nxt.low in lx.COLOUR_WORDS and nxt.low.isalpha():
        return True
    if tok.low not in lx.COLOUR_WORDS:
        return False
    return nxt.tag == "SHP" or (nxt.tag == "W" and nxt.low.isalpha() and noun_in([nxt.low]) is not None)


def _value_follows(tokens: list[Token], i: int) -> bool:
    """Whether a number (or "a", as in "a pound") follows token ``i``: then "around" hedges that value."""
    nxt = tokens[i + 1] if i + 1 < len(tokens) else None
    return nxt is not None and (nxt.tag in NUMBER_TAGS or nxt.tag == "A")


_BY_WORDS = frozenset({"x", "×", "by", "*"})
_IMPERIAL = frozenset({"inch", "foot", "yard", "ounce", "pound", "fluid_ounce"})
_METRIC_LENGTH = frozenset({"millimeter", "centimeter", "meter"})


def _imperial_text(tokens: list[Token]) -> bool:
    """True when the text's units are imperial (an ounce, pound, inch or foot) and none is a metric
    length: there "7 in diameter" is seven inches."""
    table = description_units()
    imperial = False
    for tok in tokens:
        if tok.tag in UNIT_TAGS:
            unit = table.get(tok.low)
            if unit is None:
                continue
            if unit.pint_name in _METRIC_LENGTH:
                return False
            if unit.pint_name in _IMPERIAL:
                imperial = True
    return imperial


def _tuple_labels(tokens: list[Token]) -> None:
    """Tag LBL the letters that label the numbers of a tuple: "L 20 x W 10 x H 5 cm" (a letter before a
    number, next to a multiplication sign) and "20L x 10W x 5H cm" (a letter glued to its number, before
    a sign or a length unit). "a 2L bottle" keeps its litre."""
    n = len(tokens)
    for i, tok in enumerate(tokens):
        if len(tok.low) != 1 or tok.low not in lx.TUPLE_LABELS:
            continue
        prev = tokens[i - 1] if i else None
        nxt = tokens[i + 1] if i + 1 < n else None
        if prev is not None and prev.tag in NUMBER_TAGS and prev.end == tok.start:
            if nxt is not None and (nxt.low in _BY_WORDS or nxt.tag == "ULEN"):
                tok.tag = "LBL"
            elif i >= 2 and tokens[i - 2].low in _BY_WORDS and (nxt is None or nxt.tag in ("CM", "SEP")):
                tok.tag = "LBL"
        elif nxt is not None and nxt.tag == "CD" and (prev is None or prev.tag not in NUMBER_TAGS):
            after = [t.low for t in tokens[i + 2 : i + 4]]
            if (prev is not None and prev.low in _BY_WORDS) or any(w in _BY_WORDS for w in after):
                tok.tag = "LBL"


def _smaller_unit_after(out: list[Token], tok: Token) -> bool:
    """True for the second unit of "1 lb 2 oz" / "5 ft 3 in": same kind and system, smaller
    (:func:`kb.measures.units.is_smaller_unit`), right after the first unit and its number."""
    k = len(out) - 1
    while k >= 0 and out[k].tag in NUMBER_TAGS:
        k -= 1
    if k == len(out) - 1 or k < 1 or out[k].tag not in UNIT_TAGS or out[k - 1].tag not in NUMBER_TAGS:
        return False
    table = description_units()
    first, second = table.get(out[k].low), table.get(tok.low)
    return first is not None and second is not None and is_smaller_unit(first, second)


def _number_before_of(out: list[Token]) -> bool:
    """True after "<number> of" or "<number> of a": "a couple of kilos", "half of a liter"."""
    k = len(out) - 1
    if k >= 0 and out[k].tag == "A":
        k -= 1
    return k >= 1 and out[k].tag == "OF" and out[k - 1].tag in NUMBER_TAGS
