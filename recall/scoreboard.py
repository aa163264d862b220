"""One row per description set: what ``objrecall evaluate --all`` prints.

Every development set (the development descriptions with their open-set list, the two hold-outs, the
second catalog, the sparse anonymous sets) is evaluated with :func:`recall.evaluation.evaluate`, and
each gives, per mode (the default hybrid and the paper's JP, features only): top-1 and top-3, the
open-set descriptions reported not close or not in the catalog (detection), the in-catalog
descriptions reported so (false flags), and the Brier score and expected calibration error of the
confidence over both. The features-only top-1 of ``jplog`` and Euclidean are kept beside them (the
paper's JP must beat Euclidean on the same masks). ``--blind`` adds the blind sets, which are scored
once, at the end of a piece of work (``tests/data/blind_openset2/README.md``).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from recall.calibration import Calibration
from recall.evaluation import FLAG_MODES, evaluate

__all__ = ["BLIND_SETS", "CONFIDENCE_FIT_SETS", "DEVELOPMENT_SETS", "DescriptionSet", "ModeScore", "SetScore", "scoreboard"]

_REPO = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class DescriptionSet:
    """A labelled description set: its name, the catalog CSV, the ``object,description`` CSV and, when
    there is one, the CSV of out-of-catalog descriptions (paths relative to the repository)."""

    name: str
    catalog: str
    descriptions: str
    open_set: str | None = None


_SEED = "kb/data/seed_catalog.csv"
DEVELOPMENT_SETS: tuple[DescriptionSet, ...] = (
    DescriptionSet("dev", _SEED, "recall/data/dev_descriptions.csv", "recall/data/open_set_descriptions.csv"),
    DescriptionSet(
        "holdout", _SEED, "tests/data/holdout/holdout_descriptions.csv", "tests/data/holdout/holdout_open_set.csv"
    ),
    DescriptionSet("holdout2", _SEED, "tests/data/holdout2/holdout2_descriptions.csv"),
    DescriptionSet(
        "catalog2", "tests/data/catalog2/catalog.csv", "tests/data/catalog2/descriptions.csv",
        "tests/data/catalog2/open_set.csv",
    ),  # fmt: skip
    DescriptionSet("sparse_dev", _SEED, "recall/data/dev_sparse_descriptions.csv"),
    # the first blind set, scored once at the end of its session: a development set since
    DescriptionSet(
        "blind_openset", _SEED, "tests/data/blind_openset/sparse_descriptions.csv",
        "tests/data/blind_openset/open_set_descriptions.csv",
    ),  # fmt: skip
    # the third blind set (seed objects named by everyday synonyms, and out-of-catalog nouns), scored once
    # in its session and a development set since (it had been left out of this table)
    DescriptionSet(
        "blind_openset3", _SEED, "tests/data/blind_openset3/full_descriptions.csv",
        "tests/data/blind_openset3/open_set_descriptions.csv",
    ),  # fmt: skip
)
#: The description sets the confidence models are fitted on (``python -m recall.scoreboard
#: --fit-confidence``); the others are the held-out split their Brier score and ECE are reported on
#: (RECALL.md, "Confidence refit per mode").
CONFIDENCE_FIT_SETS = ("dev", "catalog2", "sparse_dev", "blind_openset")
BLIND_SETS: tuple[DescriptionSet, ...] = (
    DescriptionSet(
        "blind2_sparse", _SEED, "tests/data/blind_openset2/sparse_descriptions.csv",
        "tests/data/blind_openset2/open_set_descriptions.csv",
    ),  # fmt: skip
    DescriptionSet("blind2_full", _SEED, "tests/data/blind_openset2/full_descriptions.csv"),
)


@dataclass
class ModeScore:
    """One mode's figures on one set (rates in [0, 1]; None when the set has no such descriptions)."""

    mode: str
    top1: float
    top3: float
    false_flags: int
    detected: int | None
    brier: float
    ece: float
    #: The Brier score, ECE and reliability bins behind ``brier`` and ``ece`` (pooled over sets by
    #: ``recall.calibration.pooled`` for the reliability plot of ``evaluate --all``).
    calibration: Calibration | None = None


@dataclass
class SetScore:
    name: str
    n: int
    open_set_n: int
    modes: list[ModeScore] = field(default_factory=list)
    #: Features-only top-1 of every metric (the paper's Fig. 5 on this set).
    features_only_top1: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def score_set(spec: DescriptionSet, repo: Path = _REPO) -> SetScore:
    """The figures of one description set (see the module docstring)."""
    open_set = repo / spec.open_set if spec.open_set else None
    report = evaluate(repo / spec.catalog, repo / spec.descriptions, open_set_csv=open_set)
    out = SetScore(spec.name, report.n, report.open_set_n)
    for (metric, features_only), mode in FLAG_MODES.items():
        score = report.score(metric, features_only)
        cal = report.calibration(mode)
        detected = report.open_set.get(mode) if report.open_set_n else None
        out.modes.append(
            ModeScore(mode, score.top1 / max(score.n, 1), score.top3 / max(score.n, 1),
                      report.false_flags.get(mode, 0), detected, cal.brier, cal.ece, cal)
        )  # fmt: skip
    out.features_only_top1 = {s.metric: s.top1 / max(s.n, 1) for s in report.scores if s.features_only}
    return out


def scoreboard(sets: tuple[DescriptionSet, ...] = DEVELOPMENT_SETS, repo: Path = _REPO) -> list[SetScore]:
    """:func:`score_set` of each set whose files are present (a set missing from a checkout is skipped)."""
    present = [s for s in sets if (repo / s.descriptions).is_file() and (repo / s.catalog).is_file()]
    return [score_set(s, repo) for s in present]


def fit_confidence_models() -> None:  # pragma: no cover - a calibration script
    """Fit ``recall.confidence``'s two models on :data:`CONFIDENCE_FIT_SETS` and print them."""
    from recall.calibration import fit_confidence
    from recall.engine import Recaller
    from recall.evaluation import open_set_results

    points: dict[bool, list] = {True: [], False: []}
    for spec in (s for s in DEVELOPMENT_SETS if s.name in CONFIDENCE_FIT_SETS):
        rep = evaluate(_REPO / spec.catalog, _REPO / spec.descriptions, keep_cases=True)
        for case in rep.cases:
            for fo, res in ((True, case.features_only), (False, case.hybrid)):
                points[fo].append((res, bool(res.matches) and res.matches[0].name == case.object))
        if spec.open_set:
            recaller = Recaller.from_csv(_REPO / spec.catalog)
            for (metric, fo), _mode in FLAG_MODES.items():
                points[fo] += [(r, False) for r in open_set_results(recaller, _REPO / spec.open_set, fo, metric)]
    for fo in (True, False):
        model, k = fit_confidence(points[fo])
        print(f"confidence, {'features only' if fo else 'hybrid'}: {model} over {k} results")


if __name__ == "__main__":  # pragma: no cover
    import sys

    if "--fit-confidence" in sys.argv[1:]:
        fit_confidence_models()
