"""The extraction shortcuts (lines skipped before any per-line reading, cached key readings, the fast
:class:`~scrapers.page.Line` build) change no output: each is compared with the full reading."""

from __future__ import annotations

from hypothesis import example, given, settings
from hypothesis import strategies as st

from scrapers import spec_pairs
from scrapers.page_lines import Line, _add_line

_WORDS = ["Weight", "Gewicht", "Height", "Width:", "Dimensions (mm)", "Maße in cm", "Max load", "Cable length",
          "Home", "Cart", "About us", "cm", "kg", "mm", "(", ")", ":", "-", "x", "30", "4,7", "1.2", "Wert [mm]",
          "Value (cm)", "Fassungsvermögen", "重量", "サイズ", "H", "W", "|", "•", "Shipping Weight", "Size"]  # fmt: skip
_TEXTS = st.lists(st.sampled_from(_WORDS), min_size=1, max_size=8).map(" ".join)


def _lines(texts: list[str]) -> list[Line]:
    return [Line(t, False, i // 2, i) for i, t in enumerate(texts)]


@settings(max_examples=300, deadline=None)
@given(st.lists(_TEXTS, min_size=1, max_size=12))
@example(["Wert [mm]", "Width", "30"])  # a unit heading without a label over a unitless row
def test_skipping_lines_changes_no_pair(texts):
    lines = _lines(texts)
    fast = spec_pairs.pairs_from_lines(lines)
    original = spec_pairs._reads_nothing
    spec_pairs._reads_nothing = lambda text: False  # every line read in full
    try:
        full = spec_pairs.pairs_from_lines(lines)
    finally:
        spec_pairs._reads_nothing = original
    assert fast == full


def test_a_line_with_a_label_or_a_unit_heading_is_read():
    assert not spec_pairs._reads_nothing("Weight")
    assert not spec_pairs._reads_nothing("Dimensions (mm)")
    assert not spec_pairs._reads_nothing("Max load")  # another's value (classify_other)
    assert not spec_pairs._reads_nothing("Wert [mm]")  # a value column's unit heading
    assert spec_pairs._reads_nothing("Home")
    assert spec_pairs._reads_nothing("Weight " + "x" * 80)  # over 80 characters: no label line


def test_the_fast_line_is_the_dataclass_line():
    lines: list[Line] = []
    _add_line(lines, "  Gewicht \n 4,7 kg ", (True, False, False, 7, 3, True))
    assert lines == [Line("Gewicht 4,7 kg", True, 7, 0, False, 3, True)]
    assert hash(lines[0]) == hash(Line("Gewicht 4,7 kg", True, 7, 0, False, 3, True))


_PROSE = st.lists(st.sampled_from(["made of", "aus", "en", "solid", "oak", "Material", "Materiál", "素材", "2",
                                   " ", "\n", "x", "é", "massivem", "Eiche", "\x00"]), max_size=8).map("".join)  # fmt: skip


@settings(max_examples=300, deadline=None)
@given(st.lists(_PROSE, max_size=10))
def test_one_scan_finds_the_lines_a_search_per_line_finds(texts):
    from scrapers.adapters.spec_table import _MATERIAL_HINT
    from scrapers.adapters.text import _MADE_OF, _SOLID
    from scrapers.page_lines import lines_matching

    lines = _lines(texts)
    for pattern in (_MATERIAL_HINT, _MADE_OF, _SOLID):
        assert lines_matching(lines, pattern) == {i for i, t in enumerate(texts) if pattern.search(t)}


_ELEMENT = st.tuples(
    st.sampled_from(["meta", "link", "div"]),
    st.sampled_from(["property", "rel", "http-equiv"]),
    st.sampled_from(["og:url", "canonical", "og:title", "content-language", "og:locale"]),
    st.sampled_from(["content", "href", "id"]),
)


@settings(max_examples=200, deadline=None)
@given(st.lists(_ELEMENT, max_size=8))
def test_the_tag_iterator_reads_what_the_xpath_reads(elements):
    from scrapers.page import Page, _attributes

    body = "".join(f'<{tag} {key}="{value}" {attr}="v{i}"><{tag} {key}="{value}"></{tag}></{tag}>'
                   for i, (tag, key, value, attr) in enumerate(elements))  # fmt: skip
    tree = Page(f"<html><head></head><body>{body}<p>x</p></body></html>", "https://example.test/").tree
    for xpath, wanted in (
        ("//link[@rel='canonical']/@href | //meta[@property='og:url']/@content",
         (("link", "rel", "canonical", "href"), ("meta", "property", "og:url", "content"))),
        ("//meta[@property='og:locale' or @http-equiv='content-language']/@content",
         (("meta", "property", "og:locale", "content"), ("meta", "http-equiv", "content-language", "content"))),
    ):  # fmt: skip
        assert _attributes(tree, wanted) == [str(v) for v in tree.xpath(xpath)]
