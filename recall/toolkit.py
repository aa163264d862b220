"""The NLTK pieces the parser uses, imported without running NLTK's package inits.

Importing any NLTK module first runs ``nltk/__init__.py``, which imports every subpackage (corpus
readers, translation metrics, parsers, the downloader, ...) and, where they are installed, ``scipy.stats``
and ``sklearn``: nearly all of the parser's start-up (``recall/PARSER.md``, "Start-up"). The parser needs
five classes from four modules. So, while this module imports them (and in the importing thread only),
NLTK's packages load *lazily*: a package module is created with its ``__path__``, but its ``__init__`` is
not run until a name is asked of it that the package defines (PEP 562's module ``__getattr__``):

1. a submodule of the package is imported as usual;
2. a name the ``__init__`` binds once, by ``from some.module import name`` with no ``import *`` after it,
   is taken from that module (read from the init's syntax tree, which is parsed, not run);
3. any other name (``__all__``, ``__version__``, a star import's names, a function the init defines) runs
   the package's whole ``__init__`` then, in the same module object.

So ``import nltk; nltk.word_tokenize`` or ``from nltk import *`` still work afterwards: they run the
inits at that moment. While the pieces are imported, scipy and scikit-learn are also reported missing
(unless imported already), as where they are not installed: NLTK guards those imports with ``except
ImportError`` (its optional ``machine_learning`` extras), for three features the parser never uses. They
import normally afterwards. An NLTK imported before this module is used as it is.
"""

from __future__ import annotations

import ast
import importlib
import importlib.abc
import importlib.machinery
import sys
import threading
import types
from pathlib import Path

__all__ = [
    "ChunkString",
    "RegexpChunkParser",
    "RegexpParser",
    "RegexpTagger",
    "RegexpTokenizer",
    "Tree",
    "UnigramTagger",
]

#: Top-level packages NLTK imports only for optional features the parser never uses.
OPTIONAL_EXTRAS = ("scipy", "sklearn")
#: The package whose inits are deferred.
LAZY_ROOT = "nltk"


class _WithoutExtras(importlib.abc.MetaPathFinder):
    """A finder that reports :data:`OPTIONAL_EXTRAS` missing to one thread."""

    def __init__(self, names: frozenset[str], thread: int) -> None:
        self.names = names
        self.thread = thread

    def find_spec(self, fullname, path, target=None):  # importlib's finder protocol
        if fullname.partition(".")[0] in self.names and threading.get_ident() == self.thread:
            raise ImportError(f"{fullname} left out while NLTK is imported (recall/toolkit.py)")
        return None  # any other module: the next finder


def init_origins(source: str) -> dict[str, str]:
    """Names a package ``__init__`` binds exactly once, by an absolute ``from module import name`` that
    no ``import *`` follows: name -> that module. Any other binding (an assignment, a def, a second
    import, a ``del``, an import inside ``try``/``if``) leaves the name out (it needs the real init)."""
    body = ast.parse(source).body
    bound: dict[str, int] = {}
    origin: dict[str, tuple[str, int]] = {}
    last_star = -1
    for at, node in enumerate(body):
        if isinstance(node, ast.ImportFrom) and any(a.name == "*" for a in node.names):
            last_star = at
            continue
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            for alias in node.names:
                origin[alias.asname or alias.name] = (f"{node.module}.{alias.name}", at)
        for sub in ast.walk(node):  # every name the statement can bind
            names: list[str] = []
            if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Store | ast.Del):
                names = [sub.id]
            elif isinstance(sub, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) and sub is node:
                names = [sub.name]
            elif isinstance(sub, ast.Import | ast.ImportFrom):
                names = [(a.asname or a.name).partition(".")[0] for a in sub.names]
            for name in names:
                bound[name] = bound.get(name, 0) + 1
    return {name: target for name, (target, at) in origin.items() if bound.get(name) == 1 and at > last_star}


class LazyPackage(types.ModuleType):
    """A package module whose ``__init__`` runs only when a name it alone defines is asked for."""

    def __getattr__(self, name: str):
        state = self.__dict__.get("_lazy_init")
        if state is None:  # the init has run (or is running): a name it does not define
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")
        if _is_submodule(self, name):
            return importlib.import_module(f"{self.__name__}.{name}")
        target = state["origins"].get(name)
        if target is not None:
            module, _, attr = target.rpartition(".")
            value = getattr(importlib.import_module(module), attr)
            setattr(self, name, value)
            return value
        with state["lock"]:
            if self.__dict__.get("_lazy_init") is state:
                del self.__dict__["_lazy_init"]
                exec(state["code"], self.__dict__)  # the package's own init, now, in this module
        try:
            return self.__dict__[name]
        except KeyError:
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}") from None


def _is_submodule(package: types.ModuleType, name: str) -> bool:
    if name.startswith("__"):
        return False
    for base in package.__dict__.get("__path__", ()):
        where = Path(base) / name
        if where.with_suffix(".py").is_file() or (where / "__init__.py").is_file():
            return True
    return False


class _LazyInitLoader(importlib.abc.Loader):
    """Creates a :class:`LazyPackage` and keeps the real loader's code for its init."""

    def __init__(self, real: importlib.abc.InspectLoader) -> None:
        self.real = real

    def create_module(self, spec):
        return LazyPackage(spec.name)

    def exec_module(self, module) -> None:
        source = self.real.get_source(module.__name__) or ""
        module.__dict__["_lazy_init"] = {
            "origins": init_origins(source),
            "code": self.real.get_code(module.__name__),
            "lock": threading.RLock(),
        }


class _LazyPackages(importlib.abc.MetaPathFinder):
    """A finder that gives one thread the packages under ``root`` as :class:`LazyPackage` s."""

    def __init__(self, root: str, thread: int) -> None:
        self.root = root
        self.thread = thread

    def find_spec(self, fullname, path, target=None):
        if fullname.partition(".")[0] != self.root or threading.get_ident() != self.thread:
            return None
        spec = importlib.machinery.PathFinder.find_spec(fullname, path)
        if spec is None or spec.submodule_search_locations is None or not hasattr(spec.loader, "get_source"):
            return None  # a plain module (or an unusual package): imported as usual
        spec.loader = _LazyInitLoader(spec.loader)
        return spec


def _forget(root: str) -> None:
    for name in [n for n in sys.modules if n == root or n.startswith(root + ".")]:
        del sys.modules[name]


def _pieces() -> tuple:
    from nltk.chunk.regexp import ChunkString, RegexpChunkParser, RegexpParser
    from nltk.tag.sequential import RegexpTagger, UnigramTagger
    from nltk.tokenize.regexp import RegexpTokenizer
    from nltk.tree.tree import Tree

    return ChunkString, RegexpChunkParser, RegexpParser, RegexpTagger, RegexpTokenizer, Tree, UnigramTagger


def _import_pieces() -> tuple:
    """The parser's NLTK classes, NLTK's package inits deferred (an NLTK imported before: as it is)."""
    if LAZY_ROOT in sys.modules:
        return _pieces()
    me = threading.get_ident()
    finders = [_LazyPackages(LAZY_ROOT, me),
               _WithoutExtras(frozenset(n for n in OPTIONAL_EXTRAS if n not in sys.modules), me)]  # fmt: skip
    sys.meta_path[:0] = finders
    try:
        return _pieces()
    except ImportError:  # an NLTK that cannot load so: forget the half import, import it plainly
        _forget(LAZY_ROOT)
    finally:
        for finder in finders:
            sys.meta_path.remove(finder)
    import nltk  # noqa: F401

    return _pieces()


ChunkString, RegexpChunkParser, RegexpParser, RegexpTagger, RegexpTokenizer, Tree, UnigramTagger = _import_pieces()
