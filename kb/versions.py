"""What tells a changed catalog: :class:`CatalogVersion`, computed by DuckDB from the rows themselves.

A version made of counts, the largest id and the latest ``updated_at`` misses a value changed without a
later ``updated_at`` (a plain ``UPDATE objects SET mass_g = ...``, a writer whose clock is behind, two
writes in one timestamp), so the version also holds a checksum of the values: the XOR of a 64-bit hash of
every object row (id, name and every feature: what recall reads) and of every alias row. A changed value
changes its row's hash and so the XOR (up to a 64-bit hash collision). It costs one scan of each table: at
1M objects and 100k aliases the queries take 0.03 s of CPU (0.004 s without the value checksum), and
``KnowledgeBase.catalog_version()`` with opening its read connection 0.06-0.08 s (0.03 s before; synthetic
catalog, load about 2; ``benchmarks/version_bench.py``), paid at most once per ``snapshot_ttl`` by the
service.
"""

from __future__ import annotations

from typing import NamedTuple

from kb.features import FEATURES

__all__ = ["CatalogVersion", "catalog_version", "content_fingerprint"]

#: The object columns the value checksum covers (what recall reads of an object).
FINGERPRINT_COLUMNS: tuple[str, ...] = ("id", "name", *FEATURES)


class CatalogVersion(NamedTuple):
    """Equal versions: the same objects, values and aliases (a tuple, compared as one)."""

    objects: int
    max_id: int
    updated_at: str
    aliases: int
    aliases_hash: int
    values_hash: int


_VALUES_HASH = f"coalesce(bit_xor(hash({', '.join(FINGERPRINT_COLUMNS)})), 0)"
_ALIASES = "SELECT count(*), coalesce(bit_xor(hash(alias, object_id)), 0) FROM object_aliases"


def content_fingerprint(con) -> list[int]:
    """[object count, XOR of the object rows' hashes, alias count, XOR of the alias rows' hashes] over the
    DuckDB connection ``con``: changes whenever what recall reads of the catalog changes."""
    objects = con.execute(f"SELECT count(*), {_VALUES_HASH} FROM objects").fetchone()
    aliases = con.execute(_ALIASES).fetchone()
    return [int(objects[0]), int(objects[1]), int(aliases[0]), int(aliases[1])]


def catalog_version(con) -> CatalogVersion:
    """The :class:`CatalogVersion` of the catalog open on ``con`` (one scan of each table)."""
    n, max_id, latest, values = con.execute(
        "SELECT count(*), coalesce(max(id), 0), coalesce(CAST(max(updated_at) AS VARCHAR), ''), "
        f"{_VALUES_HASH} FROM objects"
    ).fetchone()
    aliases, mixed = con.execute(_ALIASES).fetchone()
    return CatalogVersion(int(n), int(max_id), str(latest), int(aliases), int(mixed), int(values))
