"""Partial sizes end to end: a page stating fewer than three extents -> a catalog object with unknown axes
(the schema the migrations build holds them), CSV export and import keep them unknown, and recall ranks
such objects on the features they have without inventing the rest."""

from __future__ import annotations

import math

import pytest

from kb.catalog import KnowledgeBase
from kb.csvio import parse_catalog_csv
from kb.features import ObjectRecord
from recall.engine import Recaller
from scrapers.extract import extract_page
from scrapers.ingest import _validate

SHADE = "<html lang='en'><head><title>Copper Pendant Shade</title></head><body><h1>Copper Pendant Shade</h1>" \
    "<table><tr><th>Diameter</th><td>45 cm</td></tr></table></body></html>"  # fmt: skip


def _catalog(tmp_path) -> KnowledgeBase:
    kb = KnowledgeBase.open(tmp_path / "partial.duckdb")
    kb.upsert(
        [
            ObjectRecord.create("copper pendant shade", a_cm=45, b_cm=45, material="metal"),
            ObjectRecord.create("kitchen towel", a_cm=70, mass_g=80),
            ObjectRecord.create("dinner plate", a_cm=27, b_cm=27, c_cm=2, mass_g=600, material="other"),
            ObjectRecord.create("storage box", a_cm=40, b_cm=30, c_cm=25, mass_g=900, material="plastic"),
        ],
        source="csv:test",
        adapter="csv",
    )
    return kb


def test_a_diameter_only_page_becomes_an_object_with_one_unknown_axis():
    record = extract_page(SHADE, "https://s.example/shade")
    clean, packages, _ = _validate(record)
    assert (clean.a_cm, clean.b_cm, clean.c_cm, clean.mass_g) == (45.0, 45.0, None, None)
    assert packages == []


def test_the_catalog_stores_partial_sizes(tmp_path):
    kb = _catalog(tmp_path)
    shade, towel = kb.get_object("copper pendant shade"), kb.get_object("kitchen towel")
    assert shade.dims_cm == (45.0, 45.0, None) and shade.mass_g is None
    assert towel.dims_cm == (70.0, None, None) and towel.mass_g == 80.0


def test_csv_export_and_import_keep_unknown_axes_unknown(tmp_path):
    kb = _catalog(tmp_path)
    text = kb.export_csv()
    records = {r.name: r for r in parse_catalog_csv(text).records}
    assert records["copper pendant shade"].dims_cm == (45.0, 45.0, None)
    assert records["kitchen towel"].dims_cm == (70.0, None, None)
    again = KnowledgeBase.open(tmp_path / "again.duckdb")
    path = tmp_path / "export.csv"
    path.write_text(text, encoding="utf-8")
    again.import_csv(path)
    assert again.get_object("kitchen towel").dims_cm == (70.0, None, None)
    assert again.get_object("copper pendant shade").mass_g is None


def test_recall_ranks_partial_objects_on_what_they_state(tmp_path):
    recaller = Recaller.from_records(_catalog(tmp_path).list_objects())
    result = recaller.recall_features({"a_cm": 45.0, "b_cm": 45.0}, features_only=True)
    assert result.matches[0].name == "copper pendant shade"
    # a stated feature the object does not have is unknown, not zero: the towel (no b) still ranks, finitely
    result = recaller.recall_features({"a_cm": 70.0, "b_cm": 5.0, "mass_g": 80.0}, features_only=True)
    names = [m.name for m in result.matches]
    assert names[0] == "kitchen towel"
    assert all(math.isfinite(m.distance) for m in result.matches)


@pytest.mark.parametrize("text", ["a round copper shade 45 cm across", "a towel 70 cm long weighing 80 g"])
def test_recall_text_over_partial_objects_gives_a_ranked_result(tmp_path, text):
    recaller = Recaller.from_records(_catalog(tmp_path).list_objects())
    result = recaller.recall_text(text)
    assert result.matches and all(math.isfinite(m.score) for m in result.matches)
