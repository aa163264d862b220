"""The ``objrecall`` command line: a thin layer over the Python API (see README).

One Typer app; each command group lives in its own module here (``catalog``: init, catalog, sql;
``parse``; ``recall``: recall, evaluate; ``ingest``: extract, ingest, demo-store; ``grasp``; ``serve``;
``demo``), whose ``register(app)`` adds its commands. Every module imports its heavy dependencies inside
the command bodies, so ``objrecall --help`` imports no numpy, NLTK, MuJoCo or FastAPI.
"""

from __future__ import annotations

import importlib

import typer

from kb.service.cli.common import ObjrecallGroup

__all__ = ["COMMAND_MODULES", "app", "main"]

app = typer.Typer(
    cls=ObjrecallGroup,
    no_args_is_help=True,
    add_completion=False,
    rich_markup_mode=None,
    help="objrecall: recall household objects from descriptions and validate their grasps.",
)

#: Modules whose ``register(app)`` adds commands, in the order ``--help`` lists them.
COMMAND_MODULES = tuple(
    f"kb.service.cli.{name}" for name in ("catalog", "demo", "parse", "recall", "ingest", "grasp", "serve")
)


def _register() -> None:
    for module in COMMAND_MODULES:
        importlib.import_module(module).register(app)


_register()


def main() -> None:
    app()
