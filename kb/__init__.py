"""objrecall knowledge base: the features vocabulary, the DuckDB catalog and its Python API."""
