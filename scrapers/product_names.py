"""The product's name on a page, under the catalog's name rules (:func:`kb.features.check_name`, the rule
the CSV import and the HTTP API apply: no control character, at most ``MAX_NAME_CHARS`` characters).

A page states its name in several places (JSON-LD, microdata, the title, the heading). Each candidate is
read as text: markup written inside a name (``<script>alert(1)</script> Mug``) is parsed, and script
or style content never enters a name. The first candidate, in the adapters' order, that passes the rules
is the name; one that does not is skipped with its reason, and when none passes, the page's name is
refused with the first reason. Besides the catalog's rules a page name must not hold U+FFFD (bytes the
page's encoding could not decode, or a NUL the HTML parser replaced: a decoding error is never a name)
and must hold at least :data:`MIN_NAME_CHARACTERS` letters or digits (a title of ``x`` names nothing).
"""

from __future__ import annotations

import re

from kb.errors import InvalidFeature
from kb.features import check_name, normalize_name

__all__ = ["MAX_NAME_WORDS", "MIN_NAME_CHARACTERS", "choose_name", "name_problem", "person_name", "plain_name"]

#: Letters or digits a page name needs at least ("x", "-" name nothing; "U2" does).
MIN_NAME_CHARACTERS = 2
#: Words a person's name of a product keeps at most (:func:`person_name`).
MAX_NAME_WORDS = 8
#: Where a store's title leaves the product's name for its keyword list: a bar, a spaced dash, a colon, a
#: comma, a slash, a sentence's end, a bracket.
_NAME_END = re.compile(r"\s[|｜/–—-]\s|[|｜]|:\s|,\s*|\.\s|\s?[(\[]")
_SIGNS = re.compile(r"[®™©℗«»“”\"]")
#: A web address standing for the store in its own title ("Play.com (UK) : ...", "... bei csv-direct.de").
_HOST = r"(?:www\.)?[a-z0-9][a-z0-9-]*(?:\.[a-z0-9-]+)*\.(?:com|net|org|shop|store|eu|co\.uk|com\.br|[a-z]{2})(?![\w.])"
_STORE_FIRST = re.compile(rf"^\s*{_HOST}(?:\s*\([^()]*\))?\s*[|｜:/–—-]\s*", re.IGNORECASE)
_STORE_LAST = re.compile(
    rf"(?:\s*[|｜:/–—-]\s*|\s+(?:bei|at|on|from|chez|su|von|auf)\s+){_HOST}(?:\s*\([^()]*\))?\s*$", re.IGNORECASE
)
_URLISH = re.compile(r"^(?:[a-z][a-z0-9+.-]*://[^/\s]*)?/\S*$", re.IGNORECASE)
_MARKUP = re.compile(r"<\s*/?\s*[a-zA-Z!][^<>]*>")
_HIDDEN = frozenset({"script", "style", "noscript", "template", "head", "iframe"})


def plain_name(text: str) -> str:
    """``text`` with markup removed (script and style content dropped), spaces collapsed."""
    if _MARKUP.search(text):
        text = _visible_text(text)
    return " ".join(text.split())


def _visible_text(markup: str) -> str:
    from lxml import etree, html

    try:
        root = html.fragment_fromstring(markup, create_parent="div")
    except (etree.ParserError, ValueError):
        return _MARKUP.sub(" ", markup)
    parts: list[str] = []

    def walk(el) -> None:
        if isinstance(el.tag, str) and el.tag.lower() in _HIDDEN:
            parts.append(el.tail or "")
            return
        parts.append(el.text or "")
        for child in el:
            walk(child)
        parts.append(el.tail or "")

    walk(root)
    return " ".join("".join(parts).split())


def person_name(title: str) -> str:
    """The product's name as a person reads it from a store's title: the brand and model and what it is, the
    store's keyword list dropped. The title up to where it leaves the name (:data:`_NAME_END`: "ViewSonic
    VX3276-4K-MHD 32 Inch 4K Monitor, IPS Display with HDR10 ..." -> "ViewSonic VX3276-4K-MHD 32 Inch 4K
    Monitor"; "Galaxy Tab S9 FE (Wi-Fi) | Samsung Levant" -> "Galaxy Tab S9 FE"), with the next part joined
    while the name is one word ("Microsoft - Surface Laptop - Copilot+ PC" -> "Microsoft Surface Laptop");
    trademark signs and quotes dropped; the store's own web address before or after the name dropped
    ("Play.com (UK) : Samsung Series 5 ..." -> "Samsung Series 5 ..."; "... Computerbildschirm bei
    csv-direct.de"); at most :data:`MAX_NAME_WORDS` words. A URL or URL path is read
    as the words of its segment with the most words ("/products/sleep-sound-therapy-system" -> "sleep sound
    therapy system").
    The title itself when nothing is left.

    >>> person_name("KÄRCHER Hochdruckreiniger »K 3 Full Control«")
    'KÄRCHER Hochdruckreiniger K 3 Full Control'
    """
    text = " ".join(_SIGNS.sub("", title).split())
    if _URLISH.match(text):
        segments = [s for s in text.split("/")[1:] if s and "." not in s[:1]]
        segment = max(reversed(segments), key=lambda s: len(re.split(r"[-_+]+", s)), default="")
        segment = re.sub(r"\.[a-z0-9]{2,5}$", "", segment, flags=re.IGNORECASE)
        text = " ".join(re.sub(r"[-_+]+", " ", segment).split()) or text
    text = _STORE_LAST.sub("", _STORE_FIRST.sub("", text)) or text  # the store's address names no product
    parts = [p.strip() for p in _NAME_END.split(text)]
    name = ""
    for part in parts:
        if part:
            name = f"{name} {part}".strip()
        if len(name.split()) >= 2:
            break
    name = " ".join(name.split()[:MAX_NAME_WORDS]).rstrip(" -&+")
    return name if sum(ch.isalnum() for ch in name) >= MIN_NAME_CHARACTERS else " ".join(title.split())


def name_problem(name: str) -> str | None:
    """Why ``name`` (as :func:`plain_name` gives it) cannot be the product's catalog name, or None."""
    if "\ufffd" in name:
        return "holds U+FFFD: bytes the page's encoding could not decode (or a NUL byte)"
    try:
        check_name("name", normalize_name(name))
    except InvalidFeature as err:
        return err.reason
    if sum(ch.isalnum() for ch in name) < MIN_NAME_CHARACTERS:
        return f"too short to name a product (fewer than {MIN_NAME_CHARACTERS} letters or digits)"
    return None


def choose_name(candidates: list[tuple[str, str]], warnings: list[str]) -> tuple[str | None, str | None]:
    """The first of ``candidates`` ((source, text), best first) that passes the rules, as plain text, and
    None; or (None, the first candidate's reason) when none passes. Each skipped candidate is a warning."""
    first_problem = None
    for source, text in candidates:
        name = plain_name(text)
        problem = name_problem(name)
        if problem is None:
            return name, None
        first_problem = first_problem or problem
        warnings.append(f"name from {source} refused: {problem} ({name[:60]!r})")
    return None, first_problem
