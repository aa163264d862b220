"""objrecall knowledge base: the features vocabulary, the DuckDB catalog and its Python API.

>>> from kb import KnowledgeBase
>>> kb = KnowledgeBase.open("catalog.duckdb")          # doctest: +SKIP
>>> kb.get_object("tennis ball").mass_g                # doctest: +SKIP
56.0
"""

from kb.catalog import ImportReport, KnowledgeBase, QueryResult
from kb.csvio import read_catalog_csv, write_catalog_csv
from kb.errors import ObjrecallError
from kb.features import FEATURES, ObjectRecord, encode, validate_features

__version__ = "0.1.0"

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
