"""A grasp-family rule fitted on real people, cross-validated by object (issue 24, "People").

The planner's family comes from its hand-written rules (``sim/grasp_rules.py``). This module asks whether
a rule *fitted* on the shared half of the Yale human grasping dataset (``sim/human_families.py``) would
agree with people more often, measured honestly:

- **By object.** Each object is one sample (its label: the family most of its recorded grasps used); the
  folds hold out whole objects, never single grasps of an object that is also in the training set.
  The outer loop leaves one object out; an inner 5-fold split of the remaining objects picks the
  regularisation (nested cross-validation), so no choice is made on the object being scored.
- **With its uncertainty.** Every figure comes with its Wilson 95 % interval: with 126 objects an
  agreement of 0.64 is 0.55-0.72.
- **Against the planner on the same objects.** The planner's rules were written before (and checked on
  the *check* part of) these data; the paired counts say where the two differ.

The fitted rule is a multinomial logistic regression on the features the planner sees for any catalog
object (log extents and mass, squeezable, fragile, shape), so it could replace the planner's family if it
were better. ``python -m sim.human_fit`` prints the comparison; ``--min-grasps 5`` keeps only objects
whose majority rests on at least five recorded grasps (41 of the 126 rest on one).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

from sim.grasps import FAMILIES
from sim.human_families import YALE_DEV_CSV, YaleObject, planner_features, read_yale_families
from sim.planner import PLANNER_VERSION, plan_grasps

__all__ = ["FitComparison", "compare", "family_features", "nested_cv_predictions", "wilson_interval"]

_SHAPES = ("thin", "compact", "prism", "long", "radial")
#: Inverse regularisation strengths the inner folds choose from.
C_GRID = (0.03, 0.1, 0.3, 1.0, 3.0)
INNER_FOLDS = 5


def wilson_interval(hits: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """The Wilson score interval of a proportion ``hits / n`` (95 % for the default ``z``)."""
    if n <= 0:
        return (0.0, 1.0)
    if not 0 <= hits <= n:
        raise ValueError(f"hits must be within 0..{n}, not {hits}")
    p = hits / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    lo = 0.0 if hits == 0 else max(0.0, min(p, centre - half))  # exact at the edges (no rounding slip)
    hi = 1.0 if hits == n else min(1.0, max(p, centre + half))
    return (lo, hi)


def family_features(o: YaleObject) -> list[float]:
    """The fitted rule's inputs: what the planner knows of any catalog object (no name, no roundness)."""
    p = planner_features(o)
    logs = [math.log(max(float(p[k]), 0.05)) for k in ("a_cm", "b_cm", "c_cm", "mass_g")]
    flags = [float(o.rigidity == "squeezable"), float(o.rigidity == "fragile")]
    return logs + flags + [float(p["shape"] == s) for s in _SHAPES]


def _fit(x: np.ndarray, y: np.ndarray, c: float):
    from sklearn.linear_model import LogisticRegression

    if len(set(y.tolist())) == 1:  # one class only: predict it
        return _Constant(int(y[0]))
    return LogisticRegression(C=c, max_iter=5000).fit(x, y)


@dataclass(frozen=True)
class _Constant:
    label: int

    def predict(self, x: np.ndarray) -> np.ndarray:
        return np.full(len(x), self.label)


def _inner_choice(x: np.ndarray, y: np.ndarray, grid: Sequence[float]) -> float:
    """The ``C`` of ``grid`` with the most inner-fold hits (the smaller C on a tie: the simpler rule)."""
    folds = np.arange(len(y)) % INNER_FOLDS
    best_c, best_hits = grid[0], -1
    for c in sorted(grid):
        hits = 0
        for k in range(INNER_FOLDS):
            train, test = folds != k, folds == k
            if test.any() and train.any():
                hits += int((_fit(x[train], y[train], c).predict(x[test]) == y[test]).sum())
        if hits > best_hits:
            best_c, best_hits = c, hits
    return best_c


def nested_cv_predictions(
    x: np.ndarray, y: np.ndarray, grid: Sequence[float] = C_GRID
) -> tuple[np.ndarray, list[float]]:
    """Leave-one-object-out predictions, each from a rule that never saw that object (nor chose its C on it)."""
    n = len(y)
    predictions = np.empty(n, dtype=int)
    chosen: list[float] = []
    for i in range(n):
        keep = np.arange(n) != i
        c = _inner_choice(x[keep], y[keep], grid)
        chosen.append(c)
        predictions[i] = int(_fit(x[keep], y[keep], c).predict(x[i : i + 1])[0])
    return predictions, chosen


@dataclass(frozen=True)
class FitComparison:
    """The fitted rule (nested CV by object) and the planner's rule on the same objects."""

    n: int
    min_grasps: int
    fitted_hits: int
    fitted_agreement: float
    fitted_ci95: tuple[float, float]
    planner_hits: int
    planner_agreement: float
    planner_ci95: tuple[float, float]
    only_fitted: int  # objects the fitted rule gets right and the planner wrong
    only_planner: int
    always_power: float
    chosen_c: dict[str, int]  # how often each C was chosen by the inner folds
    planner_version: str

    def summary(self) -> dict:
        return asdict(self)


def compare(objects: Sequence[YaleObject], min_grasps: int = 1) -> FitComparison:
    """Score the fitted family rule (nested CV by object) and the planner on ``objects``."""
    chosen_objects = [o for o in objects if o.n_grasps >= min_grasps]
    n = len(chosen_objects)
    if n < 2 * INNER_FOLDS:
        raise ValueError(f"need at least {2 * INNER_FOLDS} objects with {min_grasps}+ grasps, have {n}")
    x = np.array([family_features(o) for o in chosen_objects])
    y = np.array([FAMILIES.index(o.majority) for o in chosen_objects])
    fitted, cs = nested_cv_predictions(x, y)
    planned = np.array(
        [FAMILIES.index(plan_grasps(planner_features(o), top=1)[0].family) for o in chosen_objects]
    )
    fit_ok, plan_ok = fitted == y, planned == y
    fh, ph = int(fit_ok.sum()), int(plan_ok.sum())
    return FitComparison(
        n=n,
        min_grasps=min_grasps,
        fitted_hits=fh,
        fitted_agreement=round(fh / n, 3),
        fitted_ci95=tuple(round(v, 3) for v in wilson_interval(fh, n)),
        planner_hits=ph,
        planner_agreement=round(ph / n, 3),
        planner_ci95=tuple(round(v, 3) for v in wilson_interval(ph, n)),
        only_fitted=int((fit_ok & ~plan_ok).sum()),
        only_planner=int((plan_ok & ~fit_ok).sum()),
        always_power=round(float((y == FAMILIES.index("power")).mean()), 3),
        chosen_c={str(c): cs.count(c) for c in sorted(set(cs))},
        planner_version=PLANNER_VERSION,
    )


def describe(result: FitComparison) -> str:
    """One line per rule, as ``python -m sim.human_fit`` prints it."""
    head = f"REAL DATA (Yale shared half, {result.n} objects with >= {result.min_grasps} recorded grasps)"
    lo, hi = result.fitted_ci95
    plo, phi = result.planner_ci95
    return "\n".join(
        [
            head,
            f"  fitted family rule, nested leave-one-object-out: {result.fitted_agreement:.1%} "
            f"({result.fitted_hits}/{result.n}, 95 % CI {lo:.1%}-{hi:.1%})",
            f"  planner's rules (version {result.planner_version}):             {result.planner_agreement:.1%} "
            f"({result.planner_hits}/{result.n}, 95 % CI {plo:.1%}-{phi:.1%})",
            f"  only the fitted rule right: {result.only_fitted}; only the planner right: "
            f"{result.only_planner}; always power: {result.always_power:.1%}",
        ]
    )


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m sim.human_fit", description=__doc__.split("\n")[0])
    parser.add_argument("--human-data", default=str(YALE_DEV_CSV), help="shared real data (default: %(default)s)")
    parser.add_argument("--min-grasps", type=int, default=1, help="keep objects with this many grasps or more")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    try:
        result = compare(read_yale_families(args.human_data), args.min_grasps)
    except (OSError, ValueError) as exc:
        print(f"Error: {exc}", file=sys.stderr)
        return 1
    print(json.dumps(result.summary()) if args.json else describe(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
