"""A grasp-family rule fitted on real people, cross-validated by object (issue 24, "People").

The planner's family comes from its hand-written rules (``sim/grasp_rules.py``). This module asks whether
a rule *fitted* on the shared half of the Yale human grasping dataset (``sim/human_families.py``) would
agree with people more often, measured honestly:

- **By object.** Each object is one sample (its label: the ``majority`` column, the family most of its
  recorded grasps used); the folds hold out whole objects, never single grasps of an object that is also
  in the training set. The outer loop leaves one object out.
- **Every choice inside the inner loop.** The model family, its hyper-parameters, the feature set, class
  weights and whether to train on the shares of an object's grasps are all one *candidate* of
  :data:`CANDIDATES`; for each held-out object, a repeated 5-fold split of the *other* objects picks the
  candidate with the most inner hits (:func:`inner_choice`), which is then fitted on those objects and
  scores the held-out one. The candidate list was written before any outer result was seen; the
  figure is that of the whole procedure, selection included.
- **The models** (:mod:`sim.family_models`): the candidates below, fitted by :func:`fit_candidate`.
- **With its uncertainty.** Every figure comes with its Wilson 95 % interval and a confusion table
  (people's majority by predicted family).
- **Against the planner on the same objects.** The planner's rules were written before (and checked on
  the *check* part of) these data; the paired counts say where the two differ.

The candidates (all on what the planner knows of any catalog object: extents, mass, shape, rigidity and
fragility, never a name or the roundness code):

- feature sets ``planner`` (log a, b, c, mass; squeezable, fragile; one flag per shape) and ``ratios``
  (those, plus log b/a, log c/a, log volume, log density);
- multinomial logistic regression on standardised features, ``C`` in (0.03, 0.1, 0.3, 1, 3), with or
  without balanced class weights, trained on the majority or on the shares (``soft``);
- a decision tree of depth 2, 3 or 4 with at least 3, 6 or 10 objects a leaf, with or without balanced
  weights;
- k nearest neighbours on standardised features, k in (5, 9, 15, 25), uniform or distance weighted.

``python -m sim.human_fit`` prints the comparison (it takes a few minutes); ``--min-grasps 5`` keeps only
objects whose majority rests on at least five recorded grasps (41 of the 126 rest on one).
:func:`fit_family_rule` runs the same selection on every object given and returns the fitted rule, which
answers for a planner feature dict (``FamilyRule.family``).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass

import numpy as np

from sim.family_models import (
    CANDIDATES,
    FEATURE_SETS,
    Candidate,
    family_features,
    feature_vector,
    fit_candidate,
    training_rows,
)
from sim.grasps import FAMILIES
from sim.human_families import YALE_DEV_CSV, YaleObject, planner_features, read_yale_families
from sim.planner import PLANNER_VERSION, plan_grasps

__all__ = [
    "CANDIDATES",
    "Candidate",
    "FamilyRule",
    "FitComparison",
    "compare",
    "confusion",
    "family_features",
    "feature_vector",
    "fit_family_rule",
    "inner_choice",
    "nested_cv_predictions",
    "training_rows",
    "wilson_interval",
]

INNER_FOLDS = 5
#: Repeats of the inner 5-fold split (each a different seeded shuffle of the remaining objects).
INNER_REPEATS = 2
#: Seed of the inner shuffles: the same for every outer fold, so a run is reproducible.
INNER_SEED = 0


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


def _inner_folds(n: int, repeats: int = INNER_REPEATS, seed: int = INNER_SEED) -> list[np.ndarray]:
    """``repeats`` fold assignments of ``n`` objects into INNER_FOLDS, each from a seeded shuffle."""
    rng = np.random.default_rng(seed)
    return [rng.permutation(np.arange(n) % INNER_FOLDS) for _ in range(repeats)]


def inner_choice(
    xs: Mapping[str, np.ndarray],
    y: np.ndarray,
    shares: np.ndarray | None,
    candidates: Sequence[Candidate] = CANDIDATES,
    repeats: int = INNER_REPEATS,
) -> Candidate:
    """The candidate with the most hits over the repeated inner folds of these objects only (the
    earlier of ``candidates``, the simpler, on a tie). ``xs`` maps a feature set to its rows."""
    folds = _inner_folds(len(y), repeats)
    best, best_hits = candidates[0], -1
    for cand in candidates:
        x = xs[cand.features]
        hits = 0
        for assignment in folds:
            for k in range(INNER_FOLDS):
                train, test = assignment != k, assignment == k
                if test.any() and train.any():
                    s = None if shares is None else shares[train]
                    hits += int((fit_candidate(cand, x[train], y[train], s).predict(x[test]) == y[test]).sum())
        if hits > best_hits:
            best, best_hits = cand, hits
    return best


def nested_cv_predictions(
    xs: Mapping[str, np.ndarray] | np.ndarray,
    y: np.ndarray,
    shares: np.ndarray | None = None,
    candidates: Sequence[Candidate] = CANDIDATES,
    repeats: int = INNER_REPEATS,
) -> tuple[np.ndarray, list[Candidate]]:
    """Leave-one-object-out predictions, each from a rule that never saw that object: neither its fit
    nor its choice of candidate. A bare array ``xs`` serves every feature set."""
    if isinstance(xs, np.ndarray):
        xs = {fs: xs for fs in FEATURE_SETS}
    n = len(y)
    predictions = np.empty(n, dtype=int)
    chosen: list[Candidate] = []
    for i in range(n):
        keep = np.arange(n) != i
        train_x = {fs: x[keep] for fs, x in xs.items()}
        train_s = None if shares is None else shares[keep]
        cand = inner_choice(train_x, y[keep], train_s, candidates, repeats)
        chosen.append(cand)
        model = fit_candidate(cand, train_x[cand.features], y[keep], train_s)
        predictions[i] = int(model.predict(xs[cand.features][i : i + 1])[0])
    return predictions, chosen


def confusion(y: np.ndarray, predicted: np.ndarray) -> dict[str, dict[str, int]]:
    """``{people's majority: {predicted family: objects}}`` over FAMILIES."""
    return {
        FAMILIES[t]: {FAMILIES[p]: int(((y == t) & (predicted == p)).sum()) for p in range(len(FAMILIES))}
        for t in range(len(FAMILIES))
    }


def _arrays(objects: Sequence[YaleObject]) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray]:
    xs = {fs: np.array([family_features(o, fs) for o in objects]) for fs in FEATURE_SETS}
    y = np.array([FAMILIES.index(o.majority) for o in objects])
    shares = np.array([[o.shares[f] for f in FAMILIES] for o in objects])
    return xs, y, shares


@dataclass
class FamilyRule:
    """A fitted family rule: the candidate the inner folds chose on all the objects, fitted on them."""

    candidate: Candidate
    model: object

    def family(self, features: Mapping) -> str:
        """The family for a planner feature dict (``feature_vector``'s keys)."""
        x = np.array([feature_vector(features, self.candidate.features)])
        return FAMILIES[int(self.model.predict(x)[0])]


def fit_family_rule(
    objects: Sequence[YaleObject], candidates: Sequence[Candidate] = CANDIDATES
) -> FamilyRule:
    """The inner selection run on every object of ``objects``, and its choice fitted on them all."""
    xs, y, shares = _arrays(objects)
    cand = inner_choice(xs, y, shares, candidates)
    return FamilyRule(cand, fit_candidate(cand, xs[cand.features], y, shares))


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
    chosen: dict[str, int]  # how often each candidate was chosen by the inner folds (by label)
    fitted_confusion: dict[str, dict[str, int]]
    planner_confusion: dict[str, dict[str, int]]
    n_candidates: int
    planner_version: str

    def summary(self) -> dict:
        return asdict(self)


def compare(
    objects: Sequence[YaleObject],
    min_grasps: int = 1,
    candidates: Sequence[Candidate] = CANDIDATES,
    repeats: int = INNER_REPEATS,
) -> FitComparison:
    """Score the fitted family rule (nested CV by object) and the planner on ``objects``."""
    chosen_objects = [o for o in objects if o.n_grasps >= min_grasps]
    n = len(chosen_objects)
    if n < 2 * INNER_FOLDS:
        raise ValueError(f"need at least {2 * INNER_FOLDS} objects with {min_grasps}+ grasps, have {n}")
    xs, y, shares = _arrays(chosen_objects)
    fitted, picks = nested_cv_predictions(xs, y, shares, candidates, repeats)
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
        chosen=dict(Counter(c.label for c in picks).most_common()),
        fitted_confusion=confusion(y, fitted),
        planner_confusion=confusion(y, planned),
        n_candidates=len(candidates),
        planner_version=PLANNER_VERSION,
    )


def _confusion_lines(title: str, table: Mapping[str, Mapping[str, int]]) -> list[str]:
    head = f"  {title:34s}" + "".join(f"{f:>14s}" for f in FAMILIES) + "    recall"
    lines = [head]
    for truth, row in table.items():
        total = sum(row.values())
        recall = f"{row[truth] / total:.1%}" if total else "-"
        lines.append(f"  {'people ' + truth:34s}" + "".join(f"{row[f]:>14d}" for f in FAMILIES) + f"{recall:>10s}")
    return lines


def describe(result: FitComparison) -> str:
    """The comparison as ``python -m sim.human_fit`` prints it."""
    head = f"REAL DATA (Yale shared half, {result.n} objects with >= {result.min_grasps} recorded grasps)"
    lo, hi = result.fitted_ci95
    plo, phi = result.planner_ci95
    lines = [
        head,
        f"  fitted family rule, nested leave-one-object-out ({result.n_candidates} candidates chosen by the "
        f"inner folds): {result.fitted_agreement:.1%} ({result.fitted_hits}/{result.n}, 95 % CI {lo:.1%}-{hi:.1%})",
        f"  planner's rules (version {result.planner_version}): {result.planner_agreement:.1%} "
        f"({result.planner_hits}/{result.n}, 95 % CI {plo:.1%}-{phi:.1%})",
        f"  only the fitted rule right: {result.only_fitted}; only the planner right: "
        f"{result.only_planner}; always power: {result.always_power:.1%}",
        *_confusion_lines("fitted rule predicts ->", result.fitted_confusion),
        *_confusion_lines("planner predicts ->", result.planner_confusion),
        "  chosen by the inner folds (outer folds):",
        *(f"    {count:4d}  {label}" for label, count in result.chosen.items()),
    ]
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m sim.human_fit", description=__doc__.split("\n")[0])
    parser.add_argument("--human-data", default=str(YALE_DEV_CSV), help="shared real data (default: %(default)s)")
    parser.add_argument("--min-grasps", type=int, default=1, help="keep objects with this many grasps or more")
    parser.add_argument(
        "--model",
        choices=("all", "logistic", "tree", "knn"),
        default="all",
        help="offer the inner folds only this model family's candidates (default: all)",
    )
    parser.add_argument(
        "--inner-repeats", type=int, default=INNER_REPEATS, help="repeats of the inner 5-fold split"
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    candidates = [c for c in CANDIDATES if args.model in ("all", c.model)]
    try:
        result = compare(
            read_yale_families(args.human_data), args.min_grasps, candidates, max(1, args.inner_repeats)
        )
    except (OSError, ValueError) as exc:
        print(f"Error: {exc}", file=sys.stderr)
        return 1
    print(json.dumps(result.summary()) if args.json else describe(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
