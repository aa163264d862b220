"""Command-line values coerced without pydantic (kb/service/cli/coercion.py) come out exactly as Typer's
own adapters make them, value and type, or fail with Typer's own error, for every parameter of every
command."""

from __future__ import annotations

from pathlib import Path

import pytest
import typer.main
from typer import _click

from kb.service.cli import app
from kb.service.cli.coercion import QuickRuntimeParam, quick_runtime_param, typer_runtime_param

SAMPLES = ["5", "0", "1", "15", "16", "65535", "65536", "-1", "+3", "05", " 5", "5 ", "1_000", "abc", "",
           "0.1", "0.05", "1.5", "10.", ".5", "1e3", "nan", "inf", "99999999999999999999", "٣",
           5, 0, 1.0, 0.1, 0.09, float("nan"), True, False, "x.csv", "/nonexistent/dir/x.csv", ".", "-",
           Path("a/b.csv"), b"bytes", "a\x00b", "~/x", "a//b/", "C:\\x"]  # fmt: skip


def _params():
    def walk(command, path):
        for param in getattr(command, "params", []):
            yield f"{' '.join(path)} {param.name}", command, param
        for name, sub in getattr(command, "commands", {}).items():
            yield from walk(sub, (*path, name))

    return list(walk(typer.main.get_command(app), ("objrecall",)))


def _outcome(runtime, value, param, ctx):
    try:
        out = runtime.coerce(value, param=param, ctx=ctx)
    except _click.exceptions.BadParameter as err:
        return "error", err.format_message()
    return "value", type(out), repr(out)


def test_the_quick_coercion_covers_the_commands_plain_parameters() -> None:
    quick = [p for _, _, p in _params() if isinstance(quick_runtime_param(p.type_descriptor), QuickRuntimeParam)]
    kinds = {p.type_descriptor.annotation for p in quick}
    assert {str, bool, int, float, Path} <= kinds and len(quick) >= 40


@pytest.mark.parametrize("label,command,param", _params(), ids=lambda x: x if isinstance(x, str) else "")
def test_every_value_comes_out_as_typers_own_coercion_makes_it(label, command, param) -> None:
    ctx = _click.Context(command, info_name="objrecall")
    quick, own = quick_runtime_param(param.type_descriptor), typer_runtime_param(param.type_descriptor)
    for value in SAMPLES:
        assert _outcome(quick, value, param, ctx) == _outcome(own, value, param, ctx), (label, value)


def test_a_one_shot_recall_imports_no_pydantic(tmp_path: Path) -> None:
    import subprocess
    import sys

    code = ("import sys\nsys.argv = ['objrecall', 'recall', '--top', '3', '--db', sys.argv[1], 'a mug']\n"
            "from kb.service.cli import main\ntry:\n    main()\nexcept SystemExit:\n    pass\n"
            "print('pydantic' in sys.modules)")  # fmt: skip
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path / "absent.duckdb")], capture_output=True,
                          text=True, timeout=300)  # fmt: skip
    assert "no catalog there" in done.stderr  # the command ran (its options coerced) and refused the file
    assert done.stdout.split()[-1] == "False"
