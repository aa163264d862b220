"""Marketplace layouts of the real-page corpus's shard f, each pinned at its boundary with a small page
written here: a description kept as lines of plain text in one text node (Trendyol), a hidden help popup
between a spec label and its value (Alza), and an axis-order hint leading a size value (notebooksbilliger).
"""

from __future__ import annotations

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.page import Page
from scrapers.page_lines import TEXT_BLOCK_LINES
from scrapers.value_forms import PROSE_WORDS, sentence_value


def record(body: str, lang: str = "tr"):
    html = f"<html lang='{lang}'><head><title>Altus Makine</title></head><body><h1>Altus Makine</h1>{body}</body></html>"
    try:
        return extract_page(html.encode(), "https://shop.test/p", "text/html")
    except ExtractionError:
        return None


def line_texts(body: str) -> list[str]:
    return [line.text for line in Page(f"<html><body>{body}</body></html>".encode(), "https://shop.test/p").lines]


# -- a block of lines in one text node ---------------------------------------------------------------


def test_a_text_node_of_several_lines_is_read_line_by_line():
    # Trendyol's description: one <li> whose text is `Label value` lines joined by line breaks
    r = record("<ul><li>Nikel Isıtıcı Var\nAğırlık 58.0 kg\nDerinlik 49.0 cm\nYükseklik 84.0 cm\nGenişlik 60.0 cm</li></ul>")
    assert r is not None and r.mass_g == 58000.0
    assert sorted(d["cm"] for d in r.dims) == [49.0, 60.0, 84.0]


def test_the_boundary_is_three_non_empty_lines():
    assert TEXT_BLOCK_LINES == 3
    assert line_texts("<p>Tambur Var\nAğırlık 58.0 kg\nDerinlik 49.0 cm</p>") == [
        "Tambur Var", "Ağırlık 58.0 kg", "Derinlik 49.0 cm",
    ]
    # two lines are the markup's own line breaks: one line, as before
    assert line_texts("<p>Ağırlık 58.0\nkg</p>") == ["Ağırlık 58.0 kg"]


def test_indentation_breaks_are_not_lines():
    # a label indented over several empty lines stays one line
    assert line_texts("<div>\n    \n   Výška \n   \n</div>") == ["Výška"]


# -- a hidden help popup -----------------------------------------------------------------------------

_ROW = (
    "<div class='row'><div class='name'><a href='/slovnik/sirka'>Šířka</a>"
    "<div class='{cls}' style='{style}'><div class='body'>Šířka spotřebiče v centimetrech. Údaj důležitý pro"
    " zamýšlené umístění pračky. Vrchem plněné pračky jsou užší.</div></div></div>"
    "<span class='value'>59,7 cm</span></div>"
)


def widths(cls: str, style: str) -> list[float]:
    r = record(_ROW.format(cls=cls, style=style) + "<p>Hmotnost: 76,5 kg</p>", lang="cs")
    return [d["cm"] for d in r.dims] if r is not None else []


def test_a_hidden_help_popup_between_label_and_value_is_not_read():
    assert widths("infoPopup infoDialog", "display:none;") == [59.7]
    assert widths("tooltip", "display: none") == [59.7]


def test_a_popup_that_is_shown_or_a_hidden_block_named_otherwise_is_read():
    # the same help sentence visible, or hidden in a block that is no popup (a closed spec tab): read
    assert widths("infoPopup infoDialog", "") == []
    assert widths("tab-content", "display:none;") == []


# -- an axis-order hint before a size ----------------------------------------------------------------


def test_an_order_hint_before_a_size_is_no_sentence():
    assert not sentence_value("(B x H x T) 305 x 17,9 x 196 mm")
    assert not sentence_value("L x W x H 30 x 20 x 10 cm")
    r = record("<table><tr><td>Abmessungen:</td><td>(B x H x T) 305 x 17,9 x 196 mm</td></tr></table>", lang="de")
    assert r is not None and sorted(d["cm"] for d in r.dims) == [1.79, 19.6, 30.5]


def test_a_caption_of_four_words_stays_a_sentence():
    assert PROSE_WORDS == 4
    assert sentence_value("The keyboard sits on 900 x 400 mm")
    assert not sentence_value("The keyboard sits 900 x 400 mm")
