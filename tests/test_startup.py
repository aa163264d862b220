"""``objrecall --help`` starts light: the command line imports its heavy libraries only inside commands."""

import subprocess
import sys

from typer.testing import CliRunner

from kb.catalog import DEFAULT_MAX_ROWS, DEFAULT_SQL_TIMEOUT
from kb.service.cli import app

HEAVY = ("numpy", "duckdb", "nltk", "mujoco", "fastapi", "pydantic", "sklearn", "matplotlib", "requests", "httpx")


def _imported_after(statement: str) -> set[str]:
    code = f"import sys\n{statement}\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    return {name.split(".")[0] for name in out.split()}


def test_the_command_line_imports_no_heavy_library():
    assert _imported_after("import kb.service.cli").isdisjoint(HEAVY)


def test_a_light_kb_module_does_not_load_the_catalog():
    assert _imported_after("import kb.errors").isdisjoint({"numpy", "duckdb"})


def test_the_kb_package_still_exports_its_api_on_first_use():
    imported = _imported_after("import kb\nassert kb.KnowledgeBase.__name__ == 'KnowledgeBase'")
    assert "duckdb" in imported


def test_sql_help_shows_the_catalogs_defaults():
    out = " ".join(CliRunner().invoke(app, ["sql", "--help"], env={"COLUMNS": "200"}).output.split())
    assert f"At most this many rows. [default: ({DEFAULT_MAX_ROWS})]" in out
    assert f"after this many seconds. [default: ({DEFAULT_SQL_TIMEOUT:g})]" in out


# ------------------------------------------------------------------ main() registers one module
def test_each_module_registers_the_commands_it_is_listed_with():
    import typer.main

    from kb.service.cli import COMMANDS, build_app

    for module, commands in COMMANDS.items():
        assert set(typer.main.get_command(build_app([module])).commands) == set(commands), module
    every = [c for commands in COMMANDS.values() for c in commands]
    assert len(every) == len(set(every))
    assert set(typer.main.get_command(app).commands) == set(every)


def test_a_command_line_needs_the_module_of_its_command_only():
    from kb.service.cli import COMMAND_MODULES, modules_for

    assert modules_for(["recall", "a cup", "--json"]) == ("kb.service.cli.recall",)
    assert modules_for(["catalog", "list"]) == ("kb.service.cli.catalog",)
    assert modules_for(["demo-store"]) == ("kb.service.cli.ingest",)
    for argv in ([], ["--help"], ["recal"], ["-x", "recall"], ["Recall"]):
        assert modules_for(argv) == COMMAND_MODULES, argv


def test_main_registers_only_the_module_of_the_command_it_runs():
    code = (
        "import sys\n"
        "sys.argv = ['objrecall', 'parse', 'a 5 cm cup', '--json']\n"
        "from kb.service.cli import main\n"
        "try:\n    main()\nexcept SystemExit as done:\n    assert done.code in (0, None), done.code\n"
        "print(' '.join(sorted(m for m in sys.modules if m.startswith('kb.service.cli.'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert '"a_cm": 5' in out
    assert out.split()[-2:] == ["kb.service.cli.common", "kb.service.cli.parse"]


def test_a_command_shows_the_same_help_and_errors_alone_as_among_all():
    from kb.service.cli import build_app

    alone = build_app(["kb.service.cli.recall"])
    for args in (["recall", "--help"], ["recall", "--top", "0", "a cup"], ["evaluate", "--help"]):
        a, b = CliRunner().invoke(alone, args), CliRunner().invoke(app, args)
        assert (a.exit_code, a.output) == (b.exit_code, b.output), args
