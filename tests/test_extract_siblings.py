"""Label and value in sibling elements with filler between them (scrapers/spec_pairs.py ``_filler``), and
several label/value pairs in one line.

Pages written here, each mirroring a layout class many stores use: a spec row whose label is followed by
an info icon or a tooltip's ``?`` before the value's element, and a value split over elements with
``approx.`` before the number and the unit in its own element."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.spec_pairs import MAX_FILLER_LINES, _filler


def page(body: str) -> str:
    return f"<html lang='en'><head><title>Lamp</title></head><body><h1>Lamp</h1>{body}</body></html>"


def mass_of(body: str):
    try:
        return extract_page(page(body), "https://shop.test/p", "text/html").mass_g
    except ExtractionError:
        return None


def test_an_info_icon_between_label_and_value():
    # layout class: <span>Weight</span><span class=tip>i</span><p>3.2 kg</p> in a grid row
    assert mass_of("<div class='row'><span>Weight</span><span class='tip'>i</span><p>3.2 kg</p></div>") == 3200.0


def test_a_value_split_over_elements_after_approx():
    # layout class: <dd><span>approx.</span> <b>3.2</b> <i>kg</i></dd>
    assert mass_of("<dl><dt>Weight</dt><dd><span>approx.</span> <b>3.2</b> <i>kg</i></dd></dl>") == 3200.0


def test_at_most_three_filler_lines_between_label_and_value():
    assert MAX_FILLER_LINES == 3
    fill3 = "<span>i</span><span>?</span><span>info</span>"
    assert mass_of(f"<div><span>Weight</span>{fill3}<p>3.2 kg</p></div>") == 3200.0
    assert mass_of(f"<div><span>Weight</span>{fill3}<span>more</span><p>3.2 kg</p></div>") is None


def test_filler_is_short_digitless_and_names_no_measurement():
    assert _filler("?") and _filler("i") and _filler("approx.") and _filler("a" * 12)
    assert not _filler("a" * 13)
    assert not _filler("ca. 3")  # a digit: a value, not filler
    assert not _filler("Height")  # a label: the next row
    assert not _filler("Cable length")  # a part's label: another row


@pytest.mark.parametrize("between", ["<span>Height</span>", "<span>" + "a" * 13 + "</span>"])
def test_a_label_or_a_longer_text_between_ends_the_search(between):
    assert mass_of(f"<div><span>Weight</span>{between}<p>3.2 kg</p></div>") is None


@pytest.mark.parametrize("sep", ["; ", ", ", " | "])
def test_several_pairs_on_one_line_keep_each_values_unit(sep):
    # layout class: one bullet or cell listing the axes, "Height: 30 cm; Width: 20 cm; Depth: 10 cm"
    from scrapers.spec_pairs import split_inline

    text = sep.join(["Height: 30 cm", "Width: 20 cm", "Depth: 10 cm"])
    assert [v for _, v, _ in split_inline(text)] == ["30 cm", "20 cm", "10 cm"]
    record = extract_page(page(f"<ul><li>{text}</li></ul>"), "https://shop.test/p", "text/html")
    assert sorted(e["cm"] for e in record.dims) == [10.0, 20.0, 30.0]
