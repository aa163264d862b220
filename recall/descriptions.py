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
    :func:`kb.files.read_input_file`), has no such column, is not UTF-8 or is not CSV, and naming the
    rows when any description is longer than :data:`MAX_DESCRIPTION_CHARS` (checked before any is
    recalled, so a batch is refused whole rather than cut off at its first long row)."""
    path = Path(path)
    try:
        text = read_input_file(path, MAX_DESCRIPTIONS_BYTES).decode("utf-8-sig")
        reader = csv.DictReader(io.StringIO(text, newline=""))
        fields = [f.strip() for f in (reader.fieldnames or [])]
        if "description" not in fields:
            columns = ", ".join(fields) or "none"
            raise DescriptionError(f"{path}: no 'description' column (columns: {columns})")
        key = (reader.fieldnames or [])[fields.index("description")]
        rows = [row.get(key) or "" for row in reader]
    except UnicodeDecodeError as err:
        raise DescriptionError(f"{path}: not UTF-8 text ({err.reason})") from None
    except csv.Error as err:
        raise DescriptionError(f"{path}: not a CSV file ({err})") from None
    except OSError as err:
        raise DescriptionError(f"{path}: cannot read the file ({err.strerror or err})") from None
    _check_lengths(path, rows)
    return rows


def _check_lengths(path: Path, rows: list[str]) -> None:
    """Refuse the file when a row's description is past the limit, naming (up to three of) those rows."""
    long_rows = [(n, len(row)) for n, row in enumerate(rows, start=1) if len(row) > MAX_DESCRIPTION_CHARS]
    if long_rows:
        named = ", ".join(f"row {n} ({size:,} characters)" for n, size in long_rows[:3])
        more = f" and {len(long_rows) - 3} more" if len(long_rows) > 3 else ""
        raise DescriptionError(
            f"{path}: description too long in {named}{more} (at most {MAX_DESCRIPTION_CHARS:,}); nothing recalled"
        )
