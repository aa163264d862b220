"""The NLTK pieces the parser uses, imported without NLTK's optional scipy and scikit-learn bridges.

Importing any part of NLTK runs its package init, which imports every subpackage; where scipy and
scikit-learn are installed (this project needs them elsewhere), ``nltk.metrics`` and ``nltk.classify``
then import ``scipy.stats`` and ``sklearn`` for three optional features (Fisher's exact test of bigram
association, ``approxrand``'s ``betai``, ``SklearnClassifier``), which is nearly all of NLTK's import
time (``recall/PARSER.md``, "Start-up"). NLTK is built to run without them: those imports are guarded
by ``except ImportError`` (they are NLTK's optional ``machine_learning`` extras). So while NLTK is first
imported, and in the importing thread only, scipy and scikit-learn are reported missing unless they are
imported already; NLTK then loads exactly as it does where they are not installed. Afterwards both
import normally (a failed import is not remembered), for this process's own uses (the k-d tree
baseline, the evaluation's calibration). The only cost: in a process that imported NLTK through this
module, those three NLTK features are unavailable. The parser uses none of them.
"""

from __future__ import annotations

import importlib.abc
import sys
import threading

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


class _WithoutExtras(importlib.abc.MetaPathFinder):
    """A finder that reports :data:`OPTIONAL_EXTRAS` missing to one thread."""

    def __init__(self, names: frozenset[str], thread: int) -> None:
        self.names = names
        self.thread = thread

    def find_spec(self, fullname, path, target=None):  # importlib's finder protocol
        if fullname.partition(".")[0] in self.names and threading.get_ident() == self.thread:
            raise ImportError(f"{fullname} left out while NLTK is imported (recall/toolkit.py)")
        return None  # any other module: the next finder


def _import_nltk() -> None:
    """Import NLTK with :data:`OPTIONAL_EXTRAS` left out; plainly if it cannot do without them."""
    if "nltk" in sys.modules:
        return
    missing = frozenset(n for n in OPTIONAL_EXTRAS if n not in sys.modules)
    finder = _WithoutExtras(missing, threading.get_ident())
    sys.meta_path.insert(0, finder)
    try:
        import nltk  # noqa: F401
    except ImportError:  # an NLTK that needs them unconditionally: forget the half import, import plainly
        for name in [n for n in sys.modules if n == "nltk" or n.startswith("nltk.")]:
            del sys.modules[name]
        sys.meta_path.remove(finder)
        import nltk  # noqa: F401
    finally:
        if finder in sys.meta_path:
            sys.meta_path.remove(finder)


_import_nltk()

from nltk.chunk import RegexpChunkParser, RegexpParser  # noqa: E402
from nltk.chunk.regexp import ChunkString  # noqa: E402
from nltk.tag import RegexpTagger, UnigramTagger  # noqa: E402
from nltk.tokenize import RegexpTokenizer  # noqa: E402
from nltk.tree import Tree  # noqa: E402
