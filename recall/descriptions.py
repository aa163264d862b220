"""Descriptions: their length limit (:data:`MAX_DESCRIPTION_CHARS`, every face's), and the ``description``
column of a CSV file that ``objrecall parse --file``, ``objrecall recall --file`` and the evaluation's
open-set file share."""

from __future__ import annotations

import csv
import io
from pathlib import Path

from kb.errors import DescriptionError
from kb.files import read_input_file

__all__ = ["MAX_DESCRIPTIONS_BYTES", "MAX_DESCRIPTION_CHARS", "read_description_column"]

#: The longest description (characters): the one limit of the recall API (``recall.parser.parse``, so
#: ``Recaller.recall_text``, the CLI and the HTTP service), refused with one DescriptionError past it.
MAX_DESCRIPTION_CHARS = 5_000

#: The largest file of descriptions read (about 300,000 descriptions of 200 characters).
MAX_DESCRIPTIONS_BYTES = 64 * 1024 * 1024


def read_description_column(path: Path) -> list[str]:
    """The ``description`` column of a CSV, in order (blank cells kept: they give empty results).

    Raises :class:`~kb.errors.DescriptionError` naming the file when it cannot be read (see
    :func:`kb.files.read_input_file`), has no such column, is not UTF-8 or is not CSV."""
    path = Path(path)
    try:
        text = read_input_file(path, MAX_DESCRIPTIONS_BYTES).decode("utf-8-sig")
        reader = csv.DictReader(io.StringIO(text, newline=""))
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
    except OSError as err:
        raise DescriptionError(f"{path}: cannot read the file ({err.strerror or err})") from None
