"""A grasp family by the object's kind, scored against real people (issue 24, task 2): a negative result.

The Yale misses (sim/PLANNER.md) are objects whose grasp follows the part held or the task, which sizes
and masses do not carry. ``sim/data/grasp_kinds.csv`` names, for 81 English head nouns in seven kinds
(force tools with a handle, cords and hoses, containers held by their body, writing tools, lids and knobs,
small parts, keys and cards), the grasp people use them in. It was written from general knowledge and the
grasp literature and committed (58361f5) **before** it was scored. :func:`score_kind_rule` answers the
table's family for an object whose head noun it names (the noun before "of", else the longest phrase of
the table ending the name: "power cord" -> cord) and the planner's first choice otherwise, beside the
planner alone. On the check part (real data) it did worse than the planner, so the planner does not use it
(sim/PLANNER.md, "A family by the object's kind").

``python -m sim.human_kinds`` prints the check part; the blind part was not scored (the rule did not help).
"""

from __future__ import annotations

import argparse
import csv
import functools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from kb.errors import InvalidFeature
from kb.kinds import words_of
from sim.grasps import GRASP_TYPES
from sim.human_families import YaleObject, is_blind, planner_features
from sim.planner import plan_grasps

__all__ = ["GRASP_KINDS_CSV", "KindScore", "KindRow", "grasp_kinds", "head_noun", "score_kind_rule"]

GRASP_KINDS_CSV = Path(__file__).parent / "data" / "grasp_kinds.csv"


@dataclass(frozen=True)
class KindRow:
    noun: str
    kind: str
    grasp_type: str
    basis: str

    @property
    def family(self) -> str:
        return GRASP_TYPES[self.grasp_type]


@functools.cache
def grasp_kinds(path: Path = GRASP_KINDS_CSV) -> dict[str, KindRow]:
    """The table, keyed by noun. Raises InvalidFeature naming the row for an unknown grasp type or a
    repeated noun."""
    out: dict[str, KindRow] = {}
    with open(path, newline="", encoding="utf-8") as fh:
        for line, row in enumerate(csv.DictReader(fh), start=2):
            r = KindRow(row["noun"].strip().lower(), row["kind"], row["grasp_type"], row.get("basis", ""))
            if r.grasp_type not in GRASP_TYPES:
                raise InvalidFeature("grasp_type", r.grasp_type, f"{path}:{line}: not a known grasp type")
            if r.noun in out:
                raise InvalidFeature("noun", r.noun, f"{path}:{line}: listed twice")
            out[r.noun] = r
    return out


def head_noun(name: str, table: dict[str, KindRow] | None = None) -> KindRow | None:
    """The table row of ``name``'s head noun: the longest table phrase ending at the word before "of"
    (or the last word), words singular (kb.kinds.words_of); None when the table has none."""
    table = grasp_kinds() if table is None else table
    words = words_of(name)
    end = words.index("of", 1) if "of" in words[1:] else len(words)
    for n in range(end, 0, -1):
        row = table.get(" ".join(words[end - n : end]))
        if row is not None:
            return row
    return None


@dataclass(frozen=True)
class KindScore:
    """Agreement with the people's majority family: the planner alone, and with the kind table's family
    wherever it names the head noun; ``by_kind``: kind -> (objects, planner right, kind rule right)."""

    part: str
    n: int
    planner_hits: int
    kind_hits: int
    by_kind: dict[str, tuple[int, int, int]]


def score_kind_rule(objects: Iterable[YaleObject], part: str = "check") -> KindScore:
    """Score the kind rule on ``part`` (check, blind or all) of ``objects``."""
    if part not in ("check", "blind", "all"):
        raise ValueError(f"part must be check, blind or all, not {part!r}")
    chosen = [o for o in objects if part == "all" or is_blind(o.object) == (part == "blind")]
    planner = kind = 0
    by_kind: dict[str, tuple[int, int, int]] = {}
    for o in chosen:
        own = plan_grasps(planner_features(o), top=1)[0].family
        row = head_noun(o.object)
        answer = row.family if row else own
        planner += own == o.majority
        kind += answer == o.majority
        if row:
            n, p, k = by_kind.get(row.kind, (0, 0, 0))
            by_kind[row.kind] = (n + 1, p + (own == o.majority), k + (answer == o.majority))
    return KindScore(part, len(chosen), planner, kind, by_kind)


def main(argv: Sequence[str] | None = None) -> int:
    from sim.human_families import YALE_DEV_CSV, read_yale_families

    parser = argparse.ArgumentParser(prog="python -m sim.human_kinds", description=__doc__.split("\n")[0])
    parser.add_argument("--human-data", default=str(YALE_DEV_CSV))
    args = parser.parse_args(argv)
    if not Path(args.human_data).is_file():
        print(f"REAL DATA (Yale human grasping dataset): not found at {args.human_data}: skipped")
        return 0
    s = score_kind_rule(read_yale_families(args.human_data), "check")
    print(
        f"REAL DATA (Yale, check part, {s.n} objects): planner {s.planner_hits}/{s.n} ({s.planner_hits / s.n:.1%}); "
        f"with the kind table's family where it names the head noun {s.kind_hits}/{s.n} ({s.kind_hits / s.n:.1%})"
    )
    for kind, (n, p, k) in sorted(s.by_kind.items()):
        print(f"  {kind:30s} {n:3d} objects: planner right {p}, kind rule right {k}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
