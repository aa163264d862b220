"""The ``objrecall`` command line: a thin layer over the Python API (see README).

One Typer app; each command group lives in its own module here (``catalog``: init, catalog, sql;
``parse``; ``recall``: recall, evaluate; ``ingest``: extract, ingest, demo-store; ``grasp``; ``serve``;
``demo``), whose ``register(app)`` adds its commands. Every module imports its heavy dependencies inside
the command bodies, so ``objrecall --help`` imports no numpy, NLTK, MuJoCo or FastAPI. :func:`main`
registers only the module of the command it runs (``objrecall recall ...`` needs neither the grasp
nor the ingestion commands: about 0.1 s less start-up); ``--help``, a bare ``objrecall`` or a word that
is no command gets every module. ``app`` (for importers and tests) holds every command. Plainly valid
option values are coerced without Typer's pydantic adapters (:mod:`kb.service.cli.coercion`).
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Sequence

import typer

from kb.service.cli import coercion
from kb.service.cli.common import ObjrecallGroup

__all__ = ["COMMANDS", "COMMAND_MODULES", "app", "build_app", "main"]

#: Modules whose ``register(app)`` adds commands, in the order ``--help`` lists them, and the top-level
#: commands (or groups) each adds (a test checks these against what they register).
COMMANDS: dict[str, tuple[str, ...]] = {
    "kb.service.cli.catalog": ("init", "sql", "catalog"),
    "kb.service.cli.demo": ("demo",),
    "kb.service.cli.parse": ("parse",),
    "kb.service.cli.recall": ("recall", "evaluate"),
    "kb.service.cli.ingest": ("extract", "ingest", "demo-store"),
    "kb.service.cli.grasp": ("grasp",),
    "kb.service.cli.serve": ("serve",),
}
COMMAND_MODULES = tuple(COMMANDS)
coercion.install()  # plainly valid values coerced without pydantic (kb/service/cli/coercion.py)


def build_app(modules: Sequence[str] = COMMAND_MODULES) -> typer.Typer:
    """The Typer app with the commands of ``modules``."""
    new = typer.Typer(
        cls=ObjrecallGroup,
        no_args_is_help=True,
        add_completion=False,
        rich_markup_mode=None,
        help="objrecall: recall household objects from descriptions and validate their grasps.",
    )
    new.callback()(_root)  # a group even with one command (else Typer makes that command the root)
    for module in modules:
        importlib.import_module(module).register(new)
    return new


def _root() -> None:
    """The root group takes no options of its own."""


def modules_for(argv: Sequence[str]) -> tuple[str, ...]:
    """The modules a command line needs: the one adding its command, else all of them."""
    if argv and not argv[0].startswith("-"):
        for module, commands in COMMANDS.items():
            if argv[0] in commands:
                return (module,)
    return COMMAND_MODULES


def __getattr__(name: str):
    """``app``: every command, built on first use (PEP 562), so that :func:`main` builds only its own."""
    if name == "app":
        globals()["app"] = built = build_app()
        return built
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def main() -> None:
    build_app(modules_for(sys.argv[1:]))()
