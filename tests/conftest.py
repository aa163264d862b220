"""Shared fixtures. NLTK_DATA points at an empty folder for the whole run: nothing may need nltk_data."""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

_EMPTY_NLTK = tempfile.mkdtemp(prefix="empty-nltk-data-")
os.environ["NLTK_DATA"] = _EMPTY_NLTK
os.environ.setdefault("MPLBACKEND", "Agg")

REPO = Path(__file__).resolve().parents[1]
SEED_CSV = REPO / "kb" / "data" / "seed_catalog.csv"
SHARED_PAGES = Path(os.environ.get("OBJRECALL_STOREFRONT_PAGES", REPO.parent / "shared" / "storefront-pages"))


def pytest_unconfigure(config) -> None:
    """Remove the empty NLTK_DATA folder made for this run (every other test file lives in tmp_path)."""
    shutil.rmtree(_EMPTY_NLTK, ignore_errors=True)


@pytest.fixture
def db_path(tmp_path: Path) -> Path:
    """A path for a fresh catalog file (not created yet)."""
    return tmp_path / "catalog.duckdb"


@pytest.fixture
def seeded_db(tmp_path: Path) -> Path:
    """A catalog file holding the seed catalog (a fresh copy per test)."""
    from kb.catalog import KnowledgeBase

    path = tmp_path / "seeded.duckdb"
    KnowledgeBase.open(path).import_csv(SEED_CSV)
    return path


@pytest.fixture
def cli_env(tmp_path: Path) -> dict[str, str]:
    """Environment for running `objrecall` as a real subprocess (same interpreter, empty NLTK_DATA)."""
    env = dict(os.environ)
    env["NLTK_DATA"] = _EMPTY_NLTK
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["OBJRECALL_DB"] = str(tmp_path / "cli.duckdb")
    return env
