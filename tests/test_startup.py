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
