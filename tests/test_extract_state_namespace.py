"""Page state after a JavaScript namespace's initialiser (issue 21): ``var DBK = window.DBK || {};`` then
``(function (Data) { Data.product = {...}; })(DBK)`` (de Bijenkorf's state; the idiom of many stores' bundles).
The empty literal first is no state: the next object literal of the script is read
(``scrapers.script_state``). Pages written here."""

from __future__ import annotations

import json

from hypothesis import given
from hypothesis import strategies as st

from scrapers.extract import extract_page
from scrapers.script_state import MAX_EMPTY_LITERALS, script_objects

STATE = {"product": {"name": "Pralines Gold Box", "groupedAttributes": [
    {"id": "composition", "attributes": [{"label": "Gewicht", "value": "385 gram", "visible": True}]}]}}


def _page(script: str) -> str:
    return (f"<html lang='nl'><head><title>Pralines Gold Box</title><script>{script}</script></head>"
            f"<body><h1>Pralines Gold Box</h1><p>Belgische bonbons.</p></body></html>")  # fmt: skip


def test_the_state_after_a_namespaces_empty_initialiser_is_read():
    script = f"var DBK = window.DBK || {{}};\n(function ( Data ) {{\n Data.product = {json.dumps(STATE['product'])};\n}})(DBK);"
    assert extract_page(_page(script), "https://shop.example/p").mass_g == 385.0


def test_a_script_of_empty_literals_only_is_no_state():
    assert script_objects("<script>var A = window.A || {}; var B = window.B || {};</script>") == []


def test_a_first_object_with_content_is_read_as_before():
    assert script_objects(f"<script>window.__STATE__ = {json.dumps(STATE)};</script>") == [STATE]


_JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.text(max_size=8),
                     lambda inner: st.dictionaries(st.text("abc", min_size=1, max_size=4), inner, max_size=3), max_leaves=8)


@given(st.dictionaries(st.text("xyz", min_size=1, max_size=4), _JSON, min_size=1, max_size=4),
       st.integers(0, MAX_EMPTY_LITERALS))
def test_an_object_after_up_to_the_limit_of_empty_initialisers_is_found(obj, empties):
    script = "".join(f"var N{i} = window.N{i} || {{}};\n" for i in range(empties)) + f"N0.state = {json.dumps(obj)};"
    assert script_objects(f"<script>{script}</script>") == [obj]
