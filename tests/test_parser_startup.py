"""The parser's start-up (issue 12): NLTK imported without its optional scipy/sklearn bridges
(recall/toolkit.py), the unit table read from its stored copy (kb/measures/units.py, tested in test_measures_units.py), kb's lazy package init."""

from __future__ import annotations

import json
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from recall.toolkit import OPTIONAL_EXTRAS, _WithoutExtras

ROOT = Path(__file__).resolve().parent.parent


def _child(code: str) -> str:
    env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "NLTK_DATA": str(ROOT / "no-nltk-data")}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_parser_start_loads_neither_scipy_sklearn_pint_nor_duckdb() -> None:
    out = _child(
        "import sys, json\n"
        "from recall.parser import parse\n"
        "v = parse('a 5 lb steel dumbbell, 30 cm long').values()\n"
        "print(json.dumps([v, sorted(m for m in ('scipy', 'sklearn', 'pint', 'duckdb') if m in sys.modules)]))"
    )
    values, loaded = json.loads(out)
    assert values["mass_g"] == pytest.approx(5 * 453.59237) and values["a_cm"] == 30
    assert loaded == []


def test_scipy_and_sklearn_import_normally_after_the_parser() -> None:
    out = _child(
        "import recall.parser, nltk\n"
        "from sklearn.neighbors import KDTree\n"
        "from scipy.stats import fisher_exact\n"
        "import numpy as np\n"
        "print(KDTree(np.eye(3)).query(np.eye(3)[:1], k=1)[1][0][0], round(fisher_exact([[1, 9], [11, 3]])[1], 4))"
    )
    assert out.split() == ["0", "0.0028"]


def test_nltk_already_imported_is_left_as_it_is() -> None:
    out = _child(
        "import nltk, sys\n"
        "import recall.parser\n"
        "a = sys.modules['nltk.metrics.association']\n"
        "print(a.fisher_exact.__module__.split('.')[0], 'scipy' in sys.modules)"
    )
    assert out.split() == ["scipy", "True"]


def test_extras_are_left_out_only_for_the_importing_thread() -> None:
    mine = _WithoutExtras(frozenset(OPTIONAL_EXTRAS), threading.get_ident())
    with pytest.raises(ImportError, match="left out while NLTK is imported"):
        mine.find_spec("sklearn.feature_extraction", None)
    with pytest.raises(ImportError):
        mine.find_spec("scipy", None)
    assert mine.find_spec("numpy", None) is None
    assert mine.find_spec("scipyx", None) is None  # a package name is matched whole
    other = _WithoutExtras(frozenset(OPTIONAL_EXTRAS), threading.get_ident() + 1)
    assert other.find_spec("sklearn", None) is None


# ------------------------------------------------------------------------------------------ kb init
def test_kb_package_names_load_on_first_use() -> None:
    import kb

    assert set(kb.__all__) == {*kb._EXPORTS, "__version__"}
    assert kb.KnowledgeBase.__module__ == "kb.catalog"
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        kb.nothing  # noqa: B018
    out = _child("import sys, kb.errors, kb.features\nprint('duckdb' in sys.modules)")
    assert out.strip() == "False"
