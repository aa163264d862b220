"""The catalog schema as SQLAlchemy Core tables (the Alembic revisions in ``migrations/`` create it).

These mirror the head revision; ``tests/test_migrations.py`` checks that they stay in step. Use them to
query the catalog with SQLAlchemy (``create_engine("duckdb:///catalog.duckdb")``) or to read the layout.
"""

from __future__ import annotations

from sqlalchemy import TIMESTAMP, BigInteger, Boolean, Column, Double, Integer, MetaData, String, Table

__all__ = ["TABLES", "grasp_validations", "ingestion_runs", "metadata", "object_aliases", "objects",
           "observations", "page_events", "pages"]

metadata = MetaData()

#: One row per object; feature columns hold the fused catalog value (None = unknown).
objects = Table(
    "objects", metadata,
    Column("id", BigInteger, primary_key=True),
    Column("name", String, nullable=False, unique=True),
    Column("a_cm", Double), Column("b_cm", Double), Column("c_cm", Double), Column("mass_g", Double),
    Column("shape", String), Column("texture", String), Column("fragility", String),
    Column("material", String), Column("rigidity", String),
    Column("source", String), Column("gtin", String), Column("canonical_url", String),
    Column("created_at", TIMESTAMP, nullable=False), Column("updated_at", TIMESTAMP, nullable=False),
)

#: Other names an object is known by (synonyms); an alias points at one object.
object_aliases = Table(
    "object_aliases", metadata,
    Column("alias", String, primary_key=True),
    Column("object_id", BigInteger, nullable=False),
)

#: Provenance: every observed value of every feature, with where and when it was seen.
observations = Table(
    "observations", metadata,
    Column("id", BigInteger, primary_key=True),
    Column("object_id", BigInteger, nullable=False),
    Column("feature", String, nullable=False),
    Column("value_num", Double), Column("value_text", String),
    Column("role", String, nullable=False),  # 'product' or 'package'
    Column("source", String, nullable=False),  # URL or file
    Column("adapter", String),  # extractor or importer
    Column("fetched_at", TIMESTAMP, nullable=False),
    Column("raw_text", String),
    Column("run_id", BigInteger),
)

ingestion_runs = Table(
    "ingestion_runs", metadata,
    Column("id", BigInteger, primary_key=True),
    Column("started_at", TIMESTAMP, nullable=False), Column("finished_at", TIMESTAMP),
    Column("status", String, nullable=False),
    Column("sources", String),
    *(Column(c, Integer, nullable=False) for c in ("fetched", "not_modified", "extracted", "rejected", "new", "updated")),
    Column("rejected_reasons", String), Column("errors", String), Column("duration_s", Double),
)

pages = Table(
    "pages", metadata,
    Column("url", String, primary_key=True),
    Column("canonical_url", String), Column("etag", String), Column("last_modified", String),
    Column("content_sha256", String), Column("status", Integer), Column("fetched_at", TIMESTAMP),
    Column("object_id", BigInteger), Column("error", String), Column("run_id", BigInteger),
)

page_events = Table(
    "page_events", metadata,
    Column("run_id", BigInteger), Column("url", String, nullable=False), Column("stage", String, nullable=False),
    Column("reason", String, nullable=False), Column("occurred_at", TIMESTAMP, nullable=False),
)

grasp_validations = Table(
    "grasp_validations", metadata,
    Column("id", BigInteger, primary_key=True),
    Column("object_name", String, nullable=False), Column("object_id", BigInteger),
    Column("features_hash", String, nullable=False),
    Column("grasp_type", String, nullable=False), Column("family", String), Column("rank", Integer),
    Column("success", Boolean), Column("outcome", String), Column("reason", String),
    Column("slip_cm", Double), Column("rotation_deg", Double),
    Column("grip_force_n", Double), Column("max_contact_force_n", Double),
    Column("seed", Integer, nullable=False), Column("simulator", String),
    Column("hand_version", String, nullable=False), Column("planner_version", String),
    Column("details", String), Column("created_at", TIMESTAMP, nullable=False),
)

TABLES = tuple(metadata.tables.values())
