"""A list of features that starts with a part or a shape (recall.openset.bare_part): "glass screen, 170 g,
thin" names no object the catalog lacks; introduced by an article ("a glass screen") it still does.
Catalog written here."""

from __future__ import annotations

import pytest
from recallers import from_sizes

from recall.engine import Recaller
from recall.openset import bare_part


@pytest.fixture(scope="module")
def recaller(tmp_path_factory) -> Recaller:
    rows = [("cell phone", 10, 5.5, 1, 100), ("micrometer", 11.5, 1.75, 1.75, 170)]
    return from_sizes(tmp_path_factory.mktemp("parts") / "catalog.csv", rows)


@pytest.mark.parametrize(
    "text", ["glass screen, 170 grams, thin", "C-shaped steel frame, 250 g", "hollow cylinder, 60 cm long"]
)
def test_a_bare_part_or_shape_names_no_foreign_object(recaller, text):
    assert recaller.described(text) is None
    assert not recaller.recall_text(text).not_in_catalog


@pytest.mark.parametrize("text", ["a glass screen, 170 grams", "the steel frame of a bed, 250 g"])
def test_an_introduced_part_still_names_the_thing(recaller, text):
    noun = recaller.described(text)
    assert noun is not None and not noun.in_catalog


def test_only_parts_and_shapes_are_read_so():
    assert bare_part("glass screen, 170 grams", ("glass", "screen"))
    assert not bare_part("kitchen tongs, metal, 12 inches", ("kitchen", "tong"))  # a name, bare
    assert not bare_part("a frame, 250 g", ("frame",)) and not bare_part("", ())


@pytest.fixture(scope="module")
def with_handles(tmp_path_factory) -> Recaller:
    rows = [("clamp handle", 15, 1, 1, 225), ("wiper handle", 15, 2, 2, 350), ("cell phone", 10, 5.5, 1, 100)]
    return from_sizes(tmp_path_factory.mktemp("handles") / "catalog.csv", rows)


@pytest.mark.parametrize("text", ["the handle of a C-clamp, 12 cm long, 8 mm thick, 50 g", "a handle of a mop, 1 m"])
def test_a_part_the_catalog_holds_is_described_not_the_whole_after_of(with_handles, text):
    """"the handle of a C-clamp": the catalog holds handles, so the whole after "of" (a c clamp, not in it)
    says whose handle it is, not that the object is missing."""
    assert with_handles.described(text) is None
    assert not with_handles.recall_text(text).not_in_catalog


def test_a_part_the_catalog_holds_no_object_of_still_reads_the_whole(recaller):
    """Boundary: where no catalog object has the part as its head noun, the whole after "of" is the noun."""
    noun = recaller.described("the handle of a C-clamp, 12 cm long, 50 g")
    assert noun is not None and noun.noun == "c clamp" and not noun.in_catalog
