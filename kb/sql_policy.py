"""What user SQL may run: one plain read (SELECT, or EXPLAIN of one; DESCRIBE, SHOW and SUMMARIZE are
SELECTs to DuckDB), the read-only PRAGMAs that describe the catalog's own tables (:data:`CATALOG_PRAGMAS`),
none of the functions that reveal the server's files or settings or run SQL built at run time, and
refusals worded in the user's own terms: a file or URL read is "reading files is not allowed", naming the
file (:func:`error_refusal`), whichever of DuckDB's errors stopped it.

These checks run inside the sandbox's worker (:mod:`kb.sandbox`) on its read-only connection, before the
query; the connection's own settings (no file or network access, locked configuration) stand behind them.
"""

from __future__ import annotations

import re

from kb.errors import QueryFailed, QueryRefused

__all__ = [
    "ALLOWED_STATEMENTS", "CATALOG_PRAGMAS", "DYNAMIC_SQL_FUNCTIONS", "HIDDEN_FUNCTIONS", "check_query",
    "error_refusal", "error_text", "file_refusal", "first_line", "statement_kind", "write_refusal",
]

#: Statement types user SQL may run (EXPLAIN only of a statement that is itself allowed).
ALLOWED_STATEMENTS = frozenset({"SELECT", "EXPLAIN"})
#: The PRAGMAs (``PRAGMA table_info('objects')``, ``pragma_table_info('objects')``) user SQL may run: they
#: only describe the catalog's own tables and views (names, columns, types), read no file and change no
#: setting. Every other PRAGMA is refused: ``database_list`` names the server's file, ``database_size`` and
#: ``platform`` its settings and machine, and the rest change settings.
CATALOG_PRAGMAS: tuple[str, ...] = ("table_info", "show_tables", "show_tables_expanded", "show")
#: Table functions refused in user SQL because they reveal the server's file paths or settings (every
#: ``pragma_*`` one but :data:`CATALOG_PRAGMAS`).
HIDDEN_FUNCTIONS: tuple[str, ...] = (
    "duckdb_databases", "duckdb_settings", "current_setting", "duckdb_extensions", "duckdb_temporary_files",
    "duckdb_secrets", "which_secret", "duckdb_logs", "duckdb_log_contexts", "duckdb_external_file_cache",
    "duckdb_memory", "pragma_(?!(?:" + "|".join(CATALOG_PRAGMAS) + r")(?![a-z0-9_]))[a-z_]+", "pg_settings",
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
    if kind == "PRAGMA" and _CATALOG_PRAGMA.match(query):
        return kind
    if kind not in ALLOWED_STATEMENTS:
        said = _leading_keyword(query)
        if said and not kind.startswith("EXPLAIN"):  # the user's word: INSTALL, not DuckDB's type LOAD
            what = f"{said} statements are"
        else:
            what = "statements of this type are" if kind == "UNKNOWN" else f"{kind} statements are"
        raise QueryRefused(f"refused: {what} not allowed{_file_statement(said, query)}; the catalog is read-only "
                           "(SELECT only)")
    return kind


#: Comments and white space before a statement's first word.
_LEAD = r"(?:\s|--[^\n]*(?:\n|\Z)|/\*.*?\*/)*"
#: The first word (two for FORCE INSTALL and UPDATE EXTENSIONS) of a statement, as the user wrote it.
_LEADING_WORD = re.compile(_LEAD + r"(force\s+install|update\s+extensions|[a-z_]+)", re.IGNORECASE | re.DOTALL)
#: ``PRAGMA name`` or ``PRAGMA name('table')`` of a catalog PRAGMA, nothing after it but a semicolon.
_CATALOG_PRAGMA = re.compile(
    _LEAD + r"pragma\s+(?:" + "|".join(CATALOG_PRAGMAS) + r")\s*(?:\(\s*'(?:[^']|'')*'\s*\))?\s*;?\s*\Z",
    re.IGNORECASE | re.DOTALL,
)
#: Statements that read or write files, and what each does: the refusal says it.
_FILE_STATEMENTS = {"ATTACH": "reading files", "IMPORT": "reading files", "EXPORT": "writing files",
                    "LOAD": "loading extensions", "INSTALL": "installing extensions",
                    "FORCE INSTALL": "installing extensions"}
#: Statement words that change data or schema, looked for when a query inside a SELECT tried to write.
_WRITE_WORD = re.compile(r"(?<![a-z0-9_])(insert|update|delete|merge|truncate|copy|create|drop|alter)(?![a-z0-9_])", re.I)


def _leading_keyword(query: str) -> str | None:
    """The statement's first word as the user wrote it (DuckDB names INSTALL and LOAD both ``LOAD``, RESET
    ``SET``, TRUNCATE ``DELETE``), upper case; None for WITH (its statement's type names it better)."""
    m = _LEADING_WORD.match(query)
    if not m or m.group(1).lower() == "with":
        return None
    return " ".join(m.group(1).upper().split())


def _quoted(query: str) -> str | None:
    """The first single-quoted literal of ``query`` (a file path, in a statement that reads one)."""
    m = re.search(r"'((?:[^']|'')*)'", query)
    return m.group(1).replace("''", "'") if m else None


def _file_statement(said: str | None, query: str) -> str:
    """For a statement that reads or writes files (ATTACH, COPY, IMPORT, EXPORT, LOAD, INSTALL): what it
    would do and the file it names (": reading files is not allowed ('/etc/passwd')"); for a PRAGMA, the
    ones that run; else ""."""
    if said == "COPY":
        bare = re.sub(r"'(?:[^']|'')*'|\"(?:[^\"]|\"\")*\"", " ", query)
        action = "writing files" if re.search(r"(?<![a-z0-9_])to(?![a-z0-9_])", bare, re.I) else "reading files"
    else:
        action = _FILE_STATEMENTS.get(said or "")
    if said == "PRAGMA":
        return f": only the PRAGMAs that describe the catalog's tables run ({', '.join(CATALOG_PRAGMAS)})"
    if action is None:
        return ""
    path = _quoted(query) if "files" in action else None
    return f": {action} is not allowed" + (f" ({path!r})" if path is not None else "")


def file_refusal(path: str) -> str:
    """The sandbox's words for a file or URL that user SQL tried to read."""
    return f"refused: reading files is not allowed ({path!r}); SQL here reads only the catalog's own tables"


#: DuckDB's errors for a file or URL read, and the path in each: its permission error (the sandbox's
#: connection has no file access), and a table name that is a path (``FROM '/etc/passwd'``: DuckDB reads a
#: quoted path as a table, and one whose extension it does not know is then "a table that does not exist").
_FILE_ERRORS = (
    re.compile(r'Permission Error: Cannot access (?:file|directory) "([^"]*)"'),
    re.compile(r'Catalog Error: Table with name "?([^"]*?[/\\~:][^"]*?|[^" ]*\.[A-Za-z0-9]{1,8})"? does not exist'),
)
#: A function of a DuckDB extension that is not loaded (``sqlite_scan``, ``read_xlsx``, ``st_point``), or one
#: DuckDB tried to install for a query (``delta_scan``): the sandbox loads none.
_EXTENSION_ERRORS = (
    re.compile(r'Function with name "?([^" ]+)"? is not in the catalog, but it exists in the (\w+) extension'),
    re.compile(r"()automatically (?:install|load) the required extension '(\w+)"),
)


def error_refusal(err: Exception) -> str | None:
    """The sandbox's own refusal for a DuckDB error that stopped a file or URL read, or a function of an
    extension; None for any other error."""
    text = str(err)
    for pattern in _FILE_ERRORS:
        m = pattern.search(text)
        if m:
            return file_refusal(m.group(1))
    for pattern in _EXTENSION_ERRORS:
        m = pattern.search(text)
        if m:
            what = f"{m.group(1)}() is in" if m.group(1) else "the query needs"
            return (f"refused: {what} DuckDB's {m.group(2)} extension, and the SQL sandbox loads no extensions "
                    "(reading files is not allowed)")
    return None


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
        raise QueryRefused(f"refused: {hidden.group(1)} reveals the server's settings or files and is not available")
    dynamic = _DYNAMIC_RE.search(query)
    if dynamic:
        raise QueryRefused(
            f"refused: {dynamic.group(1)}() runs SQL built at run time, which cannot be checked; write the query itself"
        )


#: The line of DuckDB's error text that says what was meant ('Did you mean "objects"?', 'Candidate bindings:').
_HINT = re.compile(r"^(Did you mean .*|Candidate bindings: .*)$", re.MULTILINE)


def error_text(err: Exception) -> str:
    """An error's first line, and DuckDB's hint of what was meant when it gives one ("Table with name objcts
    does not exist! (Did you mean "objects"?)"): the text is one line either way."""
    hint = _HINT.search(str(err))
    return first_line(err) + (f" ({hint.group(1).strip()})" if hint else "")


def first_line(err: Exception) -> str:
    """The first line of an error's text (its type's name when it has none)."""
    return str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
