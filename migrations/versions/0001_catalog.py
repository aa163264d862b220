"""Catalog: objects, their aliases, and the provenance of every observed value.

Revision ID: 0001_catalog
Revises:
Create Date: 2026-11-22

Written by hand for DuckDB: integer keys come from explicit sequences created here; keys and indexes are
declared in CREATE TABLE; measurements are DOUBLE (SQLAlchemy's Float would be a 4-byte REAL).
No foreign keys: DuckDB turns updates of referenced rows into errors; the catalog code keeps them consistent.
"""

from alembic import op

revision = "0001_catalog"
down_revision = None
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.execute("CREATE SEQUENCE objects_id_seq START 1")
    op.execute("CREATE SEQUENCE observations_id_seq START 1")
    op.execute(
        """
        CREATE TABLE objects (
            id BIGINT PRIMARY KEY DEFAULT nextval('objects_id_seq'),
            name VARCHAR NOT NULL UNIQUE,
            a_cm DOUBLE, b_cm DOUBLE, c_cm DOUBLE, mass_g DOUBLE,
            shape VARCHAR, texture VARCHAR, fragility VARCHAR, material VARCHAR, rigidity VARCHAR,
            source VARCHAR,
            gtin VARCHAR,
            canonical_url VARCHAR,
            created_at TIMESTAMP NOT NULL DEFAULT current_timestamp,
            updated_at TIMESTAMP NOT NULL DEFAULT current_timestamp,
            CHECK (a_cm IS NULL OR a_cm > 0),
            CHECK (b_cm IS NULL OR b_cm > 0),
            CHECK (c_cm IS NULL OR c_cm > 0),
            CHECK (mass_g IS NULL OR mass_g > 0)
        )
        """
    )
    op.execute(
        """
        CREATE TABLE object_aliases (
            alias VARCHAR PRIMARY KEY,
            object_id BIGINT NOT NULL
        )
        """
    )
    op.execute(
        """
        CREATE TABLE observations (
            id BIGINT PRIMARY KEY DEFAULT nextval('observations_id_seq'),
            object_id BIGINT NOT NULL,
            feature VARCHAR NOT NULL,
            value_num DOUBLE,
            value_text VARCHAR,
            role VARCHAR NOT NULL DEFAULT 'product',
            source VARCHAR NOT NULL,
            adapter VARCHAR,
            fetched_at TIMESTAMP NOT NULL DEFAULT current_timestamp,
            raw_text VARCHAR,
            run_id BIGINT
        )
        """
    )


def downgrade() -> None:
    op.execute("DROP TABLE observations")
    op.execute("DROP TABLE object_aliases")
    op.execute("DROP TABLE objects")
    op.execute("DROP SEQUENCE observations_id_seq")
    op.execute("DROP SEQUENCE objects_id_seq")
