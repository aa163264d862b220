"""Alembic environment for the objrecall DuckDB catalog.

Run through :func:`kb.migrate.upgrade` (``objrecall init``), which passes an open SQLAlchemy connection in
``config.attributes["connection"]``; the ``alembic`` command line also works with ``-x db=PATH``.
"""

from __future__ import annotations

from alembic import context
from alembic.ddl.impl import DefaultImpl
from sqlalchemy import create_engine


class AlembicDuckDBImpl(DefaultImpl):
    """Alembic does not know the duckdb dialect until an impl registers it."""

    __dialect__ = "duckdb"
    transactional_ddl = True


def run_migrations_online() -> None:
    connection = context.config.attributes.get("connection")
    if connection is None:
        db = context.get_x_argument(as_dictionary=True).get("db") or context.config.get_main_option("db_path")
        engine = create_engine(f"duckdb:///{db}")
        with engine.connect() as conn:
            context.configure(connection=conn, transaction_per_migration=False)
            with context.begin_transaction():
                context.run_migrations()
            conn.commit()
        engine.dispose()
        return
    context.configure(connection=connection)
    with context.begin_transaction():
        context.run_migrations()


if context.is_offline_mode():
    raise SystemExit("objrecall migrations run online only (DuckDB DDL is transactional)")
run_migrations_online()
