"""How a label's words are written, read apart from what they mean (:mod:`scrapers.labels` decides that):
German, Dutch and Nordic compounds (``Verpackungsgewicht``, ``Schlauchlänge``) split at a known
measurement suffix, and labels written without spaces (zh, ja, ko) read token by token, longest first,
over the tables of :mod:`scrapers.label_vocabulary`.
"""

from __future__ import annotations

import re

from scrapers.label_vocabulary import (
    CJK_TOKEN_LENGTHS,
    CJK_TOKENS,
    COMPOUND_PREFIXES,
    COMPOUND_SUFFIXES,
    KIND_WORDS,
)

__all__ = ["cjk_component", "cjk_kinds", "compound_kind", "has_cjk", "split_compound"]

#: Kana, CJK ideographs, Hangul syllables and jamo: labels written without spaces.
_CJK = re.compile("[\u3040-\u30ff\u4e00-\u9fff\uac00-\ud7af\u1100-\u11ff]")
_SUFFIXES = tuple(COMPOUND_SUFFIXES)


def has_cjk(text: str) -> bool:
    return _CJK.search(text) is not None


def cjk_kinds(squashed: str) -> tuple[list[str], bool] | None:
    """The kinds a label written without spaces names and whether it names a package (``商品パッケージの
    寸法``), when every token is in the table (ASCII order letters ``W×D×H`` skipped); None otherwise."""
    kinds: list[str] = []
    package = False
    i = 0
    while i < len(squashed):
        for n in CJK_TOKEN_LENGTHS:
            hit = CJK_TOKENS.get(squashed[i : i + n])
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
    return kinds, package


def cjk_component(squashed: str) -> tuple[str, str] | None:
    """(kind, part) for a CJK label ending in a measurement token after a part's name (``電源コードの長さ``:
    the cord's length, ``取っ手の高さ``)."""
    for n in CJK_TOKEN_LENGTHS:
        if len(squashed) <= n:
            continue
        hit = CJK_TOKENS.get(squashed[-n:])
        if hit is not None and hit[0] == "kind":
            part = squashed[:-n].rstrip("の的")
            if part and part not in CJK_TOKENS:
                return hit[1], part
    return None


def compound_kind(word: str) -> str | None:
    """The kind a compound's measurement suffix names, whatever its prefix (``schlauchlänge`` -> length)."""
    if not word.endswith(_SUFFIXES):
        return None
    for suffix in COMPOUND_SUFFIXES:
        if word.endswith(suffix) and len(word) > len(suffix) + 2:
            return KIND_WORDS[suffix]
    return None


def split_compound(word: str) -> tuple[str, bool] | None:
    """(kind, whether the prefix names a package) for a compound of a known prefix and a measurement
    suffix (``artikelgewicht``, ``verpackungsgewicht``); None for an unknown prefix."""
    if not word.endswith(_SUFFIXES):
        return None
    for suffix in COMPOUND_SUFFIXES:
        if word.endswith(suffix) and len(word) > len(suffix):
            prefix = word[: -len(suffix)].rstrip("-")
            if prefix in COMPOUND_PREFIXES:
                return KIND_WORDS[suffix], COMPOUND_PREFIXES[prefix]
    return None
