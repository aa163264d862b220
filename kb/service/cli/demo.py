"""``objrecall demo``: the main job (:mod:`kb.service.mainjob`) from the command line."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from kb.service.cli.common import DbOption, JsonOption, emit, resolve_db


def demo(
    db: DbOption = None,
    out: Annotated[Path, typer.Option("--out", help="Where to write the report.")] = Path("reports/demo"),
    workers: Annotated[int, typer.Option(help="Simulation worker processes.")] = 2,
    json_out: JsonOption = False,
) -> None:
    """The main job, offline: seed catalog -> ingest the demo storefront -> recall -> validate grasps -> report."""
    from kb.service.mainjob import run_demo

    result = run_demo(resolve_db(db), out, workers=workers)
    if json_out:
        emit(result.to_dict())


def register(app: typer.Typer) -> None:
    """Add ``demo``."""
    app.command("demo")(demo)
