"""Scoring the description parser against known objects, the way the paper's Fig. 4 does.

* ``r2_dims``: coefficient of determination (1 - SS_res / SS_tot) of parsed vs true dimensions, over
  every (description, a/b/c) pair where the parser stated that dimension ("matched a/b/c": parsed a is
  compared with true a, and so on).
* ``r2_mass``: the same for mass.
* ``category_accuracy``: for each categorical feature, the share of correct values among the
  descriptions where the parser stated it; ``category_coverage`` the share of descriptions where it
  stated one; ``confusion`` counts true -> parsed (``"-"`` when not stated).

:func:`score_parses` is what ``objrecall evaluate`` calls; ``python -m recall.parse_eval`` scores the
development set (``recall/data/dev_descriptions.csv`` against ``kb/data/seed_catalog.csv``).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from kb.features import CATEGORICAL_FEATURES, DIMENSIONS, ObjectRecord, normalize_name
from recall.parser import ParsedDescription

__all__ = ["ParseScores", "load_labeled", "r2_score", "score_parses", "DEV_SET", "SEED_CATALOG"]

_ROOT = Path(__file__).resolve().parent.parent
DEV_SET = Path(__file__).resolve().parent / "data" / "dev_descriptions.csv"
SEED_CATALOG = _ROOT / "kb" / "data" / "seed_catalog.csv"


def r2_score(true: Sequence[float], pred: Sequence[float]) -> float | None:
    """1 - SS_res / SS_tot; None with fewer than two pairs or no spread in ``true``."""
    if len(true) != len(pred):
        raise ValueError("true and pred differ in length")
    if len(true) < 2:
        return None
    mean = sum(true) / len(true)
    ss_tot = sum((t - mean) ** 2 for t in true)
    if ss_tot == 0:
        return None
    ss_res = sum((t - p) ** 2 for t, p in zip(true, pred, strict=True))
    return 1.0 - ss_res / ss_tot


@dataclass
class ParseScores:
    n: int
    r2_dims: float | None
    r2_mass: float | None
    n_dims: int  # dimension pairs scored
    n_mass: int
    coverage: dict[str, float]  # share of descriptions (with a known truth) stating each numeric feature
    category_accuracy: dict[str, float | None]
    category_coverage: dict[str, float]
    confusion: dict[str, dict[str, dict[str, int]]] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def score_parses(pairs: Iterable[tuple[ParsedDescription, ObjectRecord]]) -> ParseScores:
    """Score parses against the true objects (see the module docstring)."""
    pairs = list(pairs)
    dim_true: list[float] = []
    dim_pred: list[float] = []
    mass_true: list[float] = []
    mass_pred: list[float] = []
    stated: dict[str, int] = {f: 0 for f in (*DIMENSIONS, "mass_g")}
    known: dict[str, int] = {f: 0 for f in (*DIMENSIONS, "mass_g")}
    correct = {f: 0 for f in CATEGORICAL_FEATURES}
    cat_stated = {f: 0 for f in CATEGORICAL_FEATURES}
    cat_known = {f: 0 for f in CATEGORICAL_FEATURES}
    confusion: dict[str, dict[str, dict[str, int]]] = {f: {} for f in CATEGORICAL_FEATURES}
    for parsed, record in pairs:
        values = parsed.values()
        for feat in (*DIMENSIONS, "mass_g"):
            truth = getattr(record, feat)
            if truth is None:
                continue
            known[feat] += 1
            if feat in values:
                stated[feat] += 1
                if feat == "mass_g":
                    mass_true.append(float(truth))
                    mass_pred.append(float(values[feat]))
                else:
                    dim_true.append(float(truth))
                    dim_pred.append(float(values[feat]))
        for feat in CATEGORICAL_FEATURES:
            truth = getattr(record, feat)
            if truth is None:
                continue
            cat_known[feat] += 1
            got = values.get(feat)
            row = confusion[feat].setdefault(str(truth), {})
            row[str(got) if got is not None else "-"] = row.get(str(got) if got is not None else "-", 0) + 1
            if got is not None:
                cat_stated[feat] += 1
                correct[feat] += int(got == truth)
    return ParseScores(
        n=len(pairs),
        r2_dims=r2_score(dim_true, dim_pred),
        r2_mass=r2_score(mass_true, mass_pred),
        n_dims=len(dim_true),
        n_mass=len(mass_true),
        coverage={f: (stated[f] / known[f] if known[f] else 0.0) for f in stated},
        category_accuracy={f: (correct[f] / cat_stated[f] if cat_stated[f] else None) for f in correct},
        category_coverage={f: (cat_stated[f] / cat_known[f] if cat_known[f] else 0.0) for f in correct},
        confusion=confusion,
    )


def load_labeled(
    descriptions: Path | str = DEV_SET, catalog: Path | str = SEED_CATALOG
) -> list[tuple[str, ObjectRecord]]:
    """(description, true object) pairs: ``descriptions`` has columns ``object,description``; the object
    is looked up by name or alias in the canonical catalog CSV. Unknown objects raise KeyError."""
    from kb.csvio import read_catalog_csv

    records = read_catalog_csv(catalog).records
    by_name: dict[str, ObjectRecord] = {}
    for rec in records:
        by_name[rec.name] = rec
        for alias in rec.aliases:
            by_name.setdefault(alias, rec)
    out: list[tuple[str, ObjectRecord]] = []
    with open(descriptions, newline="", encoding="utf-8-sig") as fh:
        for row in csv.DictReader(fh):
            name = normalize_name(row.get("object") or "")
            if name not in by_name:
                raise KeyError(f"{descriptions}: object {name!r} is not in {catalog}")
            out.append(((row.get("description") or ""), by_name[name]))
    return out


def _residuals(items: list[tuple[str, ObjectRecord, ParsedDescription]]) -> list[tuple[float, str, str]]:
    """Worst relative errors (for finding parser rules that fail)."""
    worst: list[tuple[float, str, str]] = []
    for text, rec, parsed in items:
        values = parsed.values()
        for feat in (*DIMENSIONS, "mass_g"):
            truth = getattr(rec, feat)
            if truth is None or feat not in values:
                continue
            got = float(values[feat])
            err = abs(math.log(max(got, 1e-6) / truth))
            worst.append((err, f"{rec.name}: {feat} true {truth:g} parsed {got:g}", text))
    return sorted(worst, reverse=True)


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m recall.parse_eval", description=__doc__.split("\n\n")[0])
    ap.add_argument("--descriptions", default=str(DEV_SET), help="CSV with object,description columns")
    ap.add_argument("--catalog", default=str(SEED_CATALOG), help="canonical catalog CSV (the truth)")
    ap.add_argument("--json", action="store_true", help="print the scores as one JSON object")
    ap.add_argument("--worst", type=int, default=0, help="also list the N worst numeric parses")
    ap.add_argument("--missing", action="store_true", help="list descriptions with no dimension or mass")
    args = ap.parse_args(argv)
    from recall.parser import parse

    labeled = load_labeled(args.descriptions, args.catalog)
    items = [(text, rec, parse(text)) for text, rec in labeled]
    scores = score_parses([(p, rec) for _t, rec, p in items])
    if args.json:
        json.dump(scores.to_dict(), sys.stdout)
        sys.stdout.write("\n")
        return 0
    print(f"descriptions: {scores.n}")
    print(f"dimensions R2: {_fmt(scores.r2_dims)} over {scores.n_dims} matched a/b/c values")
    print(f"mass R2:       {_fmt(scores.r2_mass)} over {scores.n_mass} values")
    print("coverage:      " + ", ".join(f"{k} {v:.0%}" for k, v in scores.coverage.items()))
    for feat in CATEGORICAL_FEATURES:
        acc = scores.category_accuracy[feat]
        print(f"{feat:10s} accuracy {_fmt(acc)}  stated in {scores.category_coverage[feat]:.0%}")
    for err, what, text in _residuals(items)[: args.worst]:
        print(f"  {err:.2f}  {what}\n        {text}")
    if args.missing:
        for text, rec, parsed in items:
            if not any(f in parsed.features for f in (*DIMENSIONS, "mass_g")):
                print(f"  none: {rec.name}: {text}")
    return 0


def _fmt(value: float | None) -> str:
    return "-" if value is None else f"{value:.3f}"


if __name__ == "__main__":
    raise SystemExit(main())
