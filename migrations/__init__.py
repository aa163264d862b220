"""Alembic migrations of the objrecall catalog (revisions written by hand)."""
