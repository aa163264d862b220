"""A field bar (``|``, ``•``, ``·``) between inline spec fields starts a new field: the words after it are the
whole label, so a part named there ("| lens height: 42mm") stays the part's, not the product's.

Layout class from real development-store pages (an eyewear store's bullet line "Lens width: 70mm | lens
height: 42mm"), pinned here on lines written for the rule.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from scrapers.spec_pairs import split_inline


def fields(text: str) -> list[tuple[str, str, str, str | None]]:
    return [(label, value, info.role, info.kind) for label, value, info in split_inline(text)]


@pytest.mark.parametrize("bar", ["|", "•", "·"])
def test_a_part_named_after_a_bar_is_the_parts(bar):
    got = fields(f"Lens width: 70mm {bar} lens height: 42mm")
    assert got == [("Lens width", "70mm", "component", "width"), ("lens height", "42mm", "component", "height")]


@pytest.mark.parametrize("bar", ["|", "•", "·"])
def test_product_fields_after_a_bar_stay_the_products(bar):
    got = fields(f"Weight: 2 kg {bar} Height: 30 cm")
    assert got == [("Weight", "2 kg", "product", "weight"), ("Height", "30 cm", "product", "height")]


def test_a_value_keeps_none_of_the_bar():
    assert [v for _, v, _ in split_inline("Size: 10 cm • Weight: 200 g •")] == ["10 cm", "200 g"]


def test_a_bar_before_the_first_field_changes_nothing():
    assert fields("| Weight: 2 kg") == [("| Weight", "2 kg", "product", "weight")]


def test_without_a_bar_the_label_is_still_the_last_words():
    # no bar: "... 70mm lens height: 42mm" keeps the shortest label that classifies ("height"), as before
    got = fields("Lens width: 70mm lens height: 42mm")
    assert got[0][2] == "component" and got[1][3] == "height"


@given(st.lists(st.sampled_from(["Weight: 2 kg", "Height: 30 cm", "Width: 20 cm", "Lens width: 5 cm"]),
                min_size=1, max_size=5), st.sampled_from([" | ", " • ", " · "]))
def test_every_field_of_a_barred_line_is_read_once_with_its_own_value(parts, bar):
    got = split_inline(bar.join(parts))
    assert [f"{label}: {value}" for label, value, _ in got] == parts
