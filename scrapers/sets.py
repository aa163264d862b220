"""A set versus one item: how many items a page sells as one (a pack of 12 bowls, a pair of curtains, a
set of four mugs), and whether a value is stated per item.

The catalog object is one item. A page selling a set often states only the set's weight (and sometimes
the set's size), so the chooser (:func:`scrapers.extract.fuse`) keeps a set's mass apart as the set's,
unless its label or text says it is one item's (``Weight per piece``, ``je Stück``, ``1個あたり``), and
warns about its dimensions. :func:`set_size` reads the count from the product's name; ``(Pack of 1)`` is
one item.
"""

from __future__ import annotations

import re

from kb.measures.words import count_words

__all__ = ["MAX_SET", "per_item", "set_apart", "set_size"]

#: Counts above this are not a set of household objects (a "500 pcs" box of screws is sold by the box).
MAX_SET = 1000
#: Count words in the store languages (:data:`kb.measures.words.COUNT_WORDS`, shared with the number reader).
_COUNT_WORDS = count_words()
_N = r"(\d{1,4}|" + "|".join(sorted(_COUNT_WORDS, key=lambda w: (-len(w), w))) + ")"
#: Ways stores write a set in a product name (en, de, fr, es, it, pt, nl, tr, ja, zh).
_SET_PATTERNS = [
    re.compile(p, re.IGNORECASE)
    for p in (
        rf"\b(?:set|pack|box|lot|bundle|case)\s+of\s+{_N}\b",
        rf"\b{_N}[\s-]*(?:pack|pk|pcs?|pieces?|piece|count|ct|teilig|tlg|stück|stk|pièces|piezas|pezzi|peças|"
        rf"stuks|adet|er[\s-]*(?:set|pack|packung)|-?teiliges?)\b",
        rf"\b(?:lot|juego|set|kit|confezione|conjunto)\s+(?:de|di|da)\s+{_N}\b",
        rf"\b{_N}\s*['’](?:li|lı|lu|lü)\b",  # Turkish "4'lü set"
        rf"\b{_N}[\s-]*(?:er|x)\s+set\b",
        r"(\d{1,4})\s*(?:個|枚|本|点|個入|枚入|本入|点入|件|只|个|套)\s*(?:セット|組|入り|入|套装|装)?",
    )
]
_PAIR = re.compile(r"\b(?:a\s+)?pair\s+of\b|\(pair\)|\b\d?\s*paar\b|\bpaire\s+de\b|\bpar\s+de\b|\bçift\b|ペア|一对|一對", re.I)
_ONE = re.compile(r"\((?:pack|set)\s+of\s+1\)|\b1[\s-]*(?:pack|pcs?|piece|count|ct|stück|er[\s-]*pack)\b", re.I)
#: Words saying a value is one item's (in a label or beside the value).
_PER_ITEM = re.compile(
    r"\b(?:each|per\s+(?:item|piece|unit|pc|bowl|mug|plate|glass|panel|curtain)|single|individual|"
    r"je\s+stück|pro\s+stück|einzeln|pièce|l'unité|par\s+pièce|cada\s+uno|por\s+unidad|ciascuno|"
    r"cadauno|adet\s+başı|tanesi)\b|[(（]\s*1\s*(?:個|枚|本|点|pc|pcs|piece|stück|adet)\s*[)）]|1個あたり|1枚あたり|1本あたり|"
    r"単品|单个|每个|每件",
    re.IGNORECASE,
)


def set_size(name: str | None) -> tuple[int, str] | None:
    """(count, the words saying so) when ``name`` sells a set of two or more items, else None."""
    if not name:
        return None
    text = name[:300]
    if _ONE.search(text):
        return None
    for pattern in _SET_PATTERNS:
        for m in pattern.finditer(text):
            raw = m.group(1).lower()
            count = int(raw) if raw.isdigit() else _COUNT_WORDS.get(raw)
            if count and 2 <= count <= MAX_SET:
                return count, m.group(0).strip()
    m = _PAIR.search(text)
    return (2, m.group(0).strip()) if m else None


def per_item(text: str | None) -> bool:
    """Whether ``text`` (a label and its value) says the value is one item's."""
    return bool(text and _PER_ITEM.search(text))


def set_apart(
    chosen: dict, the_set: tuple[int, str] | None, warnings: list[str],
    decisions: list[dict],
) -> float | None:
    """On a page selling a set (:func:`set_size`), the chosen mass is the set's unless its
    text says it is one item's: it is taken from ``chosen`` and returned (the set's mass), with a warning
    and its decision changed. The chosen dimensions stay, with a warning that they may be the set's."""
    if the_set is None:
        return None
    count, words = the_set
    mass_obs, dims_obs = chosen["mass"], chosen["dims"]
    set_mass = None
    if mass_obs is not None and not per_item(mass_obs.raw):
        set_mass, chosen["mass"] = mass_obs.value, None
        warnings.append(
            f"mass: the page sells a set of {count} ({words!r}); {mass_obs.value:g} g is the set's weight, "
            f"not one item's (about {mass_obs.value / count:.4g} g each if the items are alike); not used"
        )
        for d in decisions:
            if d["feature"] == "mass" and d["decision"].startswith("chosen"):
                d["decision"] = f"the set's value (a set of {count}, {words!r}), kept apart"
                d["role"] = "set"
    if dims_obs is not None and not per_item(dims_obs.raw):
        warnings.append(f"dims: the page sells a set of {count} ({words!r}); the size may be the set's, not one item's")
    return set_mass
