#!/usr/bin/env python3
"""How far two labellings of the real-page corpus agree.

    python scripts/label_agreement.py [--first labels-a.jsonl labels-b.jsonl] [--second check-labels.jsonl]

Every page of the second labelling (by default ``tests/data/real_pages/check-labels.jsonl``, the second
labeller's sample) is compared with the same id in the first (by default ``labels-a.jsonl`` and
``labels-b.jsonl``). Per page:

* **dims agree** when both ``dims_cm`` are null, or both state the same number of extents and each extent
  (both sorted largest first) is within 2 % of the other's;
* **mass agrees** when both ``mass_g`` are null, or both are numbers within 2 % of each other.

"Within 2 %" is ``|a - b| <= 0.02 * max(|a|, |b|)``: symmetric, and exactly 2 % of the larger agrees.
The script prints both agreement rates and every disagreement with the two labels' values (and the
second label's ``resolution`` when it has one), and exits 0; a page of the second labelling that the first
lacks is counted as a disagreement on both.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
CORPUS_DIR = ROOT / "tests" / "data" / "real_pages"
FIRST = (CORPUS_DIR / "labels-a.jsonl", CORPUS_DIR / "labels-b.jsonl")
SECOND = CORPUS_DIR / "check-labels.jsonl"
TOLERANCE = 0.02


def within(a: float, b: float, tolerance: float = TOLERANCE) -> bool:
    """``a`` and ``b`` differ by at most ``tolerance`` of the larger magnitude (the bound included)."""
    return abs(a - b) <= tolerance * max(abs(a), abs(b))


def dims_agree(first: Sequence[float] | None, second: Sequence[float] | None) -> bool:
    if first is None or second is None:
        return first is None and second is None
    if len(first) != len(second):
        return False
    return all(within(a, b) for a, b in zip(sorted(first, reverse=True), sorted(second, reverse=True), strict=True))


def mass_agrees(first: float | None, second: float | None) -> bool:
    if first is None or second is None:
        return first is None and second is None
    return within(first, second)


@dataclass(frozen=True)
class PageComparison:
    """One page's two labels, side by side."""

    id: str
    first: dict[str, Any] | None
    second: dict[str, Any]

    @property
    def dims_agree(self) -> bool:
        return self.first is not None and dims_agree(self.first.get("dims_cm"), self.second.get("dims_cm"))

    @property
    def mass_agrees(self) -> bool:
        return self.first is not None and mass_agrees(self.first.get("mass_g"), self.second.get("mass_g"))


@dataclass(frozen=True)
class Agreement:
    pages: tuple[PageComparison, ...]

    @property
    def dims_agreeing(self) -> int:
        return sum(p.dims_agree for p in self.pages)

    @property
    def mass_agreeing(self) -> int:
        return sum(p.mass_agrees for p in self.pages)

    def disagreements(self) -> list[PageComparison]:
        return [p for p in self.pages if not (p.dims_agree and p.mass_agrees)]


def compare(first: Iterable[dict[str, Any]], second: Iterable[dict[str, Any]]) -> Agreement:
    """Each row of ``second`` against the row of ``first`` with its id (a later row of ``first`` with the
    same id replaces an earlier one, as ``scrapers.corpus.load_corpus`` does)."""
    by_id = {row["id"]: row for row in first}
    return Agreement(tuple(PageComparison(row["id"], by_id.get(row["id"]), row) for row in second))


def read_jsonl(paths: Iterable[Path]) -> list[dict[str, Any]]:
    rows = []
    for path in paths:
        for line in Path(path).read_text(encoding="utf-8").splitlines():
            if line.strip():
                rows.append(json.loads(line))
    return rows


def _rate(n: int, total: int) -> str:
    return f"{n}/{total} ({n / total:.2f})" if total else "0/0"


def report(agreement: Agreement) -> str:
    total = len(agreement.pages)
    lines = [f"pages compared: {total}",
             f"dims agree: {_rate(agreement.dims_agreeing, total)}",
             f"mass agrees: {_rate(agreement.mass_agreeing, total)}"]
    disagreements = agreement.disagreements()
    lines.append(f"disagreements: {len(disagreements)}")
    for page in disagreements:
        if page.first is None:
            lines.append(f"  {page.id}: not in the first labelling")
            continue
        if not page.dims_agree:
            lines.append(f"  {page.id} dims: first {page.first.get('dims_cm')} second {page.second.get('dims_cm')}")
        if not page.mass_agrees:
            lines.append(f"  {page.id} mass: first {page.first.get('mass_g')} second {page.second.get('mass_g')}")
        if page.second.get("resolution"):
            lines.append(f"    resolution: {page.second['resolution']}")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--first", type=Path, nargs="+", default=list(FIRST), help="the first labelling's files")
    parser.add_argument("--second", type=Path, default=SECOND, help="the second labelling's file")
    args = parser.parse_args(argv)
    print(report(compare(read_jsonl(args.first), read_jsonl([args.second]))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
