"""One fetched page, decoded and parsed once, shared by every extractor.

:class:`Page` holds the decoded text, the lxml tree (built lazily), the page language and its decimal-mark
convention, the JSON-LD blocks and JSON payloads, its title candidates and canonical address, and the
visible text as :class:`~scrapers.page_lines.Line` s in document order, each with its context (a package
block, a site-wide block, its parent element), built by :mod:`scrapers.page_lines`, which also drops the
containers of other products (:data:`~scrapers.page_lines.FOREIGN_CONTAINER`).
"""

from __future__ import annotations

import json
import re
from functools import cached_property
from typing import Any

from scrapers.encodings import decode_body
from scrapers.page_lines import (
    FOREIGN_CONTAINER,
    MAX_LINES,
    PACKAGE_CONTAINER,
    Line,
    decimal_mark_of_lines,
    lines_matching,
    text_content,
    visible_lines,
    visible_text,
)
from scrapers.quantities import decimal_comma_for
from scrapers.script_state import script_objects

__all__ = [
    "FOREIGN_CONTAINER",
    "MAX_LINES",
    "PACKAGE_CONTAINER",
    "Line",
    "Page",
    "decode_body",
    "lines_matching",
    "text_content",
]

_LD_JSON = re.compile(
    r"<script\b[^>]*\btype\s*=\s*[\"']?application/ld\+json[\"']?[^>]*>(.*?)</script\s*>",
    re.IGNORECASE | re.DOTALL,
)
_WS = re.compile(r"\s+")


class Page:
    """A decoded page with its parsed views, each computed on first use."""

    def __init__(self, body: str | bytes, url: str, content_type: str | None = None):
        self.url = url
        self.content_type = (content_type or "").lower()
        self.text = decode_body(body, content_type)
        #: True when :attr:`lines` stopped at :data:`MAX_LINES`.
        self.truncated = False

    @property
    def is_json(self) -> bool:
        head = self.text.lstrip()[:1]
        return "json" in self.content_type or (head in ("{", "[") and "<html" not in self.text[:2000].lower())

    @cached_property
    def json(self) -> Any:
        """The page parsed as JSON (for JSON endpoints), or None."""
        try:
            return json.loads(self.text)
        except (ValueError, RecursionError):
            return None

    @cached_property
    def tree(self):
        """The lxml HTML tree (plain ``lxml.etree`` elements: faster to walk than ``lxml.html``'s), or None
        when the text is not HTML at all."""
        from lxml import etree

        text = re.sub(r"^\s*<\?xml[^>]*\?>", "", self.text)
        if not text.strip():
            return None
        try:
            return etree.fromstring(text, _html_parser())
        except Exception:  # noqa: BLE001 - lxml raises several types on garbage; garbage has no tree
            return None

    @cached_property
    def lang(self) -> str | None:
        tree = self.tree
        if tree is not None:
            lang = tree.get("lang") or tree.get("xml:lang")
            if lang and lang.strip():
                return lang.strip()
            for content in _attributes(tree, (("meta", "property", "og:locale", "content"),
                                              ("meta", "http-equiv", "content-language", "content"))):  # fmt: skip
                if content.strip():
                    return content.strip()
        return None

    @cached_property
    def decimal_comma(self) -> bool | None:
        """Whether the page writes decimal commas, decided from the page itself, never from the host it was
        served from (the same saved page read from 127.0.0.1 reads the same): its declared language
        (``<html lang>``, ``og:locale``, ``content-language``), else a JSON-LD ``inLanguage``, else the
        number forms of its visible text (:func:`decimal_mark_of_lines`); None when nothing says."""
        lang = self.lang or self._jsonld_language()
        if lang:
            return decimal_comma_for(lang, None)
        return decimal_mark_of_lines(self.lines)

    def _jsonld_language(self) -> str | None:
        for data, _ in self.jsonld_blocks:
            for node in data if isinstance(data, list) else [data]:
                lang = node.get("inLanguage") if isinstance(node, dict) else None
                if isinstance(lang, str) and lang.strip():
                    return lang.strip()
        return None

    @cached_property
    def jsonld_blocks(self) -> list[tuple[Any, str | None]]:
        """Each ``application/ld+json`` block parsed on its own: (data, None) or (None, reason)."""
        blocks = []
        for m in _LD_JSON.finditer(self.text):
            blocks.append(_loads_lenient(m.group(1)))
        return blocks

    @cached_property
    def script_payloads(self) -> list[Any]:
        """JSON objects embedded in other scripts (``wf.extend({...})``, ``window.__STATE__ = {...}``,
        ``<script type="application/json">``): the first object literal of each script that parses, as
        JSON, else as a JavaScript object literal (unquoted keys, single quotes, trailing commas:
        ``chompjs``, which reads 316 of the 1,525 object-bearing scripts of the real development pages
        against 239 for JSON alone), and the objects of ``JSON.parse("…")`` calls
        (:mod:`scrapers.script_state`)."""
        return script_objects(self.text)

    @cached_property
    def title(self) -> str | None:
        titles = self.titles
        return titles[0] if titles else None

    @cached_property
    def titles(self) -> list[str]:
        """The page's title candidates, best first (og:title, the product title element, a title-like
        heading, ``<title>``, the first heading), each once; script and style text is never part of one."""
        tree = self.tree
        if tree is None:
            return []
        found: list[str] = []
        for xp in (
            (("meta", "property", "og:title", "content"),),
            "//@id[. = 'productTitle' or . = 'title']/.. | //@itemprop[. = 'name']/..",
            "//h1[contains(@class, 'title') or contains(@class, 'name')]",
            "//title",
            "//h1",
        ):
            for hit in tree.xpath(xp) if isinstance(xp, str) else _attributes(tree, xp):
                text = hit if isinstance(hit, str) else visible_text(hit)
                text = _WS.sub(" ", text).strip()
                if text and text not in found:
                    found.append(text)
                    break
        return found[:5]

    @cached_property
    def canonical_url(self) -> str | None:
        tree = self.tree
        if tree is None:
            return None
        for href in _attributes(tree, (("link", "rel", "canonical", "href"), ("meta", "property", "og:url", "content"))):
            if href.strip():
                return href.strip()
        return None

    @cached_property
    def lines(self) -> list[Line]:
        """Visible text nodes in document order, outside scripts and other products' containers
        (:func:`scrapers.page_lines.visible_lines`)."""
        tree = self.tree
        if tree is None:
            return []
        lines, self.truncated = visible_lines(tree)
        return lines

    def site_wide_line(self, index: int) -> bool:
        """Whether visible line ``index`` sits in a site-wide block (False for an index out of range)."""
        lines = self.lines
        return 0 <= index < len(lines) and lines[index].site_wide


def _attributes(tree, wanted: tuple[tuple[str, str, str, str], ...]) -> list[str]:
    """In document order, attribute ``attr`` of each ``tag`` element whose ``key`` attribute is ``value``, for
    each (tag, key, value, attr) of ``wanted``: the XPath ``//tag[@key='value']/@attr`` (a union of them),
    by lxml's tag iterator (a third of the XPath's time)."""
    found = []
    for el in tree.iter(*dict.fromkeys(tag for tag, _, _, _ in wanted)):
        for tag, key, value, attr in wanted:
            if el.tag == tag and el.get(key) == value and (text := el.get(attr)) is not None:
                found.append(text)
                break
    return found


def _html_parser():
    from lxml import etree

    return etree.HTMLParser(remove_comments=True, remove_pis=True, no_network=True)


def _loads_lenient(text: str) -> tuple[Any, str | None]:
    """JSON-LD text parsed, tolerating HTML comments, CDATA wrappers and trailing commas."""
    cleaned = text.strip()
    cleaned = re.sub(r"^\s*(?:<!--|//\s*<!\[CDATA\[|<!\[CDATA\[)", "", cleaned)
    cleaned = re.sub(r"(?:-->|//\s*\]\]>|\]\]>)\s*$", "", cleaned).strip()
    if not cleaned:
        return None, "empty JSON-LD block"
    try:
        return json.loads(cleaned), None
    except (ValueError, RecursionError):
        pass
    relaxed = re.sub(r",\s*([}\]])", r"\1", cleaned)
    relaxed = re.sub(r"[\x00-\x1f]", " ", relaxed)
    try:
        return json.loads(relaxed), None
    except (ValueError, RecursionError) as err:
        return None, f"malformed JSON-LD block ({str(err)[:80]})"
