"""A page's product name passes the catalog's one name rule (kb.features.check_name: the CSV import's and
the API's), is plain text (markup parsed, script and style content dropped), and a decoding error never
becomes a name; a refused candidate gives way to the next one, and with none the page's name is refused
with the reason (a blind test found a 5000-character name, "nul? jar" and "x" stored)."""

from __future__ import annotations

import json

import pytest

from kb.errors import InvalidFeature
from kb.features import MAX_NAME_CHARS, ObjectRecord, check_name
from scrapers.extract import extract_page
from scrapers.product_names import name_problem, plain_name

URL = "http://127.0.0.1:1/p/mug"


def _page(name: str | None, title: str = "x", h1: str = "", size: str = "9 x 9 x 10 cm") -> str:
    data = {"@context": "https://schema.org", "@type": "Product", "size": size}
    if name is not None:
        data["name"] = name
    block = json.dumps(data).replace("</", "<\\/")  # the page escapes "</script>" inside its JSON
    return (
        f'<html><head><title>{title}</title><script type="application/ld+json">{block}</script></head>'
        f"<body><h1>{h1}</h1><table><tr><th>Weight</th><td>320 g</td></tr></table></body></html>"
    )


def test_the_name_rule_is_pinned_at_its_length_cap() -> None:
    check_name("name", "z" * MAX_NAME_CHARS)
    with pytest.raises(InvalidFeature, match="201 characters"):
        check_name("name", "z" * (MAX_NAME_CHARS + 1))
    with pytest.raises(InvalidFeature, match="at most 200"):
        ObjectRecord.create("z" * (MAX_NAME_CHARS + 1))  # every path in shares it
    assert ObjectRecord.create("z" * MAX_NAME_CHARS).name == "z" * MAX_NAME_CHARS


@pytest.mark.parametrize("bad", ["\x00", "\x1b", "\x07", "\x7f"])
def test_a_control_character_is_refused_in_a_page_name(bad: str) -> None:
    assert "control character" in name_problem(f"Nul{bad} Jar")


def test_a_replacement_character_is_refused_as_a_decoding_error() -> None:
    assert "U+FFFD" in name_problem("Caf\ufffd Mug")


@pytest.mark.parametrize("name,problem", [("x", True), ("-", True), ("U2", False), ("Mug", False)])
def test_a_page_name_needs_two_letters_or_digits(name: str, problem: bool) -> None:
    assert (name_problem(name) is not None) is problem


@pytest.mark.parametrize(
    "text,plain",
    [
        ("<script>alert('x')</script><img src=x onerror=alert(1)> Hostile Mug", "Hostile Mug"),
        ("<style>h1{}</style><b>Bold</b> Mug", "Bold Mug"),
        ("Mug <3 for you", "Mug <3 for you"),
        ("Plain   Mug", "Plain Mug"),
    ],
)
def test_markup_in_a_name_is_read_as_text_without_script_or_style(text: str, plain: str) -> None:
    assert plain_name(text) == plain


def test_an_over_long_name_gives_way_to_the_next_candidate() -> None:
    record = extract_page(_page("Z" * (MAX_NAME_CHARS + 1), title="Plain Mug"), URL)
    assert record.name == "Plain Mug" and "name" not in record.refused
    assert any("at most 200" in w for w in record.warnings)
    assert extract_page(_page("Z" * MAX_NAME_CHARS, title="Plain Mug"), URL).name == "Z" * MAX_NAME_CHARS


def test_a_name_of_markup_is_read_without_its_script() -> None:
    record = extract_page(_page("<script>alert('x')</script><img src=x onerror=alert(1)> Hostile Mug"), URL)
    assert record.name == "Hostile Mug"


def test_a_heading_with_a_script_stands_in_for_a_title_that_names_nothing() -> None:
    record = extract_page(_page(None, title="x", h1="<script>alert('x')</script> Hostile Mug"), URL)
    assert record.name == "Hostile Mug"


def test_a_script_only_name_is_no_name() -> None:
    record = extract_page(_page("<script>alert(1)</script>", title="<b></b>", h1="<script>x</script>"), URL)
    assert record.name is None


@pytest.mark.parametrize(
    "body",
    [
        b"<html><body><h1>Nul\x00 Jar</h1>Dimensions: 10 x 10 x 12 cm. Weight: 350 g</body></html>",
        b"<html><body><h1>Caf\xe9 Mug \xff\xfe</h1>Dimensions: 9 x 9 x 10 cm, 320 g</body></html>",
    ],
)
def test_a_nul_or_an_undecodable_byte_refuses_the_name_with_the_reason(body: bytes) -> None:
    record = extract_page(body, URL, "text/html; charset=utf-8")
    assert record.name is None and "U+FFFD" in record.refused["name"]


def test_a_header_utf8_the_bytes_are_not_gives_way_to_the_pages_own_meta_charset() -> None:
    body = '<html><head><meta charset="windows-1252"></head><body><h1>Wärme Mug</h1><table><tr><th>Weight</th><td>320 g</td></tr></table></body></html>'
    record = extract_page(body.encode("cp1252"), URL, "text/html; charset=utf-8")
    assert record.name == "Wärme Mug"
    no_meta = body.replace('<meta charset="windows-1252">', "").encode("cp1252")
    assert "U+FFFD" in extract_page(no_meta, URL, "text/html; charset=utf-8").refused["name"]
