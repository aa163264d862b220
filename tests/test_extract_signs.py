"""A value stated with a minus sign ("Weight: -600 g", "-27 x 27 x 2 cm") is refused with its reason on
every value path, never read as positive (a blind test found the sign dropped); a dash that is a range or
a bullet is not a sign."""

from __future__ import annotations

import json

import pytest

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.quantities import parse_dims, parse_length, parse_mass
from scrapers.signs import minus_before

URL = "http://127.0.0.1:1/p/thing"


@pytest.mark.parametrize(
    "text",
    [
        "-600",
        "Weight: -600",
        "Weight:-600",
        "(-600",
        "=-600",
        "Weight -600",
        "27 x -600",
        "27 × -600",
        "\u2212600",
    ],
)
def test_a_minus_glued_to_a_number_after_a_label_or_at_the_start_is_a_sign(text: str) -> None:
    assert minus_before(text, len(text) - 3)


@pytest.mark.parametrize(
    "text", ["- 600", "10 -600", "10-600", "10 cm -600", '10" -600', "AB-600", "600", "–600"]
)
def test_a_range_dash_a_bullet_a_code_or_an_en_dash_is_no_sign(text: str) -> None:
    assert not minus_before(text, len(text) - 3)


@pytest.mark.parametrize(
    "text,value",
    [("-5 cm", -5.0), ("Length: -5 cm", -5.0), ("5 cm", 5.0), ("- 5 cm", 5.0), ("\u22125 mm", -0.5)],
)
def test_a_length_keeps_its_stated_sign(text: str, value: float) -> None:
    assert parse_length(text) == pytest.approx(value)


@pytest.mark.parametrize(
    "text,grams",
    [("-600 g", -600.0), ("Weight: -0.6 kg", -600.0), ("-1 lb 2 oz", -510.291416), ("- 600 g", 600.0)],
)
def test_a_mass_keeps_its_stated_sign(text: str, grams: float) -> None:
    assert parse_mass(text) == pytest.approx(grams)


def test_a_range_is_still_no_negative_value() -> None:
    assert parse_length("10 -20 cm") is None and parse_length("10 cm -20 cm") is None
    assert parse_mass("2 lb 20 oz") is None  # refused two-unit mass: not one mass, not negative


@pytest.mark.parametrize(
    "text,values", [("-27 x 27 x 2 cm", (-27.0, 27.0, 2.0)), ("27 x 27 x -2 cm", (27.0, 27.0, -2.0))]
)
def test_each_extent_of_a_size_keeps_its_sign(text: str, values: tuple) -> None:
    assert parse_dims(text)[0].values_cm == values


def _html(body: str, head: str = "") -> str:
    return f"<html lang='en'><head><title>Plate</title>{head}</head><body><h1>Negative Plate</h1>{body}</body></html>"


def _jsonld(product: dict) -> str:
    data = {"@context": "https://schema.org", "@type": "Product", "name": "Negative Plate", **product}
    return f'<script type="application/ld+json">{json.dumps(data)}</script>'


PAGES = {
    "spec table": _html("<table><tr><th>Dimensions</th><td>-27 x 27 x 2 cm</td></tr>"
                        "<tr><th>Weight</th><td>-600 g</td></tr></table>"),
    "spec axes": _html("<table><tr><th>Length</th><td>-27 cm</td></tr><tr><th>Width</th><td>27 cm</td></tr>"
                       "<tr><th>Weight</th><td>-0.6 kg</td></tr></table>"),
    "jsonld text": _html("", _jsonld({"size": "-27 x 27 x 2 cm", "weight": "-600 g"})),
    "jsonld numbers": _html("", _jsonld({
        "width": {"@type": "QuantitativeValue", "value": -27, "unitCode": "CMT"},
        "depth": {"@type": "QuantitativeValue", "value": 27, "unitCode": "CMT"},
        "weight": {"@type": "QuantitativeValue", "value": -600, "unitCode": "GRM"}})),
    "microdata": _html('<div itemscope itemtype="https://schema.org/Product"><span itemprop="name">Plate</span>'
                       '<div itemprop="weight" itemscope itemtype="https://schema.org/QuantitativeValue">'
                       '<span itemprop="value">-600</span><meta itemprop="unitCode" content="GRM"></div></div>'),
    "free text": _html("<p>This plate measures -27 x 27 x 2 cm and is sold alone.</p>"
                       "<p>It is -27 cm long and 27 cm wide, a plain plate.</p>"),
    "bullets": _html("<ul><li>Item weight: -600 g</li><li>Product dimensions: -27 x 27 x 2 cm</li></ul>"),
}  # fmt: skip


@pytest.mark.parametrize("path", list(PAGES))
def test_a_page_stating_only_negative_values_is_rejected_with_the_reason(path: str) -> None:
    with pytest.raises(ExtractionError, match="not positive"):
        extract_page(PAGES[path], URL, "text/html")


def test_a_negative_value_is_refused_beside_a_positive_one_and_never_read_as_positive() -> None:
    page = _html("<table><tr><th>Dimensions</th><td>27 x 27 x 2 cm</td></tr>"
                 "<tr><th>Weight</th><td>-600 g</td></tr></table>")  # fmt: skip
    record = extract_page(page, URL, "text/html")
    assert record.dims_cm == (27.0, 27.0, 2.0) and record.mass_g is None
    assert "not positive" in record.refused["mass"]
    assert any("mass -600 g is not positive" in w for w in record.warnings)


def test_a_bulleted_value_is_read() -> None:
    record = extract_page(_html("<ul><li>Weight: - 600 g</li><li>Dimensions: 27 x 27 x 2 cm</li></ul>"), URL)
    assert record.mass_g == 600.0 and record.dims_cm == (27.0, 27.0, 2.0)
