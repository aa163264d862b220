"""objrecall knowledge base: the features vocabulary, the DuckDB catalog and its Python API.

>>> from kb import KnowledgeBase
>>> kb = KnowledgeBase.open("catalog.duckdb")          # doctest: +SKIP
>>> kb.get_object("tennis ball").mass_g                # doctest: +SKIP
56.0

The names below are imported on first use (PEP 562), so that importing one storage module
(``kb.errors``, ``kb.features``) does not load DuckDB and the catalog.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

#: public name -> the module that defines it
_EXPORTS = {
    "FEATURES": "kb.features",
    "ImportReport": "kb.catalog",
    "KnowledgeBase": "kb.catalog",
    "ObjectRecord": "kb.features",
    "ObjrecallError": "kb.errors",
    "QueryResult": "kb.catalog",
    "encode": "kb.features",
    "read_catalog_csv": "kb.csvio",
    "validate_features": "kb.features",
    "write_catalog_csv": "kb.csvio",
}

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

if TYPE_CHECKING:
    from kb.catalog import ImportReport, KnowledgeBase, QueryResult
    from kb.csvio import read_catalog_csv, write_catalog_csv
    from kb.errors import ObjrecallError
    from kb.features import FEATURES, ObjectRecord, encode, validate_features


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'kb' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
