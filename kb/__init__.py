"""objrecall knowledge base: the features vocabulary, the DuckDB catalog and its Python API.

>>> from kb import KnowledgeBase
>>> kb = KnowledgeBase.open("catalog.duckdb")          # doctest: +SKIP
>>> kb.get_object("tennis ball").mass_g                # doctest: +SKIP
56.0
"""

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from kb.catalog import ImportReport, KnowledgeBase, QueryResult
    from kb.csvio import read_catalog_csv, write_catalog_csv
    from kb.errors import ObjrecallError
    from kb.features import FEATURES, ObjectRecord, encode, validate_features

__version__ = "0.1.0"

#: Where each public name lives. They are imported on first use (PEP 562), so that importing one light
#: module of the package (``kb.errors``, say, from the command line) does not load DuckDB and numpy.
_EXPORTS = {
    "ImportReport": "kb.catalog",
    "KnowledgeBase": "kb.catalog",
    "QueryResult": "kb.catalog",
    "read_catalog_csv": "kb.csvio",
    "write_catalog_csv": "kb.csvio",
    "ObjrecallError": "kb.errors",
    "FEATURES": "kb.features",
    "ObjectRecord": "kb.features",
    "encode": "kb.features",
    "validate_features": "kb.features",
}


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    if not name.startswith("_"):  # a submodule not imported yet (``kb.catalog`` after ``import kb``)
        try:
            return importlib.import_module(f"kb.{name}")
        except ModuleNotFoundError as err:
            if err.name != f"kb.{name}":
                raise
    raise AttributeError(f"module 'kb' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})


__all__ = [
    "FEATURES",
    "ImportReport",
    "KnowledgeBase",
    "ObjectRecord",
    "ObjrecallError",
    "QueryResult",
    "__version__",
    "encode",
    "read_catalog_csv",
    "validate_features",
    "write_catalog_csv",
]
