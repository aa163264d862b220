"""How a value and its label are read (issue 21, the reading half): small pages written here, one per
layout class seen on real stores, each pinned at its boundary.

* A value "for" the one size an article comes in (``27 cm (talla One Size)``: Zalando's bag rows; ``taille
  unique``, ``Einheitsgröße``, ``taglia unica``) is the product's; a value for one of several sizes (``71 cm
  (talla M)``) stays a variant's (``scrapers.value_forms.for_one_size``).
* A bound is not the product's extent: a bound word before the figure (``Up to 9.9 cm``: a store's search
  filter under ``Height``, Amazon; ``bis 58,5 cm``, ``jusqu'à``, ``hasta``, ``fino a``, ``até``, ``do``, ``nad``,
  ``tot``, ``upp till``, ``max. 5 kg``, ``最大``) or an open end after it (``30 cm & above``, ``6ft4+``, ``oder
  mehr``, ``以上``, ``이하``) makes it a limit (role capacity), like a comparison sign (``<5ft``); a lower
  bound's "Starting at 2.8 lb" (the lightest configuration) and a bound inside a bracket after the
  product's figure (``120 cm (max. 140 cm)``) do not (``scrapers.value_forms.bound_value``).
* A header row names each column once: a label written twice (a review form's ``Height`` legend over its
  ``Height`` title, then the brackets ``<5ft (152cm)``, ``5ft-5ft3 (153cm-162cm)``: Gymshark) is no header
  row, and its brackets are a list, not the product's (``scrapers.spec_pairs._header_row``).
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.value_forms import bound_value, for_one_size

SIZE_WORDS = ["size", "talla", "taille", "taglia", "Größe", "tamanho", "maat", "rozmiar", "beden", "storlek"]
ONE_SIZE = ["One Size", "one-size", "Onesize", "OS", "unique", "única", "unica", "único", "Uni", "universal",
            "uniwersalny", "univerzální", "Free Size", "Einheitsgröße", "Tek Ebat"]  # fmt: skip
SIZES = ["M", "XS", "XXL", "S/M", "38", "40", "122", "3XL"]


def _rows(*rows: tuple[str, str]) -> str:
    cells = "".join(f"<div><span>{label}</span><span>{value}</span></div>" for label, value in rows)
    return (f"<html lang='es'><head><title>Mochila - dark red</title></head><body><h1>Mochila - dark red</h1>"
            f"<div class='details'>{cells}</div></body></html>")  # fmt: skip


def test_values_for_the_only_size_are_the_products():
    rows = [("Altura:", "27 cm (talla One Size)"), ("Largo:", "19 cm (talla One Size)"),
            ("Ancho:", "8.5 cm (talla One Size)")]  # fmt: skip
    assert extract_page(_rows(*rows), "https://shop.example/p").dims_cm == (27.0, 19.0, 8.5)


def test_values_for_one_of_several_sizes_stay_a_variants():
    rows = [("Altura:", "27 cm (talla M)"), ("Largo:", "19 cm (talla M)"), ("Peso:", "180 g")]
    record = extract_page(_rows(*rows), "https://shop.example/p")
    assert record.dims_cm is None and record.mass_g == 180.0


@given(st.sampled_from(SIZE_WORDS), st.sampled_from(ONE_SIZE), st.floats(0.5, 300), st.booleans())
def test_a_one_size_name_after_the_size_word_keeps_the_value_the_products(word, name, number, bracket):
    value = f"{number:.1f} cm ({word} {name})" if bracket else f"{number:.1f} cm in {word} {name}"
    assert not for_one_size(value)


@given(st.sampled_from(SIZE_WORDS), st.sampled_from(SIZES), st.floats(0.5, 300), st.booleans())
def test_a_named_size_makes_the_value_a_variants(word, size, number, bracket):
    value = f"{number:.1f} cm ({word} {size})" if bracket else f"{number:.1f} cm in {word} {size}"
    assert for_one_size(value)


BOUND_BEFORE = ["Up to", "up to", "bis", "bis zu", "höchstens", "unter", "über", "jusqu'à", "moins de", "hasta",
                "menos de", "fino a", "oltre", "até", "tot", "maximaal", "do", "nad", "poniżej", "až", "upp till",
                "opptil", "op til", "max.", "Max", "max", "máx.", "maks.", "min.", "at least", "最大", "최대"]  # fmt: skip
BOUND_AFTER = ["& above", "and above", "and over", "+", "oder mehr", "und mehr", "et plus", "o más", "e oltre",
               "ou mais", "i więcej", "en meer", "och mer", "以上", "以下", "이상", "이하"]  # fmt: skip
UNITS = ["cm", "mm", "kg", "g", "in", "lb", "Zoll", ""]


@given(st.sampled_from(BOUND_BEFORE), st.floats(0.1, 400), st.sampled_from(UNITS), st.booleans())
def test_a_bound_word_before_the_figure_is_a_bound(word, number, unit, dot_space):
    value = f"{word}{' ' if dot_space or not word.isascii() else ''}{number:.1f} {unit}".strip()
    assert bound_value(value)


@given(st.floats(0.1, 400), st.sampled_from(UNITS), st.sampled_from(BOUND_AFTER))
def test_an_open_end_after_the_figure_is_a_bound(number, unit, end):
    assert bound_value(f"{number:.1f} {unit} {end}".replace("  ", " "))


@given(st.floats(0.1, 400), st.sampled_from(UNITS),
       st.sampled_from(["", " (max. 140 cm)", " x 20 x 10 cm", " + 2 cm", ", for rooms of 20 m2 and more"]))
def test_a_plain_figure_is_no_bound(number, unit, tail):
    assert not bound_value(f"{number:.1f} {unit}{tail}")


@pytest.mark.parametrize("value", ["Starting at 2.8 lb (1.27 kg)", "ca. 30 cm", "Mini 30 cm", "Maxi 2 kg",
                                   "Overall: 30 cm", "3 Stück à 30 cm", "10 to 19.9 cm"])  # fmt: skip
def test_words_that_are_not_bounds(value):
    assert not bound_value(value)


def _filter_page(rows: str, extra: str = "") -> str:
    return (f"<html lang='en'><head><title>Wall Lamp</title></head><body><h1>Wall Lamp</h1>{rows}{extra}"
            f"</body></html>")  # fmt: skip


FACETS = ("<div><span>Height</span></div><ul><li>Up to 9.9 cm</li><li>10 to 19.9 cm</li><li>20 to 29.9 cm</li>"
          "<li>30 cm &amp; above</li></ul>")  # fmt: skip


def test_a_search_filters_buckets_are_not_the_products_size():
    with pytest.raises(ExtractionError):
        extract_page(_filter_page(FACETS), "https://shop.example/p")
    spec = "<table><tr><th>Product Dimensions</th><td>18L x 25W x 24H Centimeters</td></tr></table>"
    assert extract_page(_filter_page(FACETS, spec), "https://shop.example/p").dims_cm == (25.0, 24.0, 18.0)


@pytest.mark.parametrize("value, dims", [("Up to 9.9 cm", None), ("9.9 cm", (9.9,)), ("bis 30 cm", None),
                                         ("30 cm", (30.0,)), ("120 cm (max. 140 cm)", (120.0,))])  # fmt: skip
def test_a_labelled_bound_is_not_the_products_extent(value, dims):
    html = _filter_page(f"<dl><dt>Height</dt><dd>{value}</dd><dt>Weight</dt><dd>2 kg</dd></dl>")
    assert extract_page(html, "https://shop.example/p").dims_cm == dims


REVIEW_FORM = ("<fieldset><legend>Height</legend><label>Height</label><ul><li>&lt;5ft (152cm)</li>"
               "<li>5ft-5ft3 (153cm-162cm)</li><li>5ft4-5ft7 (163cm-172cm)</li><li>6ft4+(193cm)</li></ul></fieldset>")


def test_a_review_forms_height_brackets_are_not_the_products():
    with pytest.raises(ExtractionError):
        extract_page(_filter_page(REVIEW_FORM), "https://shop.example/shirt")


def test_a_header_row_of_distinct_labels_still_pairs_with_the_row_under_it():
    # the boundary: the same layout with two different labels is a header row over its values
    html = _filter_page("<div>Height</div><div>Width</div><div>153 cm</div><div>60 cm</div>")
    assert extract_page(html, "https://shop.example/p").dims_cm == (153.0, 60.0)
