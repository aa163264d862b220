"""Descriptions read from a CSV file: the ``description`` column that ``objrecall parse --file``,
``objrecall recall --file`` and the evaluation's open-set file share."""

from __future__ import annotations

import csv
from pathlib import Path

from kb.errors import DescriptionError

__all__ = ["read_description_column"]


def read_description_column(path: Path) -> list[str]:
    """The ``description`` column of a CSV, in order (blank cells kept: they give empty results).

    Raises :class:`~kb.errors.DescriptionError` naming the file when it has no such column, is not UTF-8
    or is not CSV."""
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            reader = csv.DictReader(fh)
            fields = [f.strip() for f in (reader.fieldnames or [])]
            if "description" not in fields:
                columns = ", ".join(fields) or "none"
                raise DescriptionError(f"{path}: no 'description' column (columns: {columns})")
            key = (reader.fieldnames or [])[fields.index("description")]
            return [row.get(key) or "" for row in reader]
    except UnicodeDecodeError as err:
        raise DescriptionError(f"{path}: not UTF-8 text ({err.reason})") from None
    except csv.Error as err:
        raise DescriptionError(f"{path}: not a CSV file ({err})") from None
