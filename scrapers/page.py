"""One fetched page, decoded and parsed once, shared by every extractor.

:class:`Page` holds the decoded text, the lxml tree (built lazily), the page language and its decimal-mark
convention, the JSON-LD blocks and JSON payloads, and the visible text as :class:`Line` s in document
order, each with its context: inside a package section or not (``id``/``class`` names like
``packaging``, ``verpackung``, ``shipping``) and its parent element (to group a package's fields).

Containers of other products are not read at all: elements whose ``id``/``class`` names a carousel,
slider, comparison, recommendation or "customers also viewed" block (see :data:`FOREIGN_CONTAINER`).
"""

from __future__ import annotations

import json
import re
from bisect import bisect_right
from dataclasses import dataclass
from functools import cached_property, lru_cache
from itertools import accumulate
from typing import Any

from kb.measures.units import units_pattern
from scrapers.encodings import decode_body
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

#: id/class words of blocks that show other products (their sizes must not leak into this product).
FOREIGN_CONTAINER = re.compile(
    r"(?:carousel|swiper|slick|slider|similar|tovsimilar|compar(?:ison|e-table|ison-table)|comparison_table|"
    r"recommend|related|also[-_]?(?:viewed|bought|like)|upsell|up-sell|cross[-_]?sell|sponsor|recently|"
    r"sims[-_]|_sims|fbt|bought[-_]together|reco[-_]|[-_]reco\b|advert|banner)",
    re.IGNORECASE,
)
#: Layout words that often show other products (a slider, a banner) but are also used as styling names of
#: the product's own blocks (``tab-specs accordion banner-margin-small``): such a block is foreign only when
#: its names do not also say it holds the product's specification (:data:`SPEC_CONTAINER`).
_WEAK_FOREIGN = re.compile(r"(?:carousel|swiper|slick|slider|sponsor|advert|banner)", re.IGNORECASE)
#: id/class words of the product's own specification or description blocks.
SPEC_CONTAINER = re.compile(
    r"(?:spec|techn|detail|descri|attribute|propert|merkmal|caracter|характер|feature)", re.IGNORECASE
)
#: A class token naming the product's own specification block (``pdp-product-specs``, ``product-details``).
_OWN_SPEC = re.compile(r"(?:pdp|product)[-_]?(?:spec|techn|detail|descri|attribute|propert|feature)", re.IGNORECASE)
#: id/class words of blocks that describe the package rather than the product.
PACKAGE_CONTAINER = re.compile(
    r"(?:packag|verpack|shipping|versand|embala|emballa|imball|colis|упаков)", re.IGNORECASE
)
#: Class tokens that state a fact about the product, not a box of package values: WooCommerce marks every
#: product's wrapper ``shipping-taxable`` and ``product_shipping_class-…``; shops flag ``free-shipping``.
_PRODUCT_FLAG = re.compile(r"taxable|shipping[_-]class|free[_-]?shipping", re.IGNORECASE)
_DROP_TAGS = frozenset(
    {"script", "style", "noscript", "template", "svg", "head", "iframe", "select", "option"}
)
_NEVER_DROP = frozenset({"html", "body", "main"})
#: A hidden help popup: an element hidden by its own ``style`` whose name says tooltip, popup, popover,
#: hint or info dialog (Alza's ``infoPopup infoDialog`` under each spec label: a sentence of help text
#: between the label and its value). Its text explains a label and is never a value; a hidden element
#: named otherwise (a closed spec tab) is read.
_HIDDEN = re.compile(r"display\s*:\s*none", re.IGNORECASE)
_HELP_POPUP = re.compile(r"tool-?tip|popup|popover|hint|info-?dialog", re.IGNORECASE)
#: Elements that hold what every page of a store shows (a header, footer, navigation, an aside): a size
#: there is a size guide's or a banner's, not the product's. ``header`` and ``footer`` count only outside
#: sectioning content (HTML's rule: inside an ``article`` or ``section`` they are that section's own).
SITE_WIDE_TAGS = frozenset({"header", "footer", "nav", "aside"})
SITE_WIDE_ROLES = frozenset({"banner", "contentinfo", "navigation", "complementary"})
_SECTIONING = frozenset({"article", "section", "main"})
_LD_JSON = re.compile(
    r"<script\b[^>]*\btype\s*=\s*[\"']?application/ld\+json[\"']?[^>]*>(.*?)</script\s*>",
    re.IGNORECASE | re.DOTALL,
)
_WS = re.compile(r"\s+")
#: Only the first this many visible text lines are read. The real pages measured have at most ~1,500
#: (a 1.8 MiB Amazon page); a page with tens of thousands is a catalogue or a spec dump, and walking all
#: of it costs seconds. :attr:`Page.truncated` says when the cap was hit.
MAX_LINES = 12_000


@dataclass(frozen=True)
class Line:
    """One visible text node: its text (spaces collapsed), whether a package block holds it, and the
    identity of its parent element (lines with the same ``group`` sit in the same element)."""

    text: str
    package: bool
    group: int
    index: int
    #: Read in a site-wide block (:data:`SITE_WIDE_TAGS`, :data:`SITE_WIDE_ROLES`): the store's header,
    #: footer, navigation or an aside, outside the product's main content.
    site_wide: bool = False


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
        """Visible text nodes in document order, outside scripts and other products' containers.

        The text nodes that hold more than spaces are found by one XPath (in C); each one's context comes
        from its element's, computed once per element from its parent's (:meth:`_context`)."""
        tree = self.tree
        if tree is None:
            return []
        lines: list[Line] = []
        contexts: dict[Any, tuple[bool, bool, bool, int] | None] = {}
        for text in tree.xpath("//text()[normalize-space()]"):
            owner = text.getparent()
            if owner is None:
                continue
            holder = owner.getparent() if text.is_tail else owner
            if holder is None:
                continue
            context = contexts.get(holder, _UNSEEN)
            if context is _UNSEEN:
                context = self._context(holder, contexts)
            if context is None:
                continue
            if len(lines) >= MAX_LINES:
                self.truncated = True
                break
            _add_line(lines, str(text), context)
        return lines

    @staticmethod
    def _context(el, contexts: dict) -> tuple[bool, bool, bool, int] | None:
        """(package, site-wide, inside sectioning content, group) of the text ``el`` holds, None when it is
        not read (inside a dropped tag or another product's container); memoised in ``contexts``."""
        chain = []
        node = el
        while node is not None and node not in contexts:
            chain.append(node)
            node = node.getparent()
        context = contexts[node] if node is not None else (False, False, False, 0)
        for node in reversed(chain):
            if context is not None:
                tag = node.tag
                if not isinstance(tag, str) or not tag or tag in _DROP_TAGS:
                    context = None  # dropped whatever its names say
                else:
                    foreign, own_package = _container_kind(node.get("id"), node.get("class"))
                    if (foreign and tag not in _NEVER_DROP) or _help_popup(node):
                        context = None
                    else:
                        package, site_wide, sectioned, _ = context
                        if not site_wide and (tag in SITE_WIDE_TAGS or node.get("role") in SITE_WIDE_ROLES):
                            site_wide = tag in ("nav", "aside") or not sectioned or node.get("role") in SITE_WIDE_ROLES
                        context = (package or own_package, site_wide, sectioned or tag in _SECTIONING, len(contexts) + 1)
            contexts[node] = context
        return context

    def site_wide_line(self, index: int) -> bool:
        """Whether visible line ``index`` sits in a site-wide block (False for an index out of range)."""
        lines = self.lines
        return 0 <= index < len(lines) and lines[index].site_wide


_UNSEEN = object()


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


def _help_popup(node) -> bool:
    style = node.get("style")
    if not style or not _HIDDEN.search(style):
        return False
    names = f"{node.get('id') or ''} {node.get('class') or ''}"
    return bool(_HELP_POPUP.search(names))


@lru_cache(maxsize=8192)
def _container_kind(ident: str | None, classes: str | None) -> tuple[bool, bool]:
    """(holds other products, holds package values) for an element's id and class (cached: pages repeat
    the same class strings thousands of times)."""
    names = f"{ident or ''} {classes or ''}".strip()
    if not names:
        return False, False
    foreign = False
    tokens = names.split()
    for token in tokens:
        m = FOREIGN_CONTAINER.search(token)
        if m and not (_WEAK_FOREIGN.fullmatch(m.group(0)) and SPEC_CONTAINER.search(names)):
            # another token naming this product's own specification outranks it (Mouser's spec table
            # is id="FindSimilarPnl" class="pdp-product-specs": "find similar" is a feature of the table)
            foreign = not any(_OWN_SPEC.search(t) and not FOREIGN_CONTAINER.search(t) for t in tokens)
            break
    return foreign, any(PACKAGE_CONTAINER.search(t) and not _PRODUCT_FLAG.search(t) for t in names.split())


#: A measured number with one or two decimals and a unit: ``1,5 kg`` (decimal comma), ``1.5 kg`` (point).
_MEASURED_UNIT = units_pattern("length", "mass")  # the words of the one unit table
_COMMA_DECIMAL = re.compile(rf"(?<![\d.,])\d{{1,4}},\d{{1,2}}\s?(?:{_MEASURED_UNIT}|€)(?![\w])", re.IGNORECASE)
_POINT_DECIMAL = re.compile(rf"(?<![\d.,])\d{{1,4}}\.\d{{1,2}}\s?(?:{_MEASURED_UNIT}|€|\$)(?![\w])", re.IGNORECASE)
#: Lines read for the page's number forms (the specification is near the top; a page is not read twice).
NUMBER_FORM_LINES = 4000


def decimal_mark_of_lines(lines: list[Line]) -> bool | None:
    """True when the visible text writes measured decimals with commas (``1,5 kg``) more often than with
    points (``1.5 kg``), False for the reverse, None on a tie (a number with three decimals, ``1,250``,
    says nothing: it may group thousands)."""
    comma = point = 0
    for line in lines[:NUMBER_FORM_LINES]:
        if "," in line.text:
            comma += len(_COMMA_DECIMAL.findall(line.text))
        if "." in line.text:
            point += len(_POINT_DECIMAL.findall(line.text))
    if comma == point:
        return None
    return comma > point


#: Joins line texts for one scan (:func:`lines_matching`): no pattern given there matches it, so no match
#: spans two lines and ``\b`` sees a line's edge as it sees the edge of a string.
_LINE_JOIN = "\x00"


def lines_matching(lines: list[Line], pattern: re.Pattern) -> set[int]:
    r"""The positions in ``lines`` of the lines ``pattern.search`` matches, found by one scan of their joined
    text (a loop of one search per line costs more on pages of thousands of lines). ``pattern`` must not
    match a NUL character (literal words, ``\s``, ``[^\W\d_]``, ``\b``; no lookbehind, no ``.``, no ``\W``)."""
    if not lines:
        return set()
    texts = [line.text for line in lines]
    starts = list(accumulate((len(t) + 1 for t in texts[:-1]), initial=0))
    return {bisect_right(starts, m.start()) - 1 for m in pattern.finditer(_LINE_JOIN.join(texts))}


def _html_parser():
    from lxml import etree

    return etree.HTMLParser(remove_comments=True, remove_pis=True, no_network=True)


def text_content(el) -> str:
    """All text inside an element, spaces collapsed."""
    return " ".join("".join(el.itertext()).split())


def visible_text(el) -> str:
    """The text inside an element a reader sees: without the text of scripts, styles and the other
    :data:`_DROP_TAGS` inside it; spaces collapsed."""
    parts: list[str] = []

    def walk(node, top: bool) -> None:
        tag = node.tag.lower() if isinstance(node.tag, str) else ""
        if not top and (tag in _DROP_TAGS or not isinstance(node.tag, str)):
            parts.append(node.tail or "")
            return
        parts.append(node.text or "")
        for child in node:
            walk(child, False)
        if not top:
            parts.append(node.tail or "")

    walk(el, True)
    return " ".join("".join(parts).split())


_new = object.__new__


#: A text node of at least this many non-empty lines is a block of lines (a marketplace's description
#: shown with its line breaks, Trendyol's ``Ağırlık 58.0 kg\nDerinlik 49.0 cm\n...``): each line is read
#: as its own; fewer breaks are the markup's indentation (``\n  Výška  \n``, ``4,7\nkg``).
TEXT_BLOCK_LINES = 3


def _add_line(lines: list[Line], text: str, context: tuple[bool, bool, bool, int]) -> None:
    if text.count("\n") >= TEXT_BLOCK_LINES - 1:
        rows = [row for row in text.split("\n") if not row.isspace() and row]
        if len(rows) >= TEXT_BLOCK_LINES:
            for row in rows:
                _add_one(lines, row, context)
            return
    _add_one(lines, text, context)


def _add_one(lines: list[Line], text: str, context: tuple[bool, bool, bool, int]) -> None:
    text = " ".join(text.split())
    if text:
        # Line(text, package, group, index, site_wide) without the frozen dataclass's slow __init__ (one
        # object.__setattr__ per field; pages have thousands of lines): the same fields, the same object
        line = _new(Line)
        line.__dict__.update(text=text, package=context[0], group=context[3], index=len(lines), site_wide=context[1])
        lines.append(line)


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
