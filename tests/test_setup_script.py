"""scripts/setup.sh says what it is doing, a line per phase, while pip runs (pip itself is replaced by a
stand-in that records its arguments, so no package is installed)."""

from __future__ import annotations

import os
import shutil
import subprocess
import textwrap
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

FAKE_PYTHON = textwrap.dedent(
    """\
    #!/usr/bin/env bash
    # stands in for python: `-m venv DIR` makes DIR/bin/python (this script); `-m pip ...` records its args
    if [ "$1 $2" = "-m venv" ]; then mkdir -p "$3/bin"; cp "$0" "$3/bin/python"; exit 0; fi
    echo "$*" >> "$(dirname "$0")/../pip-calls"
    [ -n "$FAIL_PIP" ] && { echo "ERROR: no matching distribution" ; exit 1; }
    exit 0
    """
)


def _project(tmp_path: Path) -> Path:
    root = tmp_path / "project"
    (root / "scripts").mkdir(parents=True)
    shutil.copy(REPO / "scripts" / "setup.sh", root / "scripts" / "setup.sh")
    (root / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    fake = tmp_path / "python"
    fake.write_text(FAKE_PYTHON)
    fake.chmod(0o755)
    return root


def _run(root: Path, tmp_path: Path, **env: str) -> subprocess.CompletedProcess:
    full = {**os.environ, "PYTHON": str(tmp_path / "python"), "OBJRECALL_APT_PACKAGES": "", **env}
    return subprocess.run(["bash", "scripts/setup.sh"], cwd=root, env=full, capture_output=True, text=True,
                          timeout=60, stdin=subprocess.DEVNULL)


def test_setup_prints_a_line_per_phase_then_nothing_when_up_to_date(tmp_path):
    root = _project(tmp_path)
    first = _run(root, tmp_path)
    assert first.returncode == 0, first.stderr
    lines = first.stderr.splitlines()
    assert [line.split(" ", 2)[1] for line in lines] == ["creating", "1/2", "2/2", "environment"], lines
    assert "about a minute" in lines[2] and lines[3].startswith("setup: environment ready in ")
    calls = (root / ".venv" / "pip-calls").read_text().splitlines()
    assert calls == ["-m pip -q install --upgrade pip", "-m pip -q install -e .[test]"]  # quiet: not a terminal
    again = _run(root, tmp_path)
    assert again.returncode == 0 and again.stderr == ""


def test_a_failed_pip_shows_its_output_and_exits_1(tmp_path):
    root = _project(tmp_path)
    failed = _run(root, tmp_path, FAIL_PIP="1")
    assert failed.returncode == 1
    assert "no matching distribution" in failed.stderr and failed.stderr.rstrip().endswith("pip install failed")
