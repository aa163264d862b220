"""Ingestion: runs with their counts, fetched pages (for conditional requests), rejected pages.

Revision ID: 0002_ingestion
Revises: 0001_catalog
Create Date: 2026-11-22
"""

from alembic import op

revision = "0002_ingestion"
down_revision = "0001_catalog"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.execute("CREATE SEQUENCE ingestion_runs_id_seq START 1")
    op.execute(
        """
        CREATE TABLE ingestion_runs (
            id BIGINT PRIMARY KEY DEFAULT nextval('ingestion_runs_id_seq'),
            started_at TIMESTAMP NOT NULL DEFAULT current_timestamp,
            finished_at TIMESTAMP,
            status VARCHAR NOT NULL DEFAULT 'running',
            sources VARCHAR,
            fetched INTEGER NOT NULL DEFAULT 0,
            not_modified INTEGER NOT NULL DEFAULT 0,
            extracted INTEGER NOT NULL DEFAULT 0,
            rejected INTEGER NOT NULL DEFAULT 0,
            new INTEGER NOT NULL DEFAULT 0,
            updated INTEGER NOT NULL DEFAULT 0,
            rejected_reasons VARCHAR,
            errors VARCHAR,
            duration_s DOUBLE
        )
        """
    )
    op.execute(
        """
        CREATE TABLE pages (
            url VARCHAR PRIMARY KEY,
            canonical_url VARCHAR,
            etag VARCHAR,
            last_modified VARCHAR,
            content_sha256 VARCHAR,
            status INTEGER,
            fetched_at TIMESTAMP,
            object_id BIGINT,
            error VARCHAR,
            run_id BIGINT
        )
        """
    )
    op.execute(
        """
        CREATE TABLE page_events (
            run_id BIGINT,
            url VARCHAR NOT NULL,
            stage VARCHAR NOT NULL,
            reason VARCHAR NOT NULL,
            occurred_at TIMESTAMP NOT NULL DEFAULT current_timestamp
        )
        """
    )


def downgrade() -> None:
    op.execute("DROP TABLE page_events")
    op.execute("DROP TABLE pages")
    op.execute("DROP TABLE ingestion_runs")
    op.execute("DROP SEQUENCE ingestion_runs_id_seq")
