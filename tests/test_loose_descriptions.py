"""A description that pins almost nothing down ("red", "a red one": no stated feature, no whole catalog name
or alias) gets at most the ranking's own posterior of its first match, 1 / competitors, never 1.00
(recall.confidence.MAX_LOOSE_FEATURES, RECALL.md "What a description pins down"). Seed catalog, texts
written here."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from kb.service.cli import app
from recall.confidence import MAX_LOOSE_FEATURES, capped_confidence
from recall.engine import Recaller


@pytest.fixture(scope="module")
def recaller(tmp_path_factory) -> Recaller:
    db = tmp_path_factory.mktemp("loose") / "seed.duckdb"
    assert CliRunner().invoke(app, ["init", "--seed", "--db", str(db)]).exit_code == 0
    return Recaller.from_db(db)


@pytest.mark.parametrize("text", ["red", "a red one", "something small and round", "thing", "qwerty"])
def test_a_description_giving_almost_nothing_is_never_sure(recaller, text) -> None:
    res = recaller.recall_text(text)
    assert res.confidence <= 1.0 / max(res.competitors or 1.0, 1.0) + 1e-9
    assert res.confidence < 0.5, (text, res.confidence)


def test_a_whole_name_or_a_stated_feature_is_not_capped_by_the_rule(recaller) -> None:
    named = recaller.recall_text("a coffee mug")  # a whole catalog name: the fitted model decides
    assert named.matches[0].name == "coffee mug" and named.confidence > 0.9
    assert MAX_LOOSE_FEATURES == 0
    capped = capped_confidence(5.0, 0.0, False, "jplog", 4.0, False, False, False, soft_only=True)
    free = capped_confidence(5.0, 0.0, False, "jplog", 4.0, False, False, False, soft_only=False)
    assert capped == pytest.approx(0.25) and free > 0.9  # the boundary: 1 / competitors exactly
