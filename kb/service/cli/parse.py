"""`objrecall parse`: a description (or a CSV of them) to catalog features (recall/PARSER.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from kb.service.cli.common import JsonOption


def register(app: typer.Typer) -> None:
    """Add this package's commands to the root app."""
    _register_parse(app)


def _register_parse(app: typer.Typer) -> None:
    """``objrecall parse``: a description (or a CSV of them) to features (recall/PARSER.md)."""

    @app.command("parse")
    def parse_command(
        text: Annotated[str | None, typer.Argument(help="The description, in quotes.")] = None,
        file: Annotated[
            Path | None, typer.Option("--file", help="CSV with a 'description' column; one result per row.")
        ] = None,
        json_out: JsonOption = False,
        tree: Annotated[bool, typer.Option("--tree", help="Also print the chunk tree.")] = False,
    ) -> None:
        """Parse an object description into catalog features (cm, g, categories) with their evidence."""
        from kb.errors import DescriptionError
        from kb.service.cli.common import emit, emit_lines
        from recall.descriptions import read_description_column
        from recall.parser import parse

        if (text is None) == (file is None):
            raise DescriptionError("give either a description TEXT or --file D.csv (not both)")
        if file is not None:
            rows = read_description_column(file)
            if json_out:
                emit_lines(_parsed_dict(parse(row), tree) for row in rows)
            else:
                _print_batch([parse(row) for row in rows])
            return
        assert text is not None
        parsed = parse(text)
        if json_out:
            emit(_parsed_dict(parsed, tree))
        else:
            _print_parsed(parsed, tree)


def _parsed_dict(parsed, with_tree: bool) -> dict:
    out = parsed.to_dict()
    if with_tree:
        out["tree"] = parsed.tree.pformat()
    return out


def _fmt_value(value) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def _print_parsed(parsed, with_tree: bool) -> None:
    from rich.console import Console
    from rich.table import Table

    console = Console()
    if parsed.is_empty():
        console.print("No features stated.")
    else:
        table = Table("feature", "value", "qualifier", "words")
        for feature, ev in parsed.features.items():
            value = _fmt_value(ev.value)
            if ev.low is not None or ev.high is not None:
                low = "" if ev.low is None else _fmt_value(ev.low)
                high = "" if ev.high is None else _fmt_value(ev.high)
                value += f" [{low}..{high}]"
            table.add_row(feature, value, ev.qualifier, ev.words)
        console.print(table)
        if parsed.mass_hint:
            console.print(f"mass hint: {parsed.mass_hint} (weak)")
    for refused in parsed.refused:  # "-10 kg", "1e308 cm": stated, not used, and why
        console.print(f"refused: {refused.words!r}: {refused.reason}", markup=False, highlight=False)
    if with_tree:
        console.print(parsed.tree.pformat(), markup=False, highlight=False)


def _print_batch(parsed_list) -> None:
    from rich.console import Console
    from rich.table import Table

    from kb.features import FEATURES

    table = Table("#", *FEATURES)
    for i, parsed in enumerate(parsed_list, start=1):
        values = parsed.values()
        table.add_row(str(i), *(_fmt_value(values[f]) if f in values else "-" for f in FEATURES))
    Console().print(table)
