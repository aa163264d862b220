"""A sort of a catalog object is offered by the ranking (NameEvidence.sorts): "a hacksaw" is in the
catalog only as its "saw" (recall.catalog_kinds.sort_of_catalog_object), so the saws get the evidence of that
head noun, as "a saw" would give them, without being named (the verdict's trust is unchanged). Catalog
written here; each condition pinned on its own."""

from __future__ import annotations

import pytest
from recallers import from_sizes

from recall.engine import Recaller
from recall.name_index import HEAD_WEIGHT

ROWS = [
    ("saw", 30, 10, 2.5, 450), ("dremel", 40, 5.5, 5.5, 450), ("hammer", 33, 13, 3, 600),
    ("spoon", 18, 4, 2, 30), ("timer", 12, 12, 4, 100),
]  # fmt: skip


@pytest.fixture(scope="module")
def recaller(tmp_path_factory) -> Recaller:
    return from_sizes(tmp_path_factory.mktemp("sorts") / "catalog.csv", ROWS)


def test_a_sort_of_a_catalog_head_gives_its_objects_that_heads_evidence(recaller):
    text = "a hacksaw, 36 cm long, 450 g"
    assert recaller.described(text).sort_of == "saw"
    names = recaller._with_sorts(recaller.names.find(text), recaller.described(text))
    saw = recaller.snapshot.names.index("saw")
    assert set(names.sorts) == {saw} and names.bonus(saw) == pytest.approx(HEAD_WEIGHT * names.sorts[saw])
    result = recaller.recall_text(text, top=3)
    assert result.matches[0].name == "saw" and not result.matches[0].matched_by_name and not result.open_set
    plain = recaller.recall_features({"a_cm": 36, "mass_g": 450}, top=3)
    assert plain.matches[0].name == "dremel"  # the features alone: the dremel's length


def test_no_sort_no_evidence_and_a_name_is_not_counted_twice(recaller):
    for text in ("a saw, 40 cm long, 450 g", "a lever, 40 cm long, 450 g", "a thing, 40 cm long, 450 g"):
        names = recaller._with_sorts(recaller.names.find(text), recaller.described(text))
        assert names.sorts == {}, text
