"""Whose value it is, classes of the real corpus's development stores pinned on pages written here:

- a WooCommerce variable product whose variations state different weights or sizes and preselect none
  sells several sizes: each variation's value is a variant's, never the product's (a seed shop's 500 g ...
  25 kg bags); the preselected variation's values are the product's; identical variations are one value;
- a vessel's rim, brim or waist is its own outline, not a part (a potter's ``rim diameter 9 cm``, a cup
  maker's ``Waist width 65mm``), while its base, lid or handle stay parts;
- a single length in a round pan's name is its diameter (``SKÄNKA Frying pan - gray, 11"``, ``Lodge 12"
  Cast Iron Skillet``), used only when the page states no product size; in any other name (a screen's
  ``27"``, a sheet pan's ``18"``) it is no extent;
- a weight a sentence states followed by a comparison (``weighs 30g, or ~5% lighter than the LCD model``,
  ``wiegt 300 g weniger als``) is a difference from another model, never the product's weight.
"""

from __future__ import annotations

import html
import json

import pytest

from kb.errors import ExtractionError
from scrapers.adapters.text import _COMPARED, _WEIGHS, _title_diameter
from scrapers.extract import extract_page
from scrapers.labels import classify_label, classify_other


def _record(body: str, title: str = "Thing"):
    page = (f"<html lang='en'><head><title>{title}</title></head>"
            f"<body class='woocommerce'><h1>{title}</h1>{body}</body></html>")  # fmt: skip
    try:
        return extract_page(page, "https://shop.test/p", "text/html")
    except ExtractionError:
        return None


# ---------------------------------------------------------------------- WooCommerce variations
def _variations_form(weights: list[str], selected: int | None) -> str:
    variations = [
        {"variation_id": i, "attributes": {"attribute_pa_sizes": f"s{i}"}, "weight_html": w, "dimensions_html": "N/A"}
        for i, w in enumerate(weights)
    ]
    options = "".join(
        f"<option value='s{i}'{' selected' if i == selected else ''}>{w}</option>" for i, w in enumerate(weights)
    )
    return (f"<form class='variations_form cart' data-product_variations='{html.escape(json.dumps(variations))}'>"
            f"<select name='attribute_pa_sizes'><option value=''>Choose an option</option>{options}</select></form>")  # fmt: skip


def _whose_mass(record) -> list[tuple[float, str]]:
    return [(round(c["value"], 1), c["decision"]) for c in record.candidates if c["feature"] == "mass"]


def test_differing_variations_with_none_selected_are_variants_not_the_product():
    r = _record(_variations_form(["0.560 kg", "1.06 kg", "2.06 kg"], None) + "<p>Width: 30 cm</p>")
    assert r is not None and r.mass_g is None
    decisions = _whose_mass(r)
    assert len(decisions) == 3 and all("variant's value" in d for _, d in decisions)


@pytest.mark.parametrize("selected", [0, 2])
def test_the_selected_variations_value_is_the_products(selected):
    weights = ["0.560 kg", "1.06 kg", "2.06 kg"]
    r = _record(_variations_form(weights, selected))
    assert r is not None and r.mass_g == pytest.approx(float(weights[selected].split()[0]) * 1000)


def test_identical_variations_state_one_value_even_with_none_selected():
    r = _record(_variations_form(["450 g", "450 g"], None))
    assert r is not None and r.mass_g == pytest.approx(450.0)


def test_a_selection_on_another_attribute_picks_no_variation():
    # the preselected option belongs to another picker: no variation is selected
    form = _variations_form(["450 g", "600 g"], None).replace(
        "</form>", "<select name='attribute_pa_colour'><option value='red' selected>Red</option></select></form>"
    )
    r = _record(form + "<p>Width: 30 cm</p>")
    assert r is not None and r.mass_g is None


# ---------------------------------------------------------------------- a vessel's outline
@pytest.mark.parametrize("label, kind, product", [
    ("rim diameter", "diameter", True),
    ("Rim Diameter", "diameter", True),
    ("Brim width", "width", True),
    ("Waist width", "width", True),
    ("Base Width", "width", False),  # a part: the base
    ("Lid diameter", "diameter", False),
    ("Handle length", "length", False),
])  # fmt: skip
def test_a_vessels_outline_is_its_own_extent_a_part_is_not(label, kind, product):
    info = classify_label(label)
    if product:
        assert info is not None and info.kind == kind and info.role == "product"
    else:
        assert info is None and classify_other(label).role == "component"


def _extents(body: str) -> list[tuple[str, float]] | None:
    r = _record(body, "Stoneware Mug")
    return None if r is None else sorted(((e["role"], e["cm"]) for e in r.dims), reverse=True)


def test_a_mugs_rim_diameter_and_height_are_its_two_extents():
    body = "<p>rim diameter 9 cm</p><p>height 9.5 cm</p><p>weight 280 g</p>"
    assert _extents(body) == [("height", 9.5), ("diameter", 9.0)]


def test_a_cups_waist_width_beside_its_base_width():
    body = "<div><span>Waist width</span><span>65mm</span></div><div><span>Base Width</span><span>47mm</span></div>" \
        "<div><span>Overall height</span><span>86mm</span></div>"
    assert _extents(body) == [("width", 6.5), ("height", 8.6)]


# ---------------------------------------------------------------------- a round pan's name
@pytest.mark.parametrize("title, cm", [
    ('Lodge 12" Cast Iron Skillet', 30.48),
    ('Lodge 12" Cast Iron Skillet: Preseasoned, 12 Inch, Gas & Induction Compatible', 30.48),  # restated
    ('SKÄNKA Frying pan - gray, 11"', 27.94),
    ("Bratpfanne Edelstahl 28 cm", 28.0),
    ("Poêle inox 24 cm", 24.0),
    ("Carbon Steel Wok 30cm", 30.0),
    ('Skillet 10" and 12"', None),  # two lengths: which one is not said
    ('Half Sheet Pan 18"', None),  # a bare pan: a sheet pan's length
    ('MSI 27" Monitor', None),  # a screen's diagonal
    ("Panasonic 32 cm speaker", None),
])  # fmt: skip
def test_a_single_length_in_a_round_pans_name_is_its_diameter(title, cm):
    found = _title_diameter(title, None)
    if cm is None:
        assert found == []
    else:
        assert [(o.value, o.roles, o.role) for o in found] == [((pytest.approx(cm),), ("diameter",), "name")]


def test_the_pages_own_size_beats_the_pans_name():
    r = _record("<table><tr><th>Diameter</th><td>26 cm</td></tr></table>", 'Frying pan, 11"')
    assert r is not None and [e["cm"] for e in r.dims] == [26.0]
    r = _record("<p>Handle length: 6 in</p><p>Weight: 1.2 kg</p>", 'Frying pan, 11"')
    assert r is not None and [(e["role"], e["cm"]) for e in r.dims] == [("diameter", pytest.approx(27.94))]


# ---------------------------------------------------------------------- a weight compared with another's
@pytest.mark.parametrize("sentence, difference", [
    ("It also weighs 30g, or ~5% lighter than the LCD model.", True),
    ("The new model weighs 200 g less than the old one.", True),
    ("Das Gerät wiegt 300 g weniger als das Vorgängermodell.", True),
    ("It weighs 2 kg more.", True),
    ("This lamp weighs 1.2 kg, more stable than ever before.", False),  # "more" modifies another word
    ("It weighs 1.2 kg and stands 40 cm tall.", False),
])  # fmt: skip
def test_a_weight_followed_by_a_comparison_is_a_difference(sentence, difference):
    m = _WEIGHS.search(sentence)
    assert m is not None and bool(_COMPARED.match(sentence, m.end())) is difference


def test_a_compared_weight_is_not_the_products():
    r = _record("<p>Thanks to a bigger fan it also weighs 30g, or ~5% lighter than the LCD model.</p>"
                "<p>Width: 30 cm</p>")  # fmt: skip
    assert r is not None and r.mass_g is None
