"""Many strings in a few NumPy arrays, found by a stable 64-bit hash: the name index's big key tables.

A catalog of N objects has about N distinct phrases (every name is one) and N distinct words (names end
in model numbers). As Python objects (a ``str`` per key, a dict slot, an ``int`` id) they cost about 140 B
per phrase and 95 B per word; here a key costs its UTF-8 bytes plus 17 B: one separator byte in the text,
its start (int32), its hash (uint64, sorted) and its id in hash order (int32). A lookup hashes the key
(:func:`key_hash`), finds its hash by binary search and compares the bytes (two keys of one hash are both
checked), so a hash collision never gives a wrong answer.

The hash is a polynomial over the bytes modulo 2^64 (the same in NumPy, :func:`key_hashes`, and in Python):
unlike Python's ``hash`` it does not change between processes, so it is stored with the keys.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence, Set

import numpy as np

__all__ = [
    "GroupColumn",
    "KeyRows",
    "StringColumn",
    "StringSet",
    "StringTable",
    "WordKeys",
    "key_hash",
    "key_hashes",
]

_P = 0x100000001B3  # the 64-bit FNV prime
_LENGTH = 0x9E3779B97F4A7C15  # mixes in the length
_MASK = (1 << 64) - 1
#: Joins the keys in the text (never inside a key: the caller refuses such keys).
SEP = 0
_SPACE = ord(" ")
_CHUNK = 1 << 22  # bytes hashed at once (bounds the temporary arrays to ~100 MB)


def key_hash(raw: bytes) -> int:
    """The stable hash of one key's UTF-8 bytes: sum of (byte + 1) * P^(L-1-i), plus L * C, mod 2^64."""
    h = 0
    for b in raw:
        h = (h * _P + b + 1) & _MASK
    return (h + len(raw) * _LENGTH) & _MASK


def key_hashes(text: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """:func:`key_hash` of every key of ``text`` (uint8; key k is ``text[starts[k] : starts[k+1] - 1]``).

    P is odd, so invertible modulo 2^64: with S the running sum of (byte + 1) * P^-j over the bytes of a
    chunk, a key's polynomial over [lo, hi) is (S[hi] - S[lo]) * P^(hi-1), three passes over the bytes."""
    n = len(starts) - 1
    out = np.zeros(n, dtype=np.uint64)
    if n == 0:
        return out
    lengths = (np.diff(starts) - 1).astype(np.int64)
    bounds = np.unique(np.searchsorted(starts[:-1], np.arange(0, int(starts[-1]) + _CHUNK, _CHUNK)))
    bounds = np.unique(np.concatenate((bounds[bounds < n], [n])))
    span = int(np.max(starts[bounds[1:]] - starts[bounds[:-1]]))
    with np.errstate(over="ignore"):
        powers = np.cumprod(np.full(span + 1, _P, dtype=np.uint64))
        powers = np.concatenate(([np.uint64(1)], powers[:-1]))  # P^0 .. P^span, modulo 2^64
        inverse = np.cumprod(np.full(span + 1, pow(_P, -1, 1 << 64), dtype=np.uint64))
        inverse = np.concatenate(([np.uint64(1)], inverse[:-1]))
        for a, b in zip(bounds[:-1], bounds[1:], strict=True):
            first = int(starts[a])
            chunk = text[first : int(starts[b])].astype(np.uint64) + np.uint64(1)
            sums = np.concatenate(([np.uint64(0)], np.cumsum(chunk * inverse[: len(chunk)], dtype=np.uint64)))
            lo = (starts[a:b] - first).astype(np.int64)
            hi = lo + lengths[a:b]
            out[a:b] = (sums[hi] - sums[lo]) * powers[np.maximum(hi - 1, 0)]
            out[a:b] += lengths[a:b].astype(np.uint64) * np.uint64(_LENGTH)
    return out


class StringTable:
    """Key k (0 <= k < n) as bytes of one text; :meth:`find` gives a key's k (-1 if absent)."""

    def __init__(self, text: np.ndarray, hashes: np.ndarray, order: np.ndarray):
        """``text``: the keys' UTF-8 bytes, each followed by a separator; ``hashes``: their hashes sorted;
        ``order``: the key of each sorted hash (what :meth:`arrays` stores)."""
        self.text, self.hashes, self.order = text, hashes, order
        ends = np.flatnonzero(text == SEP).astype(np.int64) + 1
        big = len(text) >= 2**31
        self.starts = np.concatenate(([0], ends)).astype(np.int64 if big else np.int32)
        if len(self.starts) - 1 != len(hashes) or len(order) != len(hashes):
            raise ValueError("string table arrays do not match")

    @classmethod
    def of(cls, keys: list[str]) -> StringTable:
        """The table of ``keys`` (distinct; refused with ValueError when one holds the separator)."""
        raw = [k.encode("utf-8") for k in keys]
        text = np.frombuffer(b"".join(r + b"\0" for r in raw), dtype=np.uint8)
        if int((text == SEP).sum()) != len(keys):
            raise ValueError("a key holds the separator")
        starts = np.concatenate(([0], np.cumsum([len(r) + 1 for r in raw], dtype=np.int64)))
        hashes = key_hashes(text, starts)
        order = np.argsort(hashes, kind="stable").astype(np.int32)
        return cls(text, hashes[order], order)

    def __len__(self) -> int:
        return len(self.hashes)

    def key(self, k: int) -> str:
        return self.text[int(self.starts[k]) : int(self.starts[k + 1]) - 1].tobytes().decode("utf-8")

    def __iter__(self) -> Iterator[str]:
        return (self.key(k) for k in range(len(self)))

    def find(self, key: str) -> int:
        raw = key.encode("utf-8")
        h = np.uint64(key_hash(raw))
        at = int(np.searchsorted(self.hashes, h))
        while at < len(self.hashes) and self.hashes[at] == h:
            k = int(self.order[at])
            if self.text[int(self.starts[k]) : int(self.starts[k + 1]) - 1].tobytes() == raw:
                return k
            at += 1
        return -1

    def arrays(self, prefix: str) -> dict[str, np.ndarray]:
        return {f"{prefix}_text": self.text, f"{prefix}_hashes": self.hashes, f"{prefix}_order": self.order}

    @classmethod
    def from_arrays(cls, data, prefix: str) -> StringTable:
        return cls(data[f"{prefix}_text"], data[f"{prefix}_hashes"], data[f"{prefix}_order"])

    @property
    def nbytes(self) -> int:
        return int(self.text.nbytes + self.hashes.nbytes + self.order.nbytes + self.starts.nbytes)


class StringSet(Set):
    """A frozen set of strings over a :class:`StringTable` (equal to any set of the same strings)."""

    def __init__(self, table: StringTable):
        self.table = table

    def __contains__(self, key) -> bool:
        return isinstance(key, str) and self.table.find(key) >= 0

    def __iter__(self) -> Iterator[str]:
        return iter(self.table)

    def __len__(self) -> int:
        return len(self.table)

    @classmethod
    def _from_iterable(cls, it) -> frozenset:
        return frozenset(it)  # what set operations (|, &, -) give: a plain frozenset

    __hash__ = Set._hash


class KeyRows:
    """key (a str, or a tuple of words joined by spaces) -> its rows, over a :class:`StringTable` and CSR
    arrays (``rows[starts[k] : starts[k+1]]``, ascending): the interface of ``recall.name_tables.RowsByKey``."""

    def __init__(self, keys: StringTable, starts: np.ndarray, rows: np.ndarray, tuples: bool = False):
        if len(starts) != len(keys) + 1:
            raise ValueError("key rows do not match the keys")
        self.keys, self.starts, self.rows, self.tuples = keys, starts, rows, tuples

    @staticmethod
    def _key(key) -> str:
        return key if isinstance(key, str) else " ".join(key)

    def __iter__(self):
        return (tuple(k.split(" ")) if self.tuples else k for k in self.keys)

    def __contains__(self, key) -> bool:
        return self.keys.find(self._key(key)) >= 0

    def __len__(self) -> int:
        return len(self.keys)

    def span(self, key) -> np.ndarray:
        k = self.keys.find(self._key(key))
        if k < 0:
            raise KeyError(key)
        return self.rows[self.starts[k] : self.starts[k + 1]]

    def __getitem__(self, key) -> set[int]:
        return set(self.span(key).tolist())

    def get(self, key, default=None):
        k = self.keys.find(self._key(key))
        return default if k < 0 else set(self.rows[self.starts[k] : self.starts[k + 1]].tolist())

    @property
    def nbytes(self) -> int:
        return int(self.keys.nbytes + self.starts.nbytes + self.rows.nbytes)


class StringColumn(Sequence):
    """A read-only list of strings over one UTF-8 text (strings joined by the separator) and int32 starts:
    the catalog's names at their bytes plus 5 B each, instead of about 75 B as Python ``str`` objects.
    Item ``i`` is decoded when asked; equal to any sequence of the same strings."""

    def __init__(self, text: np.ndarray, count: int):
        ends = np.flatnonzero(text == SEP).astype(np.int64)
        if count and len(ends) != count - 1 or not count and len(text):
            raise ValueError("string count")
        big = len(text) >= 2**31
        self.text = text
        self.starts = np.concatenate(([0], ends + 1, [len(text) + 1])).astype(np.int64 if big else np.int32)
        self._n = count

    def __len__(self) -> int:
        return self._n

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(self._n))]
        i = int(i)
        if i < 0:
            i += self._n
        if not 0 <= i < self._n:
            raise IndexError(i)
        return self.text[int(self.starts[i]) : int(self.starts[i + 1]) - 1].tobytes().decode("utf-8")

    def __iter__(self) -> Iterator[str]:
        return iter(self.text.tobytes().decode("utf-8").split("\0") if self._n else ())

    def __eq__(self, other) -> bool:
        if isinstance(other, Sequence) and not isinstance(other, str):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))
        return NotImplemented

    __hash__ = None  # like a list

    @property
    def nbytes(self) -> int:
        return int(self.text.nbytes + self.starts.nbytes)


class GroupColumn(Sequence):
    """A read-only list of tuples of strings (row i: ``strings[starts[i] : starts[i+1]]``, a
    :class:`StringColumn`): the catalog's aliases at their bytes plus 4 B per row, instead of a list
    slot per row and a tuple per aliased row. Equal to any sequence of the same tuples."""

    def __init__(self, strings: StringColumn, starts: np.ndarray):
        if len(starts) == 0 or int(starts[-1]) != len(strings):
            raise ValueError("group starts do not match the strings")
        self.strings = strings
        self.starts = starts.astype(np.int32 if len(strings) < 2**31 else np.int64)

    def __len__(self) -> int:
        return len(self.starts) - 1

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        i = int(i)
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        a, b = int(self.starts[i]), int(self.starts[i + 1])
        return tuple(self.strings[j] for j in range(a, b))

    def __iter__(self) -> Iterator[tuple[str, ...]]:
        flat = list(self.strings)
        bounds = self.starts.tolist()
        return (tuple(flat[a:b]) for a, b in zip(bounds[:-1], bounds[1:], strict=True))

    def __eq__(self, other) -> bool:
        if isinstance(other, Sequence) and not isinstance(other, str):
            return len(self) == len(other) and all(
                tuple(a) == tuple(b) for a, b in zip(self, other, strict=True)
            )
        return NotImplemented

    __hash__ = None  # like a list

    @property
    def nbytes(self) -> int:
        return int(self.strings.nbytes + self.starts.nbytes)


class WordKeys:
    """word -> the keys holding it, for keys that are words joined by spaces (the name index's phrases):
    every word of every key hashed at once (:func:`key_hashes`, the words cut at the spaces and
    separators), sorted by hash. A lookup finds the word's hash by binary search and compares the bytes
    of every word of that hash, so it is exact. 16 B per word of a key (hash, key, start, length)."""

    def __init__(self, text: np.ndarray):
        """``text``: the keys' UTF-8 bytes, each followed by :data:`SEP` (:attr:`StringTable.text`)."""
        ends = ((text == SEP) | (text == _SPACE)).nonzero()[0]
        starts = np.concatenate(([0], ends + 1))
        last = text[ends] == SEP  # the key's last word
        key = np.cumsum(last) - last
        hashes = key_hashes(text, starts)
        order = np.argsort(hashes, kind="stable")
        self.text, self.hashes = text, hashes[order]
        self.keys = key[order].astype(np.int32)
        self.starts = starts[:-1][order].astype(np.int64 if len(text) >= 2**31 else np.int32)
        self.lengths = np.diff(starts)[order].astype(np.int32) - 1

    def keys_of(self, word: str) -> np.ndarray:
        """The keys (ascending, with repeats when a key holds the word twice) that hold ``word``."""
        raw = word.encode("utf-8")
        h = np.uint64(key_hash(raw))
        lo, hi = int(np.searchsorted(self.hashes, h)), int(np.searchsorted(self.hashes, h, "right"))
        keys, starts = self.keys[lo:hi], self.starts[lo:hi]
        same = self.lengths[lo:hi] == len(raw)
        if len(raw):
            at = starts[:, None].astype(np.int64) + np.arange(len(raw))
            same &= (self.text[at] == np.frombuffer(raw, dtype=np.uint8)).all(axis=1)
        return keys[same]

    @property
    def nbytes(self) -> int:
        return int(self.hashes.nbytes + self.keys.nbytes + self.starts.nbytes + self.lengths.nbytes)
