"""The parser's start-up (issue 12): NLTK imported without its optional scipy/sklearn bridges
(recall/toolkit.py), the unit table read from its stored copy (recall/units.py), kb's lazy package init."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from recall import lexicon, units
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


# ---------------------------------------------------------------------------------------- unit table
def test_stored_unit_table_equals_a_fresh_pint_build() -> None:
    fresh = units.build_unit_table()
    stored = units._read_stored(units.STORED_TABLE)
    assert stored is not None, f"{units.STORED_TABLE} is stale: run python -m recall.units --write"
    assert list(stored) == list(fresh)  # same words, same order
    assert stored == fresh  # same kind, pint name and factor, exactly
    assert dict(units.unit_table()) == fresh


def test_stored_unit_table_is_what_the_writer_writes() -> None:
    assert units.STORED_TABLE.read_text(encoding="utf-8") == units.table_to_json(units.build_unit_table())


def _stored() -> dict:
    return json.loads(units.STORED_TABLE.read_text(encoding="utf-8"))


def _edit(data: dict, word: str, row) -> dict:
    data["units"][word] = row
    return data


@pytest.mark.parametrize(
    "change",
    [
        lambda d: d["units"].pop("cm") and d,  # a lexicon word missing
        lambda d: _edit(d, "parsec", ["length", "parsec", 3.0857e18]),  # a word the lexicon lacks
        lambda d: _edit(d, "cm", ["length", "meter", 1.0]),  # another pint name
        lambda d: _edit(d, "cm", ["mass", "centimeter", 1.0]),  # another kind
        lambda d: _edit(d, "cm", ["length", "centimeter", 0.0]),  # not positive
        lambda d: _edit(d, "cm", ["length", "centimeter", -1.0]),
        lambda d: _edit(d, "cm", ["length", "centimeter", math.inf]),
        lambda d: _edit(d, "cm", ["length", "centimeter", "1.0"]),  # not a number
    ],
)
def test_a_stale_or_damaged_stored_table_is_not_used(change, tmp_path: Path) -> None:
    path = tmp_path / "units.json"
    path.write_text(json.dumps(change(_stored())), encoding="utf-8")
    assert units._read_stored(path) is None  # unit_table() then builds it with pint


def test_a_missing_or_unreadable_stored_table_is_not_used(tmp_path: Path) -> None:
    assert units._read_stored(tmp_path / "absent.json") is None
    (tmp_path / "bad.json").write_text("{not json", encoding="utf-8")
    assert units._read_stored(tmp_path / "bad.json") is None
    (tmp_path / "short.json").write_text(json.dumps({"units": {"cm": ["length", "centimeter"]}}), "utf-8")
    assert units._read_stored(tmp_path / "short.json") is None


def test_the_stored_table_lists_every_lexicon_unit() -> None:
    rows = _stored()["units"]
    for kind, words in (("length", lexicon.LENGTH_UNITS), ("mass", lexicon.MASS_UNITS),
                        ("volume", lexicon.VOLUME_UNITS)):  # fmt: skip
        for word, name in words.items():
            assert rows[word][:2] == [kind, name]


# ------------------------------------------------------------------------------------------ kb init
def test_kb_package_names_load_on_first_use() -> None:
    import kb

    assert set(kb.__all__) == {*kb._EXPORTS, "__version__"}
    assert kb.KnowledgeBase.__module__ == "kb.catalog"
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        kb.nothing  # noqa: B018
    out = _child("import sys, kb.errors, kb.features\nprint('duckdb' in sys.modules)")
    assert out.strip() == "False"
