"""What a catalog folder holds beside its ``catalog.csv``, for catalogs imported from published data sets.

* ``ids.csv`` (``id,name``): the data set's own object ids ("003_cracker_box") and the catalog names they
  were imported as, so that description sets written against the data set can label objects by id
  (:func:`read_ids`; ``recall.evaluation`` maps such labels to names).
* ``floors.csv`` (``feature,at_least``): a data set that records values in bins whose top bin is open
  ("15 cm or more") stores the bin's value, and declares it here: a catalog value at or above the floor
  is a lower bound (:func:`read_floors`). The recall's closeness and the 4x disagreement rule then count
  only a stated value *below* it as a difference (``recall.metrics.relative_errors``); the ranking reads
  a stated value above the floor as the floor (``FeatureQuery.within_floors``: "7 kg" against a top bin
  "1000 g or more"), so that the top bin is not ranked below an object whose value is unknown.

* ``bins.csv`` (``feature,below,above``): a data set that records classes, not measurements (the Yale
  grasping data's size and mass classes), declares what a stored value x stands for: the class
  [x / below, x * above], each factor at least 1; ``above`` may be ``inf``, a lower bound (a data set
  that records the size of the part grasped, not of the whole object: the whole is at least as large).
  The closeness and the 4x rule then count only the distance outside the class (:func:`read_bins`); the
  ranking ranks by the stated interval widened to the classes (``FeatureQuery.within_classes``).

The files are optional; a folder without them has no ids, no floors and no bins. Malformed files are refused with
the file, row and reason (:class:`kb.errors.RecallError`).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from kb.errors import RecallError
from kb.features import NUMERIC_FEATURES, normalize_name

__all__ = ["read_bins", "read_floors", "read_ids"]


def _rows(path: Path, columns: tuple[str, str]) -> list[tuple[int, str, str]]:
    try:
        with path.open(encoding="utf-8-sig", newline="") as fh:
            reader = csv.DictReader(fh)
            header = [h.strip().lower() for h in reader.fieldnames or []]
            if not set(columns) <= set(header):
                raise RecallError(
                    f"{path}: needs the columns {','.join(columns)} (has {','.join(header) or 'none'})"
                )
            reader.fieldnames = header
            return [
                (n, (r[columns[0]] or "").strip(), (r[columns[1]] or "").strip())
                for n, r in enumerate(reader, 2)
            ]
    except (UnicodeDecodeError, csv.Error) as err:
        raise RecallError(f"{path}: not a UTF-8 CSV file ({err})") from None


def read_ids(catalog_csv: str | Path) -> dict[str, str]:
    """id -> catalog name from ``ids.csv`` beside ``catalog_csv`` ({} when there is none). An id given
    twice, or an empty cell, is refused."""
    path = Path(catalog_csv).with_name("ids.csv")
    if not path.is_file():
        return {}
    out: dict[str, str] = {}
    for row, ident, name in _rows(path, ("id", "name")):
        if not ident or not name:
            raise RecallError(f"{path} row {row}: an id and a name are both needed")
        if ident in out:
            raise RecallError(f"{path} row {row}: id {ident!r} is given twice")
        out[ident] = normalize_name(name)
    return out


def read_floors(catalog_csv: str | Path) -> dict[str, float]:
    """feature -> floor from ``floors.csv`` beside ``catalog_csv`` ({} when there is none). Only the
    numeric features (sizes and mass) can have a floor, each once, with a positive number."""
    path = Path(catalog_csv).with_name("floors.csv")
    if not path.is_file():
        return {}
    out: dict[str, float] = {}
    for row, feature, value in _rows(path, ("feature", "at_least")):
        if feature not in NUMERIC_FEATURES:
            raise RecallError(
                f"{path} row {row}: {feature!r} is no numeric feature ({', '.join(NUMERIC_FEATURES)})"
            )
        try:
            floor = float(value)
        except ValueError:
            raise RecallError(f"{path} row {row}: at_least {value!r} is not a number") from None
        if not floor > 0 or feature in out:
            raise RecallError(f"{path} row {row}: {feature} needs one positive floor, not {value!r}")
        out[feature] = floor
    return out


def read_bins(catalog_csv: str | Path) -> dict[str, tuple[float, float]]:
    """feature -> (below, above) from ``bins.csv`` beside ``catalog_csv`` ({} when there is none): a stored
    value x stands for [x / below, x * above]. Only numeric features, each once, with factors of at least 1
    (``above`` may be ``inf``)."""
    path = Path(catalog_csv).with_name("bins.csv")
    if not path.is_file():
        return {}
    out: dict[str, tuple[float, float]] = {}
    rows = _rows(path, ("feature", "below"))
    above = {n: a for n, _, a in _rows(path, ("feature", "above"))}
    for row, feature, below in rows:
        if feature not in NUMERIC_FEATURES:
            raise RecallError(
                f"{path} row {row}: {feature!r} is no numeric feature ({', '.join(NUMERIC_FEATURES)})"
            )
        try:
            factors = (float(below), float(above[row]))
        except ValueError:
            raise RecallError(
                f"{path} row {row}: below {below!r} and above {above[row]!r} must be numbers"
            ) from None
        if feature in out or not all(f >= 1.0 for f in factors) or math.isinf(factors[0]):
            raise RecallError(
                f"{path} row {row}: {feature} needs one class, factors of at least 1 (below finite), "
                f"not {below!r}, {above[row]!r}"
            )
        out[feature] = factors
    return out
