"""The tables behind :class:`recall.engine.NameIndex`, built column-wise (pyarrow string kernels and
NumPy), not name by name: about 1 µs per name instead of ~10 µs.

Per catalog name or alias (a *phrase*) the rules are those of ``recall.engine`` (``normalize_words``)
and :mod:`recall.names` (``name_core``, ``_head``): its words and its core (variant labels dropped) each
name the row; the head noun of the core and its suffixes of at least ``MIN_SUFFIX`` letters ("spoon" in "teaspoon") are head
keys of the row, with the materials the phrase states besides its head; a core of material words and
generic nouns naming one material is *generic*. Python runs once per distinct word (plurals) and per
distinct head (suffixes), and per phrase only for the few phrases that are not ASCII. The tables are
read through small mappings with the interface ``NameIndex.find`` uses (``in``, ``[]`` giving a set of
rows, ``get``). A test checks them against the name-by-name rules on real and random names.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Sequence

import numpy as np

from recall.names import GENERIC_NOUNS, is_variant_label, tables_by_rules

__all__ = ["COLUMNWISE_FROM", "NameTables", "RowsByKey", "name_tables"]

#: Catalogs with at least this many names and aliases are built column-wise; smaller ones name by name
#: (pyarrow's import alone, ~0.3 s, costs more than the rules on a few thousand names).
COLUMNWISE_FROM = 20_000


def name_tables(names: Sequence[str], aliases: Sequence[Sequence[str]], materials, min_suffix: int):
    """The tables of :class:`recall.engine.NameIndex`: column-wise from :data:`COLUMNWISE_FROM`
    phrases, else by the rules one name at a time (the same tables; a test checks they are equal)."""
    if len(names) >= COLUMNWISE_FROM or len(names) + sum(map(len, aliases)) >= COLUMNWISE_FROM:
        return NameTables(names, aliases, materials, min_suffix)
    return tables_by_rules(names, aliases, materials, min_suffix)


_PARENS = r"\([^)]*\)|\[[^\]]*\]"
_SEPARATORS = "[^a-z0-9]+"


class RowsByKey:
    """key (a str, or a tuple of words joined by spaces) -> the set of rows, over CSR arrays."""

    def __init__(self, keys: list[str], starts: np.ndarray, rows: np.ndarray, tuples: bool = False):
        self.ids = dict(zip(keys, range(len(keys)), strict=True))
        self.starts, self.rows, self.tuples = starts, rows, tuples

    def __iter__(self):
        return (tuple(k.split(" ")) if self.tuples else k for k in self.ids)

    @staticmethod
    def _key(key) -> str:
        return key if isinstance(key, str) else " ".join(key)

    def __contains__(self, key) -> bool:
        return self._key(key) in self.ids

    def __len__(self) -> int:
        return len(self.ids)

    def span(self, key) -> np.ndarray:
        i = self.ids[self._key(key)]
        return self.rows[self.starts[i] : self.starts[i + 1]]

    def __getitem__(self, key) -> set[int]:
        return set(self.span(key).tolist())

    def get(self, key, default=None):
        return self[key] if key in self else default


class _HeadMaterials:
    """(head key, row) -> the materials the row's phrases with that head state, or None (some phrase
    states none, or no such pair)."""

    def __init__(self, heads: RowsByKey, masks: np.ndarray, materials: Sequence[str]):
        self.heads, self.masks, self.materials = heads, masks, materials

    def get(self, key, default=None):
        word, row = key
        if word not in self.heads:
            return default
        i = self.heads.ids[word]
        lo, hi = self.heads.starts[i], self.heads.starts[i + 1]
        at = lo + int(np.searchsorted(self.heads.rows[lo:hi], row))
        if at >= hi or self.heads.rows[at] != row or not self.masks[at]:
            return default
        return {m for b, m in enumerate(self.materials) if self.masks[at] >> b & 1}


class _RowsByMaterial:
    """material -> the set of rows of that material (computed when asked: only generic names ask)."""

    def __init__(self, materials: Sequence[str | None]):
        self.materials = np.asarray(list(materials), dtype=object)

    def get(self, material, default=None):
        rows = set(np.flatnonzero(self.materials == material).tolist()) if len(self.materials) else set()
        return rows or default


def _group(keys: np.ndarray, rows: np.ndarray, values: np.ndarray | None = None):
    """Sort (key id, row) pairs, drop duplicate pairs; CSR starts per key id (+ values per pair)."""
    order = np.lexsort((rows, keys))
    keys, rows = keys[order], rows[order]
    values = None if values is None else values[order]
    first = np.ones(len(keys), dtype=bool)
    first[1:] = (keys[1:] != keys[:-1]) | (rows[1:] != rows[:-1])
    if values is not None:  # a pair's value: 0 if any of its entries is 0, else the OR of them
        group = np.cumsum(first) - 1
        zero = np.zeros(int(first.sum()), dtype=bool)
        np.logical_or.at(zero, group, values == 0)
        ored = np.zeros(int(first.sum()), dtype=values.dtype)
        np.bitwise_or.at(ored, group, values)
        values = np.where(zero, 0, ored).astype(values.dtype)
    keys, rows = keys[first], rows[first]
    starts = np.searchsorted(keys, np.arange(int(keys.max(initial=-1)) + 2))
    return starts.astype(np.int64), rows.astype(np.int32), values


class NameTables:
    """Phrases, generic phrases, head keys with their stated materials, vocabulary (see the module)."""

    def __init__(self, names: Sequence[str], aliases: Sequence[Sequence[str]], materials, min_suffix: int):
        texts = list(names)
        texts.extend(itertools.chain.from_iterable(aliases))  # the owner of each: its row
        per_row = np.fromiter(map(len, aliases), dtype=np.int64, count=len(aliases))
        owners = np.concatenate((np.arange(len(names)), np.repeat(np.arange(len(aliases)), per_row)))
        n_phr = len(texts)
        words, wpar, core, cpar = _words_and_cores(texts)
        # word ids of the singular forms (Python once per distinct word), and what each word is
        vocab = _Vocabulary(words, core)
        words, core = vocab.ids[: len(words)], vocab.ids[len(words) :]
        keep = ~_variant_labels(core, cpar, vocab.label)
        core, cpar = core[keep], cpar[keep]
        core_keys = vocab.join(core, cpar, n_phr)
        spoken = np.zeros(n_phr, dtype=bool)
        spoken[wpar] = True  # a phrase with no word names nothing
        self.phrases = _phrases(vocab.join(words, wpar, n_phr), core_keys, spoken, owners)
        self.longest = int(np.bincount(wpar, minlength=1).max(initial=0))
        head, live = _heads(core, cpar, vocab, n_phr, spoken)
        # materials stated besides the head (bits of CATEGORIES["material"]); generic cores: one stated
        # material, a generic head, only generic nouns, material words and "of"
        wbits = np.where(core == head[cpar], 0, vocab.material_bit[core])
        stated = np.zeros(n_phr, dtype=np.int64)
        np.bitwise_or.at(stated, cpar, wbits)
        other = np.zeros(n_phr, dtype=bool)
        np.logical_or.at(other, cpar, ~vocab.allowed[core])
        one = (stated != 0) & ((stated & (stated - 1)) == 0)
        generic = live & one & ~other & vocab.generic_noun[np.maximum(head, 0)]
        self.generic: dict[tuple[str, ...], str] = {
            tuple(core_keys[p].as_py().split(" ")): vocab.materials[int(stated[p]).bit_length() - 1]
            for p in np.flatnonzero(generic).tolist()
        }
        self.heads, key_of, masks = _head_keys(head, live, stated, owners, vocab, min_suffix)
        self.head_materials = _HeadMaterials(self.heads, masks, vocab.materials)
        self.by_material = _RowsByMaterial(list(materials or ()))
        self.vocabulary = frozenset(vocab.singular) | frozenset(key_of)


def _words_and_cores(texts: list[str]):
    """Every phrase's words and its core (the words outside parentheses; all its words when it is all in
    parentheses), each with the phrase it belongs to, cores in phrase order."""
    import pyarrow as pa

    words, wpar = _tokens(texts, strip_parens=False)
    core, cpar = _tokens(texts, strip_parens=True)
    has_core = np.zeros(len(texts), dtype=bool)
    has_core[cpar] = True
    back = np.flatnonzero(~has_core[wpar])
    core = pa.concat_arrays([core, words.take(pa.array(back))])
    cpar = np.concatenate((cpar, wpar[back]))
    order = np.argsort(cpar, kind="stable")
    return words, wpar, core.take(pa.array(order)), cpar[order]


def _phrases(word_keys, core_keys, spoken: np.ndarray, owners: np.ndarray) -> RowsByKey:
    """Phrase -> rows: a phrase's words and its core both name its row."""
    import pyarrow as pa

    kid, uniq = _encode(pa.concat_arrays([word_keys.filter(spoken), core_keys.filter(spoken)]))
    starts, rows, _ = _group(kid, np.concatenate((owners[spoken], owners[spoken])))
    return RowsByKey(uniq, starts, rows, tuples=True)


def _heads(core: np.ndarray, cpar: np.ndarray, vocab: _Vocabulary, n_phr: int, spoken: np.ndarray):
    """(head word id per phrase, -1 without one; whether the phrase has a head): the word before the first
    "of" after the first word, else the last word of its core."""
    cstart = np.searchsorted(cpar, np.arange(n_phr))
    cend = np.searchsorted(cpar, np.arange(n_phr), "right")
    pos = np.arange(len(core)) - cstart[cpar]
    of = np.flatnonzero(vocab.of[core] & (pos >= 1))
    none = np.iinfo(np.int64).max
    first_of = np.full(n_phr, none)
    np.minimum.at(first_of, cpar[of], of)
    live = spoken & (cend > cstart)
    head = np.full(n_phr, -1, dtype=np.int64)
    head_at = np.where(first_of < none, first_of - 1, cend - 1)
    head[live] = core[head_at[live]]
    return head, live


def _head_keys(head, live, stated, owners, vocab: _Vocabulary, min_suffix: int):
    """Head key -> rows (each head and its suffixes of at least ``min_suffix`` letters, once per distinct
    head), the keys in order, and each (key, row) pair's stated-material bits."""
    hs, hinv = np.unique(head[live], return_inverse=True)
    suffixes = [[h, *(h[c:] for c in range(1, len(h) - min_suffix + 1))] for h in vocab.words(hs)]
    per = np.array([len(x) for x in suffixes], dtype=np.int64)
    key_of: dict[str, int] = {}
    flat = np.array([key_of.setdefault(k, len(key_of)) for x in suffixes for k in x], dtype=np.int64)
    kstart = np.concatenate(([0], np.cumsum(per)))
    reps = per[hinv]
    src = np.repeat(np.flatnonzero(live), reps)
    which = np.repeat(kstart[hinv], reps) + np.arange(reps.sum()) - np.repeat(np.cumsum(reps) - reps, reps)
    starts, rows, masks = _group(flat[which], owners[src], stated[src])
    return RowsByKey(list(key_of), starts, rows), key_of, masks


class _Vocabulary:
    """The distinct words of the phrases: raw token -> singular word id, and per word id what it is."""

    def __init__(self, words, core):
        import pyarrow as pa
        import pyarrow.compute as pc

        from kb.features import CATEGORIES
        from kb.kinds import singular as _singular
        from recall.lexicon import MATERIAL_WORDS

        enc = pa.concat_arrays([words, core]).dictionary_encode()
        raw_ids = np.asarray(enc.indices.to_numpy(zero_copy_only=False), dtype=np.int64)
        digits = np.asarray(pc.match_substring_regex(enc.dictionary, "^[0-9]+$").to_numpy(zero_copy_only=False), dtype=bool)
        # Python's singular for the words, not for the numbers (a number is its own singular)
        ids: dict[str, int] = {}
        to_id = np.empty(len(digits), dtype=np.int64)
        named = np.flatnonzero(~digits)
        to_id[named] = [ids.setdefault(_singular(w), len(ids)) for w in enc.dictionary.filter(~digits).to_pylist()]
        to_id[digits] = len(ids) + np.arange(int(digits.sum()))
        self.ids = to_id[raw_ids]
        words_only = list(ids)
        self.singular = words_only + enc.dictionary.filter(digits).to_pylist()
        self.array = pa.array(self.singular, type=pa.large_string())
        self.materials = list(CATEGORIES["material"])
        bit = {w: 1 << self.materials.index(m) for w, m in MATERIAL_WORDS.items()}
        n_num = int(digits.sum())

        def per_word(test, number, dtype):
            values = [test(w) for w in words_only] + [number] * n_num
            return np.array(values or [number], dtype=dtype)

        self.label = per_word(is_variant_label, True, bool)
        self.material_bit = per_word(lambda w: bit.get(w, 0), 0, np.int64)
        self.allowed = per_word(lambda w: w in GENERIC_NOUNS or w in MATERIAL_WORDS or w == "of", False, bool)
        self.of = per_word(lambda w: w == "of", False, bool)
        self.generic_noun = per_word(lambda w: w in GENERIC_NOUNS, False, bool)

    def words(self, ids: np.ndarray) -> list[str]:
        return [self.singular[i] for i in ids.tolist()]

    def join(self, ids: np.ndarray, par: np.ndarray, n: int):
        """Per phrase, its words joined by spaces ("" when it has none)."""
        import pyarrow as pa
        import pyarrow.compute as pc

        offsets = pa.array(np.searchsorted(par, np.arange(n + 1)).astype(np.int64))
        lists = pa.LargeListArray.from_arrays(offsets, self.array.take(pa.array(ids)))
        return pc.binary_join(lists, pa.scalar(" ", type=pa.large_string()))


def _encode(values) -> tuple[np.ndarray, list[str]]:
    """Distinct strings (hashing, no sort) and the index of each value among them."""
    enc = values.dictionary_encode()
    return np.asarray(enc.indices.to_numpy(zero_copy_only=False), dtype=np.int64), enc.dictionary.to_pylist()


def _tokens(texts: list[str], strip_parens: bool):
    """Lower-case word tokens (apostrophes dropped) of each text, as flat words and their text's index
    (``recall.engine.normalize_words`` before the singular); non-ASCII texts go through Python."""
    import pyarrow as pa
    import pyarrow.compute as pc

    from kb.kinds import _WORD  # the tokens of kb.kinds.words_of (letters of any script)

    arr = pa.array(texts, type=pa.large_string())
    ascii_ = np.asarray(pc.string_is_ascii(arr).to_numpy(zero_copy_only=False), dtype=bool)
    low = pc.utf8_lower(arr)
    if strip_parens:
        low = pc.replace_substring_regex(low, _PARENS, " ")
    low = pc.replace_substring(pc.replace_substring(low, "'", ""), "\u2019", "")
    parts = pc.split_pattern_regex(low, _SEPARATORS)
    flat = pc.list_flatten(parts)
    parent = np.asarray(pc.list_parent_indices(parts).to_numpy(), dtype=np.int64)
    keep = np.asarray(pc.not_equal(flat, "").to_numpy(zero_copy_only=False), dtype=bool) & ascii_[parent]
    words, par = [flat.filter(keep)], [parent[keep]]
    for i in np.flatnonzero(~ascii_).tolist():  # Python's rules for the rest
        text = re.sub(_PARENS, " ", texts[i]) if strip_parens else texts[i]
        found = _WORD.findall(text.lower().replace("'", "").replace("\u2019", ""))
        words.append(pa.array(found, type=pa.large_string()))
        par.append(np.full(len(found), i, dtype=np.int64))
    par = np.concatenate(par)
    order = np.argsort(par, kind="stable")
    return pa.concat_arrays(words).take(pa.array(order)), par[order]


def _variant_labels(core: np.ndarray, cpar: np.ndarray, label: np.ndarray) -> np.ndarray:
    """Which words are trailing numbers, single letters or variant words ("no", "v") of their phrase;
    the first word of a phrase never is (``name_core`` keeps one word)."""
    lab = label[core] if len(core) else np.zeros(0, dtype=bool)
    n = int(cpar.max(initial=-1)) + 1
    starts = np.searchsorted(cpar, np.arange(n))
    ends = np.searchsorted(cpar, np.arange(n), "right")
    cum = np.concatenate(([0], np.cumsum(~lab)))
    index = np.arange(len(core))
    after = cum[ends[cpar]] - cum[index + 1]  # words of its phrase after it that are no label
    return lab & (after == 0) & (index - starts[cpar] >= 1)
