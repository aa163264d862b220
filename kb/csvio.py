"""The canonical catalog CSV: reading with per-cell reasons, and writing.

Header: ``name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity`` (this order when written;
any order when read). Blank cells mean unknown. Optional extra columns: ``aliases`` (separated by ``;``)
and ``source``; other extra columns are kept in ``ObjectRecord.extra``. Rows are numbered as a spreadsheet
shows them: the header is row 1, the first object row 2.

Refused, naming row, column and reason: a row with more or fewer cells than the header, a NUL byte in any
cell, a name spanning lines or holding control characters (what an unbalanced quote produces), a name over
:data:`MAX_NAME_CHARS` characters, ``nan``/``inf`` or other non-numbers in a number cell, and every value
:mod:`kb.features` refuses. Refused as a whole file: an unbalanced quote running to the end, a cell over
:data:`MAX_CELL_CHARS` characters, a column named twice in the header, a missing column, a file that cannot
be read or is not UTF-8.

Spreadsheet safety: a text cell that a spreadsheet would run as a formula (one starting with ``=``, ``+``,
``-``, ``@``, a tab or a carriage return) is written with a ``'`` in front (:func:`spreadsheet_cell`), and the
reader takes that ``'`` off again (:func:`read_spreadsheet_cell`), so export -> import gives back the exact
name. A plain number (``-5``, ``+1.5e3``) is left as it is: a spreadsheet reads it as a number, not a formula.
Every CSV this project writes (the catalog export here, the grasp report's ``results.csv``) escapes its cells
with :func:`spreadsheet_cell`.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from kb.errors import CatalogImportError, InvalidFeature
from kb.features import CSV_COLUMNS, FEATURES, MAX_NAME_CHARS, ObjectRecord, normalize_name
from kb.files import read_input_file

__all__ = [
    "CsvReadResult",
    "SkippedRow",
    "parse_catalog_csv",
    "read_catalog_csv",
    "read_spreadsheet_cell",
    "spreadsheet_cell",
    "write_catalog_csv",
]

ALIAS_SEPARATOR = ";"
OPTIONAL_COLUMNS = ("aliases", "source")
#: The longest cell read (the ``csv`` module's field limit); a longer one refuses the whole file.
MAX_CELL_CHARS = 131_072
#: The largest catalog CSV read (a million objects take about 150 MB).
MAX_CSV_BYTES = 1024 * 1024 * 1024
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
#: First characters that make a spreadsheet (Excel, LibreOffice, Google Sheets) read a cell as a formula.
FORMULA_STARTS = frozenset("=+-@\t\r")
#: What escapes a formula-like cell (the spreadsheets' own "this is text" mark).
TEXT_MARK = "'"
_PLAIN_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def _formula_like(text: str) -> bool:
    """Whether ``text`` needs the text mark: it starts like a formula (and is not a plain number), or it is
    itself marks in front of such a text (so that ``'=x`` written as ``''=x`` reads back as ``'=x``)."""
    stripped = text.lstrip(TEXT_MARK)
    if not stripped or stripped[0] not in FORMULA_STARTS:
        return False
    return stripped != text or _PLAIN_NUMBER.fullmatch(stripped) is None


def spreadsheet_cell(text: str) -> str:
    """``text`` as a CSV cell a spreadsheet cannot run as a formula: a ``'`` in front when it starts with
    ``=``, ``+``, ``-``, ``@``, tab or CR (plain numbers excepted). :func:`read_spreadsheet_cell` undoes
    it."""
    return TEXT_MARK + text if _formula_like(text) else text


def read_spreadsheet_cell(cell: str) -> str:
    """The text :func:`spreadsheet_cell` wrote as ``cell`` (any other cell is returned unchanged, so a
    hand-written ``'n sync`` keeps its quote)."""
    if cell.startswith(TEXT_MARK) and _formula_like(cell[1:]):
        return cell[1:]
    return cell


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
        text = read_input_file(path, MAX_CSV_BYTES).decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise CatalogImportError(str(path), [(0, "-", f"not UTF-8 text ({err.reason})")]) from None
    except FileNotFoundError:
        raise CatalogImportError(str(path), [(0, "-", "no such file")]) from None
    except IsADirectoryError:
        raise CatalogImportError(str(path), [(0, "-", "is a folder, not a CSV file")]) from None
    except OSError as err:
        raise CatalogImportError(str(path), [(0, "-", f"cannot read the file ({err.strerror or err})")]) from None
    return parse_catalog_csv(text, label=str(path), skip_invalid=skip_invalid)


def parse_catalog_csv(text: str, *, label: str = "<csv>", skip_invalid: bool = False) -> CsvReadResult:
    """Like :func:`read_catalog_csv` for CSV text already in memory (``label`` names it in errors).

    A broken file (an unbalanced quote, a cell over :data:`MAX_CELL_CHARS`, a duplicated header column) is
    refused as a whole, whatever ``skip_invalid`` says: nothing after the break can be trusted.
    """
    reader = csv.reader(io.StringIO(text), strict=True)
    rows = _records(reader, label)
    header = _header(next(rows, None), label)
    result = CsvReadResult()
    problems: list[SkippedRow] = []
    seen: dict[str, int] = {}
    for rownum, cells in rows:
        if all(not c.strip() for c in cells):
            continue  # blank line
        problem = _shape_problem(rownum, cells, header)
        if problem is not None:
            problems.append(problem)
            continue
        try:
            record = _row_to_record(dict(zip(header, cells, strict=True)))
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


def _records(reader, label: str):
    """(row number, cells) of each record; a malformed file raises :class:`CatalogImportError` naming the
    record where the ``csv`` module gave up (an unbalanced quote is found at the end of the file)."""
    rownum = 0
    while True:
        rownum += 1
        try:
            cells = next(reader)
        except StopIteration:
            return
        except csv.Error as err:
            reason = str(err)
            if "field larger than field limit" in reason:
                reason = f"a cell over {MAX_CELL_CHARS:,} characters"
            elif "unexpected end of data" in reason or "EOF" in reason:
                reason = "unbalanced quote: a quoted cell runs to the end of the file"
            raise CatalogImportError(label, [(rownum, "-", f"malformed CSV ({reason})")]) from None
        yield rownum, cells


def _header(first: tuple[int, list[str]] | None, label: str) -> list[str]:
    header = [h.strip() for h in (first[1] if first else [])]
    if not any(header):
        raise CatalogImportError(label, [(1, "-", "empty file: no header")])
    repeated = sorted({h for h in header if header.count(h) > 1})
    if repeated:
        raise CatalogImportError(label, [(1, h, "column appears more than once in the header") for h in repeated])
    missing = [c for c in CSV_COLUMNS if c not in header]
    if missing:
        raise CatalogImportError(label, [(1, c, "missing column in header") for c in missing])
    return header


def _shape_problem(rownum: int, cells: list[str], header: list[str]) -> SkippedRow | None:
    """Why a row cannot be read as an object at all (cell count, control characters, implausible name)."""
    if len(cells) != len(header):
        return SkippedRow(rownum, "-", f"{len(cells)} cells, header has {len(header)}")
    for column, cell in zip(header, cells, strict=True):
        if "\x00" in cell:
            return SkippedRow(rownum, column, "contains a NUL byte")
    name = cells[header.index("name")]
    if any(ch in name for ch in "\r\n") or _CONTROL.search(name):
        return SkippedRow(rownum, "name", "spans several lines or holds control characters (an unbalanced quote?)")
    if len(name.strip()) > MAX_NAME_CHARS:
        return SkippedRow(rownum, "name", f"implausible name: {len(name.strip()):,} characters (at most {MAX_NAME_CHARS})")
    return None


def _row_to_record(row: dict[str, str | None]) -> ObjectRecord:
    row = {k: read_spreadsheet_cell(v) if isinstance(v, str) else v for k, v in row.items()}
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
        cells = (
            [normalize_name(rec.name)]
            + [_cell(getattr(rec, f)) for f in FEATURES]
            + [ALIAS_SEPARATOR.join(rec.aliases), rec.source or ""]
        )
        writer.writerow([spreadsheet_cell(c) for c in cells])
    text = buf.getvalue()
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text
