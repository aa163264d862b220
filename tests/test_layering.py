"""The house's floors, read from the code's own imports (module level and inside functions, with ``ast``).

- ``kb`` storage (every module of ``kb/`` outside ``kb/service/``) imports nothing from ``recall``,
  ``scrapers``, ``sim`` or the faces (``kb.service``);
- ``recall``, ``scrapers`` and ``sim`` never import the faces;
- no two modules of the project import each other, directly or round a longer circle.

An import of ``a.b`` counts as an arrow to ``a.b`` only (not to the package ``a``), and ``from a import b``
as an arrow to the module ``a.b`` when there is one, else to ``a``.
"""

from __future__ import annotations

import ast
import graphlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("kb", "recall", "scrapers", "sim")
FACES = "kb.service"

#: Arrows left out of the circle check, each with the issue that removes it. Keep this empty.
TOLERATED_ARROWS: dict[tuple[str, str], str] = {}


def module_name(path: Path, root: Path = ROOT) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def project_modules(root: Path = ROOT) -> dict[str, Path]:
    """Every module of the project's packages, by dotted name."""
    return {
        module_name(p, root): p
        for pkg in PACKAGES
        for p in sorted((root / pkg).rglob("*.py"))
        if "__pycache__" not in p.parts
    }


def imports_of(name: str, path: Path, known: set[str]) -> set[str]:
    """The project modules that module ``name`` (at ``path``) imports, wherever the import statement is."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join([*anchor, base] if base else anchor)
            for alias in node.names:
                full = f"{base}.{alias.name}"
                found.add(full if full in known else base)
    return {m for m in found if m in known and m != name}


def import_graph(root: Path = ROOT) -> dict[str, set[str]]:
    modules = project_modules(root)
    known = set(modules)
    return {name: imports_of(name, path, known) for name, path in modules.items()}


def _within(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def layering_violations(graph: dict[str, set[str]]) -> list[str]:
    """Every arrow that points from a lower floor to a higher one, as ``importer -> imported``."""
    bad = []
    for importer, imported in sorted(graph.items()):
        if _within(importer, FACES):
            continue
        if _within(importer, "kb"):
            forbidden = ("recall", "scrapers", "sim", FACES)
        else:
            forbidden = (FACES,)
        bad += [f"{importer} -> {m}" for m in sorted(imported) if any(_within(m, f) for f in forbidden)]
    return bad


def import_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One circle of imports (first module repeated at the end), or None when there is none."""
    pruned = {a: {b for b in bs if (a, b) not in TOLERATED_ARROWS} for a, bs in graph.items()}
    try:
        graphlib.TopologicalSorter(pruned).prepare()
    except graphlib.CycleError as err:
        return list(reversed(err.args[1]))
    return None


@pytest.fixture(scope="module")
def graph() -> dict[str, set[str]]:
    return import_graph()


def test_the_graph_sees_module_and_function_level_imports(graph):
    # module level: the catalog imports the features vocabulary
    assert "kb.features" in graph["kb.catalog"]
    # inside a function: the demo command imports the main job only when it runs
    assert "kb.service.mainjob" in graph["kb.service.cli.demo"]
    assert len(graph) > 40


def test_storage_and_stages_never_import_upwards(graph):
    assert layering_violations(graph) == []


def test_no_import_circles(graph):
    assert import_cycle(graph) is None


def test_tolerated_arrows_still_exist(graph):
    """A tolerated arrow that is gone must leave the list, so the list cannot hide a new circle."""
    assert [arrow for arrow in TOLERATED_ARROWS if arrow[1] not in graph.get(arrow[0], set())] == []


# ------------------------------------------------------------------ the checks themselves catch what they should
def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = tmp_path / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    for pkg in PACKAGES:
        (tmp_path / pkg).mkdir(exist_ok=True)
        (tmp_path / pkg / "__init__.py").touch()
    return tmp_path


def test_an_upward_import_inside_a_function_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "kb/catalog.py": "def f():\n    from recall.engine import Recaller\n",
        "recall/engine.py": "Recaller = 1\n",
        "sim/planner.py": "import kb.service.cli\n",
        "kb/service/__init__.py": "",
        "kb/service/cli.py": "from recall import engine\nfrom kb import catalog\n",
    })  # fmt: skip
    graph = import_graph(root)
    assert layering_violations(graph) == ["kb.catalog -> recall.engine", "sim.planner -> kb.service.cli"]


def test_a_relative_import_resolves_to_the_module(tmp_path):
    root = _tree(tmp_path, {
        "recall/search.py": "from .snapshot import load\nfrom . import metrics\n",
        "recall/snapshot.py": "load = 1\n",
        "recall/metrics.py": "",
    })  # fmt: skip
    assert import_graph(root)["recall.search"] == {"recall.snapshot", "recall.metrics"}


def test_a_circle_is_caught_however_long(tmp_path):
    root = _tree(tmp_path, {
        "recall/a.py": "import recall.b\n",
        "recall/b.py": "def f():\n    from recall import c\n",
        "recall/c.py": "from recall.a import x\n",
    })  # fmt: skip
    cycle = import_cycle(import_graph(root))
    assert cycle is not None and cycle[0] == cycle[-1] and set(cycle) == {"recall.a", "recall.b", "recall.c"}


def test_no_circle_in_a_chain(tmp_path):
    root = _tree(tmp_path, {"recall/a.py": "import recall.b\n", "recall/b.py": "import kb\n"})
    assert import_cycle(import_graph(root)) is None
