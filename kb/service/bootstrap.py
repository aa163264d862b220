"""Making a catalog ready to serve: create or upgrade the database, install the recall SQL macros, load the
seed catalog. Used by ``objrecall init`` and the main job (``objrecall demo``)."""

from __future__ import annotations

import importlib.resources
from pathlib import Path

from kb.catalog import KnowledgeBase

__all__ = ["demo_descriptions_path", "init_db", "install_sql_extras", "seed_catalog_path"]


def seed_catalog_path() -> Path:
    """The seed catalog CSV shipped in the package."""
    return Path(str(importlib.resources.files("kb") / "data" / "seed_catalog.csv"))


def demo_descriptions_path() -> Path:
    """The sample descriptions the main job recalls."""
    return Path(str(importlib.resources.files("kb") / "data" / "demo_descriptions.csv"))


def install_sql_extras(kb: KnowledgeBase) -> bool:
    """Install the recall macros (``jp_distance`` ...) when the recall package provides them."""
    try:
        from recall.sql import install_macros
    except ImportError:
        return False
    with kb.connect(write=True) as con:
        install_macros(con)
    return True


def init_db(db: Path, *, seed: bool) -> KnowledgeBase:
    """The catalog at ``db``, created or upgraded to the latest schema, with the recall macros; ``seed``
    upserts the seed catalog."""
    kb = KnowledgeBase.open(db)
    install_sql_extras(kb)
    if seed:
        kb.import_csv(seed_catalog_path())
    return kb
