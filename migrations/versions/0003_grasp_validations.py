"""Grasp validations: one row per simulated trial (object x grasp type x seed x hand version).

Revision ID: 0003_grasp_validations
Revises: 0002_ingestion
Create Date: 2026-11-22

``features_hash`` identifies the object's feature values the trial used, so a trial is re-run (not
resumed) when the catalog values change.
"""

from alembic import op

revision = "0003_grasp_validations"
down_revision = "0002_ingestion"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.execute("CREATE SEQUENCE grasp_validations_id_seq START 1")
    op.execute(
        """
        CREATE TABLE grasp_validations (
            id BIGINT PRIMARY KEY DEFAULT nextval('grasp_validations_id_seq'),
            object_name VARCHAR NOT NULL,
            object_id BIGINT,
            features_hash VARCHAR NOT NULL DEFAULT '',
            grasp_type VARCHAR NOT NULL,
            family VARCHAR,
            rank INTEGER,
            success BOOLEAN,
            outcome VARCHAR,
            reason VARCHAR,
            slip_cm DOUBLE,
            rotation_deg DOUBLE,
            grip_force_n DOUBLE,
            max_contact_force_n DOUBLE,
            seed INTEGER NOT NULL DEFAULT 0,
            simulator VARCHAR,
            hand_version VARCHAR NOT NULL DEFAULT '',
            planner_version VARCHAR,
            details VARCHAR,
            created_at TIMESTAMP NOT NULL DEFAULT current_timestamp,
            UNIQUE (object_name, grasp_type, seed, hand_version, features_hash)
        )
        """
    )


def downgrade() -> None:
    op.execute("DROP TABLE grasp_validations")
    op.execute("DROP SEQUENCE grasp_validations_id_seq")
