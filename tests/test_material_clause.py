"""A material word in a comma clause of its own is the object's material (blind-test finding: "the office
thing that clips paper together, metal, ..." was read as paper, and the stapler missed)."""

from __future__ import annotations

import pytest
from recallers import seed

from recall.parser import parse


@pytest.mark.parametrize(
    ("text", "material"),
    [
        ("the office thing that clips paper together, metal, about 6 in long", "metal"),
        ("a thing that clips paper together, metal", "metal"),  # at the end of the sentence
        ("cuts wood easily, mostly plastic, 20 cm", "plastic"),  # with a word of degree
        ("a bag for paper, white plastic", "plastic"),  # with a colour
        ("holds glass jars, stainless steel and plastic", "metal"),  # two materials: the first
        ("Rubber, wraps paper, 5 cm", "rubber"),  # at the start
        ("clips paper together, 6 in long", "paper"),  # the only material word is still used
        ("a wooden spoon with a plastic handle", "wood"),  # no clause of its own: the ranks as before
        ("a drill with a rubber grip, made of plastic", "plastic"),
        ("paper and metal clips, about 3 cm", "paper"),  # not alone: a noun in the clause
    ],
)
def test_a_material_alone_in_its_clause_is_the_objects(text, material):
    assert parse(text).values().get("material") == material


def test_the_stapler_is_metal_and_among_the_first_three():
    result = seed().recall_text(
        "the office thing that clips paper together, metal, about 6 in long and heavy-ish"
    )
    assert result.query["values"]["material"] == "metal"
    assert "stapler" in [m.name for m in result.matches[:3]]
