"""The Joint Probability distance in plain SQL: DuckDB macros stored in the catalog file.

``objrecall init`` calls :func:`install_macros`; the macros then live in the DuckDB file, so anyone with
SQL can rank objects (``objrecall sql``, the DuckDB CLI, a notebook). They follow the rules of
:mod:`recall.metrics` exactly (a test checks NumPy and SQL agree):

* ``jp_term(v, q)``: one numeric feature, ``ln(1 + |v − q|)``; ``q`` NULL (not stated) → 0; ``v`` NULL
  (unknown in the catalog) → ``ln(1 + 0.5·|q|)``.
* ``jp_range_term(v, lo, hi, q)``: a qualified numeric feature (``lo``/``hi`` NULL = unbounded; ``q``, the
  stated value, sets the unknown penalty).
* ``jp_cat_term(v, q)``: a categorical feature (one-hot): 0 if equal, ``2 ln 2`` if different, ``ln 2`` if
  the catalog value is unknown, 0 if not stated.
* ``jp_distance(a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity, qa := ..., qb
  := ..., qc := ..., qmass := ..., qshape := ..., qtexture := ..., qfragility := ..., qmaterial := ...,
  qrigidity := ...)``: the sum; query parameters default to NULL (not stated).
* ``jp_rank(qa := ..., ...)``: a table macro, every object with its distance, nearest first (ties by name,
  as the NumPy engine's row order is the catalog's name order).

Example::

    SELECT name, distance FROM jp_rank(qa := 15.5, qb := 8, qc := 1.5, qmaterial := 'plastic') LIMIT 5;
"""

from __future__ import annotations

from recall.metrics import UNKNOWN_NUMERIC_FRACTION

__all__ = ["MACROS_SQL", "MACRO_NAMES", "install_macros"]

_QUERY_PARAMS = "qa := NULL, qb := NULL, qc := NULL, qmass := NULL, qshape := NULL, qtexture := NULL, " \
    "qfragility := NULL, qmaterial := NULL, qrigidity := NULL"  # fmt: skip

MACROS_SQL = f"""
CREATE OR REPLACE MACRO jp_term(v, q) AS
    CASE WHEN q IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(1 + {UNKNOWN_NUMERIC_FRACTION!r} * abs(q))
         ELSE ln(1 + abs(v - q)) END;

CREATE OR REPLACE MACRO jp_range_term(v, lo, hi, q) AS
    CASE WHEN q IS NULL AND lo IS NULL AND hi IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(1 + {UNKNOWN_NUMERIC_FRACTION!r} * abs(coalesce(q, lo, hi)))
         ELSE ln(1 + greatest(coalesce(lo - v, 0.0), coalesce(v - hi, 0.0), 0.0)) END;

CREATE OR REPLACE MACRO jp_cat_term(v, q) AS
    CASE WHEN q IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(2)
         WHEN lower(v) = lower(q) THEN 0.0
         ELSE 2 * ln(2) END;

CREATE OR REPLACE MACRO jp_distance(a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity,
                                    {_QUERY_PARAMS}) AS
    jp_term(a_cm, qa) + jp_term(b_cm, qb) + jp_term(c_cm, qc) + jp_term(mass_g, qmass)
    + jp_cat_term(shape, qshape) + jp_cat_term(texture, qtexture) + jp_cat_term(fragility, qfragility)
    + jp_cat_term(material, qmaterial) + jp_cat_term(rigidity, qrigidity);

CREATE OR REPLACE MACRO jp_rank({_QUERY_PARAMS}) AS TABLE
    SELECT name,
           jp_distance(a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity,
                       qa := qa, qb := qb, qc := qc, qmass := qmass, qshape := qshape, qtexture := qtexture,
                       qfragility := qfragility, qmaterial := qmaterial, qrigidity := qrigidity) AS distance
    FROM objects
    ORDER BY distance, name;
"""

MACRO_NAMES: tuple[str, ...] = ("jp_term", "jp_range_term", "jp_cat_term", "jp_distance", "jp_rank")


def install_macros(con) -> None:
    """Create (or replace) the macros in the database of the DuckDB connection ``con`` (needs write
    access; ``jp_rank`` needs the ``objects`` table to exist when it is used, not when it is created)."""
    for statement in MACROS_SQL.split(";"):
        if statement.strip():
            con.execute(statement)
