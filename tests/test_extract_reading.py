"""How a value and its label are read (issue 21, the reading half): small pages written here, one per
layout class seen on real stores, each pinned at its boundary.

* A value "for" the one size an article comes in (``27 cm (talla One Size)``: Zalando's bag rows; ``taille
  unique``, ``Einheitsgröße``, ``taglia unica``) is the product's; a value for one of several sizes (``71 cm
  (talla M)``) stays a variant's (``scrapers.value_forms.for_one_size``).
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from scrapers.extract import extract_page
from scrapers.value_forms import for_one_size

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
