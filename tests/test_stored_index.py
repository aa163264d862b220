"""The recall index stored beside the catalog (recall/stored_index.py): reloaded only while the catalog
and the code are those it was built from, rebuilt (atomically) after any change, and recalling exactly
what a freshly built recaller recalls."""

from __future__ import annotations

import csv
import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from kb.catalog import KnowledgeBase
from recall import stored_index
from recall.engine import Recaller
from recall.snapshot import load_snapshot
from recall.stored_index import index_path, load_index

ROOT = Path(__file__).resolve().parent.parent
DEV = ROOT / "recall" / "data" / "dev_descriptions.csv"

ADJECTIVES = ["red", "blue", "steel", "wooden", "glass", "soft", "kids", "travel"]
NOUNS = ["mug", "tea cup", "teaspoon", "tennis ball", "cutting board", "wood piece", "jar of honey", "toy"]


def _add_synthetic(db: Path, n: int) -> None:
    """``n`` objects with varied names (adjective noun number), features and an alias for every 7th."""
    adjectives = ", ".join(repr(a) for a in ADJECTIVES)
    nouns = ", ".join(repr(a) for a in NOUNS)
    with KnowledgeBase.open(db).connect(write=True) as con:
        con.execute(
            "INSERT INTO objects (name, a_cm, b_cm, c_cm, mass_g, shape, material, created_at, updated_at) "
            f"SELECT list_element([{adjectives}], (i % 8)::INT + 1) || ' ' || list_element([{nouns}], "
            "(i // 8 % 8)::INT + 1) || ' ' || i, 1 + i % 97, 1 + i % 53, 0.5 + i % 11, "
            "CASE WHEN i % 13 = 0 THEN NULL ELSE 5 + i % 991 END, "
            "list_element(['compact', 'prism', NULL], (i % 3)::INT + 1), "
            "list_element(['metal', 'wood', 'glass', 'plastic', NULL], (i % 5)::INT + 1), now(), now() "
            f"FROM range({n}) t(i)"
        )
        con.execute(
            "INSERT INTO object_aliases (alias, object_id) SELECT 'model ' || id || ' holder', id FROM objects "
            "WHERE id % 7 = 0"
        )


@pytest.fixture(scope="module")
def big_db(tmp_path_factory) -> Path:
    """The seed catalog plus enough synthetic objects to be stored (and built column-wise)."""
    path = tmp_path_factory.mktemp("stored") / "big.duckdb"
    KnowledgeBase.open(path).import_csv(ROOT / "kb" / "data" / "seed_catalog.csv")
    _add_synthetic(path, stored_index.STORED_FROM)
    return path


@pytest.fixture
def db(big_db: Path, tmp_path: Path) -> Path:
    copy = tmp_path / "catalog.duckdb"
    shutil.copy(big_db, copy)
    return copy


def _texts() -> list[str]:
    with DEV.open(encoding="utf-8") as f:
        dev = [row["description"] for row in csv.DictReader(f)]
    return dev[:60] + ["a red mug 1234", "model 700 holder", "a wooden tea cup", "a steel wood piece", "a toy"]


def _same_recall(a: Recaller, b: Recaller) -> None:
    for text in _texts():
        assert a.recall_text(text).to_dict() == b.recall_text(text).to_dict(), text


def test_a_stored_index_recalls_what_a_fresh_build_recalls(db: Path) -> None:
    built = load_index(db)
    assert built.origin == "built" and index_path(db).is_file()
    stored = load_index(db)
    assert stored.origin == "stored"
    a, b = built.snapshot, stored.snapshot
    assert a.names == b.names and a.aliases == b.aliases and a.version == b.version
    for x, y in zip([*a.num_cols, *a.cat_cols], [*b.num_cols, *b.cat_cols], strict=True):
        assert x.dtype == y.dtype and np.array_equal(x, y, equal_nan=True)
    assert set(built.tables.phrases) == set(stored.tables.phrases)
    assert built.tables.generic == stored.tables.generic and built.tables.vocabulary == stored.tables.vocabulary
    _same_recall(Recaller(load_snapshot(db)), Recaller.from_db(db))


def test_a_small_catalog_is_stored_by_the_rules_tables_too(seeded_db: Path) -> None:
    assert load_index(seeded_db, store=False).origin == "built, not stored"
    assert not index_path(seeded_db).exists()
    assert load_index(seeded_db).origin == "built"
    assert load_index(seeded_db).origin == "stored"
    _same_recall(Recaller(load_snapshot(seeded_db)), Recaller.from_db(seeded_db))


def _write(db: Path, sql: str) -> None:
    with KnowledgeBase.open(db, upgrade=False).connect(write=True) as con:
        con.execute(sql)


@pytest.mark.parametrize(
    "change",
    [
        "INSERT INTO object_aliases (alias, object_id) SELECT 'zorbulator', min(id) FROM objects",
        "UPDATE object_aliases SET alias = 'zorbulator' WHERE alias = (SELECT min(alias) FROM object_aliases)",
        "UPDATE objects SET name = 'zorbulator' WHERE id = (SELECT min(id) FROM objects)",
        "UPDATE objects SET mass_g = 1234.5 WHERE id = (SELECT max(id) FROM objects)",  # updated_at kept
        "UPDATE objects SET material = NULL WHERE id = (SELECT min(id) FROM objects WHERE material IS NOT NULL)",
        "DELETE FROM object_aliases WHERE object_id = (SELECT max(object_id) FROM object_aliases)",
        "INSERT INTO objects (name, a_cm, created_at, updated_at) VALUES ('zorbulator', 3, now(), now())",
    ],
)
def test_any_change_to_what_recall_reads_rebuilds_the_index(db: Path, change: str) -> None:
    before = load_index(db)
    assert load_index(db).origin == "stored"
    _write(db, change)
    after = load_index(db)
    assert after.origin == "built" and after.snapshot.version != before.snapshot.version
    assert load_index(db).origin == "stored"
    fresh = load_snapshot(db)
    assert after.snapshot.names == fresh.names and after.snapshot.aliases == fresh.aliases
    for x, y in zip(after.snapshot.num_cols + after.snapshot.cat_cols, fresh.num_cols + fresh.cat_cols, strict=True):
        assert np.array_equal(x, y, equal_nan=True)


@pytest.mark.parametrize(
    "change",
    [
        "INSERT INTO object_aliases (alias, object_id) SELECT 'zorbulator', min(id) FROM objects",
        "UPDATE object_aliases SET alias = 'zorbulator' WHERE alias = (SELECT min(alias) FROM object_aliases)",
        "UPDATE object_aliases SET object_id = (SELECT min(id) FROM objects) "
        "WHERE alias = (SELECT max(alias) FROM object_aliases)",
        "DELETE FROM object_aliases WHERE alias = (SELECT min(alias) FROM object_aliases)",
    ],
)
def test_an_alias_only_change_gives_a_new_catalog_version(db: Path, change: str) -> None:
    """No object row changes (count, largest id and latest update stay): the version still moves, so the
    cached snapshot (and the service's recaller) is rebuilt with the new aliases."""
    kb = KnowledgeBase.open(db, read_only=True)
    before, snap = kb.catalog_version(), load_snapshot(db)
    assert load_snapshot(db) is snap  # unchanged: the cached one
    _write(db, change)
    after = kb.catalog_version()
    assert after[:3] == before[:3] and after != before
    fresh = load_snapshot(db)
    assert fresh is not snap and fresh.aliases != snap.aliases


def test_a_write_outside_what_recall_reads_keeps_the_catalog_version(db: Path) -> None:
    kb = KnowledgeBase.open(db, read_only=True)
    before = kb.catalog_version()
    _write(
        db,
        "INSERT INTO ingestion_runs (id, started_at, status, fetched, not_modified, extracted, rejected, "
        "new, updated) VALUES (999999, now(), 'ok', 0, 0, 0, 0, 0, 0)",
    )
    assert kb.catalog_version() == before


def test_the_next_recall_sees_a_change(db: Path) -> None:
    assert Recaller.from_db(db).recall_text("a zorbulator").matches == []  # no such name: nothing stated
    assert load_index(db).origin == "stored"
    _write(db, "INSERT INTO object_aliases (alias, object_id) SELECT 'zorbulator', id FROM objects "
               "WHERE name = 'tomato soup can'")  # fmt: skip
    result = Recaller.from_db(db).recall_text("a zorbulator")
    assert result.matches[0].name == "tomato soup can" and result.matches[0].matched_by_name


def test_a_change_outside_what_recall_reads_keeps_the_index(db: Path) -> None:
    load_index(db)
    _write(db, "UPDATE objects SET source = 'elsewhere', updated_at = now()")
    assert load_index(db).origin == "stored"


def test_other_code_rebuilds_the_index(db: Path, monkeypatch) -> None:
    load_index(db)
    monkeypatch.setattr(stored_index, "code_version", lambda: "another version")
    assert load_index(db).origin == "built"
    assert load_index(db).origin == "stored"


@pytest.mark.parametrize("damage", [b"", b"not a zip", None])
def test_a_damaged_index_file_is_rebuilt(db: Path, damage: bytes | None) -> None:
    load_index(db)
    file = index_path(db)
    data = file.read_bytes()
    file.write_bytes(damage if damage is not None else data[: len(data) // 2])
    assert load_index(db).origin == "built"
    assert load_index(db).origin == "stored"


def test_an_unwritable_directory_goes_without_the_file(db: Path, monkeypatch) -> None:
    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(stored_index.tempfile, "mkstemp", refuse)
    index = load_index(db)
    assert index.origin == "built, not stored" and not index_path(db).exists()
    assert len(index.snapshot) > stored_index.STORED_FROM


def test_a_failed_write_leaves_the_old_file_and_no_temporary(db: Path, monkeypatch) -> None:
    load_index(db)
    old = index_path(db).read_bytes()
    _write(db, "UPDATE objects SET a_cm = 77 WHERE id = (SELECT min(id) FROM objects)")

    def fail(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(stored_index.os, "replace", fail)
    assert load_index(db).origin == "built, not stored"
    assert index_path(db).read_bytes() == old
    assert [p.name for p in db.parent.iterdir() if p.name.endswith(".tmp")] == []
    monkeypatch.undo()
    assert load_index(db).origin == "built"  # the old file no longer fits the catalog
    assert not any(p.suffix == ".tmp" for p in db.parent.iterdir())


def test_a_name_holding_the_separator_is_not_stored(db: Path) -> None:
    _write(db, "UPDATE objects SET name = 'odd' || chr(0) || 'name' WHERE id = (SELECT min(id) FROM objects)")
    assert load_index(db).origin == "built, not stored"
    assert not index_path(db).exists()


def test_the_index_file_holds_arrays_only(db: Path) -> None:
    load_index(db)
    with np.load(index_path(db), allow_pickle=False) as data:
        assert all(data[k].dtype != object for k in data.files)
    assert os.path.getsize(index_path(db)) > 0


# ----------------------------------------------------------------- the catalog file's state shortcut
def _no_catalog_access(monkeypatch) -> None:
    def refuse(*args, **kwargs):
        raise AssertionError("the catalog was opened")

    monkeypatch.setattr(KnowledgeBase, "connect", refuse)


def test_settled_unchanged_catalog_files_are_not_opened_again(db: Path, monkeypatch) -> None:
    monkeypatch.setattr(stored_index, "SETTLED_S", 0.0)
    assert load_index(db).origin == "built"
    with monkeypatch.context() as m:
        _no_catalog_access(m)
        index = load_index(db)
        assert index.origin == "stored" and len(index.snapshot) > stored_index.STORED_FROM
        _same_recall(Recaller(index.snapshot, index.tables), Recaller.from_db(db))
    _write(db, "INSERT INTO object_aliases (alias, object_id) SELECT 'zorbulator', min(id) FROM objects")
    assert load_index(db).origin == "built"  # the files changed: the fingerprint decides
    assert "zorbulator" in {a for row in load_index(db).snapshot.aliases for a in row}


def test_a_change_that_keeps_the_content_is_fingerprinted_and_the_index_kept(db: Path, monkeypatch) -> None:
    monkeypatch.setattr(stored_index, "SETTLED_S", 0.0)
    load_index(db)
    _write(db, "UPDATE objects SET source = 'elsewhere'")
    assert load_index(db).origin == "stored"  # opened (the state changed), same content
    with monkeypatch.context() as m:
        _no_catalog_access(m)
        assert load_index(db).origin == "stored"  # and the new state noted


def test_files_changed_just_before_their_fingerprint_are_always_checked(db: Path, monkeypatch) -> None:
    monkeypatch.setattr(stored_index, "SETTLED_S", 3600.0)  # every file is "just changed"
    load_index(db)
    assert not stored_index._state_path(index_path(db)).exists()
    _no_catalog_access(monkeypatch)
    with pytest.raises(AssertionError, match="the catalog was opened"):
        load_index(db)


@pytest.mark.parametrize("field", [2, 3, 4])  # size, modification time, change time
def test_a_noted_state_differing_in_any_field_is_not_trusted(db: Path, monkeypatch, field: int) -> None:
    monkeypatch.setattr(stored_index, "SETTLED_S", 0.0)
    load_index(db)
    note = stored_index._state_path(index_path(db))
    noted = json.loads(note.read_text())
    noted["state"][0][field] += 1
    note.write_text(json.dumps(noted))
    _no_catalog_access(monkeypatch)
    with pytest.raises(AssertionError, match="the catalog was opened"):
        load_index(db)


def test_a_note_for_another_index_is_not_trusted(db: Path, monkeypatch) -> None:
    monkeypatch.setattr(stored_index, "SETTLED_S", 0.0)
    load_index(db)
    note = stored_index._state_path(index_path(db))
    noted = json.loads(note.read_text())
    noted["catalog"][1] ^= 1
    note.write_text(json.dumps(noted))
    _no_catalog_access(monkeypatch)
    with pytest.raises(AssertionError, match="the catalog was opened"):
        load_index(db)


def test_settled_is_strictly_older_than_the_margin() -> None:
    state = [[1, 2, 3, 10_000_000_000, 10_000_000_000], None]
    margin = int(stored_index.SETTLED_S * 1e9)
    assert stored_index._settled(state, 10_000_000_000 + margin + 1)
    assert not stored_index._settled(state, 10_000_000_000 + margin)
    assert not stored_index._settled([None, None], 10**20)
