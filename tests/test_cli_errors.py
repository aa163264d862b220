"""Every command's error path: one ``Error: ...`` line on stderr, never a boxed usage error or a traceback;
exit code 1 for an error, 2 for a usage error (an unknown option or command, a bad option value), as click
has it (README: "Errors are one line on stderr and exit code 1; usage errors exit 2")."""

from __future__ import annotations

import subprocess

import pytest
import typer.main
from typer.testing import CliRunner

from kb.service.cli import app
from kb.service.cli.common import USAGE_EXIT

runner = CliRunner()


def _leaf_commands() -> list[list[str]]:
    out: list[list[str]] = []

    def walk(cmd, path):
        if hasattr(cmd, "commands"):
            for name, sub in cmd.commands.items():
                walk(sub, [*path, name])
        else:
            out.append(path)

    walk(typer.main.get_command(app), [])
    return out


def _assert_one_line_error(result, args, code: int = 1):
    assert result.exit_code == code, (args, result.exit_code, result.output)
    lines = [ln for ln in result.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error: "), (args, result.stderr)
    assert "Traceback" not in result.output and "╭" not in result.output, (args, result.output)


def test_every_command_is_covered():
    assert len(_leaf_commands()) >= 15


@pytest.mark.parametrize("command", _leaf_commands(), ids=" ".join)
def test_an_unknown_option_is_one_line_exit_2(command):
    result = runner.invoke(app, [*command, "--no-such-option"])
    _assert_one_line_error(result, command, USAGE_EXIT)
    assert "--no-such-option" in result.stderr and "--help" in result.stderr


def test_missing_files_are_one_line_exit_1(tmp_path):
    missing = str(tmp_path / "missing" / "nothing-here")
    cases = [
        ["sql", "select 1", "--db", missing],
        ["parse", "--file", missing],
        ["recall", "a red mug", "--db", missing],
        ["recall", "--file", missing, "--db", missing],
        ["evaluate", "--catalog", missing, "--descriptions", missing],
        ["extract", missing],
        ["ingest", "--sources", missing, "--db", str(tmp_path / "c.duckdb")],
        ["catalog", "import", missing, "--db", str(tmp_path / "c.duckdb")],
        ["catalog", "export", "-", "--db", missing],
        ["catalog", "list", "--db", missing],
        ["catalog", "show", "mug", "--db", missing],
        ["catalog", "summary", "--db", missing],
        ["grasp", "plan", "a red mug", "--catalog", missing],
        ["grasp", "validate", "mug", "--db", missing],
    ]
    for args in cases:
        _assert_one_line_error(runner.invoke(app, args), args)


def test_bad_values_are_one_line_exit_2(tmp_path):
    for args in (["catalog", "list", "--limit", "many"], ["sql"], ["sql", "select 1", "--timeout", "soon"],
                 ["recall", "a mug", "--top", "-x"], ["no-such-command"]):
        _assert_one_line_error(runner.invoke(app, args), args, USAGE_EXIT)


@pytest.mark.parametrize("text", ["-5 cm mug", "-0.5 kg", "-.5 m long"])
def test_a_description_starting_with_a_minus_says_to_put_dashes_before_it(text, seeded_db):
    for command in (["recall"], ["parse"], ["grasp", "plan"]):
        result = runner.invoke(app, [*command, text])
        _assert_one_line_error(result, command, USAGE_EXIT)
        assert "put -- before it" in result.stderr, result.stderr
    result = runner.invoke(app, ["recall", "--db", str(seeded_db), "--json", "--", text])
    assert result.exit_code == 0 and "negative: a size or a mass is more than zero" in result.stdout


def test_an_unknown_word_option_gets_no_dash_hint():
    assert "put --" not in runner.invoke(app, ["recall", "-x"]).stderr


def test_a_duckdb_file_that_is_no_catalog_is_one_line(tmp_path):
    import duckdb

    other = tmp_path / "other.duckdb"
    duckdb.connect(str(other)).close()
    _assert_one_line_error(runner.invoke(app, ["catalog", "show", "mug", "--db", str(other)]), "show")


def test_the_installed_script_says_the_same(tmp_path, cli_env):
    proc = subprocess.run(["objrecall", "catalog", "import", str(tmp_path / "no-such.csv")], capture_output=True,
                          text=True, env=cli_env, timeout=120)
    assert proc.returncode == 1 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and proc.stderr.startswith("Error: ") and "no-such.csv" in proc.stderr


def test_help_needs_no_value_and_bare_command_shows_help():
    result = runner.invoke(app, ["catalog", "list", "--help"], env={"COLUMNS": "80"})
    assert result.exit_code == 0
    assert "<bool>" not in result.stdout and "OBJRECALL_DB" in result.stdout
    result = runner.invoke(app, [])
    assert result.exit_code == 0 and "Usage:" in result.stdout


def test_refused_sql_is_one_line_exit_1(seeded_db):
    for query in ("UPDATE EXTENSIONS", "UPDATE EXTENSIONS (httpfs)", "SELECT len(range(0, 3000000000))",
                  "COPY objects TO '/tmp/x.csv'", "select 1; select 2"):
        result = runner.invoke(app, ["sql", query, "--db", str(seeded_db)])
        _assert_one_line_error(result, query)
        assert "refused" in result.stderr or "one statement" in result.stderr


def test_a_folder_as_the_catalog_is_one_line_for_every_command(tmp_path, monkeypatch):
    """``--db .``, ``--db ""`` (the current folder) or a folder in $OBJRECALL_DB: one line naming the folder,
    for commands that read the catalog through different paths (the recall index beside it raised a
    ValueError for ``.`` and ``/``)."""
    monkeypatch.chdir(tmp_path)
    for db in (".", "", str(tmp_path)):
        for args in (["recall", "a red mug"], ["sql", "select 1"], ["catalog", "list"], ["grasp", "plan", "a mug"]):
            result = runner.invoke(app, [*args, "--db", db])
            _assert_one_line_error(result, [*args, db])
            assert "is a folder, not a catalog file" in result.stderr, (args, db, result.stderr)
    monkeypatch.setenv("OBJRECALL_DB", str(tmp_path))
    result = runner.invoke(app, ["catalog", "list"])
    _assert_one_line_error(result, "env")
    assert "is a folder" in result.stderr
