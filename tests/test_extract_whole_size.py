"""A whole size written in a single-dimension field (JSON-LD ``width: "5000 x 8 x 8 cm"``, a spec row
``Width: 30 x 20 x 10 cm``) is read as the size or refused, never as one of its figures; and a statement
refused as impossible is not replaced by a partial read of the same statement elsewhere (a blind test
found the absurd teacup stored as 8 cm)."""

from __future__ import annotations

import json

import pytest

from scrapers.adapters import Observation
from scrapers.extract import extract_page, fuse

URL = "http://127.0.0.1:1/p/teacup"


def _jsonld_page(width, extra: str = "") -> str:
    data = {"@context": "https://schema.org", "@type": "Product", "name": "Giant Teacup", "width": width,
            "weight": {"@type": "QuantitativeValue", "value": 300, "unitCode": "GRM"}}  # fmt: skip
    return (
        f'<html><head><script type="application/ld+json">{json.dumps(data)}</script></head>'
        f"<body><h1>Giant Teacup</h1>{extra}</body></html>"
    )


def _spec_page(label: str, value: str) -> str:
    return (
        f"<html><head><title>Teacup</title></head><body><h1>Giant Teacup</h1><table><tr><th>{label}</th>"
        f"<td>{value}</td></tr><tr><th>Weight</th><td>300 g</td></tr></table></body></html>"
    )


@pytest.mark.parametrize(
    "width", ["5000 x 8 x 8 cm", {"@type": "QuantitativeValue", "value": "5000 x 8 x 8 cm"}]
)
def test_an_absurd_whole_size_in_a_jsonld_width_is_refused(width) -> None:
    record = extract_page(_jsonld_page(width), URL, "text/html")
    assert record.dims_cm is None and "absurd" in record.refused["dims"]


def test_a_plausible_whole_size_in_a_jsonld_width_is_the_size_with_a_note() -> None:
    record = extract_page(_jsonld_page("30 x 20 x 10 cm"), URL, "text/html")
    assert record.dims_cm == (30.0, 20.0, 10.0)
    assert any("whole size" in w for w in record.warnings)


def test_one_length_in_a_jsonld_width_stays_one_extent() -> None:
    record = extract_page(_jsonld_page("8 cm"), URL, "text/html")
    assert record.dims == [{"role": "width", "cm": 8.0}]


@pytest.mark.parametrize("label", ["Width", "Height", "Diameter"])
def test_a_whole_size_in_a_spec_row_for_one_axis_is_read_as_the_size_or_refused(label: str) -> None:
    assert extract_page(_spec_page(label, "30 x 20 x 10 cm"), URL).dims_cm == (30.0, 20.0, 10.0)
    assert "absurd" in extract_page(_spec_page(label, "5000 x 8 x 8 cm"), URL).refused["dims"]


def test_one_length_in_a_spec_row_stays_one_extent() -> None:
    assert extract_page(_spec_page("Width", "8 cm"), URL).dims == [{"role": "width", "cm": 8.0}]


def _obs(value, source: str, raw: str, order: int = 0) -> Observation:
    return Observation("dims", value, rank=1, order=order, raw=raw, source=source)


def test_a_refused_statement_is_not_replaced_by_a_partial_read_of_itself() -> None:
    refused = _obs((5000.0, 8.0, 8.0), "spec_table", "Dimensions: 5000 x 8 x 8 cm")
    partial = _obs((8.0,), "jsonld", "width: 5000 x 8 x 8 cm")
    mass = Observation("mass", 300.0, raw="Weight: 300 g", source="spec_table")
    record = fuse([partial, refused, mass], URL)
    assert record.dims_cm is None and "absurd" in record.refused["dims"]
    assert any("partial read of a refused statement" in w for w in record.warnings)


def test_another_statement_of_the_feature_is_still_used() -> None:
    refused = _obs((5000.0, 8.0, 8.0), "spec_table", "Dimensions: 5000 x 8 x 8 cm")
    other = _obs((8.0, 8.0, 10.0), "jsonld", "size: 10 x 8 x 8 cm")
    record = fuse([other, refused], URL)
    assert record.dims_cm == (10.0, 8.0, 8.0) and record.refused == {}


def test_the_teacup_page_is_rejected_whole() -> None:
    page = _jsonld_page(
        "5000 x 8 x 8 cm", "<table><tr><th>Dimensions</th><td>5000 x 8 x 8 cm</td></tr></table>"
    )
    record = extract_page(page, URL)
    assert record.dims_cm is None and "absurd" in record.refused["dims"] and record.mass_g == 300.0
