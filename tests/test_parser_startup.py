"""The parser's start-up (issue 12): NLTK imported without its optional scipy/sklearn bridges
(recall/toolkit.py), the unit table read from its stored copy (kb/measures/units.py, tested in test_measures_units.py), kb's lazy package init."""

from __future__ import annotations

import json
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from recall.toolkit import OPTIONAL_EXTRAS, _LazyPackages, _WithoutExtras, init_origins

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


def test_the_parser_runs_no_nltk_package_init() -> None:
    out = _child(
        "import sys, json\n"
        "import recall.parser\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith('nltk'))))"
    )
    loaded = set(json.loads(out))
    assert {"nltk.tokenize.regexp", "nltk.tag.sequential", "nltk.chunk.regexp", "nltk.tree.tree"} <= loaded
    # what nltk/__init__.py, nltk/tokenize/__init__.py and nltk/classify/__init__.py would import
    assert loaded.isdisjoint({"nltk.corpus", "nltk.translate", "nltk.downloader", "nltk.tokenize.punkt",
                              "nltk.classify.maxent", "nltk.stem", "nltk.text"})  # fmt: skip


def test_nltk_names_still_load_on_first_use_after_the_parser() -> None:
    out = _child(
        "import recall.parser, nltk\n"
        "from nltk import *\n"
        "from nltk.tokenize import TreebankWordTokenizer\n"
        "print(nltk.__version__.count('.') >= 1, RegexpTokenizer is nltk.tokenize.regexp.RegexpTokenizer,\n"
        "      TreebankWordTokenizer().tokenize('a 5 cm cup'), 'nltk.corpus' in __import__('sys').modules)"
    )
    assert out.split() == ["True", "True", "['a',", "'5',", "'cm',", "'cup']", "True"]


def test_parses_are_the_same_with_nltk_fully_imported() -> None:
    texts = [*(row.split(",", 1)[1] for row in
               (ROOT / "recall/data/dev_descriptions.csv").read_text(encoding="utf-8").splitlines()[1:80]),
             "", "½ lb", "twenty-one cm", "a 3 x 4 x 5 in box of 2 kg", "!!!"]  # fmt: skip
    code = ("import json, sys\n{first}from recall.parser import parse\n"
            "print(json.dumps([[parse(t).to_dict(), str(parse(t).tree)] for t in json.loads(sys.argv[1])]))")
    def run(first: str) -> list:
        env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "NLTK_DATA": str(ROOT / "no-nltk-data")}
        done = subprocess.run([sys.executable, "-c", code.format(first=first), json.dumps(texts)],
                              capture_output=True, text=True, env=env, timeout=300)  # fmt: skip
        assert done.returncode == 0, done.stderr
        return json.loads(done.stdout)

    assert run("") == run("import nltk\n")


def test_init_origins_keep_only_names_bound_once_by_a_from_import() -> None:
    source = (
        "from a.b import One, Two as Second, Three\n"
        "import c.d\n"
        "from .rel import Rel\n"
        "Three = 3\n"
        "try:\n    from e import Guarded\nexcept ImportError:\n    pass\n"
        "def f(): pass\n"
        "from g import Late\n"
        "from h import *\n"
        "from i import After\n"
        "from j import Deleted\n"
        "del Deleted\n"
    )
    assert init_origins(source) == {"After": "i.After"}  # a later `import *` may rebind the others
    assert init_origins("from a.b import One, Two as Second\nfrom x import y\n") == {
        "One": "a.b.One", "Second": "a.b.Two", "y": "x.y"}  # fmt: skip


def test_a_lazy_package_runs_its_init_only_for_names_only_the_init_defines(tmp_path: Path, monkeypatch) -> None:
    pkg = tmp_path / "lazydemo_pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text(
        "import builtins\nbuiltins.LAZYDEMO_RUNS = getattr(builtins, 'LAZYDEMO_RUNS', 0) + 1\n"
        "from lazydemo_pkg.a import A\nB = 2\n", encoding="utf-8")  # fmt: skip
    (pkg / "a.py").write_text("A = 'a'\n", encoding="utf-8")
    (pkg / "sub" / "__init__.py").write_text("raise RuntimeError('never run')\n", encoding="utf-8")
    (pkg / "sub" / "leaf.py").write_text("from lazydemo_pkg import A\nLEAF = A + '!'\n", encoding="utf-8")
    import builtins

    monkeypatch.syspath_prepend(str(tmp_path))
    finder = _LazyPackages("lazydemo_pkg", threading.get_ident())
    sys.meta_path.insert(0, finder)
    try:
        import lazydemo_pkg.sub.leaf as leaf
    finally:
        sys.meta_path.remove(finder)
        monkeypatch.setattr(builtins, "LAZYDEMO_RUNS", getattr(builtins, "LAZYDEMO_RUNS", 0), raising=False)
    try:
        import lazydemo_pkg

        assert leaf.LEAF == "a!" and lazydemo_pkg.A == "a"
        assert builtins.LAZYDEMO_RUNS == 0  # neither init ran: A came from lazydemo_pkg.a
        assert lazydemo_pkg.B == 2  # defined by the init itself: it runs now, once
        assert builtins.LAZYDEMO_RUNS == 1 and lazydemo_pkg.B == 2
        with pytest.raises(AttributeError, match="no attribute 'missing'"):
            lazydemo_pkg.missing  # noqa: B018
        assert builtins.LAZYDEMO_RUNS == 1
    finally:
        for name in [n for n in sys.modules if n.startswith("lazydemo_pkg")]:
            del sys.modules[name]


# ------------------------------------------------------------------------------------------ kb init
def test_kb_package_names_load_on_first_use() -> None:
    import kb

    assert set(kb.__all__) == {*kb._EXPORTS, "__version__"}
    assert kb.KnowledgeBase.__module__ == "kb.catalog"
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        kb.nothing  # noqa: B018
    out = _child("import sys, kb.errors, kb.features\nprint('duckdb' in sys.modules)")
    assert out.strip() == "False"
