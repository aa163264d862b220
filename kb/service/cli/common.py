"""What every ``objrecall`` command shares: the ``--db`` and ``--json`` options, output and error handling.

Each command-group module of this package (``catalog``, ``parse``, ``recall``, ``ingest``, ``grasp``,
``serve``, ``demo``) exposes a ``register(app)`` function that adds its commands to the one Typer app in
``kb/service/cli/__init__.py``; heavy libraries (MuJoCo, NLTK, scikit-learn, FastAPI) are imported inside
the command bodies so ``objrecall --help`` stays fast.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from kb.connections import database_reason
from kb.errors import CatalogUnreadable, DatabaseError, ObjrecallError
from kb.jsonable import to_jsonable

__all__ = ["USAGE_EXIT", "DbOption", "JsonOption", "ObjrecallGroup", "default_db_path", "emit", "emit_lines", "resolve_db"]

ENV_DB = "OBJRECALL_DB"
#: Exit code of a usage error (a bad option or value, an unknown command, a missing file argument), as click
#: and typer have it; every other error is 1.
USAGE_EXIT = 2


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
    """The catalog file ``--db`` names, else the default; an empty path or a folder is refused here, for every
    command alike (a folder is never a catalog; an empty ``--db ""`` is the current folder)."""
    path = Path(db) if db is not None else default_db_path()
    if db is None and not os.environ.get(ENV_DB):
        path.parent.mkdir(parents=True, exist_ok=True)  # the default data folder, made on first use
    if path.is_dir():
        raise DatabaseError(f"{path}: is a folder, not a catalog file (give a file path, e.g. {path / 'catalog.duckdb'})")
    _RESOLVED.append(path)
    return path


#: The catalog files this process's commands resolved (the last one is named by a database error that
#: reaches :class:`ObjrecallGroup` without a file name of its own).
_RESOLVED: list[Path] = []


def emit(data: Any) -> None:
    """Print one JSON document on one line."""
    sys.stdout.write(json.dumps(to_jsonable(data), ensure_ascii=False) + "\n")


def emit_lines(items: Iterable[Any]) -> None:
    """Print JSON Lines, one object per item, flushing as it goes."""
    for item in items:
        sys.stdout.write(json.dumps(to_jsonable(item), ensure_ascii=False) + "\n")
        sys.stdout.flush()


class ObjrecallGroup(TyperGroup):
    """Root command group: an :class:`ObjrecallError` becomes one ``Error: ...`` line on stderr and exit
    code 1; a usage error (a bad option or value, an unknown command, a file argument that does not
    exist) one such line and exit code 2 (:data:`USAGE_EXIT`, click's)."""

    def main(self, args: Any = None, prog_name: Any = None, complete_var: Any = None,
             standalone_mode: bool = True, **extra: Any) -> Any:
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except typer.TyperException as err:  # click's UsageError, BadParameter, NoSuchOption, FileError, ...
            if not standalone_mode:
                raise
            if type(err).__name__ == "NoArgsIsHelpError":  # a bare `objrecall` or group: the help, exit 0
                sys.stdout.write(err.format_message() + "\n")
                sys.exit(0)
            ctx = getattr(err, "ctx", None)
            hint = f" (see `{ctx.command_path} --help`)" if ctx is not None else ""
            _fail(f"{err.format_message()}{_dash_hint(err, ctx)}{hint}", exit_now=True, code=USAGE_EXIT)
        except typer.Abort:
            if not standalone_mode:
                raise
            _fail("aborted", exit_now=True)
        if not standalone_mode:
            return rv
        sys.exit(rv if isinstance(rv, int) else 0)

    def invoke(self, ctx: Any) -> Any:
        _RESOLVED.clear()  # only this command's catalog file is named
        try:
            return super().invoke(ctx)
        except ObjrecallError as err:
            _fail(str(err))
        except (FileNotFoundError, IsADirectoryError, NotADirectoryError, PermissionError) as err:
            _fail(f"{err.filename}: {err.strerror}")
        except Exception as err:
            if "duckdb" not in type(err).__module__:
                raise
            # a DuckDB file that is not an objrecall catalog, or one damaged: name it and the reason
            if _RESOLVED:
                _fail(str(CatalogUnreadable(_RESOLVED[-1], database_reason(err))))
            _fail(f"database error (is this an objrecall catalog?): {database_reason(err)}")


def _dash_hint(err: Exception, ctx: Any) -> str:
    """For an unknown option that is a number ("-5", "-.5 kg"): the text was read as an option; say how to
    pass a description that starts with a minus sign."""
    name = str(getattr(err, "option_name", "") or "")
    if not (name.startswith("-") and (name[1:2].isdigit() or name[1:2] == ".")):
        return ""
    path = ctx.command_path if ctx is not None else "objrecall recall"
    return f": a text starting with '-' is read as an option; put -- before it: {path} -- \"{name} ...\""


def _fail(message: str, *, exit_now: bool = False, code: int = 1) -> None:
    """One line on stderr and exit code ``code`` (1: an error; :data:`USAGE_EXIT` for a usage error; no
    traceback); ``exit_now`` outside a running command."""
    sys.stderr.write(f"Error: {' '.join(message.split())}\n")
    if exit_now:
        sys.exit(code)
    raise typer.Exit(code)
