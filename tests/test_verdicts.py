"""The rule that judges an extraction against a corpus label (scrapers/verdicts.py): each condition of
"dims right", "mass right" and "invented" on its own, at its boundary. Records and labels written here."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from scrapers.records import ProductRecord
from scrapers.verdicts import TOLERANCE, invented, judge, page_numbers, truth_of, within


def rec(*extents, mass=None, roles=None):
    roles = roles or ["extent"] * len(extents)
    return ProductRecord(name="x", url="u", dims=[{"role": r, "cm": v} for r, v in zip(roles, extents, strict=True)],
                         mass_g=mass)  # fmt: skip


def label(dims=None, mass=None, **extra):
    return {"dims_cm": dims, "mass_g": mass, **extra}


def test_within_is_two_percent_of_the_larger_value_inclusive():
    assert TOLERANCE == 0.02
    assert within(100.0, 98.0) and within(98.0, 100.0)
    assert not within(100.0, 97.9) and not within(97.9, 100.0)


def test_every_stated_extent_found_and_every_extracted_one_stated():
    want = label([30.0, 20.0, 10.0])
    assert judge(rec(10.1, 29.8, 20.0), want).dims_right  # order free, within 2 %
    assert not judge(rec(30.0, 20.0), want).dims_right  # one stated extent missing
    assert not judge(rec(30.0, 20.0, 10.0, 5.0), label([30.0, 20.0, 10.0])).dims_right  # one not stated
    assert not judge(rec(30.0, 20.0, 9.7), want).dims_right  # 3 % off
    assert not judge(None, want).dims_right


def test_a_page_stating_no_extent_must_give_none():
    assert judge(rec(), label(None)).dims_right and judge(None, label(None)).dims_right
    assert not judge(rec(12.0), label(None)).dims_right


def test_a_diameter_may_stand_for_two_equal_label_values_but_not_other_roles():
    want = label([21.5, 7.2, 7.2])
    assert judge(rec(21.5, 7.2, roles=["height", "diameter"]), want).dims_right
    assert not judge(rec(21.5, 7.2, roles=["height", "width"]), want).dims_right
    assert judge(rec(7.2, roles=["diameter"]), label([7.2])).dims_right
    # a diameter stands for at most two values: one extent cannot cover three
    assert not judge(rec(7.2, roles=["diameter"]), label([7.2, 7.2, 7.2])).dims_right


def test_mass_right_within_two_percent_or_both_none():
    assert judge(None, label(None, None)).mass_right
    assert judge(rec(mass=1020.0), label(None, 1000.0)).mass_right
    assert not judge(rec(mass=1021.0), label(None, 1000.0)).mass_right
    assert not judge(rec(mass=500.0), label(None, None)).mass_right
    assert not judge(rec(), label(None, 500.0)).mass_right
    v = judge(rec(mass=5.0), label([1.0], 6.0))
    assert v.problems == ["dims [] != [1.0]", "mass 5.0 != 6.0"]


def test_a_page_that_is_not_a_product_page_states_nothing():
    assert truth_of(label([30.0], 100.0, is_product_page=False)) == ([], None)
    assert truth_of(label([30.0], 100.0)) == ([30.0], 100.0)
    v = judge(rec(30.0, mass=100.0), label([30.0], 100.0, is_product_page=False))
    assert not v.dims_right and not v.mass_right


def test_invented_a_value_the_label_gives_another_thing():
    want = label([30.0], 100.0, package_mass_g=250.0,
                 not_product=[{"whose": "size chart", "dims_cm": [44.0, 40.0]}])  # fmt: skip
    numbers = page_numbers("30 cm 100 g 250 g 44 40")
    assert invented(rec(30.0, mass=100.0), want, numbers) == []
    assert invented(rec(44.0, mass=250.0), want, numbers) == [
        "dims 44: a value the page gives another thing", "mass 250: a value the page gives another thing"]
    assert invented(None, want, numbers) == []


def test_invented_a_value_stated_nowhere_in_any_unit():
    want = label([30.0], None)
    # 12 in = 30.48 cm: stated (in inches); 3 kg = 3000 g: stated (in kg)
    numbers = page_numbers("Width 12 in, weight 3 kg")
    assert invented(rec(30.48, mass=3000.0), want, numbers) == []
    assert invented(rec(77.0), want, numbers) == ["dims 77: stated nowhere on the page"]
    assert invented(rec(mass=1234.0), want, numbers) == ["mass 1234: stated nowhere on the page"]
    # the product's own value is never invented, even when the page text was not given
    assert invented(rec(30.0), want, set()) == []


def test_page_numbers_read_both_decimal_marks_fractions_and_compound_units():
    numbers = page_numbers("3,2 Kg; 1.250 g; 8 1/2 in; ¾ in; 5' 3\"; 1 lb 4 oz; 2 kg 300 g; 1'200 g")
    for n in (3.2, 32.0, 1.25, 1250.0, 8.5, 0.75, 63.0, 20.0, 2300.0, 1200.0):
        assert n in numbers, n


@given(st.decimals(min_value="0.01", max_value="99999", places=2), st.sampled_from([".", ","]))
def test_page_numbers_find_any_decimal_with_either_mark(value, mark):
    text = f"Weight: {str(value).replace('.', mark)} kg"
    assert any(within(float(value), n, 1e-9) for n in page_numbers(text))


def test_a_diameter_beside_an_equal_width_is_one_stated_axis():
    # a round knob's "Width: 13/16"" and "Diameter: 13/16"": the label lists the axis once
    want = label([2.857, 2.064])
    assert judge(rec(2.857, 2.064, 2.064, roles=["depth", "width", "diameter"]), want).dims_right
    # only a diameter collapses, and only onto an equal extent (within 2 %)
    assert not judge(rec(2.857, 2.064, 2.064, roles=["depth", "width", "height"]), want).dims_right
    assert not judge(rec(2.857, 2.064, 2.2, roles=["depth", "width", "diameter"]), want).dims_right
    assert judge(rec(2.857, 2.064, 2.064 * 1.02, roles=["depth", "width", "diameter"]), want).dims_right
    # nothing collapses when the label states all three
    assert judge(rec(62.5, 62.5, 39.1, roles=["width", "diameter", "height"]), label([62.5, 62.5, 39.1])).dims_right
