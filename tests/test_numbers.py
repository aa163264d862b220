"""The number grammar of descriptions (kb/measures/words.py, digits by kb/measures/numbers.py)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.measures.numbers import digits_value
from kb.measures.words import is_number_token, number_value
from kb.measures.words import parse_number_words as parse_number

CASES = [
    ("15", 15),
    ("7.5", 7.5),
    (".5", 0.5),
    ("7,5", 7.5),  # decimal comma (one or two digits)
    ("12,25", 12.25),
    ("1,000", 1000),  # thousands separator (three digits)
    ("1,250.5", 1250.5),
    ("1/2", 0.5),
    ("3/4", 0.75),
    ("½", 0.5),
    ("7½", 7.5),
    ("7 1/4", 7.25),
    ("7 and 1/2", 7.5),
    ("fifteen", 15),
    ("twenty one", 21),
    ("twenty-one", 21),
    ("ninety nine", 99),
    ("a hundred", 100),
    ("one hundred and five", 105),
    ("a hundred and fifty", 150),
    ("two hundred thirty four", 234),
    ("fifteen hundred", 1500),
    ("one thousand two hundred", 1200),
    ("fifteen and half", 15.5),
    ("fifteen and a half", 15.5),
    ("one and a half", 1.5),
    ("seven and quarter", 7.25),
    ("seven and a quarter", 7.25),
    ("twenty one and half", 21.5),
    ("two and three quarters", 2.75),
    ("three quarters", 0.75),
    ("a quarter", 0.25),
    ("half", 0.5),
    ("a half", 0.5),
    ("one half", 0.5),
    ("half a", 0.5),  # "half a liter"
    ("a dozen", 12),
    ("two dozen", 24),
    ("a couple", 2),
    ("a couple of", 2),
    ("a third", 1 / 3),
    ("a million", 1_000_000),  # scale words: "million" was not a number, so "a million grams" vanished
    ("two million", 2_000_000),
    ("1.5 million", 1_500_000),
    ("two million three hundred thousand", 2_300_000),
    ("a billion", 1_000_000_000),
]


@pytest.mark.parametrize("text", ["million million", "a dozen million", "two million dozen", "a billion million"])
def test_a_scale_word_after_a_scale_or_a_dozen_is_no_number(text: str) -> None:
    assert parse_number(text) is None


@pytest.mark.parametrize(("text", "expected"), CASES)
def test_number_grammar(text: str, expected: float) -> None:
    assert parse_number(text) == pytest.approx(expected)


@pytest.mark.parametrize(
    "text",
    ["three four", "half twenty", "and", "a", "fifteen and", "twenty twenty", "one two", "", "cm", "x"],
)
def test_not_one_number(text: str) -> None:
    assert parse_number(text) is None


def test_number_value_takes_tokens() -> None:
    assert number_value(["fifteen", "and", "half"]) == 15.5
    assert number_value([]) is None


def test_digits_value() -> None:
    assert digits_value("3/0") is None
    assert digits_value("abc") is None
    assert is_number_token("Twenty") and is_number_token("twenty-one") and not is_number_token("cm")


_UNITS = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine"]
_TEENS = ["ten", "eleven", "twelve", "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen",
          "nineteen"]  # fmt: skip
_TENS = ["", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety"]


def _words(n: int, hyphen: bool = False, use_and: bool = False) -> str:
    """English words for 0 <= n < 1_000_000 (independent of the module under test)."""
    if n < 10:
        return _UNITS[n]
    if n < 20:
        return _TEENS[n - 10]
    if n < 100:
        tens, unit = divmod(n, 10)
        if not unit:
            return _TENS[tens]
        return _TENS[tens] + ("-" if hyphen else " ") + _UNITS[unit]
    if n < 1000:
        hundreds, rest = divmod(n, 100)
        head = _UNITS[hundreds] + " hundred"
        if not rest:
            return head
        return head + (" and " if use_and else " ") + _words(rest, hyphen)
    if n >= 1_000_000:
        millions, rest = divmod(n, 1_000_000)
        head = _words(millions, hyphen) + " million"
        return head if not rest else head + " " + _words(rest, hyphen, use_and)
    thousands, rest = divmod(n, 1000)
    head = _words(thousands, hyphen) + " thousand"
    return head if not rest else head + " " + _words(rest, hyphen, use_and)


@given(st.integers(min_value=0, max_value=999_999_999), st.booleans(), st.booleans())
def test_integers_rendered_as_words_parse_back(n: int, hyphen: bool, use_and: bool) -> None:
    assert parse_number(_words(n, hyphen, use_and)) == n


@given(st.integers(min_value=1, max_value=99), st.sampled_from([("half", 0.5), ("quarter", 0.25)]))
def test_whole_and_fraction(n: int, frac: tuple[str, float]) -> None:
    word, value = frac
    assert parse_number(f"{_words(n)} and {word}") == n + value
    assert parse_number(f"{_words(n)} and a {word}") == n + value


@given(st.decimals(min_value=0, max_value=10_000, places=2, allow_nan=False, allow_infinity=False))
def test_decimals_parse_back(d) -> None:
    assert parse_number(str(d)) == pytest.approx(float(d))


@given(st.text(max_size=60))
def test_any_text_is_a_number_or_none(text: str) -> None:
    value = parse_number(text)
    assert value is None or value >= 0


# --- forms gained from the shared reader (kb/measures): what the extractor knew, the parser now reads ---
@pytest.mark.parametrize(
    ("text", "feature", "value"),
    [("it weighs 0,500 kg", "mass_g", 500.0),  # was 500 kg: "0,500" is never five hundred
     ("it weighs 1.250,5 g", "mass_g", 1250.5),  # was 5 g
     ("it weighs 1.000.000 mg", "mass_g", 1000.0),
     ("a box １５ｃｍ long", "a_cm", 15.0),  # full-width digits and unit
     ("a box 15 cmt long", "a_cm", 15.0)],  # the UN/CEFACT code of the one table
)  # fmt: skip
def test_the_parser_reads_the_page_forms(text: str, feature: str, value: float) -> None:
    from recall.parser import parse

    assert parse(text).values()[feature] == pytest.approx(value)


def test_the_parser_does_not_join_metric_and_imperial_units() -> None:
    from recall.parser import parse

    assert parse("it weighs 1 kg 2 lb").values()["mass_g"] == pytest.approx(1000.0)  # was 1907 g
    refused = parse("it weighs 1.5 lb 2 oz").refused
    assert refused and "not a whole number before ounce" in refused[0].reason
    assert parse("it weighs 1 lb 2 oz").values()["mass_g"] == pytest.approx(510.291, rel=1e-4)
