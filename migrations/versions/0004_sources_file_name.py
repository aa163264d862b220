"""ingestion_runs.sources holds the sources file's name, not its path on the server.

Revision ID: 0004_sources_file_name
Revises: 0003_grasp_validations
Create Date: 2026-12-02

The column used to read ``/srv/app/scrapers/demo_sources.toml: demo, demo-shopify-json``: anyone with SQL
access (``objrecall sql``, ``POST /sql``) could read the server's directory layout. It now reads
``demo_sources.toml: demo, demo-shopify-json`` (``scrapers.sources.Sources.describe``); the upgrade
rewrites old rows the same way (the part before the first ": " is cut to its last path component; a
lookup run's ``lookup {...}`` row holds no path and is left alone). The paths are not kept, so the
downgrade leaves the rows as they are.
"""

import re

import sqlalchemy as sa
from alembic import op

revision = "0004_sources_file_name"
down_revision = "0003_grasp_validations"
branch_labels = None
depends_on = None


def public_sources(text: str) -> str:
    """``/a/b/stores.toml: x, y`` -> ``stores.toml: x, y``; anything else unchanged."""
    if text.startswith("lookup "):
        return text
    head, sep, rest = text.partition(": ")
    if not sep or not re.search(r"[/\\]", head):
        return text
    return re.split(r"[/\\]", head)[-1] + sep + rest


def upgrade() -> None:
    bind = op.get_bind()
    rows = bind.execute(
        sa.text("SELECT id, sources FROM ingestion_runs WHERE sources IS NOT NULL")
    ).fetchall()
    for run_id, sources in rows:
        public = public_sources(sources)
        if public != sources:
            bind.execute(
                sa.text("UPDATE ingestion_runs SET sources = :s WHERE id = :id"), {"s": public, "id": run_id}
            )


def downgrade() -> None:
    pass  # the paths were not kept: the rows stay as they are
