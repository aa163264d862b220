"""Page state shipped in scripts: the first object literal of each script (JSON, else a JavaScript object
literal read by chompjs), and the objects of its ``JSON.parse("…")`` calls."""

from __future__ import annotations

import json
import re
from typing import Any

__all__ = ["MAX_PARSED_STRINGS", "MAX_SCRIPT_CHARS", "script_objects"]

#: A JavaScript object literal longer than this is not read (page state of that size is a catalogue).
MAX_SCRIPT_CHARS = 2_000_000


#: State shipped as a JSON string literal (``window.__DATA__ = JSON.parse("{\\"product\\": ...}")``): the
#: object is inside the string, escaped.
_JSON_PARSE = re.compile(r"JSON\.parse\(\s*(?=\")")
MAX_PARSED_STRINGS = 8


def _parsed_strings(body: str, decoder: json.JSONDecoder) -> list[Any]:
    """The objects of a script's ``JSON.parse("…")`` calls (at most :data:`MAX_PARSED_STRINGS`)."""
    out: list[Any] = []
    if "JSON.parse(" not in body:
        return out
    for m in _JSON_PARSE.finditer(body):
        try:
            literal, _ = decoder.raw_decode(body[m.end() : m.end() + MAX_SCRIPT_CHARS])
            obj = json.loads(literal) if isinstance(literal, str) and literal.lstrip()[:1] in "{[" else None
        except (ValueError, RecursionError):
            continue
        if obj is not None:
            out.append(obj)
            if len(out) >= MAX_PARSED_STRINGS:
                break
    return out


def _js_object(text: str) -> Any:
    """The first JavaScript object literal of ``text`` (chompjs), or None."""
    if not any(ch in text[:200] for ch in ":'"):
        return None
    try:
        import chompjs

        obj = chompjs.parse_js_object(text)
    except Exception:  # noqa: BLE001 - chompjs raises ValueError and others on what is not an object
        return None
    return obj if isinstance(obj, (dict, list)) and obj else None


_SCRIPT = re.compile(r"<script\b([^>]*)>(.*?)</script\s*>", re.IGNORECASE | re.DOTALL)

def script_objects(text: str) -> list[Any]:
    """Every script's objects of ``text`` (a page's HTML) but JSON-LD blocks, in page order."""
    payloads = []
    decoder = json.JSONDecoder()
    for m in _SCRIPT.finditer(text):
        attrs, body = m.group(1), m.group(2)
        if "ld+json" in attrs.lower() or len(body) < 20:
            continue
        payloads.extend(_parsed_strings(body, decoder))
        obj = _first_object(body, decoder)
        if obj is not None:
            payloads.append(obj)
    return payloads


#: Empty literals skipped before a script's state object: ``var DBK = window.DBK || {};`` (a namespace's
#: initialiser) comes before ``Data.product = {...}`` in the common JavaScript namespace idiom.
MAX_EMPTY_LITERALS = 4


def _first_object(body: str, decoder: json.JSONDecoder) -> Any:
    """The first non-empty object literal of a script (JSON, else a JavaScript literal), or None. After an
    empty literal (``window.DBK || {}``) the next braces are tried, at most :data:`MAX_EMPTY_LITERALS` more."""
    start = body.find("{")
    after_empty = False
    for _ in range(MAX_EMPTY_LITERALS + 1):
        if start < 0:
            return None
        try:
            obj, end = decoder.raw_decode(body, start)
        except (ValueError, RecursionError):
            obj = _js_object(body[start : start + MAX_SCRIPT_CHARS])
            if obj is not None or not after_empty:
                return obj
            start = body.find("{", start + 1)  # "(function (Data) {": a function body, its first statement next
            continue
        if obj != {}:
            return obj
        after_empty = True
        start = body.find("{", end)
    return None
