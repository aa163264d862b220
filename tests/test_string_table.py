"""The name index's compact key tables (recall/string_table.py): every key found, no other, the NumPy
and Python hashes equal (they are stored in one process and computed in another), collisions resolved
by the bytes."""

from __future__ import annotations

import numpy as np
import pytest

from recall import string_table
from recall.string_table import KeyRows, StringSet, StringTable, key_hash

KEYS = ["a", "red mug 12", "", "tea cup", "tasse à thé", "x" * 3000, "red mug 1", "red mug 12 "] + [
    f"k{i}" for i in range(2000)
]


@pytest.mark.parametrize("chunk", [1 << 22, 7, 1])  # keys across chunk boundaries, one byte per chunk
def test_numpy_hashes_are_the_python_hash_of_every_key(monkeypatch, chunk):
    monkeypatch.setattr(string_table, "_CHUNK", chunk)
    table = StringTable.of(KEYS)
    assert [int(h) for h in table.hashes] == sorted(key_hash(k.encode()) for k in KEYS)
    assert [table.find(k) for k in KEYS] == list(range(len(KEYS)))
    assert list(table) == KEYS


def test_only_the_keys_are_found():
    table = StringTable.of(KEYS)
    for absent in ("red mug", "red mug 12  ", "A", "tasse a the", "x" * 2999, "k2000", " "):
        assert table.find(absent) == -1, absent


def test_keys_of_one_hash_are_told_apart_by_their_bytes(monkeypatch):
    monkeypatch.setattr(string_table, "key_hash", lambda raw: 0)
    monkeypatch.setattr(string_table, "key_hashes", lambda text, starts: np.zeros(len(starts) - 1, np.uint64))
    table = StringTable.of(["cup", "mug", "bowl"])
    assert [table.find(k) for k in ("cup", "mug", "bowl", "pan")] == [0, 1, 2, -1]


def test_a_key_holding_the_separator_is_refused():
    with pytest.raises(ValueError):
        StringTable.of(["cup", "m\x00ug"])


def test_set_and_rows_behave_as_a_frozenset_and_a_dict_of_sets():
    words = StringSet(StringTable.of(["mug", "cup", "ball"]))
    assert words == frozenset({"mug", "cup", "ball"}) and frozenset({"mug", "cup", "ball"}) == words
    assert "mug" in words and "pan" not in words and ("mug",) not in words and len(words) == 3
    assert words | {"pan"} == {"mug", "cup", "ball", "pan"} and words - {"cup"} == {"mug", "ball"}
    phrases = KeyRows(StringTable.of(["tea cup", "mug"]), np.array([0, 2, 3]), np.array([4, 9, 1], np.int32),
                      tuples=True)  # fmt: skip
    assert ("tea", "cup") in phrases and "tea cup" in phrases and ("tea",) not in phrases
    assert (
        phrases[("tea", "cup")] == {4, 9} and phrases.get(("mug",)) == {1} and phrases.get(("pan",), ()) == ()
    )
    assert set(phrases) == {("tea", "cup"), ("mug",)} and len(phrases) == 2
    with pytest.raises(KeyError):
        phrases.span(("pan",))


@pytest.mark.parametrize(
    "strings", [[], ["only"], ["", "mug", ""], ["tasse à thé", "red mug 12", "x" * 3000]]
)
def test_a_string_column_is_the_list_it_holds(strings):
    from recall.stored_index import _blob
    from recall.string_table import StringColumn

    column = StringColumn(_blob(strings), len(strings))
    assert column == strings and strings == column and list(column) == strings and len(column) == len(strings)
    assert [column[i] for i in range(len(strings))] == strings and column[::-1] == strings[::-1]
    if strings:
        assert column[-1] == strings[-1] and column[np.int64(0)] == strings[0]
    with pytest.raises(IndexError):
        column[len(strings)]
    assert column != [*strings, "more"]


@pytest.mark.parametrize("groups", [[], [()], [(), ("mug",), (), ("a", "b", "")], [("tasse à thé",), ()]])
def test_a_group_column_is_the_list_of_tuples_it_holds(groups):
    from recall.stored_index import _blob
    from recall.string_table import GroupColumn, StringColumn

    flat = [s for g in groups for s in g]
    starts = np.concatenate(([0], np.cumsum([len(g) for g in groups]))).astype(np.int64)
    column = GroupColumn(StringColumn(_blob(flat), len(flat)), starts)
    assert column == groups and groups == column and list(column) == groups and len(column) == len(groups)
    assert [column[i] for i in range(len(groups))] == groups and column[1:] == groups[1:]
    if groups:
        assert column[-1] == groups[-1]
    with pytest.raises(IndexError):
        column[len(groups)]
