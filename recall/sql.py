"""Every recall metric in plain SQL: DuckDB macros stored in the catalog file.

``objrecall init`` calls :func:`install_macros`; the macros then live in the DuckDB file, so anyone with
SQL can rank objects (``objrecall sql``, the DuckDB CLI, a notebook). They follow the rules of
:mod:`recall.metrics` for stated point values (a test checks that NumPy and SQL rank alike, on the same
masks, with the same distances to 1e-6: the engine holds float32 values, SQL the stored doubles):

* ``jp_term(v, q)``: one numeric feature, ``ln(1 + |v − q|)``; ``q`` NULL (not stated) → 0; ``v`` NULL
  (unknown in the catalog) → ``ln(1 + 0.5·|q|)``. ``jp_range_term(v, lo, hi, q)``: a qualified feature
  (``lo``/``hi`` NULL = unbounded; ``q``, the stated value, sets the unknown penalty).
* ``jp_cat_term(v, q)``: a categorical feature (one-hot): 0 if equal, ``2 ln 2`` if different, ``ln 2``
  if the catalog value is unknown, 0 if not stated.
* ``jplog_term(v, q)``: JP in log units (``jplog``, the hybrid's default): ``ln(1 + |ln v − ln q| / ln
  1.1)``; an unknown value is off by a factor 1.5. ``jplog_range_term(v, lo, hi, q)`` likewise.
* ``<metric>_distance(a_cm, b_cm, c_cm, mass_g, shape, texture, fragility, material, rigidity, qa :=
  ..., qb := ..., qc := ..., qmass := ..., qshape := ..., qtexture := ..., qfragility := ...,
  qmaterial := ..., qrigidity := ...)`` for ``jp``, ``jplog``, ``euclidean``, ``minkowski`` (p = 4)
  and ``cosine``; query parameters default to NULL (not stated). ``kdtree_distance``: the k-d tree's
  distance, Euclidean with an unknown numeric value imputed as the median of the known values of its
  column over the catalog (``kd_term(v, q, fill)``), categories one-hot as ``euclidean``; the tree only
  finds the nearest rows faster, so the macro ranks alike (ties aside: the tree orders them its own way).
* ``jp_rank(qa := ..., ...)`` and ``jplog_rank(...)``: table macros, every object with its distance,
  nearest first (ties by name, as the engine's row order is the catalog's name order).

Example::

    SELECT name, distance FROM jplog_rank(qa := 15.5, qb := 8, qc := 1.5, qmaterial := 'plastic') LIMIT 5;
"""

from __future__ import annotations

import math

from kb.features import CATEGORICAL_FEATURES
from recall.metrics import LOG_FLOOR, LOG_STEP, MINKOWSKI_P, UNKNOWN_NUMERIC_FRACTION

__all__ = ["MACROS_SQL", "MACRO_NAMES", "install_macros"]

_NUMERIC = (("a_cm", "qa"), ("b_cm", "qb"), ("c_cm", "qc"), ("mass_g", "qmass"))
_CATEGORICAL = tuple((f, f"q{f}") for f in CATEGORICAL_FEATURES)
_COLUMNS = ", ".join(c for c, _ in (*_NUMERIC, *_CATEGORICAL))
_QUERY_PARAMS = ", ".join(f"{q} := NULL" for _, q in (*_NUMERIC, *_CATEGORICAL))
_PASS = ", ".join(f"{q} := {q}" for _, q in (*_NUMERIC, *_CATEGORICAL))
_U = repr(UNKNOWN_NUMERIC_FRACTION)
_LOG_STEP = repr(LOG_STEP)
_LOG_FLOOR = repr(LOG_FLOOR)
#: ln(1 + log-units of a factor 1 + UNKNOWN_NUMERIC_FRACTION): the jplog penalty of an unknown value.
_LOG_UNKNOWN = repr(math.log1p(math.log1p(UNKNOWN_NUMERIC_FRACTION) / LOG_STEP))


def _sum(template: str) -> str:
    """``template`` (with {v} and {q}) summed over the numeric columns."""
    return " + ".join(template.format(v=v, q=q) for v, q in _NUMERIC)


def _cat_sum(macro: str) -> str:
    """``macro(column, parameter)`` summed over the categorical columns."""
    return " + ".join(f"{macro}({v}, {q})" for v, q in _CATEGORICAL)


def _distance(name: str, body: str) -> str:
    return f"CREATE OR REPLACE MACRO {name}_distance({_COLUMNS},\n    {_QUERY_PARAMS}) AS\n    {body};\n"


def _rank(name: str) -> str:
    return (
        f"CREATE OR REPLACE MACRO {name}_rank({_QUERY_PARAMS}) AS TABLE\n"
        f"    SELECT name, {name}_distance({_COLUMNS}, {_PASS}) AS distance\n"
        "    FROM objects ORDER BY distance, name;\n"
    )


_LN = f"ln(greatest({{}}, {_LOG_FLOOR})) / {_LOG_STEP}"  # log units of a value

MACROS_SQL = (
    f"""
CREATE OR REPLACE MACRO jp_term(v, q) AS
    CASE WHEN q IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(1 + {_U} * abs(q))
         ELSE ln(1 + abs(v - q)) END;

CREATE OR REPLACE MACRO jp_range_term(v, lo, hi, q) AS
    CASE WHEN q IS NULL AND lo IS NULL AND hi IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(1 + {_U} * abs(coalesce(q, lo, hi)))
         ELSE ln(1 + greatest(coalesce(lo - v, 0.0), coalesce(v - hi, 0.0), 0.0)) END;

CREATE OR REPLACE MACRO jp_cat_term(v, q) AS
    CASE WHEN q IS NULL THEN 0.0
         WHEN v IS NULL THEN ln(2)
         WHEN lower(v) = lower(q) THEN 0.0
         ELSE 2 * ln(2) END;

CREATE OR REPLACE MACRO jplog_term(v, q) AS
    CASE WHEN q IS NULL THEN 0.0
         WHEN v IS NULL THEN {_LOG_UNKNOWN}
         ELSE ln(1 + abs({_LN.format("v")} - {_LN.format("q")})) END;

CREATE OR REPLACE MACRO jplog_range_term(v, lo, hi, q) AS
    CASE WHEN q IS NULL AND lo IS NULL AND hi IS NULL THEN 0.0
         WHEN v IS NULL THEN {_LOG_UNKNOWN}
         ELSE ln(1 + greatest(coalesce({_LN.format("lo")} - {_LN.format("v")}, 0.0),
                              coalesce({_LN.format("v")} - {_LN.format("hi")}, 0.0), 0.0)) END;

-- the squared (one-hot) difference of a category: 0 equal, 2 different, 1 unknown, 0 not stated
CREATE OR REPLACE MACRO onehot_sq(v, q) AS
    CASE WHEN q IS NULL THEN 0.0 WHEN v IS NULL THEN 1.0 WHEN lower(v) = lower(q) THEN 0.0 ELSE 2.0 END;

-- a numeric difference with the unknown rule (0 when not stated)
CREATE OR REPLACE MACRO num_diff(v, q) AS
    CASE WHEN q IS NULL THEN 0.0 WHEN v IS NULL THEN {_U} * abs(q) ELSE abs(v - q) END;

-- cosine's catalog vector: an unknown value imputed as q * (1 + {_U}), a category as its one-hot
CREATE OR REPLACE MACRO cos_x(v, q) AS
    CASE WHEN q IS NULL THEN 0.0 WHEN v IS NULL THEN q * (1 + {_U}) ELSE v END;
CREATE OR REPLACE MACRO cos_dot_cat(v, q) AS
    CASE WHEN q IS NULL OR v IS NULL THEN 0.0 WHEN lower(v) = lower(q) THEN 1.0 ELSE 0.0 END;
CREATE OR REPLACE MACRO cos_known_cat(v, q) AS
    CASE WHEN q IS NULL OR v IS NULL THEN 0.0 ELSE 1.0 END;
CREATE OR REPLACE MACRO cos_stated(q) AS CASE WHEN q IS NULL THEN 0.0 ELSE 1.0 END;

-- the k-d tree's squared numeric difference: an unknown value imputed as its column's median (fill)
CREATE OR REPLACE MACRO kd_term(v, q, fill) AS
    CASE WHEN q IS NULL THEN 0.0 ELSE (coalesce(v, fill) - q) ** 2 END;
"""
    + _distance("jp", f"{_sum('jp_term({v}, {q})')} + {_cat_sum('jp_cat_term')}")
    + _distance("jplog", f"{_sum('jplog_term({v}, {q})')} + {_cat_sum('jp_cat_term')}")
    + _distance("euclidean", f"sqrt({_sum('num_diff({v}, {q}) ** 2')} + {_cat_sum('onehot_sq')})")
    + _distance(
        "minkowski",
        f"({_sum(f'num_diff({{v}}, {{q}}) ** {MINKOWSKI_P}')} + {_cat_sum('onehot_sq')}) ** (1.0 / {MINKOWSKI_P})",
    )
    + _distance(
        "cosine",
        f"""CASE WHEN ({_sum('cos_x({v}, {q}) ** 2')} + {_cat_sum('cos_known_cat')}) = 0
              OR ({_sum('coalesce({q}, 0.0) ** 2')} + {' + '.join(f'cos_stated({q})' for _, q in _CATEGORICAL)}) = 0
         THEN 1.0
         ELSE 1.0 - ({_sum('cos_x({v}, {q}) * coalesce({q}, 0.0)')} + {_cat_sum('cos_dot_cat')})
              / (sqrt({_sum('cos_x({v}, {q}) ** 2')} + {_cat_sum('cos_known_cat')})
                 * sqrt({_sum('coalesce({q}, 0.0) ** 2')} + {' + '.join(f'cos_stated({q})' for _, q in _CATEGORICAL)}))
         END""",
    )
    + _distance(
        "kdtree",
        "sqrt("
        + " + ".join(f"kd_term({v}, {q}, (SELECT coalesce(median({v}), 0.0) FROM objects))" for v, q in _NUMERIC)
        + f" + {_cat_sum('onehot_sq')})",
    )
    + _rank("jp")
    + _rank("jplog")
)

MACRO_NAMES: tuple[str, ...] = (
    "jp_term", "jp_range_term", "jp_cat_term", "jplog_term", "jplog_range_term", "onehot_sq", "num_diff",
    "cos_x", "cos_dot_cat", "cos_known_cat", "cos_stated", "kd_term", "jp_distance", "jplog_distance",
    "euclidean_distance", "minkowski_distance", "cosine_distance", "kdtree_distance", "jp_rank", "jplog_rank",
)  # fmt: skip


def install_macros(con) -> None:
    """Create (or replace) the macros in the database of the DuckDB connection ``con`` (needs write
    access; the rank macros need the ``objects`` table when they are used, not when they are created)."""
    for statement in MACROS_SQL.split(";"):  # (no semicolon in the comments)
        if statement.strip():
            con.execute(statement)
