"""A variant picker's options are choices, never the product's stated size (issue 21's invented values).

Pages here are small HTML written here, each mirroring a layout class many stores use: a size picker of
buttons under a ``Taille`` / ``Size`` label (a development store's mattress base, none chosen), swatches,
``role=option`` and ``role=radio`` lists. An option the page marks chosen (``aria-checked``, a ``selected``
class) is the product's size when its text states one with a unit."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.page import Page
from scrapers.page_lines import _marked_selected, _picker_option


def _read(body: str):
    html = f"<html lang='fr'><head><title>Sommier relaxation</title></head><body><h1>Sommier relaxation</h1>{body}</body></html>"
    try:
        return extract_page(html, "https://shop.example/p/1", "text/html")
    except ExtractionError:
        return None


def _picker(options: list[str], option: str = "<button class='size-item'>{}</button>", label: str = "Taille") -> str:
    return f"<div><span>{label}</span><div class='sizes'>{''.join(option.format(o) for o in options)}</div></div>"


SIZES = ["2x70x190cm", "2x80x200cm", "90x190 cm"]
HEIGHT = "<table><tr><th>Hauteur</th><td>12 cm</td></tr></table>"


@pytest.mark.parametrize(
    "option",
    [
        "<button class='size-item'>{}</button>",  # a button per size
        "<button><span>{}</span></button>",  # the text in an element inside the button
        "<li role='option'>{}</li>",  # a listbox
        "<div role='radio'>{}</div>",  # a radio group
        "<a class='swatch'>{}</a>",  # a swatch list
        "<span class='variant-option'>{}</span>",
    ],
)
def test_a_pickers_first_option_is_no_product_size(option):
    record = _read(_picker(SIZES, option) + HEIGHT)
    assert record is not None and record.dims_cm == (12.0,)
    variants = [c for c in record.candidates if c["feature"] == "dims" and c["role"] == "variant"]
    assert variants and variants[0]["decision"].startswith("not the product's: a variant's value")


def test_the_same_lines_outside_a_picker_stay_the_products_size():
    # the boundary: the same label and values as a table row of one value each (no picker, no list)
    record = _read("<table><tr><th>Taille</th><td>2x70x190cm</td></tr></table>" + HEIGHT)
    assert record is not None and record.dims_cm[:2] == (190.0, 70.0)


def test_a_picker_with_one_size_beside_a_colour_picker_stays_the_products():
    # one option per picker is no choice between sizes: the size is the product's
    record = _read(_picker(["2x70x190cm"]) + _picker(["rouge", "bleu"], label="Couleur"))
    assert record is not None and record.dims_cm[:2] == (190.0, 70.0)


@pytest.mark.parametrize(
    "chosen",
    [
        "<button class='size-item' aria-checked='true'>{}</button>",
        "<button class='size-item selected'>{}</button>",
        "<button class='size-item is-active'>{}</button>",
        "<li role='option' aria-selected='true'>{}</li>",
    ],
)
def test_the_option_marked_chosen_is_the_products_size(chosen):
    options = "<button class='size-item'>2x70x190cm</button>" + chosen.format("2x80x200cm")
    record = _read(f"<div><span>Taille</span><div>{options}</div></div>" + HEIGHT)
    assert record is not None and record.dims_cm[:2] == (200.0, 80.0)
    chosen_rows = [c for c in record.candidates if c["decision"].startswith("chosen")]
    assert chosen_rows[0]["text"].startswith("selected option: 2x80x200cm")


def test_a_chosen_option_without_a_unit_gives_no_size():
    options = "<button class='size-item selected'>80x200</button><button class='size-item'>90x200</button>"
    record = _read(f"<div><span>Taille</span><div>{options}</div></div>" + HEIGHT)
    assert record is not None and record.dims_cm == (12.0,)


def test_lines_carry_their_picker_and_choice():
    page = Page(_picker(["A 1", "B 2"]), "https://s.test/")
    lines = {line.text: line for line in page.lines}
    assert lines["A 1"].picker and lines["A 1"].picker == lines["B 2"].picker
    assert lines["Taille"].picker == 0
    marked = Page("<div><button>A</button><button class='selected'>B</button></div>", "https://s.test/").lines
    assert [(line.text, line.selected) for line in marked] == [("A", False), ("B", True)]


def test_a_first_option_marked_chosen_is_the_pickers_default_state():
    # a configurator checks its first size before anybody chose (two development stores): no size stated
    options = ("<button role='radio' aria-checked='true'>2x70x190cm</button>"
               "<button role='radio' aria-checked='false'>2x80x200cm</button>")  # fmt: skip
    record = _read(f"<div><span>Taille</span><div role='radiogroup'>{options}</div></div>" + HEIGHT)
    assert record is not None and record.dims_cm == (12.0,)
    lines = Page(options, "https://s.test/").lines
    assert [line.selected for line in lines] == [False, False]


@pytest.mark.parametrize(
    ("attrs", "selected"),
    [
        ({"aria-selected": "true"}, True),
        ({"aria-selected": "false"}, False),
        ({"aria-pressed": "TRUE"}, True),
        ({"class": "swatch swatch--selected"}, True),
        ({"class": "swatch is-checked"}, True),
        ({"class": "swatch inactive"}, False),  # a word ending in "active" is not the token
        ({"class": "swatch unselected"}, False),
        ({"checked": ""}, True),
        ({}, False),
    ],
)
def test_marked_selected_at_its_boundary(attrs, selected):
    from lxml import etree

    assert _marked_selected(etree.Element("button", attrs)) is selected


@pytest.mark.parametrize(
    ("tag", "attrs", "option"),
    [
        ("button", {}, True),
        ("li", {"role": "option"}, True),
        ("div", {"role": "radio"}, True),
        ("li", {"role": "listitem"}, False),
        ("a", {"class": "color-swatch"}, True),
        ("div", {"class": "size-item"}, True),
        ("div", {"class": "product-option__value"}, True),
        ("div", {"class": "size-guide"}, False),
        ("div", {"class": "options-panel"}, False),
    ],
)
def test_picker_option_at_its_boundary(tag, attrs, option):
    from lxml import etree

    assert _picker_option(etree.Element(tag, attrs), tag, attrs.get("role")) is option


@given(st.lists(st.sampled_from(["12 cm", "2x70x190cm", "rouge", "80 x 200 cm", "M", "1,5 kg"]), min_size=1, max_size=5))
def test_pickers_never_raise_and_never_give_an_unchosen_options_size(options):
    record = _read(_picker(options))
    if record is not None and len(set(options)) > 1:
        assert not any(c["decision"].startswith("chosen") and c["role"] == "variant" for c in record.candidates)
