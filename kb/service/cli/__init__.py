"""The ``objrecall`` command line: a thin layer over the Python API (see README)."""

from __future__ import annotations

import importlib

import typer

from kb.cli_common import ObjrecallGroup

app = typer.Typer(
    cls=ObjrecallGroup,
    no_args_is_help=True,
    add_completion=False,
    help="objrecall: recall household objects from descriptions and validate their grasps.",
)

#: Modules whose ``register(app)`` adds commands; each imports its heavy dependencies lazily.
COMMAND_MODULES = ("kb.commands", "recall.cli", "recall.cli_recall", "scrapers.cli", "sim.cli", "kb.service")


def _register() -> None:
    for module in COMMAND_MODULES:
        try:
            mod = importlib.import_module(module)
        except ModuleNotFoundError as err:
            if err.name == module:
                continue
            raise
        mod.register(app)


_register()


def main() -> None:
    app()


if __name__ == "__main__":
    main()
