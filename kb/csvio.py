"""The canonical catalog CSV: reading with per-cell reasons, and writing.

Header: ``name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity`` (this order when written;
any order when read). Blank cells mean unknown. Optional extra columns: ``aliases`` (separated by ``;``)
and ``source``; other extra columns are kept in ``ObjectRecord.extra``. Rows are numbered as a spreadsheet
shows them: the header is row 1, the first object row 2.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from kb.errors import CatalogImportError, InvalidFeature
from kb.features import CSV_COLUMNS, FEATURES, ObjectRecord, normalize_name

__all__ = ["CsvReadResult", "SkippedRow", "read_catalog_csv", "write_catalog_csv", "parse_catalog_csv"]

ALIAS_SEPARATOR = ";"
OPTIONAL_COLUMNS = ("aliases", "source")


@dataclass(frozen=True)
class SkippedRow:
    row: int
    column: str
    reason: str

    def __str__(self) -> str:
        return f"row {self.row}, column {self.column}: {self.reason}"


@dataclass
class CsvReadResult:
    records: list[ObjectRecord] = field(default_factory=list)
    skipped: list[SkippedRow] = field(default_factory=list)


def read_catalog_csv(path: str | Path, *, skip_invalid: bool = False) -> CsvReadResult:
    """Read and validate a canonical CSV file.

    Every row is checked. With ``skip_invalid=False`` any problem raises :class:`CatalogImportError`
    listing every bad row (row, column, reason); with ``skip_invalid=True`` the valid rows are returned
    and the bad ones listed in ``skipped``.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as err:
        raise CatalogImportError(str(path), [(0, "-", f"not UTF-8 text ({err.reason})")]) from None
    return parse_catalog_csv(text, label=str(path), skip_invalid=skip_invalid)


def parse_catalog_csv(text: str, *, label: str = "<csv>", skip_invalid: bool = False) -> CsvReadResult:
    """Like :func:`read_catalog_csv` for CSV text already in memory (``label`` names it in errors)."""
    reader = csv.DictReader(io.StringIO(text))
    header = [h.strip() for h in (reader.fieldnames or [])]
    if not header:
        raise CatalogImportError(label, [(1, "-", "empty file: no header")])
    reader.fieldnames = header
    missing = [c for c in CSV_COLUMNS if c not in header]
    if missing:
        raise CatalogImportError(label, [(1, c, "missing column in header") for c in missing])
    result = CsvReadResult()
    problems: list[SkippedRow] = []
    seen: dict[str, int] = {}
    for offset, row in enumerate(reader):
        rownum = offset + 2
        if None in row:  # more cells than header columns
            problems.append(SkippedRow(rownum, "-", f"{len(header) + len(row[None])} cells, header has {len(header)}"))
            continue
        if all((v or "").strip() == "" for v in row.values()):
            continue  # blank line
        try:
            record = _row_to_record(row)
        except InvalidFeature as err:
            problems.append(SkippedRow(rownum, err.field, err.reason))
            continue
        if record.name in seen:
            problems.append(SkippedRow(rownum, "name", f"duplicate of row {seen[record.name]} ({record.name!r})"))
            continue
        seen[record.name] = rownum
        result.records.append(record)
    if problems and not skip_invalid:
        raise CatalogImportError(label, [(p.row, p.column, p.reason) for p in problems])
    result.skipped = problems
    return result


def _row_to_record(row: dict[str, str | None]) -> ObjectRecord:
    features = {f: (row.get(f) or "").strip() or None for f in FEATURES}
    aliases = [a.strip() for a in (row.get("aliases") or "").split(ALIAS_SEPARATOR) if a.strip()]
    source = (row.get("source") or "").strip() or None
    extra = {
        k: v for k, v in row.items() if k not in CSV_COLUMNS and k not in OPTIONAL_COLUMNS and v not in (None, "")
    }
    return ObjectRecord.create(row.get("name"), aliases=aliases, source=source, extra=extra, **features)


def _cell(value: object) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value)


def write_catalog_csv(records: Iterable[ObjectRecord], path: str | Path | None = None) -> str:
    """Write records as canonical CSV (with ``aliases`` and ``source`` columns); returns the text."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow([*CSV_COLUMNS, *OPTIONAL_COLUMNS])
    for rec in records:
        writer.writerow(
            [normalize_name(rec.name)]
            + [_cell(getattr(rec, f)) for f in FEATURES]
            + [ALIAS_SEPARATOR.join(rec.aliases), rec.source or ""]
        )
    text = buf.getvalue()
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text
