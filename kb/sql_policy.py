"""What user SQL may run: one plain read (SELECT, or EXPLAIN of one), none of the functions that reveal
the server's files or run SQL built at run time, and refusals worded in the user's own terms.

These checks run inside the sandbox's worker (:mod:`kb.sandbox`) on its read-only connection, before the
query; the connection's own settings (no file or network access, locked configuration) stand behind them.
"""

from __future__ import annotations

import re

from kb.errors import QueryFailed, QueryRefused

__all__ = [
    "ALLOWED_STATEMENTS", "DYNAMIC_SQL_FUNCTIONS", "HIDDEN_FUNCTIONS", "check_query", "first_line",
    "statement_kind", "write_refusal",
]

#: Statement types user SQL may run (EXPLAIN only of a statement that is itself allowed).
ALLOWED_STATEMENTS = frozenset({"SELECT", "EXPLAIN"})
#: Table functions refused in user SQL because they reveal the server's file paths or settings.
HIDDEN_FUNCTIONS: tuple[str, ...] = (
    "duckdb_databases", "duckdb_settings", "current_setting", "duckdb_extensions", "duckdb_temporary_files",
    "duckdb_secrets", "which_secret", "duckdb_logs", "duckdb_log_contexts", "duckdb_external_file_cache",
    "duckdb_memory", "pragma_[a-z_]+", "pg_settings",
)
#: Functions refused when called because they run SQL built from a string at run time, which no check of
#: the query's text can see into (``query('select * from duckdb_' || 'settings()')``).
DYNAMIC_SQL_FUNCTIONS: tuple[str, ...] = ("query", "query_table", "json_execute_serialized_sql")
_HIDDEN_RE = re.compile(r"(?<![a-z0-9_])(" + "|".join(HIDDEN_FUNCTIONS) + r")(?![a-z0-9_])", re.IGNORECASE)
_DYNAMIC_RE = re.compile(
    r"(?<![a-z0-9_])(" + "|".join(DYNAMIC_SQL_FUNCTIONS) + r")\"?\s*\(", re.IGNORECASE
)

def statement_kind(con, query: str) -> str:
    """The one statement's type name; refuses several statements and any type not allowed."""
    import duckdb

    try:
        statements = con.extract_statements(query)
    except duckdb.Error as err:
        raise QueryFailed(f"SQL error: {first_line(err)}") from None
    if len(statements) != 1:
        raise QueryRefused(f"one statement at a time, got {len(statements)}")
    try:
        kind = statements[0].type.name
    except ValueError:  # a statement type this DuckDB's Python API cannot name (UPDATE EXTENSIONS, ...)
        kind = "UNKNOWN"  # refused below like any other type not on the allow-list
    if kind == "EXPLAIN":
        inner = re.sub(r"^\s*explain(\s+analy[sz]e)?\s", "", query, count=1, flags=re.IGNORECASE)
        if inner != query and statement_kind(con, inner) == "SELECT":
            return kind
        kind = "EXPLAIN (of a statement that is not a SELECT)"
    if kind not in ALLOWED_STATEMENTS:
        said = _leading_keyword(query)
        if said and not kind.startswith("EXPLAIN"):  # the user's word: INSTALL, not DuckDB's type LOAD
            what = f"{said} statements are"
        else:
            what = "statements of this type are" if kind == "UNKNOWN" else f"{kind} statements are"
        raise QueryRefused(f"refused: {what} not allowed; the catalog is read-only (SELECT only)")
    return kind


#: Comments and white space before a statement's first word.
_LEAD = r"(?:\s|--[^\n]*(?:\n|\Z)|/\*.*?\*/)*"
#: The first word (two for FORCE INSTALL and UPDATE EXTENSIONS) of a statement, as the user wrote it.
_LEADING_WORD = re.compile(_LEAD + r"(force\s+install|update\s+extensions|[a-z_]+)", re.IGNORECASE | re.DOTALL)
#: Statement words that change data or schema, looked for when a query inside a SELECT tried to write.
_WRITE_WORD = re.compile(r"(?<![a-z0-9_])(insert|update|delete|merge|truncate|copy|create|drop|alter)(?![a-z0-9_])", re.I)


def _leading_keyword(query: str) -> str | None:
    """The statement's first word as the user wrote it (DuckDB names INSTALL and LOAD both ``LOAD``, RESET
    ``SET``, TRUNCATE ``DELETE``), upper case; None for WITH (its statement's type names it better)."""
    m = _LEADING_WORD.match(query)
    if not m or m.group(1).lower() == "with":
        return None
    return " ".join(m.group(1).upper().split())


def write_refusal(query: str) -> str:
    """The sandbox's own words for a write inside a SELECT (``WITH x AS (DELETE ... RETURNING *) SELECT ...``),
    which DuckDB's read-only connection stops before it runs."""
    bare = re.sub(r"'(?:[^']|'')*'|\"(?:[^\"]|\"\")*\"|--[^\n]*|/\*.*?\*/", " ", query, flags=re.DOTALL)
    word = _WRITE_WORD.search(bare)
    inside = f" ({word.group(1).upper()} inside the query)" if word else ""
    return f"refused: the query writes{inside}; the catalog is read-only (SELECT only)"


def check_query(con, query: str) -> None:
    """Refuse ``query`` (:class:`~kb.errors.QueryRefused`) unless it is one allowed statement that calls no
    hidden or dynamic-SQL function; a query DuckDB cannot parse is :class:`~kb.errors.QueryFailed`."""
    statement_kind(con, query)
    hidden = _HIDDEN_RE.search(query)
    if hidden:
        raise QueryRefused(f"refused: {hidden.group(1)} reveals server settings and is not available")
    dynamic = _DYNAMIC_RE.search(query)
    if dynamic:
        raise QueryRefused(
            f"refused: {dynamic.group(1)}() runs SQL built at run time, which cannot be checked; write the query itself"
        )


def first_line(err: Exception) -> str:
    """The first line of an error's text (its type's name when it has none)."""
    return str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
