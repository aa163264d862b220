"""The visible text of a page as :class:`Line` s, in document order, each with its context.

:func:`visible_lines` walks the lxml tree once: text outside scripts, styles and other dropped tags and
outside containers of other products (elements whose ``id``/``class`` names a carousel, slider,
comparison, recommendation or "customers also viewed" block: :data:`FOREIGN_CONTAINER`) and hidden help
popups; each line says whether a package block holds it (``packaging``, ``verpackung``, ``shipping``:
:data:`PACKAGE_CONTAINER`), whether it sits in a site-wide block (header, footer, nav, aside) and which
element it sits in (``group``). Also the readers of lines that need no tree: the page's decimal mark from
its number forms (:func:`decimal_mark_of_lines`) and one scan for the lines a pattern matches
(:func:`lines_matching`).
"""

from __future__ import annotations

import re
from bisect import bisect_right
from dataclasses import dataclass
from functools import lru_cache
from itertools import accumulate
from typing import Any

from kb.measures.units import units_pattern

__all__ = [
    "FOREIGN_CONTAINER",
    "MAX_LINES",
    "PACKAGE_CONTAINER",
    "TEXT_BLOCK_LINES",
    "Line",
    "decimal_mark_of_lines",
    "lines_matching",
    "text_content",
    "visible_lines",
    "visible_text",
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
    #: Read inside one option of a variant picker (:func:`_picker_option`): the ``group`` of the element
    #: holding the picker's options (lines of one picker share it), 0 outside any picker.
    picker: int = 0
    #: Inside a picker option the page marks as chosen (:func:`_marked_selected`), other than its first
    #: (a first option checked is the picker's default state: :func:`_first_option`).
    selected: bool = False


def visible_lines(tree) -> tuple[list[Line], bool]:
    """The visible text nodes of ``tree`` in document order, outside scripts and other products'
    containers, and whether the walk stopped at :data:`MAX_LINES`.

    The text nodes that hold more than spaces are found by one XPath (in C); each one's context comes
    from its element's, computed once per element from its parent's (:func:`_context`)."""
    lines: list[Line] = []
    contexts: dict[Any, Context | None] = {}
    for text in tree.xpath("//text()[normalize-space()]"):
        owner = text.getparent()
        if owner is None:
            continue
        holder = owner.getparent() if text.is_tail else owner
        if holder is None:
            continue
        context = contexts.get(holder, _UNSEEN)
        if context is _UNSEEN:
            context = _context(holder, contexts)
        if context is None:
            continue
        if len(lines) >= MAX_LINES:
            return lines, True
        _add_line(lines, str(text), context)
    return lines, False


#: (package, site-wide, inside sectioning content, group, picker, selected): a line's context.
Context = tuple[bool, bool, bool, int, int, bool]
_ROOT: Context = (False, False, False, 0, 0, False)


def _context(el, contexts: dict) -> Context | None:
    """The :data:`Context` of the text ``el`` holds, None when it is not read (inside a dropped tag or
    another product's container); memoised in ``contexts``. An element inside a picker option inherits
    the option's picker (the ``group`` of the option's parent: every option of one picker shares it)."""
    chain = []
    node = el
    while node is not None and node not in contexts:
        chain.append(node)
        node = node.getparent()
    context = contexts[node] if node is not None else _ROOT
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
                    package, site_wide, sectioned, parent, picker, selected = context
                    role = node.get("role")
                    if not site_wide and (tag in SITE_WIDE_TAGS or role in SITE_WIDE_ROLES):
                        site_wide = tag in ("nav", "aside") or not sectioned or role in SITE_WIDE_ROLES
                    if not picker and parent and _picker_option(node, tag, role):
                        picker, selected = parent, _marked_selected(node) and not _first_option(node)
                    context = (package or own_package, site_wide, sectioned or tag in _SECTIONING, len(contexts) + 1,
                               picker, selected)  # fmt: skip
        contexts[node] = context
    return context


_UNSEEN = object()
#: Roles of one choice among several (WAI-ARIA): a listbox's ``option``, a radio group's ``radio``.
_OPTION_ROLES = frozenset({"option", "radio", "menuitemradio"})
#: A class token naming one swatch or option of a variant picker (``swatch``, ``size-item``,
#: ``variant-option``, ``product-option__value``).
_OPTION_CLASS = re.compile(r"swatch|(?:size|variant|option)[-_]+(?:item|option|value|button|btn)\b|"
                           r"(?:variant|option)[-_]+(?:value|item)s?$", re.IGNORECASE)  # fmt: skip
#: Attributes and class tokens a page marks its chosen option with.
_SELECTED_ARIA = ("aria-selected", "aria-checked", "aria-pressed", "aria-current")
_SELECTED_CLASS = re.compile(r"(?:^|[-_])(?:selected|active|checked|current|chosen)$", re.IGNORECASE)


def _picker_option(node, tag: str, role: str | None) -> bool:
    """Whether ``node`` is one option of a variant picker: a ``button``, an element of an option role
    (:data:`_OPTION_ROLES`), or one a class token names a swatch or a picker's option (:data:`_OPTION_CLASS`).
    ``select``'s ``option`` elements are not read as lines at all (:data:`_DROP_TAGS`)."""
    if tag == "button" or role in _OPTION_ROLES:
        return True
    classes = node.get("class")
    return bool(classes) and any(_OPTION_CLASS.search(t) for t in classes.split())


def _first_option(node) -> bool:
    """Whether no option of the same picker comes before ``node``: a first option marked chosen is the
    picker's default state, not a choice (two development stores' configurators check their first size,
    labelled no size of the product's)."""
    return not any(
        isinstance(sib.tag, str) and _picker_option(sib, sib.tag, sib.get("role"))
        for sib in node.itersiblings(preceding=True)
    )


def _marked_selected(node) -> bool:
    """Whether a picker option says it is the chosen one: ``aria-selected`` (``-checked``, ``-pressed``,
    ``-current``) ``true``, a ``selected`` or ``checked`` attribute, or a class token ``selected``,
    ``active``, ``is-checked``, ``swatch--current``..."""
    if any((node.get(a) or "").strip().lower() == "true" for a in _SELECTED_ARIA):
        return True
    if node.get("selected") is not None or node.get("checked") is not None:
        return True
    classes = node.get("class")
    return bool(classes) and any(_SELECTED_CLASS.search(t) for t in classes.split())


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


def _add_line(lines: list[Line], text: str, context: Context) -> None:
    if text.count("\n") >= TEXT_BLOCK_LINES - 1:
        rows = [row for row in text.split("\n") if not row.isspace() and row]
        if len(rows) >= TEXT_BLOCK_LINES:
            for row in rows:
                _add_one(lines, row, context)
            return
    _add_one(lines, text, context)


def _add_one(lines: list[Line], text: str, context: Context) -> None:
    text = " ".join(text.split())
    if text:
        # Line(text, package, group, index, site_wide, picker, selected) without the frozen dataclass's slow
        # __init__ (one object.__setattr__ per field; pages have thousands of lines): the same fields
        line = _new(Line)
        line.__dict__.update(text=text, package=context[0], group=context[3], index=len(lines), site_wide=context[1],
                             picker=context[4], selected=context[5])  # fmt: skip
        lines.append(line)
