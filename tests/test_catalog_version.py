"""KnowledgeBase.catalog_version(): any change of what recall reads moves it, whether or not updated_at moved;
writes elsewhere keep it; it is a function of the content (a change undone gives the old version back)."""

from __future__ import annotations

from pathlib import Path

import pytest

from kb.catalog import KnowledgeBase
from kb.features import FEATURES
from kb.versions import content_fingerprint
from recall.snapshot import load_snapshot

#: A new value for each column recall reads, written with plain SQL that leaves updated_at alone.
CHANGES = {
    "name": "name = name || ' (old)'",
    "a_cm": "a_cm = a_cm + 0.001",
    "b_cm": "b_cm = coalesce(b_cm, 1) * 2",
    "c_cm": "c_cm = NULL",
    "mass_g": "mass_g = coalesce(mass_g, 1) + 1",
    "shape": "shape = CASE WHEN shape = 'radial' THEN 'prism' ELSE 'radial' END",
    "texture": "texture = CASE WHEN texture = 'rough' THEN 'smooth' ELSE 'rough' END",
    "fragility": "fragility = CASE WHEN fragility = 'fragile' THEN 'sturdy' ELSE 'fragile' END",
    "material": "material = CASE WHEN material = 'wood' THEN 'metal' ELSE 'wood' END",
    "rigidity": "rigidity = CASE WHEN rigidity = 'rigid' THEN 'soft' ELSE 'rigid' END",
}
TARGET = "WHERE name = 'tennis ball'"


def _write(db: Path, sql: str) -> None:
    with KnowledgeBase.open(db, upgrade=False).connect(write=True) as con:
        con.execute(sql)


def test_every_column_recall_reads_is_covered() -> None:
    assert set(CHANGES) == {"name", *FEATURES}


@pytest.mark.parametrize("column", sorted(CHANGES))
def test_a_value_changed_without_a_new_updated_at_moves_the_version(seeded_db: Path, column: str) -> None:
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    before = kb.catalog_version()
    _write(seeded_db, f"UPDATE objects SET {CHANGES[column]} {TARGET}")
    after = kb.catalog_version()
    assert (after.objects, after.max_id, after.updated_at) == (
        before.objects,
        before.max_id,
        before.updated_at,
    )
    assert after != before and after.values_hash != before.values_hash


def test_two_values_swapped_between_objects_move_the_version(seeded_db: Path) -> None:
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    before = kb.catalog_version()
    _write(
        seeded_db,
        "UPDATE objects SET mass_g = CASE name WHEN 'tennis ball' THEN (SELECT mass_g FROM objects WHERE name = "
        "'tv remote') ELSE (SELECT mass_g FROM objects WHERE name = 'tennis ball') END "
        "WHERE name IN ('tennis ball', 'tv remote')",
    )
    assert kb.catalog_version() != before


def test_the_version_is_a_function_of_the_content(seeded_db: Path) -> None:
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    before = kb.catalog_version()
    _write(seeded_db, f"UPDATE objects SET mass_g = mass_g + 1 {TARGET}")
    assert kb.catalog_version() != before
    _write(seeded_db, f"UPDATE objects SET mass_g = mass_g - 1 {TARGET}")
    assert kb.catalog_version() == before


def test_writes_outside_what_recall_reads_keep_the_version(seeded_db: Path) -> None:
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    before = kb.catalog_version()
    _write(seeded_db, f"UPDATE objects SET source = 'elsewhere' {TARGET}")
    _write(
        seeded_db,
        "INSERT INTO ingestion_runs (id, started_at, status, fetched, not_modified, extracted, rejected, "
        "new, updated) VALUES (999999, now(), 'ok', 0, 0, 0, 0, 0, 0)",
    )
    assert kb.catalog_version() == before


def test_the_value_checksum_is_the_content_fingerprint(seeded_db: Path) -> None:
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    version = kb.catalog_version()
    with kb.connect() as con:
        fingerprint = content_fingerprint(con)
    assert fingerprint == [version.objects, version.values_hash, version.aliases, version.aliases_hash]


def test_the_recall_snapshot_sees_a_value_changed_without_a_new_updated_at(seeded_db: Path) -> None:
    before = load_snapshot(seeded_db)
    i = before.names.index("tennis ball")
    mass = list(before.num_cols[3])[i]  # a_cm, b_cm, c_cm, mass_g
    _write(seeded_db, f"UPDATE objects SET mass_g = mass_g + 100 {TARGET}")
    after = load_snapshot(seeded_db)
    assert after is not before
    assert list(after.num_cols[3])[after.names.index("tennis ball")] == pytest.approx(mass + 100)


def test_the_stored_recall_index_fingerprints_the_same_content(seeded_db: Path) -> None:
    """recall.stored_index keeps its own copy of the fingerprint (the speed helper's module): the two agree."""
    from recall.stored_index import catalog_fingerprint

    with KnowledgeBase.open(seeded_db, read_only=True).connect() as con:
        assert catalog_fingerprint(con) == content_fingerprint(con)
