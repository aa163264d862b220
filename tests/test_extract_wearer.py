"""A garment page's note on who wears which size: its lengths are the wearer's, never the product's.

Pages here are small HTML written here, mirroring the layout class of fashion stores (COS, Arket, Weekday,
& Other Stories, Gymshark: "Model is 189cm tall and wearing a size M", "Model is 6'0" and wears size M"),
where the description's only length is often the model's height."""

from __future__ import annotations

import pytest

from kb.errors import ExtractionError
from scrapers.adapters.text import _wearers_sentence
from scrapers.extract import extract_page


def page(description: str) -> str:
    return (f"<html lang='en'><head><title>Ribbed T-Shirt</title></head><body><h1>Ribbed T-Shirt</h1>"
            f"<div class='description'><p>{description}</p></div></body></html>")  # fmt: skip


@pytest.mark.parametrize("text", [
    "Back length of size M is 69.5cm / Model is 189cm tall and wearing a size M",
    "Regular fit. The model is 185 cm tall and wears size L.",
    "Das Model ist 189 cm hoch und trägt Größe M.",
])  # fmt: skip
def test_the_wearers_height_is_not_read(text):
    with pytest.raises(ExtractionError):
        extract_page(page(text), "https://shop.example/shirt")


def test_a_height_in_another_sentence_is_still_read():
    record = extract_page(page("The vase is 30 cm tall / Model wears size M"), "https://shop.example/vase")
    assert record.dims_cm == (30.0,)


def test_without_the_wearing_clause_the_sentence_is_a_measurement():
    record = extract_page(page("The lamp is 189 cm tall and made of steel."), "https://shop.example/lamp")
    assert record.dims_cm == (189.0,)


@pytest.mark.parametrize("text, at, wearer", [
    ("Model is 189cm tall and wearing a size M", 9, True),
    ("Le mannequin mesure 189 cm de haut et porte une taille M", 20, True),
    ("It is 30 cm tall. Model wears size M", 6, False),
    ("It is 30 cm tall; sizes S to XL", 6, False),
])  # fmt: skip
def test_wearers_sentence(text, at, wearer):
    assert _wearers_sentence(text, at) is wearer
