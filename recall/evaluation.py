"""Evaluation of the recall on labelled descriptions: the paper's Fig. 5, plus the hybrid and parse scores.

:func:`evaluate` builds a temporary knowledge base from a canonical catalog CSV, parses every description
of a ``object,description`` CSV once, recalls it with every metric (features only, as the paper) and with
the hybrid, and reports top-1 / top-3 accuracy, the parse scores (``recall.parse_eval``) and each miss with
its reason. ``objrecall evaluate`` prints it; ``python -m recall.evaluation --fit`` also prints the
calibration of the confidence and of the open-set threshold (see ``recall/RECALL.md``).
"""

from __future__ import annotations

import csv
import math
import tempfile
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import normalize_name
from recall.calibration import Calibration, calibration
from recall.engine import DEFAULT_METRIC, HEAD_WEIGHT, NAME_WEIGHT, Recaller, RecallResult
from recall.metrics import METRICS, FeatureQuery
from recall.misses import explained_miss

__all__ = ["PAPER_TOP1", "Case", "EvaluationReport", "MetricScore", "Miss", "evaluate", "read_descriptions"]

_HERE = Path(__file__).resolve().parent
DEV_SET = _HERE / "data" / "dev_descriptions.csv"
OPEN_SET = _HERE / "data" / "open_set_descriptions.csv"
SEED_CATALOG = _HERE.parent / "kb" / "data" / "seed_catalog.csv"
#: The paper's Fig. 5 (top-1 accuracy, %, 100 descriptions of 100 objects).
PAPER_TOP1 = {"jp": 92, "euclidean": 85, "minkowski": 82, "cosine": 59, "kdtree": 85}
#: The hybrid rows of the table: the default (JP in log units + names) and the paper's JP + names.
HYBRID_METRICS = (DEFAULT_METRIC[False], "jp")


@dataclass
class MetricScore:
    metric: str
    features_only: bool
    n: int
    top1: int
    top3: int

    @property
    def top1_pct(self) -> float:
        return 100.0 * self.top1 / self.n if self.n else 0.0

    @property
    def top3_pct(self) -> float:
        return 100.0 * self.top3 / self.n if self.n else 0.0

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["top1_pct"] = round(self.top1_pct, 1)
        d["top3_pct"] = round(self.top3_pct, 1)
        d["paper_top1_pct"] = PAPER_TOP1.get(self.metric) if self.features_only else None
        return d


@dataclass
class Miss:
    mode: str  # "jp" (features only) or "jp+names"
    object: str
    got: str
    description: str
    reason: str


@dataclass
class Case:
    """One labelled description with its JP results (features only and hybrid), for calibration."""

    object: str
    description: str
    features_only: RecallResult
    hybrid: RecallResult


@dataclass
class EvaluationReport:
    n: int
    scores: list[MetricScore]
    parse: dict[str, Any]
    misses: list[Miss]
    unknown_objects: list[str] = field(default_factory=list)
    cases: list[Case] = field(default_factory=list, repr=False)
    #: Open-set flags per mode ("jp" features only, "jplog+names" the default hybrid): ``false_flags``
    #: counts the in-catalog descriptions flagged (of ``n``); ``open_set`` the open-set descriptions
    #: flagged (of ``open_set_n``, when an open-set CSV was given) and ``open_set_confident`` those with
    #: confidence >= 0.9 all the same.
    false_flags: dict[str, int] = field(default_factory=dict)
    open_set_n: int = 0
    open_set: dict[str, int] = field(default_factory=dict)
    open_set_confident: dict[str, int] = field(default_factory=dict)
    #: Per mode: (confidence, right) of every in-catalog and open-set result, and their calibration.
    points: dict[str, list[tuple[float, bool]]] = field(default_factory=dict, repr=False)

    def calibration(self, mode: str) -> Calibration:
        """Brier, ECE and reliability bins of ``mode``'s results (in-catalog and open-set)."""
        pts = self.points.get(mode, [])
        return calibration([c for c, _ in pts], [r for _, r in pts])

    def score(self, metric: str, features_only: bool = True) -> MetricScore:
        for s in self.scores:
            if s.metric == metric and s.features_only == features_only:
                return s
        raise KeyError(metric)

    def to_dict(self) -> dict[str, Any]:
        return {
            "n": self.n,
            "scores": [s.to_dict() for s in self.scores],
            "parse": self.parse,
            "misses": [asdict(m) for m in self.misses],
            "unknown_objects": self.unknown_objects,
            "false_flags": dict(self.false_flags),
            "open_set_n": self.open_set_n,
            "open_set_flagged": dict(self.open_set),
            "open_set_confident": dict(self.open_set_confident),
            "calibration": {mode: self.calibration(mode).to_dict() for mode in self.points},
        }


def read_descriptions(path: str | Path) -> list[tuple[str, str]]:
    """(object, description) pairs of a CSV with columns ``object,description`` (any case; ``name`` or
    ``id`` for ``object`` also; others ignored)."""
    path = Path(path)
    try:
        return _read_descriptions(path)
    except UnicodeDecodeError as err:
        raise RecallError(f"{path}: not UTF-8 text ({err.reason})") from None
    except csv.Error as err:
        raise RecallError(f"{path}: not a CSV file ({err})") from None


def _read_descriptions(path: Path) -> list[tuple[str, str]]:
    with path.open(encoding="utf-8-sig", newline="") as fh:
        reader = csv.DictReader(fh)
        header = [h.strip().lower() for h in reader.fieldnames or []]
        for other in ("name", "id"):  # a catalog-style label column, or a data set's object id
            if "object" not in header and other in header:
                header[header.index(other)] = "object"
        missing = [c for c in ("object", "description") if c not in header]
        if missing:
            raise RecallError(f"{path}: missing column(s) {', '.join(missing)} (need object,description)")
        reader.fieldnames = header
        out = []
        for row in reader:
            obj, text = (row.get("object") or "").strip(), (row.get("description") or "").strip()
            if obj and text:
                out.append((normalize_name(obj), text))
    if not out:
        raise RecallError(f"{path}: no descriptions")
    return out


def _loose_key(label: str) -> str:
    """A label as words: case, underscores, hyphens, apostrophes and plurals do not matter."""
    from recall.engine import normalize_words

    return " ".join(normalize_words(label))


def _loose_labels(names: list[str], aliases: list[tuple[str, ...]]) -> dict[str, str]:
    """Loose key -> catalog name, for description labels written differently from the catalog's names
    ("wood_cylinder", "Rubik's cube" for "rubiks cube"); a key shared by two objects is left out."""
    out: dict[str, str | None] = {}
    for name, alias in zip(names, aliases, strict=True):
        for label in (name, *alias):
            key = _loose_key(label)
            out[key] = name if out.get(key, name) == name else None
    return {k: v for k, v in out.items() if v is not None}


def _recaller_from_catalog(catalog_csv: Path, workdir: Path) -> Recaller:
    """A temporary knowledge base (DuckDB file) holding the catalog, and a recaller over it that reads what
    the catalog's folder declares of its values (:mod:`recall.catalog_folder`: floors and bins)."""
    from kb.catalog import KnowledgeBase
    from recall.catalog_folder import read_bins, read_floors

    kb = KnowledgeBase.open(workdir / "evaluation.duckdb")
    kb.import_csv(catalog_csv)
    try:
        from recall.sql import install_macros

        with kb.connect(write=True) as con:
            install_macros(con)
    except Exception:  # noqa: BLE001 - the macros are a convenience here
        pass
    recaller = Recaller.from_db(workdir / "evaluation.duckdb")
    recaller.floors = read_floors(catalog_csv)
    recaller.bins = read_bins(catalog_csv)
    return recaller


#: The two modes whose misses and open-set flags are reported: the paper's method and the default hybrid.
FLAG_MODES = {("jp", True): "jp", (DEFAULT_METRIC[False], False): f"{DEFAULT_METRIC[False]}+names"}
CONFIDENT = 0.9


def evaluate(
    catalog_csv: str | Path,
    descriptions_csv: str | Path,
    *,
    open_set_csv: str | Path | None = None,
    keep_cases: bool = False,
) -> EvaluationReport:
    """Evaluate recall of the descriptions against the catalog (see the module docstring); with
    ``open_set_csv`` (a ``description`` column of objects not in the catalog) also how many of those are
    flagged open-set."""
    from kb.features import ObjectRecord
    from recall.catalog_folder import read_ids
    from recall.parse_eval import score_parses
    from recall.parser import parse

    pairs = read_descriptions(descriptions_csv)
    with tempfile.TemporaryDirectory(prefix="objrecall-eval-") as tmp:
        recaller = _recaller_from_catalog(Path(catalog_csv), Path(tmp))
    snap = recaller.snapshot
    label, index = _labeller(snap, read_ids(catalog_csv))
    tally = _Tally()
    unknown: list[str] = []
    parse_pairs: list[tuple[Any, ObjectRecord]] = []
    for obj, text in pairs:
        obj = label(obj)
        if obj not in index:
            unknown.append(obj)
            continue
        parsed = parse(text)
        parse_pairs.append((parsed, snap.record(index[obj])))
        results = _recall_every_mode(recaller, parsed)
        tally.add(recaller, obj, text, FeatureQuery.from_parsed(parsed), results)
        if keep_cases:
            tally.cases.append(Case(obj, text, results[("jp", True)], results[(DEFAULT_METRIC[False], False)]))
    n = tally.n
    scores = [MetricScore(m, True, n, *tally.hits[(m, True)]) for m in METRICS]
    scores += [MetricScore(m, False, n, *tally.hits[(m, False)]) for m in HYBRID_METRICS]
    parse_scores = score_parses(parse_pairs) if parse_pairs else None
    parse_dict = asdict(parse_scores) if parse_scores is not None else {}
    parse_dict.pop("confusion", None)
    report = EvaluationReport(
        n, scores, parse_dict, tally.misses, unknown, tally.cases, tally.false_flags, points=tally.points
    )
    if open_set_csv is not None:
        _add_open_set(report, recaller, open_set_csv)
    return report


def _labeller(snap, ids: dict[str, str] | None = None):
    """(label -> catalog name: the name itself, the data set's id of it (``ids``: the catalog folder's
    ``ids.csv``), an alias or a loose match, else the label unchanged; catalog name -> row)."""
    index = {n: i for i, n in enumerate(snap.names)}
    alias_of = {a: n for n, aliases in zip(snap.names, snap.aliases, strict=True) for a in aliases}
    alias_of.update({normalize_name(k): v for k, v in (ids or {}).items()})
    loose = _loose_labels(snap.names, snap.aliases)

    def label(obj: str) -> str:
        return obj if obj in index else alias_of.get(obj, loose.get(_loose_key(obj), obj))

    return label, index


def _recall_every_mode(recaller: Recaller, parsed: Any) -> dict[tuple[str, bool], RecallResult]:
    """(metric, features only) -> the top 3 of every metric features only and of the hybrid metrics."""
    results = {(m, True): recaller.recall_parsed(parsed, top=3, metric=m, features_only=True) for m in METRICS}
    for metric in HYBRID_METRICS:
        results[(metric, False)] = recaller.recall_parsed(parsed, top=3, metric=metric, features_only=False)
    return results


@dataclass
class _Tally:
    """Counts over the in-catalog descriptions: hits (top-1, top-3) per mode, false flags and confidence
    points of the flag modes, the explained misses and the kept cases."""

    n: int = 0
    hits: dict[tuple[str, bool], list[int]] = field(
        default_factory=lambda: {**{(m, True): [0, 0] for m in METRICS}, **{(m, False): [0, 0] for m in HYBRID_METRICS}}
    )
    false_flags: dict[str, int] = field(default_factory=lambda: dict.fromkeys(FLAG_MODES.values(), 0))
    points: dict[str, list[tuple[float, bool]]] = field(default_factory=dict)
    misses: list[Miss] = field(default_factory=list)
    cases: list[Case] = field(default_factory=list)

    def add(self, recaller: Recaller, obj: str, text: str, query: FeatureQuery, results) -> None:
        self.n += 1
        for key, res in results.items():
            names = [m.name for m in res.matches]
            if key in FLAG_MODES:
                self.false_flags[FLAG_MODES[key]] += res.open_set
                self.points.setdefault(FLAG_MODES[key], []).append((res.confidence, names[:1] == [obj]))
            self.hits[key][0] += bool(names[:1] == [obj])
            self.hits[key][1] += obj in names[:3]
            if key in FLAG_MODES and names[:1] != [obj]:
                self.misses.append(Miss(*explained_miss(recaller, key, obj, text, query, res)))


def _add_open_set(report: EvaluationReport, recaller: Recaller, open_set_csv: str | Path) -> None:
    """Detection (flagged), confident anyway, and the confidence points of the open-set descriptions."""
    for (metric, features_only), mode in FLAG_MODES.items():
        results = open_set_results(recaller, open_set_csv, features_only, metric)
        report.open_set_n = len(results)
        report.open_set[mode] = sum(r.open_set for r in results)
        report.open_set_confident[mode] = sum(r.confidence >= CONFIDENT for r in results)
        report.points.setdefault(mode, []).extend((r.confidence, False) for r in results if r.matches)


def open_set_results(
    recaller: Recaller, path: str | Path, features_only: bool = False, metric: str | None = None
) -> list[RecallResult]:
    """Recall every ``description`` of an open-set CSV (objects not in the catalog)."""
    from recall.descriptions import read_description_column

    texts = read_description_column(Path(path))
    return [recaller.recall_text(t, features_only=features_only, metric=metric) for t in texts]


def _main() -> None:  # pragma: no cover - a calibration script
    import argparse
    import json

    ap = argparse.ArgumentParser(
        description="Evaluate recall on the development set; --fit prints calibrations."
    )
    ap.add_argument("--catalog", default=str(SEED_CATALOG))
    ap.add_argument("--descriptions", default=str(DEV_SET))
    ap.add_argument("--open-set", default=str(OPEN_SET))
    ap.add_argument("--fit", action="store_true")
    args = ap.parse_args()
    report = evaluate(args.catalog, args.descriptions, keep_cases=True)
    print(json.dumps(report.to_dict()["scores"], indent=1))
    for m in report.misses:
        print(f"[{m.mode}] {m.object} -> {m.got}: {m.reason}\n    {m.description}")
    if args.fit:
        import recall.name_index as name_index

        for w_name, w_head in ((0.6, 0.3), (0.6, 0.4), (0.7, 0.3), (0.7, 0.4), (0.5, 0.3)):
            name_index.NAME_WEIGHT, name_index.HEAD_WEIGHT = w_name, w_head
            r = evaluate(args.catalog, args.descriptions)
            print(
                f"NAME_WEIGHT {w_name} HEAD_WEIGHT {w_head}: hybrid top-1 "
                f"{r.score(DEFAULT_METRIC[False], False).top1_pct:.1f} % (jp + names "
                f"{r.score('jp', False).top1_pct:.1f} %)"
            )
        name_index.NAME_WEIGHT, name_index.HEAD_WEIGHT = NAME_WEIGHT, HEAD_WEIGHT
        recaller = Recaller.from_csv(args.catalog)
        print("confidence models: python -m recall.scoreboard --fit-confidence")
        right = sorted(
            c.hybrid.closeness
            for c in report.cases
            if c.hybrid.closeness is not None and c.hybrid.matches[0].name == c.object
        )
        q = np.percentile(right, [50, 90, 99])
        print(
            f"closeness of right hybrid matches: p50 {q[0]:.2f} p90 {q[1]:.2f} p99 {q[2]:.2f} max {max(right):.2f}"
        )
        for res in open_set_results(recaller, args.open_set):
            best = res.best.name if res.best else None
            close = res.closeness if res.closeness is not None else math.nan
            print(
                f"open-set {close:.2f} {res.open_set} {res.unknown_noun} {best} {res.confidence:.2f}: "
                f"{(res.text or '')[:60]}"
            )


if __name__ == "__main__":
    _main()
