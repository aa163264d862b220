"""Whether a recall needs the store lookup, and what the description calls the thing to search for.

A recall is looked up (:func:`lookup_reason`) when the catalog cannot answer it: nothing recalled, the
recall's verdict that the object is not in the catalog or nothing is close, a low confidence, a first
match that is not the thing the subject names (:func:`unnamed_subject`), and two cases where the
catalog's match, however close, is a *kind* of the thing while the description names a *product*:

* **A proper name the catalog does not hold** (:func:`proper_name`): a word of the subject phrase the text
  writes with a capital letter ("*Bose* wireless headphones", "a *Keychron* keyboard", "a *Sony Xperia*
  smartphone") that is no word of the catalog's names and aliases and no lexicon noun, feature word or
  colour: a brand, a model or a title. The catalog's "headphones" are headphones, not these.
* **Contents the match does not name** (:func:`unnamed_contents`): "a <container> of <contents>" ("a jar
  of pasta sauce", "a bag of potato chips", "a gallon jug of milk") recalled as an object whose name
  lacks the contents' head noun (the seed's plain "glass jar", a "potato"): the thing sold is the
  contents in their container, and the stores are searched for the contents first
  (:func:`contents_phrase`). A name that holds it ("a can of soda" -> soda can, "a pair of scissors")
  asks nothing.
* **A named match that does not settle the description** (:func:`loose_fit`): the text names the catalog
  object, but its values are not the object's own as a person rounds them: the mean relative error is
  above :data:`scrapers.lookup_store.SETTLED_ERROR` (0.05), the error within which a store's page settles
  a search. A catalog object named by a kind's noun ("frying pan", "coffee mug", "candle") is one product
  of that kind; fitting more loosely, it is a sibling of the one described (another size), as a store's
  page that fits loosely is, and the stores may sell the one described ("a black frying pan, about 23 cm
  across and 5 cm deep" as the seed's 0.23 frying pan, "a handmade stoneware coffee mug, 9 cm tall, 280 g"
  at 0.10, "an unscented pillar candle" at 0.16). Above the plain threshold (PLAIN, 0.30) a store's
  product could not even fit as it does ("a 12 inch cast iron skillet, a bit over 8 pounds" as the frying
  pan, 0.34). Descriptions written from the catalog's own values fit within 0.00-0.03.

The lookup keeps the catalog's match when no store product fits (:mod:`recall.lookup`), so a lookup
asked here costs a search, never a worse answer.
"""

from __future__ import annotations

import re

from recall.engine import GENERIC_NOUNS, RecallResult, subject_phrase

__all__ = [
    "LOOKUP_BELOW_CONFIDENCE",
    "contents_phrase",
    "lookup_reason",
    "loose_fit",
    "phrase_words",
    "proper_name",
    "unnamed_contents",
    "unnamed_subject",
]

#: A recall less confident than this is looked up.
LOOKUP_BELOW_CONFIDENCE = 0.5


def lookup_reason(result: RecallResult, threshold: float = LOOKUP_BELOW_CONFIDENCE, names=None) -> str | None:
    """Why ``result`` needs a lookup, or None when it does not (module docstring). ``names``: the catalog's
    :class:`recall.name_index.NameIndex`, for the proper-name rule (without it that rule is not read)."""
    if not result.matches:
        return "nothing in the catalog was recalled"
    if result.not_in_catalog and result.described is not None:
        return f"the catalog has no {result.described.english} (nearest: {result.best.name})"
    if result.open_set:
        return f"not in the catalog (nearest: {result.best.name}, not a close match)"
    other = unnamed_subject(result)
    if other is not None:
        return f"the recalled {result.best.name} is no {other}, and the text names no catalog object"
    if result.confidence < threshold:
        return f"confidence {result.confidence:.2f} is below {threshold:g}"
    contents = unnamed_contents(result)
    if contents is not None:
        return f"the recalled {result.best.name} does not name what the text says it holds ({contents})"
    name = proper_name(result, names) if names is not None else None
    if name is not None:
        return f"the text names {name}, which the recalled {result.best.name} is not known by"
    loose = loose_fit(result)
    if loose is not None:
        return f"the recalled {result.best.name} fits only loosely ({loose:.2f}): the stores may sell the one described"
    return None


def loose_fit(result: RecallResult) -> float | None:
    """The closeness of the first match when the text names it and it is above the error that settles a
    store's search (:data:`scrapers.lookup_store.SETTLED_ERROR`; module docstring), else None."""
    from scrapers.lookup_store import SETTLED_ERROR

    best = result.best
    if best is None or not best.matched_by_name or result.closeness is None:
        return None
    return result.closeness if result.closeness > SETTLED_ERROR else None


def unnamed_subject(result: RecallResult) -> str | None:
    """The subject's head noun when the recall's first match is another thing: the head is a noun (a
    lexicon noun, or a word that is no feature word, colour or adjective: :func:`recall.openset.noun_like`;
    never a generic noun), the text
    names the match neither by a name or alias nor by a head noun, and neither the noun nor its English
    name is a word of the match's name. "crunchy peanut butter, 1 kg" recalled as the master chef can (a
    coffee can) at confidence 0.93: a butter is no can, so the catalog's match, however close its sizes,
    is evidence of nothing and the stores are asked (issue 22). None otherwise."""

    from recall.names import words_of
    from recall.openset import noun_in, noun_like
    from recall.words import COLOURS, material_words

    best = result.best
    if best is None or best.matched_by_name or best.name_part > 0:
        return None
    text = result.text or ""
    phrase = phrase_words(text, keep_generic=True)
    head = phrase[-1] if phrase else None
    if head is None or head in GENERIC_NOUNS or head in material_words():
        return None  # "a kitchen tool", "a glass object", "paper, 9 by 4 inches": no noun names a thing
    if re.search(rf"\b{re.escape(head)}s?[- ](?:like|shaped|style|sized)\b", text.lower()):
        return None  # "a ball-like fruit": a comparison
    lexicon = noun_in([head]) is not None  # a lexicon noun that is a shade word too: "a tail *light*"
    if not (lexicon or (head not in COLOURS and (noun_like(head) or result.unknown_noun == head))):
        return None
    words = set(words_of(best.name))
    english = words_of(result.described.english)[-1:] if result.described is not None else []
    return None if head in words or any(w in words for w in english) else head


def phrase_words(text: str, keep_generic: bool = False) -> tuple[str, ...]:
    """The subject phrase's words without units and (unless ``keep_generic``) generic nouns: what names
    something to search for. The phrase's head stays when it is a lexicon noun that is a unit word too and
    no number counts it ("a glass *cup*", "a 4 oz *cup*"; not "2 *cups* of flour"): a unit names no object,
    a head always does."""
    from kb.kinds import noun_in
    from kb.measures.aliases import PARSER_LANGUAGES
    from kb.measures.units import unit_table

    units = unit_table(PARSER_LANGUAGES)
    words = subject_phrase(text)
    head = words[-1] if words else None
    if head in units and (noun_in([head]) is None or re.search(rf"\d\s*{re.escape(head)}", text.lower())):
        head = None  # a unit, or a counted one: a quantity
    return tuple(
        w for i, w in enumerate(words)
        if (w not in units or (i == len(words) - 1 and w == head)) and (keep_generic or w not in GENERIC_NOUNS)
    )  # fmt: skip


def contents_phrase(text: str) -> tuple[str, ...]:
    """The words after "of" that follow the subject phrase's head ("a jar of *pasta and pizza sauce*, 280 g",
    "a gallon jug of *whole milk*"), as a subject phrase (units and generic nouns dropped); () when the
    subject is not followed by "of" or what follows names no thing: its head a feature word or material
    ("a ball of smooth *rubber*", "a block of about eight cm *long*") or no noun
    (:func:`recall.unheld.noun_like`)."""
    from recall.subject import feature_words
    from recall.unheld import noun_like
    from recall.words import material_words

    phrase = phrase_words(text, keep_generic=True)
    if not phrase:
        return ()
    m = re.search(rf"\b{re.escape(phrase[-1])}(?:e?s)?\s+of\s+(.*)", text.lower())
    contents = phrase_words(m.group(1)) if m else ()
    if not contents or contents[-1] in feature_words() or contents[-1] in material_words():
        return ()
    return contents if noun_like(contents[-1]) else ()


def unnamed_contents(result: RecallResult) -> str | None:
    """The contents' head noun when the text is "<head> of <contents>" and the recall's first match's name
    holds no word for it (module docstring), else None."""
    from recall.names import words_of

    best = result.best
    contents = contents_phrase(result.text or "")
    if best is None or not contents:
        return None
    return None if contents[-1] in set(words_of(best.name)) else contents[-1]


def proper_name(result: RecallResult, names) -> str | None:
    """The first word of the subject phrase (and of what follows "of") that the text writes with a capital
    letter and that is no word of the catalog's names and aliases (``names.vocabulary``), no lexicon noun,
    feature word, colour or determiner (module docstring), as the text writes it; None when there is none."""
    from kb.kinds import noun_in, singular
    from recall.subject import feature_words
    from recall.words import COLOURS

    text = result.text or ""
    wanted = set(phrase_words(text)) | set(contents_phrase(text))
    known = names.vocabulary | feature_words() | COLOURS | {"a", "an", "the", "this", "that", "my", "our"}
    for m in re.finditer(r"[^\W\d_][\w'\u2019-]*", text):
        word = m.group(0)
        low = singular(word.lower().replace("'", "").replace("\u2019", ""))
        if not any(c.isupper() for c in word) or low not in wanted or low in known or word.lower() in known:
            continue
        if noun_in([low]) is None:
            return word
    return None
