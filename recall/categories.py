"""Categories of a description (material, shape, rigidity, texture, fragility) and its mass hint.

:func:`read_categories` collects, per sentence, every category word with its rank (the object's own
material beats a part's, a geometric shape word beats an object-kind noun; rules in
``recall/PARSER.md``, "Categories"), drops negated ones (fragility flips), and the mass hints ("light",
"heavy") and cue words the dimension rules use (ball, cylinder, flat, ...). :func:`resolve_categories`
picks one word per feature: the highest rank, then the first.
"""

from __future__ import annotations

from recall import lexicon as lx
from recall.reading import Reading
from recall.tags import CATEGORY_TAGS, NUMBER_TAGS
from recall.tokens import Token

__all__ = ["read_categories", "resolve_categories"]


def _negated(segment: list[Token], i: int) -> bool:
    for j in range(i - 1, max(-1, i - 4), -1):
        tag = segment[j].tag
        if segment[j].low in ("or", "nor") and j >= 1 and segment[j - 1].tag in CATEGORY_TAGS:
            return tag == "NEG" or _negated(segment, j - 1)  # "not made of glass or ceramic"
        if tag in ("CM", "SEP", "AND"):
            return False
        if tag == "NEG":
            return True
    return False


#: Words that may stand beside a material word in a comma clause of its own ("mostly plastic", "solid
#: oak", "metal and plastic"): the clause still only states the object's material.
_MATERIAL_CLAUSE_WORDS = frozenset(
    "mostly mainly all solid pure real genuine entirely white black grey gray silver gold golden red green "
    "blue yellow orange pink purple brown beige clear transparent dark bright".split()
)


def _alone_in_clause(segment: list[Token], i: int) -> bool:
    """Whether the material word at ``i`` makes up a comma clause (or the sentence) of its own with only
    other material words, :data:`_MATERIAL_CLAUSE_WORDS` (degree words, colours) and "and"/"or" ("Metal, about 6 in long",
    "..., stainless steel and plastic, ..."): the object's own material, as a listing states it, not
    the material of something it acts on or holds ("clips *paper* together", "cuts *wood*")."""
    lo = i
    while lo > 0 and segment[lo - 1].tag not in ("CM", "SEP"):
        lo -= 1
    hi = i
    while hi + 1 < len(segment) and segment[hi + 1].tag not in ("CM", "SEP"):
        hi += 1
    return all(
        t.tag in ("MAT", "AND") or t.low in ("or", "&") or t.low in _MATERIAL_CLAUSE_WORDS
        for t in segment[lo : hi + 1]
    )


def _in_part_phrase(segment: list[Token], i: int, through_and: bool = False) -> bool:
    """True when the word at ``i`` describes a part or a container, not the object: a part noun follows it
    ("rubber grip", "plastic bag", "long stem") or it is in a phrase opened by "with"/"in"/"on" ("with a
    rubber grip", "in a tin cup"; a comma, a sentence end or, unless ``through_and``, "and" closes the
    phrase: a material after "and" may be the object's, a shape noun after "and" is still a part)."""
    if i + 1 < len(segment) and segment[i + 1].low in lx.PART_NOUNS:
        return True
    for j in range(i - 1, max(-1, i - (7 if through_and else 4)), -1):
        t = segment[j]
        if t.tag in ("CM", "SEP") or (t.tag == "AND" and not through_and):
            return False
        if t.low in lx.PART_PREPOSITIONS and segment[j + 1].tag not in ("DIM", "DIMN", *NUMBER_TAGS):
            return True  # not "7 cm in diameter and round", "with 500 ml"
    return False


def _material_rank(segment: list[Token], i: int) -> int:
    """2: the object's own material ("made of X", "X body", "the body is X"); 0: a part's ("with a
    rubber grip"); 1: any other mention."""
    if i >= 2 and segment[i - 1].low in ("of", "from"):
        if segment[i - 2].low in ("made", "out", "built", "constructed", "consists"):
            return 2  # "made of plastic" beats a material in a name
    if i + 1 < len(segment) and segment[i + 1].low in lx.BODY_WORDS:
        return 2  # "a plastic body", "clear plastic barrel"
    if _alone_in_clause(segment, i):
        return 2  # "..., metal, about 6 in long": a listed attribute, not "clips *paper* together"
    for j in range(i - 1, max(-1, i - 4), -1):
        if segment[j].low in lx.BODY_WORDS:
            return 2  # "the body is aluminium", "body: steel"
        if segment[j].tag in ("CM", "SEP", "AND"):
            break
    return 0 if _in_part_phrase(segment, i) else 1


def read_categories(segment: list[Token], base: int, reading: Reading) -> None:
    """Add one sentence's cue words, mass hints and category words (with their rank) to ``reading``
    (``base``: the index of the sentence's first token in the text)."""
    for i, tok in enumerate(segment):
        _add_cue(segment, i, reading)
        if tok.tag == "MH":
            hint = lx.MASS_HINT_WORDS[tok.low]
            if _negated(segment, i):
                hint = "heavy" if hint == "light" else "light"
            reading.mass_hints.append(hint)
            continue
        found = _category(segment, i, base + i, reading)
        if found is None:
            continue
        feature, value, rank = found
        if _negated(segment, i):
            if feature == "fragility":
                value = lx.NEGATED_FRAGILITY[value]
            else:
                continue
        reading.categories.setdefault(feature, []).append((rank, base + i, value, tok))


def _add_cue(segment: list[Token], i: int, reading: Reading) -> None:
    """The word as a cue of the object's form for the dimension rules (ball, bottle, flat, ...)."""
    tok = segment[i]
    if tok.tag in NUMBER_TAGS or (tok.low == "can" and tok.tag != "SHP"):
        return
    nxt = segment[i + 1].low if i + 1 < len(segment) else ""
    if nxt in lx.BALL_COMPOUND_HEADS and (tok.low in lx.SPHERE_WORDS or tok.low.endswith(lx.BALL_SUFFIX)):
        return  # "baseball cap", "ball bearing": not a ball
    if tok.low in lx.VESSEL_WORDS and i and segment[i - 1].low in ("the", "its", "at"):
        return  # "wide at the bowl": a part
    reading.cue_words.add(tok.low)
    if tok.low.endswith(lx.BALL_SUFFIX) and len(tok.low) > len(lx.BALL_SUFFIX):
        reading.cue_words.add(lx.BALL_SUFFIX)  # "softball", "basketball"


def _category(segment: list[Token], i: int, pos: int, reading: Reading) -> tuple[str, str, int] | None:
    """(feature, value, rank) the word at ``i`` states, before negation; None when it states none."""
    tok = segment[i]
    tag = tok.tag
    nxt = segment[i + 1].low if i + 1 < len(segment) else ""
    if tag == "DIM" and tok.low in ("long", "elongated") and pos not in reading.in_dim_chunk:
        if any(t.low == "as" for t in segment[max(0, i - 3) : i]):
            return None  # "twice as long as it is wide": a proportion, not a long shape
        if _in_part_phrase(segment, i, True):
            return None  # "with a long stem", "a long handle": a part is long
        return "shape", "long", 2
    if _ball_compound(tok.low, nxt) and tag not in CATEGORY_TAGS:
        # "a superball", "a softball": a ball, as for the dimensions (rank 0 in a part phrase)
        return "shape", "radial", 0 if _in_part_phrase(segment, i, True) else 2
    if tag in CATEGORY_TAGS:
        feature = CATEGORY_TAGS[tag]
        if feature == "shape":
            shape = _shape(segment, i, nxt)
            return None if shape is None else ("shape", *shape)
        value = lx.TABLES[feature][tok.low]
        rank = _material_rank(segment, i) if feature == "material" else 1
        if feature in ("texture", "fragility") and i >= 1 and segment[i - 1].low in lx.MEDIUM_WORDS:
            value = "medium"
        return feature, value, rank
    if tok.low in lx.MEDIUM_WORDS and nxt:
        if nxt in ("texture", "surface", "roughness", "finish"):
            return "texture", "medium", 1
        if nxt in ("fragility", "fragile", "strength"):
            return "fragility", "medium", 1
    return None


def _ball_compound(word: str, nxt: str) -> bool:
    """A word ending in "ball" ("softball", "superball") that is not a compound head's modifier
    ("baseball cap"): a ball, as the dimension rules read it."""
    return (
        word.isalpha() and word.endswith(lx.BALL_SUFFIX) and len(word) > len(lx.BALL_SUFFIX)
        and nxt not in lx.BALL_COMPOUND_HEADS
    )  # fmt: skip


def _shape(segment: list[Token], i: int, nxt: str) -> tuple[str, int] | None:
    """(shape, priority) of a shape word, 0 in a part phrase or before "of" of a container; None when it
    names something else's shape ("bottle opener", "thin plastic", "a bar of soap")."""
    tok = segment[i]
    value, rank = lx.SHAPE_WORDS[tok.low]
    if nxt in lx.MODIFIED_HEADS and tok.low not in lx.MODIFIED_HEADS:
        return None  # "bottle opener", "pen holder": the shape of something else
    if tok.low == "thin" and i + 1 < len(segment) and segment[i + 1].tag == "MAT":
        return None  # "thin plastic", "thin glass": the wall, not the object's shape
    if nxt == "of" and tok.low in lx.MEASURE_NOUNS:
        return None  # "a bar of soap"
    if (nxt == "of" and tok.low in lx.CONTAINER_NOUNS) or _in_part_phrase(segment, i, True):
        rank = 0  # "a tube of toothpaste", "with a long stem", "in a tin cup"
    return value, rank


def resolve_categories(reading: Reading) -> dict[str, tuple[str, Token]]:
    """Feature -> (value, the token that states it): the highest rank, then the first."""
    out: dict[str, tuple[str, Token]] = {}
    for feature, cands in reading.categories.items():
        best = max(cands, key=lambda c: (c[0], -c[1]))
        _rank, _pos, value, tok = best
        out[feature] = (value, tok)
    return out
