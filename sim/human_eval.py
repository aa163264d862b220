"""How often the planner's first choice is the grasp people use, on ``sim/data/human_grasps.csv``.

Each row of that file is a household object (the seed catalog's features) with the grasp people most
commonly use to pick it up or hold it for use (``human_grasp_type``, a key of ``sim.grasps.GRASP_TYPES``,
and its ``human_family``) and, in ``source``, what that label rests on. The labels are ours, from the
grasp literature and observation, not a measured data set: see ``sim/PLANNER.md``, "Agreement with
people".

``python -m sim.human_eval`` prints the agreement (top-1 type, top-1 family, type within the top 3) and
the objects where the planner and people differ, then, clearly apart, the family agreement on the shared
real data (the Yale human grasping dataset, ``sim/human_families.py``; ``--part check`` by default, the
blind part only with ``--part blind``); ``--json`` prints one JSON object instead.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from kb.errors import InvalidFeature
from sim.grasps import GRASP_TYPES
from sim.planner import PLANNER_VERSION, plan_grasps

__all__ = ["HUMAN_GRASPS_CSV", "Agreement", "HumanGrasp", "ObjectResult", "evaluate", "read_human_grasps"]

HUMAN_GRASPS_CSV = Path(__file__).parent / "data" / "human_grasps.csv"
_FEATURE_COLUMNS = ("a_cm", "b_cm", "c_cm", "mass_g", "shape", "material", "rigidity", "fragility", "texture")


@dataclass(frozen=True)
class HumanGrasp:
    """One labelled object: its features and the grasp people use."""

    object: str
    features: dict
    grasp_type: str
    family: str
    source: str


@dataclass(frozen=True)
class ObjectResult:
    object: str
    human_type: str
    human_family: str
    planned_types: tuple[str, ...]
    planned_family: str

    @property
    def type_match(self) -> bool:
        return self.planned_types[0] == self.human_type

    @property
    def family_match(self) -> bool:
        return self.planned_family == self.human_family

    @property
    def top3_match(self) -> bool:
        return self.human_type in self.planned_types[:3]


@dataclass(frozen=True)
class Agreement:
    """Fractions of objects where the planner agrees with people."""

    n: int
    top1_type: float
    top1_family: float
    top3_type: float
    planner_version: str
    results: tuple[ObjectResult, ...]

    def summary(self) -> dict:
        return {k: v for k, v in asdict(self).items() if k != "results"}


def read_human_grasps(path: str | Path = HUMAN_GRASPS_CSV) -> list[HumanGrasp]:
    """The labelled objects of ``path``. Raises InvalidFeature naming the row for a bad label."""
    out: list[HumanGrasp] = []
    with open(path, newline="", encoding="utf-8") as fh:
        for line, row in enumerate(csv.DictReader(fh), start=2):
            gt, fam = row.get("human_grasp_type", ""), row.get("human_family", "")
            where = f"{path}:{line}"
            if gt not in GRASP_TYPES:
                raise InvalidFeature("human_grasp_type", gt, f"{where}: not a known grasp type")
            if GRASP_TYPES[gt] != fam:
                raise InvalidFeature("human_family", fam, f"{where}: {gt} is a {GRASP_TYPES[gt]} grasp")
            features = {k: (row.get(k) or None) for k in _FEATURE_COLUMNS}
            for k in ("a_cm", "b_cm", "c_cm", "mass_g"):
                if features[k] is not None:
                    try:
                        features[k] = float(features[k])
                    except ValueError:
                        raise InvalidFeature(k, features[k], f"{where}: not a number") from None
            out.append(HumanGrasp(row["object"], features, gt, fam, row.get("source", "")))
    return out


def evaluate(rows: Sequence[HumanGrasp] | None = None) -> Agreement:
    """Plan every labelled object and compare the planner's ranking with the people's grasp."""
    rows = read_human_grasps() if rows is None else rows
    results = []
    for r in rows:
        plans = plan_grasps({**r.features, "name": r.object})  # the name gives its kind (a pan: its handle)
        results.append(
            ObjectResult(
                r.object, r.grasp_type, r.family, tuple(p.grasp_type for p in plans), plans[0].family
            )
        )
    n = len(results)

    def frac(xs: list[bool]) -> float:
        return round(sum(xs) / n, 3) if n else 0.0

    return Agreement(
        n=n,
        top1_type=frac([x.type_match for x in results]),
        top1_family=frac([x.family_match for x in results]),
        top3_type=frac([x.top3_match for x in results]),
        planner_version=PLANNER_VERSION,
        results=tuple(results),
    )


def _real_data_lines(path: str, part: str) -> tuple[list[str], dict | None]:
    """The shared real data's lines (or a note that it is absent) and its JSON summary."""
    from sim.human_families import evaluate_families, read_yale_families

    if not Path(path).is_file():
        return [f"REAL DATA (Yale human grasping dataset): not found at {path}: skipped"], None
    result = evaluate_families(read_yale_families(path), part)
    lines = [
        f"REAL DATA (Yale human grasping dataset, {result.part} part, {result.n} objects): planner family "
        f"= people's majority {result.family_agreement:.1%} (always power {result.always_power:.1%}); "
        f"expected agreement (people's share of the planner's family) {result.expected_agreement:.1%} "
        f"(always power {result.expected_always_power:.1%})"
    ]
    if part != "check":  # the blind part's rows are never looked at (sim/PLANNER.md): its figures only
        return lines, result.summary()
    lines += [f"  {o:24s} people {m:13s} planner {f}" for o, m, f in result.misses]
    return lines, {**result.summary(), "misses": [list(x) for x in result.misses]}


def main(argv: Sequence[str] | None = None) -> int:
    from sim.human_families import YALE_DEV_CSV

    parser = argparse.ArgumentParser(prog="python -m sim.human_eval", description=__doc__.split("\n")[0])
    parser.add_argument(
        "--csv", default=str(HUMAN_GRASPS_CSV), help="labels written here (default: %(default)s)"
    )
    parser.add_argument(
        "--human-data", default=str(YALE_DEV_CSV), help="shared real data (default: %(default)s)"
    )
    parser.add_argument(
        "--part",
        choices=("check", "blind", "all"),
        default="check",
        help="part of the real data to score (blind: once, at the end of a change; sim/PLANNER.md)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    try:
        result = evaluate(read_human_grasps(args.csv))
        real_lines, real = _real_data_lines(args.human_data, args.part)
    except (OSError, InvalidFeature) as exc:
        print(f"Error: {exc}", file=sys.stderr)
        return 1
    if args.json:
        misses = [asdict(r) for r in result.results if not r.type_match]
        print(json.dumps({**result.summary(), "type_misses": misses, "real_data": real}))
        return 0
    print(
        f"LABELS WRITTEN HERE ({args.csv}): planner {result.planner_version}, {result.n} objects: "
        f"top-1 type {result.top1_type:.1%}, "
        f"top-1 family {result.top1_family:.1%}, type in top 3 {result.top3_type:.1%}"
    )
    for r in result.results:
        if not r.type_match:
            mark = "family ok" if r.family_match else "FAMILY"
            print(f"  {r.object:24s} people {r.human_type:26s} planner {r.planned_types[0]:26s} {mark}")
    print("\n".join(real_lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
