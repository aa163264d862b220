"""The recall index stored beside the catalog: the snapshot's columns and the name tables, built once.

Building a :class:`~recall.engine.Recaller` over a large catalog costs seconds (reading the columns, and
the name tables of :mod:`recall.names`: about 7 µs per name at 1M). So :func:`load_index` keeps what it
built in a file beside the DuckDB catalog (``catalog.duckdb.recall-index``) and reloads it while the
catalog has not changed. The file records two versions and is used only when both are equal:

* the catalog's **content fingerprint** (:func:`catalog_fingerprint`), computed by DuckDB in the same
  read-only connection the columns would be read in: the count and XOR of a 64-bit hash of every object
  row (id, name, every feature) and of every alias row. Any write that changes what recall reads changes
  it (an alias added without touching its object as well), whoever made the write;
* the **code version** (:func:`code_version`): a hash of the source of the modules that make the index.

Checking the fingerprint means opening the catalog (importing DuckDB, ~0.2 s of a one-shot command). So
beside the index a small note (``.recall-index.checked``) records the catalog files' state (device,
inode, size, modification and change times of the file and its write-ahead log) when their content was
fingerprinted; while the files are exactly in that state the index is read without opening the catalog.
Any write changes the state; one within the file system's time resolution of the note could leave the
same times, so a state is noted only when the files had been left alone for :data:`SETTLED_S` seconds
before the fingerprint was taken (the "racy git" rule). Within that time, or after any change, the
fingerprint decides.

When either version differs the index is rebuilt and the file replaced atomically (written beside it, then
``os.replace``); a reader sees the old file or the new one, never half of one. A file that cannot be read
(damaged, another format) is rebuilt; a directory that cannot be written just goes without the file.
The file holds NumPy arrays only (``np.load(allow_pickle=False)``): loading it runs no code.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import time
import zipfile
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

from kb.features import CATEGORICAL_FEATURES, CATEGORIES, NUMERIC_FEATURES

__all__ = [
    "FORMAT",
    "STORED_FROM",
    "RecallIndex",
    "catalog_fingerprint",
    "code_version",
    "current_version",
    "index_path",
    "load_index",
    "read_index",
    "write_index",
]

#: The file layout's version (the code version covers what the tables mean).
FORMAT = 2
#: Catalogs with at least this many objects keep their index in a file (reading it back is faster than
#: building from the first object on: 169 objects, 8 ms instead of 30).
STORED_FROM = 1
#: Catalog files last changed this long before they were fingerprinted are known by their file state
#: (device, inode, size, modification and change times, see :func:`file_state`) afterwards.
SETTLED_S = 3.0
#: Joins the strings of one array in the file (names, aliases and keys never hold it: refused if they do).
_SEP = "\x00"
#: The modules whose code decides what the stored index holds.
_SOURCES = ("recall/names.py", "recall/name_tables.py", "recall/stored_index.py", "recall/snapshot.py",
            "recall/lexicon.py", "recall/lexicon_categories.py", "recall/string_table.py", "kb/kinds.py", "kb/features.py")  # fmt: skip
_ROOT = Path(__file__).resolve().parent.parent
MATERIALS = tuple(CATEGORIES["material"])


@dataclass
class RecallIndex:
    """What a recaller is built from: the snapshot and its name tables (see :class:`~recall.name_tables.NameTables`)."""

    snapshot: Any
    tables: Any
    #: "stored" (read from the file), "built" (and written), "built, not stored" (small, or unwritable).
    origin: str = "built"


def index_path(db: str | Path) -> Path:
    db = Path(db)
    return db.with_name(db.name + ".recall-index")


def code_version() -> str:
    """A hash of the source of the modules that build the index (a change there makes old files stale)."""
    digest = hashlib.sha1(str(FORMAT).encode())
    for rel in _SOURCES:
        path = _ROOT / rel
        digest.update(rel.encode() + b"\0" + (path.read_bytes() if path.exists() else b"-"))
    return digest.hexdigest()


def catalog_fingerprint(con) -> list[int]:
    """Counts and XORs of row hashes of ``objects`` (id, name, features) and ``object_aliases``: changes
    whenever what recall reads of the catalog changes."""
    cols = ", ".join(("id", "name", *NUMERIC_FEATURES, *CATEGORICAL_FEATURES))
    objects = con.execute(f"SELECT count(*), coalesce(bit_xor(hash({cols})), 0) FROM objects").fetchone()
    aliases = con.execute("SELECT count(*), coalesce(bit_xor(hash(alias, object_id)), 0) FROM object_aliases").fetchone()
    return [int(objects[0]), int(objects[1]), int(aliases[0]), int(aliases[1])]


def load_index(db: str | Path, *, store: bool | None = None) -> RecallIndex:
    """The snapshot and name tables of the catalog at ``db``: from the stored file when the catalog and
    the code are those it was built from, else built (and stored, for catalogs of :data:`STORED_FROM`
    objects or more; ``store`` forces either way)."""
    db = Path(db)
    file = index_path(db)
    code = code_version()
    if store is not False:
        unchanged = _read_if_file_unchanged(db, file, code)
        if unchanged is not None:
            return unchanged
    from kb.catalog import KnowledgeBase
    from recall.snapshot import read_columns

    checked_at, state = time.time_ns(), file_state(db)  # before the read: a later write changes the state
    with KnowledgeBase.open(db, read_only=True).connect() as con:
        fingerprint = catalog_fingerprint(con)
        stored = read_index(file, fingerprint, code) if store is not False else None
        if stored is None:
            snapshot = read_columns(con, version=("fingerprint", *fingerprint))
    if stored is not None:
        _record_state(file, state, checked_at, fingerprint, code)
        return stored
    tables = build_tables(snapshot)
    wanted = store if store is not None else len(snapshot) >= STORED_FROM
    written = write_index(file, RecallIndex(snapshot, tables), fingerprint, code) if wanted else None
    if written is not None:
        _record_state(file, state, checked_at, fingerprint, code)
        return written
    return RecallIndex(snapshot, tables, "built, not stored")


def current_version(db: str | Path) -> tuple:
    """The version :func:`load_index` would give the snapshot of the catalog at ``db`` now
    (``("fingerprint", ...)``), without reading the index or the columns: from the note beside the index
    while the catalog files are as noted, else the content fingerprint (one read-only connection; noted
    in turn when the files had settled). A long-running reader (the service) compares it with the
    version of the recaller it holds, and reloads only when they differ."""
    db = Path(db)
    file = index_path(db)
    code = code_version()
    try:
        noted = json.loads(_state_path(file).read_bytes())
        if noted.get("code") == code and _settled(noted["state"], noted["checked_at"]):
            if noted["state"] == file_state(db):
                return ("fingerprint", *noted["catalog"])
    except (OSError, ValueError, KeyError, TypeError):
        pass
    from kb.catalog import KnowledgeBase

    checked_at, state = time.time_ns(), file_state(db)
    with KnowledgeBase.open(db, read_only=True).connect() as con:
        fingerprint = catalog_fingerprint(con)
    if file.exists():  # a note of the files' content, for the next check (and load_index)
        _record_state(file, state, checked_at, fingerprint, code)
    return ("fingerprint", *fingerprint)


# ------------------------------------------------------------------- the catalog file's own state
def file_state(db: Path) -> list:
    """(device, inode, size, mtime, ctime in ns) of the catalog file and of its write-ahead log (None
    when there is none): any write to the catalog changes it."""
    out: list = []
    for path in (db, db.with_name(db.name + ".wal")):
        try:
            st = path.stat()
        except FileNotFoundError:
            out.append(None)
            continue
        out.append([st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns])
    return out


def _settled(state: list, checked_at: int) -> bool:
    """Whether the files were last changed at least :data:`SETTLED_S` before ``checked_at``: then a
    later write cannot leave the same times (file times are coarser than nanoseconds; racy git)."""
    times = [t for entry in state if entry for t in entry[3:]]
    return bool(times) and max(times) < checked_at - int(SETTLED_S * 1e9)


def _state_path(file: Path) -> Path:
    return file.with_name(file.name + ".checked")


def _record_state(file: Path, state: list, checked_at: int, fingerprint: list[int], code: str) -> None:
    """Note beside the index that the catalog files in ``state`` hold the content ``fingerprint`` (only
    when they had settled; atomically; nothing when the directory cannot be written)."""
    if not _settled(state, checked_at):
        return
    text = json.dumps({"state": state, "checked_at": checked_at, "catalog": fingerprint, "code": code})
    _replace(_state_path(file), lambda out: out.write(text.encode()))


def _read_if_file_unchanged(db: Path, file: Path, code: str) -> RecallIndex | None:
    """The stored index without opening the catalog, when its files are exactly as they were when their
    content was last fingerprinted (and had settled then); None otherwise."""
    try:
        noted = json.loads(_state_path(file).read_bytes())
        if noted.get("code") != code or not _settled(noted["state"], noted["checked_at"]):
            return None
        if noted["state"] != file_state(db):
            return None
        return read_index(file, noted["catalog"], code)  # the index's own fingerprint must be that one
    except (OSError, ValueError, KeyError, TypeError):
        return None


def build_tables(snapshot):
    """The name tables of :class:`~recall.engine.NameIndex` for ``snapshot``."""
    from recall.name_tables import name_tables
    from recall.names import MIN_SUFFIX

    codes = snapshot.cat_cols[CATEGORICAL_FEATURES.index("material")]
    materials = [MATERIALS[c] if c >= 0 else None for c in codes.tolist()]
    return name_tables(snapshot.names, snapshot.aliases, materials, MIN_SUFFIX)


# ------------------------------------------------------------------------------------------- writing
def _blob(strings) -> np.ndarray:
    text = _SEP.join(strings)
    if text.count(_SEP) != max(len(strings) - 1, 0):
        raise ValueError("a string holds the separator")
    return np.frombuffer(text.encode("utf-8"), dtype=np.uint8)


def _csr(mapping, key_text) -> tuple[list[str], np.ndarray, np.ndarray]:
    """Keys (as text), CSR starts and the sorted rows of each key of a key -> rows mapping."""
    keys = list(mapping)
    rows = [np.sort(np.fromiter(mapping[k], dtype=np.int32)) for k in keys]
    starts = np.concatenate(([0], np.cumsum([len(r) for r in rows], dtype=np.int64)))
    return [key_text(k) for k in keys], starts, np.concatenate(rows) if rows else np.zeros(0, np.int32)


def _index_array(starts) -> np.ndarray:
    """CSR starts as int32 when they fit (4 B per key instead of 8)."""
    starts = np.asarray(starts, np.int64)
    return starts.astype(np.int32) if len(starts) and starts[-1] < 2**31 else starts


def _table_arrays(tables) -> dict[str, np.ndarray]:
    """The name tables as arrays: CSR phrases and heads (with the materials mask of each (head, row))."""
    from recall.name_tables import RowsByKey
    from recall.string_table import KeyRows, StringTable

    out: dict[str, np.ndarray] = {}
    if isinstance(tables.phrases, KeyRows):  # read back from a file (stored again as it is)
        phrase_keys, pstarts, prows = list(tables.phrases.keys), tables.phrases.starts, tables.phrases.rows
        head_keys, hstarts, hrows = list(tables.heads.ids), tables.heads.starts, tables.heads.rows
        masks = tables.head_materials.masks
    elif isinstance(tables.phrases, RowsByKey):  # built column-wise: already CSR
        phrase_keys, pstarts, prows = list(tables.phrases.ids), tables.phrases.starts, tables.phrases.rows
        head_keys, hstarts, hrows = list(tables.heads.ids), tables.heads.starts, tables.heads.rows
        masks = tables.head_materials.masks
    else:  # built by the rules: dicts of sets
        phrase_keys, pstarts, prows = _csr(tables.phrases, " ".join)
        head_keys, hstarts, hrows = _csr(tables.heads, str)
        bit = {m: 1 << i for i, m in enumerate(MATERIALS)}
        masks = np.zeros(len(hrows), dtype=np.int64)
        for k, key in enumerate(head_keys):
            for at in range(int(hstarts[k]), int(hstarts[k + 1])):
                stated = tables.head_materials.get((key, int(hrows[at])))
                masks[at] = sum(bit[m] for m in stated) if stated else 0
    mask_type = np.uint8 if len(MATERIALS) <= 8 else np.uint16 if len(MATERIALS) <= 16 else np.int64
    out.update(**StringTable.of(phrase_keys).arrays("phrase"), phrase_starts=_index_array(pstarts),
               phrase_rows=np.asarray(prows, np.int32), head_keys=_blob(head_keys),
               head_starts=np.asarray(hstarts, np.int64), head_rows=np.asarray(hrows, np.int32),
               head_masks=np.asarray(masks, mask_type), generic_keys=_blob([" ".join(k) for k in tables.generic]),
               generic_materials=_blob(list(tables.generic.values())),
               **StringTable.of(sorted(tables.vocabulary)).arrays("vocabulary"))  # fmt: skip
    return out


def write_index(file: Path, index: RecallIndex, fingerprint: list[int], code: str) -> RecallIndex | None:
    """Write ``index`` to ``file`` atomically; returns it as read back from the arrays written (the
    compact tables of a stored index), or None (and nothing written) when it cannot be written."""
    snap = index.snapshot
    try:
        flat = [a for row in snap.aliases for a in row]
        arrays = {
            "names": _blob(snap.names),
            "alias_text": _blob(flat),
            "alias_starts": np.concatenate(([0], np.cumsum([len(a) for a in snap.aliases], dtype=np.int64))),
            "num": np.stack(snap.num_cols) if len(snap) else np.zeros((len(NUMERIC_FEATURES), 0), np.float32),
            "cat": np.stack(snap.cat_cols) if len(snap) else np.zeros((len(CATEGORICAL_FEATURES), 0), np.int8),
            **_table_arrays(index.tables),
        }
    except ValueError:  # a separator inside a name: not storable
        return None
    meta = {"format": FORMAT, "code": code, "catalog": fingerprint, "n": len(snap), "aliases": len(flat),
            "longest": int(index.tables.longest), "generic": len(index.tables.generic),
            "vocabulary": len(index.tables.vocabulary)}  # fmt: skip
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    if not _replace(file, lambda out: np.savez(out, **arrays)):
        return None
    return _from_arrays(arrays, meta, origin="built")


def _replace(file: Path, write) -> bool:
    """Write ``file`` through ``write(binary file)`` beside it, then rename it over: readers see the old
    file or the new one. False (and no file left) when it cannot be written."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=file.name + ".", suffix=".tmp", dir=file.parent)
    except OSError:
        return False
    try:
        with os.fdopen(fd, "wb") as out:
            write(out)
        os.replace(tmp, file)
        return True
    except OSError:
        return False
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


# ------------------------------------------------------------------------------------------- reading
def _strings(arr: np.ndarray, count: int) -> list[str]:
    if count == 0:
        return []
    out = arr.tobytes().decode("utf-8").split(_SEP)
    if len(out) != count:
        raise ValueError("string count")
    return out


def read_index(file: Path, fingerprint: list[int], code: str) -> RecallIndex | None:
    """The index stored in ``file`` when it was built from this catalog content and this code; None when
    it was not, or the file is missing or unreadable."""
    try:
        with np.load(file, allow_pickle=False) as data:
            meta = json.loads(data["meta"].tobytes())
            if meta.get("format") != FORMAT or meta.get("code") != code or meta.get("catalog") != fingerprint:
                return None
            return _from_arrays({k: data[k] for k in data.files}, meta)
    except (OSError, EOFError, ValueError, KeyError, TypeError, zipfile.BadZipFile):
        return None  # missing, damaged or another layout: rebuilt


def _from_arrays(data: dict[str, np.ndarray], meta: dict, origin: str = "stored") -> RecallIndex:
    from recall.name_tables import RowsByKey, _HeadMaterials
    from recall.snapshot import CatalogSnapshot
    from recall.string_table import GroupColumn, KeyRows, StringColumn, StringSet, StringTable

    n = int(meta["n"])
    names = StringColumn(data["names"], n)
    aliases = GroupColumn(StringColumn(data["alias_text"], int(meta["aliases"])), data["alias_starts"])
    if len(aliases) != n:
        raise ValueError("alias rows")
    num, cat = data["num"], data["cat"]
    snap = CatalogSnapshot.from_columns(names, aliases, list(num), list(cat),
                                        version=("fingerprint", *meta["catalog"]))  # fmt: skip
    pstarts, hstarts = data["phrase_starts"], data["head_starts"]
    phrases = KeyRows(StringTable.from_arrays(data, "phrase"), pstarts, data["phrase_rows"], tuples=True)
    heads = RowsByKey(_strings(data["head_keys"], len(hstarts) - 1), hstarts, data["head_rows"])
    gkeys = _strings(data["generic_keys"], int(meta["generic"]))
    generic = dict(zip((tuple(k.split(" ")) for k in gkeys), _strings(data["generic_materials"], len(gkeys)),
                       strict=True))  # fmt: skip
    codes = cat[CATEGORICAL_FEATURES.index("material")] if n else np.zeros(0, np.int8)
    vocabulary = StringSet(StringTable.from_arrays(data, "vocabulary"))
    if len(vocabulary) != int(meta["vocabulary"]):
        raise ValueError("vocabulary count")
    tables = SimpleNamespace(
        phrases=phrases,
        generic=generic,
        by_material=RowsByMaterialCode(codes),
        heads=heads,
        head_materials=_HeadMaterials(heads, data["head_masks"], list(MATERIALS)),
        vocabulary=vocabulary,
        longest=int(meta["longest"]),
    )
    return RecallIndex(snap, tables, origin)


class RowsByMaterialCode:
    """material -> the set of rows of that material, from the snapshot's int8 material codes (1 B per
    row, shared with the snapshot; what ``recall.name_tables._RowsByMaterial`` holds as a Python list)."""

    def __init__(self, codes: np.ndarray):
        self.codes = codes

    def get(self, material, default=None):
        if material not in MATERIALS:
            return default
        rows = set(np.flatnonzero(self.codes == MATERIALS.index(material)).tolist())
        return rows or default
