"""Schema migrations: bring a DuckDB catalog file to the Alembic head (or any revision).

The revisions live in the top-level ``migrations`` package and are written by hand (see its docstrings).
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path

from alembic import command
from alembic.config import Config
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy import create_engine, pool

from kb.connections import database_reason, is_lock_conflict, is_unreadable_file
from kb.errors import CatalogUnreadable, MigrationError

__all__ = ["current_revision", "downgrade", "head_revision", "upgrade"]


def _config() -> Config:
    cfg = Config()
    cfg.set_main_option("script_location", str(importlib.resources.files("migrations")))
    return cfg


def head_revision() -> str:
    return ScriptDirectory.from_config(_config()).get_current_head() or ""


def _run(path: Path, action, revision: str) -> None:
    engine = create_engine(f"duckdb:///{path}", poolclass=pool.NullPool)
    try:
        with engine.connect() as conn:
            cfg = _config()
            cfg.attributes["connection"] = conn
            action(cfg, revision)
            conn.commit()
    except MigrationError:
        raise
    except Exception as err:  # DuckDB DDL is transactional: a failed migration changed nothing
        if is_lock_conflict(err):
            raise MigrationError(f"{path}: migration to {revision} failed: {err}") from err  # retried by the caller
        if is_unreadable_file(err):
            raise CatalogUnreadable(path, database_reason(err)) from None
        raise MigrationError(f"{path}: migration to {revision} failed: {database_reason(err)}") from err
    finally:
        engine.dispose()


def upgrade(path: str | Path, revision: str = "head") -> None:
    """Create or upgrade the database file at ``path`` to ``revision`` (default: head)."""
    _run(Path(path), command.upgrade, revision)


def downgrade(path: str | Path, revision: str = "base") -> None:
    """Downgrade the database file at ``path`` to ``revision`` (default: base, an empty schema)."""
    _run(Path(path), command.downgrade, revision)


def current_revision(path: str | Path) -> str | None:
    engine = create_engine(f"duckdb:///{path}", poolclass=pool.NullPool)
    try:
        with engine.connect() as conn:
            return MigrationContext.configure(conn).get_current_revision()
    finally:
        engine.dispose()
