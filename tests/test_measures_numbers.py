"""The one number reader (kb/measures/numbers.py, words.py, text.py), read by the description parser and the
extractor alike: round-trips of numbers formatted in each form, the decimal-mark rule at its boundaries,
fractions, refusals, and the same reading on both sides."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kb.features import MAX_DIM_CM, MAX_MASS_G
from kb.measures.numbers import digits_value, fold_width, format_decimal, parse_number
from kb.measures.text import clean_text
from kb.measures.units import unit_table
from recall.parser import parse
from scrapers.normalize import check_dims, check_mass
from scrapers.quantities import parse_dims, parse_length, parse_mass

_DC = st.sampled_from([None, True, False])


def _grouped(whole: int, sep: str) -> str:
    return f"{whole:,}".replace(",", sep)


# ----------------------------------------------------------------------------- digits, each form
@settings(max_examples=300, deadline=None)
@given(st.integers(0, 10**9), st.integers(0, 99), _DC)
def test_grouped_thousands_with_a_decimal_round_trip_in_any_locale(whole: int, cents: int, dc) -> None:
    value = whole + cents / 100
    point = f"{_grouped(whole, ',')}.{cents:02d}"  # 1,234,567.89
    comma = f"{_grouped(whole, '.')},{cents:02d}"  # 1.234.567,89
    assert parse_number(point, dc) == pytest.approx(value)
    assert parse_number(comma, dc) == pytest.approx(value)
    assert digits_value(point, dc) == pytest.approx(value)


@settings(max_examples=300, deadline=None)
@given(st.integers(1, 10**6), st.integers(1, 99), _DC)
def test_one_or_two_decimals_after_a_comma_are_decimals_in_any_locale(whole: int, frac: int, dc) -> None:
    digits = str(frac) if frac % 10 or frac < 10 else str(frac // 10)
    assert parse_number(f"{whole},{digits}", dc) == pytest.approx(float(f"{whole}.{digits}"))


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 999), st.integers(0, 999))
def test_a_comma_before_three_digits_follows_the_locale(whole: int, three: int) -> None:
    text = f"{whole},{three:03d}"
    assert parse_number(text, True) == pytest.approx(whole + three / 1000)  # a decimal-comma page
    assert parse_number(text, False) == whole * 1000 + three  # a decimal-point page
    assert parse_number(text, None) == whole * 1000 + three  # unknown, as the parser's descriptions
    assert parse_number(f"0,{three:03d}", None) == pytest.approx(three / 1000)  # "0,500": never 500


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 999), st.integers(0, 999))
def test_a_dot_before_three_digits_groups_only_in_a_decimal_comma_locale(whole: int, three: int) -> None:
    text = f"{whole}.{three:03d}"
    assert parse_number(text, True) == whole * 1000 + three
    assert parse_number(text, False) == pytest.approx(whole + three / 1000)
    assert parse_number(text, None) == pytest.approx(whole + three / 1000)
    assert parse_number(f"0.{three:03d}", True) == pytest.approx(three / 1000)


def test_the_locale_rule_at_its_boundaries() -> None:
    assert parse_number("1,23", None) == 1.23 and parse_number("1,2345", None) == 1.2345  # not three digits
    assert parse_number("1,234", None) == 1234 and parse_number("1,234", True) == 1.234  # exactly three
    assert parse_number("1,234,567", True) == 1234567  # two groups are never decimals
    assert parse_number("1,23,456", None) is None  # a malformed grouping is not a number
    assert parse_number(".5") == 0.5 and parse_number("") is None and parse_number("1.2.3") is None


@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=1e-6, max_value=1e300, allow_nan=False))
def test_scientific_notation_round_trips(value: float) -> None:
    assert digits_value(f"{value:e}") == pytest.approx(float(f"{value:e}"))


def test_too_large_numbers_are_inf_for_the_parser_and_none_for_pages() -> None:
    assert digits_value("9" * 400) == math.inf and digits_value("1e400") == math.inf
    assert parse_number("9" * 400) is None


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 10**6), _DC)
def test_full_width_digits_read_as_ascii(value: int, dc) -> None:
    wide = "".join(chr(ord(c) + 0xFEE0) for c in str(value))
    assert fold_width(wide) == str(value) and len(fold_width(wide + "ｃｍ")) == len(wide) + 2
    assert digits_value(fold_width(wide), dc) == value


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 99), st.sampled_from([2, 4, 8, 16, 32, 64]), st.data())
def test_mixed_fractions_read_alike_on_both_sides(whole: int, den: int, data) -> None:
    num = data.draw(st.integers(1, den - 1))
    sep = data.draw(st.sampled_from([" ", "-"]))
    text = f"{whole}{sep}{num}/{den} inches" if whole else f"{num}/{den} inches"
    expected = (whole + num / den) * 2.54
    assert parse_length(text) == pytest.approx(expected, rel=1e-4), text
    assert parse(f"a box {text} long").values()["a_cm"] == pytest.approx(expected, rel=1e-3), text


def test_fractions_shops_do_not_write_stay_text() -> None:
    assert clean_text("4/5 stars") == "4/5 stars"  # a rating
    assert clean_text("3/3 inch") == "3/3 inch"  # no proper fraction
    assert clean_text("1/128 inch") == "1/128 inch"  # a denominator shops do not write
    assert clean_text("1/64 inch") == "0.015625 inch" and digits_value("1/0") is None


@settings(max_examples=100, deadline=None)
@given(st.integers(1, 99), st.sampled_from(sorted("½¼¾⅓⅔⅛⅜⅝⅞")))
def test_vulgar_fractions_read_alike_on_both_sides(whole: int, char: str) -> None:
    expected = whole + digits_value(char)
    assert parse_length(f"{whole}{char} cm") == pytest.approx(expected, rel=1e-3)
    assert parse(f"a box {whole}{char} cm long").values()["a_cm"] == pytest.approx(expected, rel=1e-3)


def test_format_decimal_never_writes_three_decimals() -> None:
    for value in (1.25, 0.125, 1.5, 2.0, 1 / 3):
        text = format_decimal(value)
        assert "." not in text or len(text.split(".")[1]) != 3
        assert parse_number(text, True) == pytest.approx(value, abs=1e-4)


# ----------------------------------------------------------------------------- the same on both sides
_ONES = "zero one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen sixteen "
_ONES += "seventeen eighteen nineteen"
_TENS = ["", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety"]


def _spelled(n: int) -> str:
    words = _ONES.split()
    if n < 20:
        return words[n]
    return _TENS[n // 10] + ("" if n % 10 == 0 else f"-{words[n % 10]}")


_LENGTH_WORDS = st.sampled_from(["cm", "mm", "inches", "inch", "centimeters", "millimetres", "feet", "meters"])
_MASS_WORDS = st.sampled_from(["g", "kg", "grams", "kilograms", "lb", "lbs", "pounds", "ounces", "oz"])


def _form(value: float, form: str) -> str:
    if form == "point":
        return format_decimal(value)
    if form == "comma":
        return format_decimal(value).replace(".", ",")
    if form == "wide":
        return "".join(chr(ord(c) + 0xFEE0) if c.isdigit() else c for c in format_decimal(value))
    return _spelled(int(value)) + (" and a half" if value % 1 else "")


_VALUE = st.integers(1, 99).flatmap(lambda n: st.sampled_from([float(n), n + 0.5, n + 0.25]))
_FORMS = st.sampled_from(["point", "comma", "wide", "words"])


@settings(max_examples=300, deadline=None)
@given(_VALUE, _LENGTH_WORDS, _FORMS)
def test_a_length_reads_the_same_in_the_parser_and_the_extractor(value: float, word: str, form: str) -> None:
    if form == "words" and value % 1 not in (0, 0.5):
        value = float(int(value))
    cm = value * unit_table()[word].factor
    if cm > MAX_DIM_CM:
        return
    text = f"{_form(value, form)} {word}"
    assert parse_length(text) == pytest.approx(cm, rel=1e-4), text
    assert parse(f"a box {text} long").values()["a_cm"] == pytest.approx(cm, rel=1e-3), text


@settings(max_examples=300, deadline=None)
@given(_VALUE, _MASS_WORDS, _FORMS)
def test_a_mass_reads_the_same_in_the_parser_and_the_extractor(value: float, word: str, form: str) -> None:
    if form == "words" and (value % 1 not in (0, 0.5) or len(word) < 2):
        value, form = float(int(value)), "point"  # spelled numbers are read before unit words, not symbols
    grams = value * unit_table()[word].factor
    text = f"{_form(value, form)} {word}"
    assert parse_mass(text) == pytest.approx(grams, rel=1e-4), text
    assert parse(f"it weighs {text}").values()["mass_g"] == pytest.approx(grams, rel=1e-3), text


# ----------------------------------------------------------------------------- refusals, with reasons
@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=0.01, max_value=5000.0).map(lambda v: round(v, 2)), st.sampled_from(["cm", "mm", "in"]))
def test_both_sides_refuse_an_absurd_length_with_a_reason(value: float, word: str) -> None:
    cm = parse_length(f"{format_decimal(value)} {word}")
    assert cm == pytest.approx(value * unit_table()[word].factor, rel=1e-6)
    page = check_dims([cm])
    description = parse(f"a box {format_decimal(value)} {word} tall")  # a length past 5 m: a long thing's
    if cm > MAX_DIM_CM:
        assert page is not None and "absurd" in page
        assert "a_cm" not in description.features and "absurd" in description.refused[0].reason
    else:
        assert page is None and description.values()["a_cm"] == pytest.approx(cm, rel=1e-3)


def test_the_limits_are_pinned_on_both_sides() -> None:
    assert check_dims([parse_length("500 cm")]) is None and parse("a pole 500 cm long").values()["a_cm"] == 500
    assert "absurd" in check_dims([parse_length("500.01 cm")])
    assert "a_cm" not in parse("a pole 500.01 cm wide").features
    # a length in its own words up to 100 m is a long flexible thing's: at least the limit, no refusal
    long = parse("a pole 500.01 cm long").features["a_cm"]
    assert (long.value, long.qualifier) == (MAX_DIM_CM, "at_least")
    assert check_mass(parse_mass("500 kg")) is None and parse("it weighs 500 kg").values()["mass_g"] == MAX_MASS_G
    assert "absurd" in check_mass(parse_mass("500.001 kg"))
    assert "absurd" in parse("it weighs 500.001 kg").refused[0].reason


@settings(max_examples=100, deadline=None)
@given(st.integers(1, 400), st.sampled_from(["cm", "kg", "g", "inches"]))
def test_a_negative_value_is_refused_by_the_parser_and_never_read_as_negative(value: int, word: str) -> None:
    parsed = parse(f"it is -{value} {word}")
    assert not any(k in parsed.features for k in ("a_cm", "mass_g"))
    assert parsed.refused and parsed.refused[0].reason.startswith("negative")
    # a page's "-" glued to the number is a sign: the reader keeps it, and the limits refuse the value
    found = parse_length(f"-{value} {word}") or parse_mass(f"-{value} {word}")
    assert found is not None and found < 0
    assert "not positive" in (check_dims([found]) if word in ("cm", "inches") else check_mass(found))


def test_zero_is_refused_on_both_sides() -> None:
    assert parse_length("0 cm") is None and parse_mass("0 g") is None and parse_dims("0 x 10 x 5 cm") == []
    assert parse("a box 0 cm long").refused[0].reason.startswith("zero")


@pytest.mark.parametrize("text", ["1e308 cm", "2.5e1 cm", "1e3 cm", "2.5E+1 cm", "3e-1 m", "1e-2 kg", "1E3 g"])
def test_a_page_value_in_scientific_notation_is_not_read_as_one_of_its_parts(text: str) -> None:
    # "1e308 cm" was read as 308 cm and "2.5e1 cm" as 1 cm (found by a blind test): no digits of it are read
    assert parse_length(text) is None and parse_mass(text) is None


@pytest.mark.parametrize("text,value", [("12.5cm", 12.5), ("E 12 cm", 12.0), ("12 cm e", 12.0)])
def test_an_e_that_is_no_exponent_leaves_the_number_alone(text: str, value: float) -> None:
    assert parse_length(text) == pytest.approx(value)
