"""Knowledge-base commands: ``init``, ``catalog import|export|list|show|summary``, ``sql``.

Each command opens the :class:`~kb.catalog.KnowledgeBase`, calls one method and prints the result (a rich
table, or one JSON document with ``--json``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from kb.errors import ObjrecallError
from kb.service.cli.common import DbOption, JsonOption, emit, resolve_db

console = Console()
catalog_app = typer.Typer(no_args_is_help=True, help="Import, export and browse the object catalog.")


def _open(db: Path | None, *, read_only: bool = False):
    """The catalog named by ``--db`` (DuckDB is imported here, not when the CLI starts)."""
    from kb.catalog import KnowledgeBase

    return KnowledgeBase.open(resolve_db(db), read_only=read_only)


def _features() -> tuple[str, ...]:
    from kb.features import FEATURES

    return FEATURES


# The defaults are kb.catalog's; the help shows them without importing DuckDB (tests/test_kb_cli.py checks).
def _default_max_rows() -> int:
    from kb.catalog import DEFAULT_MAX_ROWS

    return DEFAULT_MAX_ROWS


def _default_timeout() -> float:
    from kb.catalog import DEFAULT_SQL_TIMEOUT

    return DEFAULT_SQL_TIMEOUT


def _fmt(value: object) -> str:
    """A cell as text; markup-like text from a scraped page (``[bold]``) is shown as it is."""
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:g}"
    return escape(str(value))


#: Below this terminal width ``catalog list`` shows the compact columns (size as axbxc, no texture or
#: fragility), so that every cell stays readable at 80 columns.
WIDE_LIST_COLUMNS = 120


def _size(obj) -> str:
    dims = [d for d in obj.dims_cm if d is not None]
    return "x".join(f"{d:g}" for d in dims) if dims else "-"


def init(
    db: DbOption = None,
    seed: Annotated[bool, typer.Option("--seed/--no-seed", help="Load the seed catalog (upsert).")] = False,
    json_out: JsonOption = False,
) -> None:
    """Create the catalog database or upgrade it to the latest schema (optionally load the seed catalog)."""
    from kb.service.bootstrap import init_db

    path = resolve_db(db)
    kb = init_db(path, seed=seed)
    info = {"db": str(path), "revision": kb.schema_revision(), "objects": kb.count_objects()}
    if json_out:
        emit(info)
    else:
        console.print(f"catalog [bold]{path}[/] at schema {info['revision']}, {info['objects']} objects")


@catalog_app.command("import")
def catalog_import(
    file: Annotated[Path, typer.Argument(help="Canonical catalog CSV.")],
    db: DbOption = None,
    skip_invalid: Annotated[bool, typer.Option("--skip-invalid", help="Import valid rows, list the rest.")] = False,
    json_out: JsonOption = False,
) -> None:
    """Import a canonical CSV in one transaction (upsert by name); a bad row imports nothing."""
    kb = _open(db)
    report = kb.import_csv(file, skip_invalid=skip_invalid)
    if json_out:
        emit(report.to_dict())
        return
    console.print(
        f"{file}: {len(report.new)} new, {len(report.updated)} updated, {report.unchanged} unchanged, "
        f"{len(report.skipped)} skipped"
    )
    for s in report.skipped:
        console.print(f"  skipped {s}", style="yellow")


@catalog_app.command("export")
def catalog_export(
    file: Annotated[Path, typer.Argument(help="Where to write the canonical CSV ('-' for stdout).")],
    db: DbOption = None,
    json_out: JsonOption = False,
) -> None:
    """Export the catalog as canonical CSV (with aliases and source)."""
    kb = _open(db, read_only=True)
    if str(file) == "-":
        typer.echo(kb.export_csv(), nl=False)
        return
    text = kb.export_csv(file)
    rows = max(text.count("\n") - 1, 0)
    if json_out:
        emit({"file": str(file), "objects": rows})
    else:
        console.print(f"wrote {rows} objects to {file}")


@catalog_app.command("list")
def catalog_list(
    db: DbOption = None,
    limit: Annotated[int | None, typer.Option(help="At most this many objects.")] = None,
    offset: Annotated[int, typer.Option(help="Skip this many objects first.")] = 0,
    json_out: JsonOption = False,
) -> None:
    """List objects with their features."""
    kb = _open(db, read_only=True)
    objects = kb.list_objects(limit=limit, offset=offset)
    if json_out:
        emit([o.to_dict() for o in objects])
        return
    wide = console.width >= WIDE_LIST_COLUMNS
    if wide:
        features = _features()
        table = Table("name", *features, title=f"{len(objects)} objects")
        for o in objects:
            table.add_row(_fmt(o.name), *(_fmt(getattr(o, f)) for f in features))
    else:
        table = Table(title=f"{len(objects)} objects", caption="texture, fragility: --json or a wider terminal")
        # wide enough for the longest word of a name (up to 20 characters) so names break between words
        longest = max((len(w) for o in objects for w in o.name.split()), default=4)
        table.add_column("name", ratio=3, overflow="fold", min_width=min(20, max(4, longest)))
        for column in ("size cm", "mass g", "shape", "material", "rigidity"):
            table.add_column(column, no_wrap=True)
        for o in objects:
            table.add_row(_fmt(o.name), _size(o), _fmt(o.mass_g), _fmt(o.shape), _fmt(o.material), _fmt(o.rigidity))
    console.print(table)


@catalog_app.command("show")
def catalog_show(
    name: Annotated[str, typer.Argument(help="Object name or alias.")],
    db: DbOption = None,
    json_out: JsonOption = False,
) -> None:
    """Show one object, its aliases and the provenance of its values."""
    kb = _open(db, read_only=True)
    obj = kb.get_object(name)
    prov = kb.provenance(obj.name)
    if json_out:
        emit({**obj.to_dict(), "provenance": prov})
        return
    table = Table("feature", "value", title=obj.name)
    for f in _features():
        table.add_row(f, _fmt(getattr(obj, f)))
    table.add_row("aliases", _fmt(", ".join(obj.aliases) or None))
    table.add_row("source", _fmt(obj.source))
    console.print(table)
    _print_provenance(prov)


def _print_provenance(prov: list[dict]) -> None:
    """Provenance grouped by source: each source (often a long URL) printed once above its values."""
    groups: dict[tuple, list[dict]] = {}
    for p in prov:
        groups.setdefault((p["source"], p["adapter"]), []).append(p)
    for (source, adapter), rows in groups.items():
        ptable = Table("feature", "value", "role", "fetched_at", title_justify="left",
                       title=f"from {_fmt(source)} ({_fmt(adapter)})")
        for p in rows:
            value = p["value_num"] if p["value_num"] is not None else p["value_text"]
            ptable.add_row(_fmt(p["feature"]), _fmt(value), _fmt(p["role"]), _fmt(p["fetched_at"])[:19])
        console.print(ptable)


@catalog_app.command("summary")
def catalog_summary(db: DbOption = None, json_out: JsonOption = False) -> None:
    """Counts: objects, per category value, observations, ingestion runs, grasp trials."""
    kb = _open(db, read_only=True)
    summary = kb.summary()
    if json_out:
        emit(summary)
        return
    console.print(f"[bold]{summary['objects']}[/] objects, {summary['observations']} observations, "
                  f"{summary['ingestion_runs']} ingestion runs, {summary['grasp_validations']} grasp trials")
    for feat in ("shape", "material", "rigidity", "texture", "fragility"):
        console.print(f"  {feat}: " + ", ".join(f"{k} {v}" for k, v in summary[feat].items()))


def sql(
    query: Annotated[str, typer.Argument(help="One read-only SQL statement (SELECT).")],
    db: DbOption = None,
    *,
    max_rows: Annotated[
        int, typer.Option(default_factory=_default_max_rows, show_default="10000", help="At most this many rows.")
    ],
    timeout: Annotated[
        float,
        typer.Option(
            default_factory=_default_timeout, show_default="10", help="Interrupt the query after this many seconds."
        ),
    ],
    json_out: JsonOption = False,
) -> None:
    """Run read-only SQL on the catalog (no file or network access, no extensions)."""
    _check_sql_options(max_rows, timeout)
    kb = _open(db, read_only=True)
    result = kb.sql(query, max_rows=max_rows, timeout_s=timeout)
    if json_out:
        emit({"columns": result.columns, "rows": result.to_dicts(), "truncated": result.truncated})
        return
    table = Table(*(_fmt(c) for c in result.columns))
    for row in result.rows:
        table.add_row(*(_fmt(v) for v in row))
    console.print(table)
    if result.truncated:
        console.print(f"(first {max_rows} rows shown)", style="yellow")


def _check_sql_options(max_rows: int, timeout: float) -> None:
    """The sandbox's limits (kb/sandbox.py), refused in the options' own names."""
    from kb.sandbox import MAX_ROWS, MAX_TIMEOUT_S

    if not 1 <= max_rows <= MAX_ROWS:
        raise ObjrecallError(f"--max-rows must be from 1 to {MAX_ROWS:,}, got {max_rows}")
    if not 0 < timeout <= MAX_TIMEOUT_S:
        raise ObjrecallError(f"--timeout must be more than 0 and at most {MAX_TIMEOUT_S:g} seconds, got {timeout:g}")


def register(app: typer.Typer) -> None:
    """Add ``init``, ``sql`` and the ``catalog`` group."""
    app.command("init")(init)
    app.command("sql")(sql)
    app.add_typer(catalog_app, name="catalog")
