"""The rules of catalog names behind :class:`recall.name_index.NameIndex`: the nouns that say what kind of
thing, not which (:data:`GENERIC_NOUNS`), a name's core without its variant labels (:func:`name_core`) and
its head noun, the name tables built by these rules one name at a time (:func:`tables_by_rules`; the
column-wise build of the same tables for large catalogs is :mod:`recall.name_tables`), the words of a
description that only a catalog name knows (:func:`name_words`) and the rows of the names with a word
(:func:`rows_with_word`).
"""

from __future__ import annotations

import functools
import re
from collections.abc import Sequence
from types import SimpleNamespace

import numpy as np

from kb.kinds import words_of

#: Nouns that say what kind of thing, not which thing: never unknown-noun evidence ("a plastic thing").
GENERIC_NOUNS = frozenset(
    {"thing", "object", "item", "device", "gadget", "tool", "utensil", "implement", "instrument", "piece",
     "chunk", "bit", "strip", "rectangle", "square", "circle", "replica", "fruit", "vegetable", "vessel",
     "container", "package", "case", "toy", "accessory", "appliance", "equipment", "stuff", "product",
     "one", "kind", "sort", "type", "shape", "something", "model", "unit", "set", "pair", "part", "size",
     "cube", "cuboid", "cylinder", "sphere", "disc", "disk", "rod", "slab", "sheet", "block", "lump", "wedge",
     "prism", "orb", "globe", "stick", "tube", "ring", "nugget",
     # what is left of or taken from a thing: a piece of it ("a wooden dowel offcut")
     "offcut", "remnant", "fragment", "shard", "sample", "specimen", "leftover",
     # collective and kind words: what sort of thing, not which ("a piece of clothing", "some cutlery")
     "cutlery", "silverware", "flatware", "crockery", "tableware", "dinnerware", "kitchenware", "cookware",
     "houseware", "stationery", "clothing", "clothes", "garment", "apparel", "footwear", "headwear",
     "electronics", "hardware", "gear", "kit", "supplies", "supply", "produce", "food", "snack", "drink",
     "beverage", "grocery", "groceries", "toiletry", "toiletries", "cosmetic", "packaging", "merchandise",
     "goods", "gift", "present", "souvenir", "decoration", "furniture", "essential", "necessity"}
)  # fmt: skip
#: Trailing words of a catalog name that number or label variants ("wood block 2", "cup no. 3", "ball b").
_VARIANT_WORDS = frozenset({"no", "nr", "num", "number", "version", "variant", "ver", "v"})

__all__ = ["MIN_SUFFIX", "name_core", "tables_by_rules"]

#: Shortest head noun matched as the end of a compound ("spoon" in "teaspoon").
MIN_SUFFIX = 4

def _unit_words() -> frozenset[str]:
    """Unit words that end a store's name after its size ("skillet 26 cm", "bottle 750 ml", "tablet 10
    inch"): the symbols and English words of the one unit table, less those that are household nouns too
    ("measuring cup", "bigfoot")."""
    from kb.measures.units import aliases_of

    words = {w for kind in ("length", "mass", "volume") for w in aliases_of(kind, frozenset({"", "en"}))}
    return frozenset(w for w in words if w.isalpha() and w not in {"cup", "cups", "foot", "feet"})


_UNITS = _unit_words()


def is_variant_label(word: str) -> bool:
    """A trailing word of a name that labels a variant or states its size, not the noun: a number or a word
    with digits ("2", "10x20", "7l"), one letter, "no"/"version", a unit ("cm" in "plate 27 cm")."""
    return len(word) == 1 or word in _VARIANT_WORDS or any(ch.isdigit() for ch in word) or word in _UNITS


def name_core(name: str) -> tuple[str, ...]:
    """The words of a catalog name without what tells variants apart: parentheses ("tennis ball (small)")
    and trailing numbers, sizes or labels ("wood block 2", "cup no. 3", "box b", "plate 27 cm"), so that its head noun is the
    noun ("block", not "2") and the text "a wood block" names every numbered wood block."""
    words = words_of(re.sub(r"\([^)]*\)|\[[^\]]*\]", " ", name)) or words_of(name)
    while len(words) > 1 and is_variant_label(words[-1]):
        words.pop()
    return tuple(words)


def _head(words: tuple[str, ...]) -> str:
    """The head noun of a name: the word before "of" ("bottle of water"), else the last word."""
    if "of" in words[1:]:
        return words[words.index("of", 1) - 1]
    return words[-1]


def tables_by_rules(names, aliases, materials, min_suffix: int) -> SimpleNamespace:
    """The tables built one name at a time (``words_of``, :func:`name_core`, ``_head``): plain dicts."""
    from recall.lexicon import MATERIAL_WORDS

    generic, by_material, phrases, heads, head_materials = {}, {}, {}, {}, {}
    for row, mat in enumerate(materials or ()):
        if mat:
            by_material.setdefault(mat, set()).add(row)
    for row, (name, alias) in enumerate(zip(names, aliases, strict=True)):
        for phrase in (name, *alias):
            words = tuple(words_of(phrase))
            if not words:
                continue
            core = name_core(phrase)
            phrases.setdefault(words, set()).add(row)
            phrases.setdefault(core, set()).add(row)  # "wood block 2" is a "wood block"
            head = _head(core)
            stated = {MATERIAL_WORDS[w] for w in core if w in MATERIAL_WORDS and w != head}
            if (
                len(stated) == 1
                and head in GENERIC_NOUNS
                and all(w in GENERIC_NOUNS or w in MATERIAL_WORDS or w == "of" for w in core)
            ):
                generic[core] = next(iter(stated))
            for key in (head, *(head[cut:] for cut in range(1, len(head) - min_suffix + 1))):
                heads.setdefault(key, set()).add(row)
                known = head_materials.get((key, row), set())
                head_materials[(key, row)] = None if known is None or not stated else known | stated
    return SimpleNamespace(
        phrases=phrases,
        generic=generic,
        by_material=by_material,
        heads=heads,
        head_materials=head_materials,
        vocabulary=frozenset(w for p in phrases for w in p) | frozenset(heads),
        longest=max((len(p) for p in phrases), default=0),
    )

def name_words(words: Sequence[str], vocabulary) -> list[str]:
    """The words of a description that only a catalog name knows: in ``vocabulary`` (the words of the
    catalog's names and aliases) but no word of the parser's lexicon (function, feature, unit, number
    words), no generic noun, of three letters or more ("wasserkocher", "sartén", "caffettiera": a
    store's own name of its object, which the lexicon need not know)."""
    from recall.subject import feature_words

    known = _tagged_words()
    return [
        w
        for w in dict.fromkeys(words)
        if w in vocabulary and len(w) >= 3 and not w.isdigit()
        and w not in known and w not in feature_words() and w not in GENERIC_NOUNS
    ]  # fmt: skip


@functools.cache
def _tagged_words() -> frozenset[str]:
    from recall.lexicon import tag_model

    return frozenset(tag_model())


def rows_with_word(phrases, word: str) -> set[int]:
    """The rows of the names and aliases (``phrases``: word tuples -> rows) that have ``word`` (only for
    a word no whole name or head noun matched). Over CSR phrases (:class:`RowsByKey`, or
    :class:`recall.string_table.KeyRows` read back from a stored index) by a word -> phrases index
    built column-wise at the first such word and kept with the phrases (:class:`WordKeys`: at 1M
    synthetic names ~0.5 s once, then ~0.1 ms a word, against a scan of every phrase in Python,
    ~0.1 s each); a dict of phrases (small catalogs, built by the rules) is scanned."""
    if not hasattr(phrases, "starts"):
        rows: set[int] = set()
        for phrase in phrases:
            if word in phrase:
                rows |= phrases[phrase]
        return rows
    index = phrases.__dict__.get("word_keys")
    if index is None:
        from recall.string_table import SEP, StringTable, WordKeys

        keys = phrases.keys if isinstance(getattr(phrases, "keys", None), StringTable) else None
        if keys is not None:
            text = keys.text
        else:
            text = np.frombuffer("".join(k + chr(SEP) for k in phrases.ids).encode(), np.uint8)
        index = phrases.__dict__.setdefault("word_keys", WordKeys(text))
    found = np.unique(index.keys_of(word))
    starts, rows_of = phrases.starts, phrases.rows
    if len(found) == 1:
        return set(rows_of[starts[found[0]] : starts[found[0] + 1]].tolist())
    lo, hi = starts[found].astype(np.int64), starts[found + 1].astype(np.int64)
    spans = hi - lo
    at = np.repeat(lo - np.cumsum(spans) + spans, spans) + np.arange(int(spans.sum()))
    return set(rows_of[at].tolist())
