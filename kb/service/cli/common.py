"""What every ``objrecall`` command shares: the ``--db`` and ``--json`` options, output and error handling.

Command modules (``kb/cli.py``, ``recall/cli.py``, ``scrapers/cli.py``, ``sim/cli.py``) each expose a
``register(app)`` function that adds their commands to the one Typer app; heavy libraries (MuJoCo,
scikit-learn, matplotlib) are imported inside the command bodies so ``objrecall --help`` stays fast.
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from kb.errors import ObjrecallError

__all__ = ["DbOption", "JsonOption", "ObjrecallGroup", "default_db_path", "emit", "emit_lines", "to_jsonable"]

ENV_DB = "OBJRECALL_DB"


def default_db_path() -> Path:
    """``$OBJRECALL_DB``, else ``$XDG_DATA_HOME/objrecall/catalog.duckdb`` (``~/.local/share/...``)."""
    env = os.environ.get(ENV_DB)
    if env:
        return Path(env)
    base = Path(os.environ.get("XDG_DATA_HOME") or Path.home() / ".local" / "share")
    return base / "objrecall" / "catalog.duckdb"


DbOption = Annotated[
    Path | None,
    typer.Option("--db", help=f"DuckDB catalog file [env {ENV_DB}; default ~/.local/share/objrecall/catalog.duckdb]"),
]
JsonOption = Annotated[bool, typer.Option("--json", help="Machine output: JSON (JSON Lines for batches).")]


def resolve_db(db: Path | None) -> Path:
    return Path(db) if db is not None else default_db_path()


def to_jsonable(value: Any) -> Any:
    """Plain JSON types for dataclasses, numpy scalars/arrays, paths, datetimes; NaN becomes null."""
    import dataclasses
    import datetime as _dt

    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        if hasattr(value, "to_dict"):
            return to_jsonable(value.to_dict())
        return to_jsonable(dataclasses.asdict(value))
    if isinstance(value, dict):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set, frozenset)):
        return [to_jsonable(v) for v in value]
    if isinstance(value, float):
        return None if math.isnan(value) or math.isinf(value) else value
    if isinstance(value, (str, int, bool)) or value is None:
        return value
    if isinstance(value, (_dt.datetime, _dt.date)):
        return value.isoformat()
    if isinstance(value, Path):
        return str(value)
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return to_jsonable(value.tolist())
    return str(value)


def emit(data: Any) -> None:
    """Print one JSON document on one line."""
    sys.stdout.write(json.dumps(to_jsonable(data), ensure_ascii=False) + "\n")


def emit_lines(items: Iterable[Any]) -> None:
    """Print JSON Lines, one object per item, flushing as it goes."""
    for item in items:
        sys.stdout.write(json.dumps(to_jsonable(item), ensure_ascii=False) + "\n")
        sys.stdout.flush()


class ObjrecallGroup(TyperGroup):
    """Root command group: an :class:`ObjrecallError` becomes one ``Error: ...`` line and exit code 1."""

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except ObjrecallError as err:
            _fail(str(err))
        except (FileNotFoundError, IsADirectoryError, PermissionError) as err:
            _fail(f"{err.filename}: {err.strerror}")


def _fail(message: str) -> None:
    """One line on stderr and exit code 1 (no traceback)."""
    sys.stderr.write(f"Error: {' '.join(message.split())}\n")
    raise typer.Exit(1)
