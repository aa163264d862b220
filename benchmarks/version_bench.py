"""What telling a changed catalog costs: ``KnowledgeBase.catalog_version()`` at 1M objects (synthetic catalog
written here), against the counts-and-latest-update version it replaced (no value checksum).

The service asks for it at most once per ``snapshot_ttl`` (1 s by default) and recall's snapshot cache on
each load. Reported in CPU seconds (process time: DuckDB's threads included; the 2 cores are shared).

Run: ``python benchmarks/version_bench.py [--objects N] [--repeat N]``.
"""

from __future__ import annotations

import argparse
import os
import shutil
import tempfile
from pathlib import Path

from timing import median_cpu_s

from kb.catalog import KnowledgeBase
from kb.versions import catalog_version

#: The version before the value checksum: counts, largest id, latest update and the aliases' checksum.
_OLD = (
    "SELECT count(*), coalesce(max(id), 0), coalesce(CAST(max(updated_at) AS VARCHAR), '') FROM objects",
    "SELECT count(*), coalesce(bit_xor(hash(alias, object_id)), 0) FROM object_aliases",
)


def _build(db: Path, objects: int) -> None:
    kb = KnowledgeBase.open(db)
    with kb.connect(write=True) as con:
        con.execute(
            "INSERT INTO objects (name, a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, "
            "rigidity, source, created_at, updated_at) SELECT 'object ' || i, 10 + i % 50, 5 + i % 20, "
            "1 + i % 5, 100 + i % 900, 'prism', 'smooth', 'sturdy', 'plastic', 'rigid', 'synthetic', now(), "
            f"now() FROM range({objects}) t(i)"
        )
        con.execute(
            "INSERT INTO object_aliases (alias, object_id) SELECT 'alias ' || id, id FROM objects WHERE id % 10 = 0"
        )



def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--objects", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="version-bench-"))
    try:
        db = work / "catalog.duckdb"
        _build(db, args.objects)
        kb = KnowledgeBase.open(db, read_only=True)
        with kb.connect() as con:
            new = median_cpu_s(lambda: catalog_version(con), args.repeat)
            old = median_cpu_s(lambda: [con.execute(q).fetchone() for q in _OLD], args.repeat)
        print(
            f"catalog_version at {args.objects:,} objects ({args.objects // 10:,} aliases; synthetic, written "
            f"here): {new:.3f} s CPU with the value checksum, {old:.3f} s without; load {os.getloadavg()[0]:.1f}"
        )
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
