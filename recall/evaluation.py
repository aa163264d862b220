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
from kb.features import CATEGORICAL_FEATURES, normalize_name
from recall.engine import HEAD_WEIGHT, NAME_WEIGHT, Recaller, RecallResult
from recall.metrics import METRICS, FeatureQuery, feature_terms

__all__ = ["PAPER_TOP1", "Case", "EvaluationReport", "MetricScore", "Miss", "evaluate", "read_descriptions"]

_HERE = Path(__file__).resolve().parent
DEV_SET = _HERE / "data" / "dev_descriptions.csv"
OPEN_SET = _HERE / "data" / "open_set_descriptions.csv"
SEED_CATALOG = _HERE.parent / "kb" / "data" / "seed_catalog.csv"
#: The paper's Fig. 5 (top-1 accuracy, %, 100 descriptions of 100 objects).
PAPER_TOP1 = {"jp": 92, "euclidean": 85, "minkowski": 82, "cosine": 59, "kdtree": 85}
HYBRID = "jp+names"


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
        }


def read_descriptions(path: str | Path) -> list[tuple[str, str]]:
    """(object, description) pairs of a CSV with columns ``object,description`` (others ignored)."""
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
        header = [h.strip() for h in reader.fieldnames or []]
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


def _recaller_from_catalog(catalog_csv: Path, workdir: Path) -> Recaller:
    """A temporary knowledge base (DuckDB file) holding the catalog, and a recaller over it."""
    from kb.catalog import KnowledgeBase

    kb = KnowledgeBase.open(workdir / "evaluation.duckdb")
    kb.import_csv(catalog_csv)
    try:
        from recall.sql import install_macros

        with kb.connect(write=True) as con:
            install_macros(con)
    except Exception:  # noqa: BLE001 - the macros are a convenience here
        pass
    return Recaller.from_db(workdir / "evaluation.duckdb")


def miss_reason(recaller: Recaller, query: FeatureQuery, true_name: str, got_name: str) -> str:
    """Why ``got_name`` beat ``true_name``: the stated features that pulled it, and the unstated ones
    that would have told them apart."""
    snap = recaller.snapshot
    index = {n: i for i, n in enumerate(snap.names)}
    t, g = index[true_name], index[got_name]
    rows = np.array([t, g])
    terms = feature_terms(snap.num[rows], snap.cat[rows], query)
    true_rec, got_rec = snap.record(t), snap.record(g)
    values = query.values()
    parts = []
    pulls = sorted(((terms[f][0] - terms[f][1], f) for f in terms), reverse=True)
    for diff, feat in pulls:
        if diff <= 1e-9:
            break
        parts.append(
            f"{feat}: stated {_fmt(values.get(feat))}, {true_name} {_fmt(getattr(true_rec, feat))} "
            f"(+{terms[feat][0]:.2f}) vs {got_name} {_fmt(getattr(got_rec, feat))} (+{terms[feat][1]:.2f})"
        )
        if len(parts) == 3:
            break
    if not query.stated:
        parts.append("no feature stated")
    unstated = [
        f"{f} ({getattr(true_rec, f)} vs {getattr(got_rec, f)})"
        for f in CATEGORICAL_FEATURES
        if f not in values and getattr(true_rec, f) != getattr(got_rec, f)
    ]
    if unstated:
        parts.append("not stated: " + ", ".join(unstated))
    if not parts:
        parts.append("tie on every stated feature")
    return "; ".join(parts)


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    return "?" if v is None else str(v)


def evaluate(
    catalog_csv: str | Path, descriptions_csv: str | Path, *, keep_cases: bool = False
) -> EvaluationReport:
    """Evaluate recall of the descriptions against the catalog (see the module docstring)."""
    from kb.features import ObjectRecord
    from recall.parse_eval import score_parses
    from recall.parser import parse

    pairs = read_descriptions(descriptions_csv)
    with tempfile.TemporaryDirectory(prefix="objrecall-eval-") as tmp:
        recaller = _recaller_from_catalog(Path(catalog_csv), Path(tmp))
    snap = recaller.snapshot
    index = {n: i for i, n in enumerate(snap.names)}
    alias_of = {a: n for n, aliases in zip(snap.names, snap.aliases, strict=True) for a in aliases}
    hits = {(m, fo): [0, 0] for m in METRICS for fo in (True,)}
    hits[("jp", False)] = [0, 0]
    misses: list[Miss] = []
    unknown: list[str] = []
    parse_pairs: list[tuple[Any, ObjectRecord]] = []
    cases: list[Case] = []
    n = 0
    for obj, text in pairs:
        obj = obj if obj in index else alias_of.get(obj, obj)
        if obj not in index:
            unknown.append(obj)
            continue
        n += 1
        parsed = parse(text)
        parse_pairs.append((parsed, snap.record(index[obj])))
        query = FeatureQuery.from_parsed(parsed)
        results: dict[tuple[str, bool], RecallResult] = {}
        for metric in METRICS:
            results[(metric, True)] = recaller.recall_parsed(parsed, top=3, metric=metric, features_only=True)
        results[("jp", False)] = recaller.recall_parsed(parsed, top=3, metric="jp", features_only=False)
        for key, res in results.items():
            names = [m.name for m in res.matches]
            hits[key][0] += bool(names[:1] == [obj])
            hits[key][1] += obj in names[:3]
            if key[0] == "jp" and names[:1] != [obj]:
                got = names[0] if names else "(nothing)"
                reason = miss_reason(recaller, query, obj, got) if names else "nothing stated or named"
                if not key[1]:
                    reason = (
                        "named: " + ", ".join(res.named) + "; " if res.named else "no name found; "
                    ) + reason
                misses.append(Miss("jp" if key[1] else HYBRID, obj, got, text, reason))
        if keep_cases:
            cases.append(Case(obj, text, results[("jp", True)], results[("jp", False)]))
    scores = [MetricScore(m, True, n, *hits[(m, True)]) for m in METRICS]
    scores.append(MetricScore("jp", False, n, *hits[("jp", False)]))
    parse_scores = score_parses(parse_pairs) if parse_pairs else None
    parse_dict = asdict(parse_scores) if parse_scores is not None else {}
    parse_dict.pop("confusion", None)
    return EvaluationReport(n, scores, parse_dict, misses, unknown, cases)


# ------------------------------------------------------------------------------------------ calibration
def fit_confidence(cases: list[Case]) -> tuple[float, float, int]:
    """Logistic fit of P(first match right) on the ranking-score margin, over the features-only and the
    hybrid results of the development set. Returns (a, b, number of points)."""
    from sklearn.linear_model import LogisticRegression

    x, y = [], []
    for case in cases:
        for res in (case.features_only, case.hybrid):
            if len(res.matches) < 2:
                continue
            x.append(res.matches[1].score - res.matches[0].score)
            y.append(int(res.matches[0].name == case.object))
    model = LogisticRegression(C=10.0).fit(np.array(x)[:, None], np.array(y))
    return float(model.intercept_[0]), float(model.coef_[0][0]), len(x)


def _main() -> None:  # pragma: no cover - a calibration script
    import argparse
    import json

    ap = argparse.ArgumentParser(
        description="Evaluate recall on the development set; --fit prints calibrations."
    )
    ap.add_argument("--catalog", default=str(SEED_CATALOG))
    ap.add_argument("--descriptions", default=str(DEV_SET))
    ap.add_argument("--fit", action="store_true")
    args = ap.parse_args()
    report = evaluate(args.catalog, args.descriptions, keep_cases=True)
    print(json.dumps(report.to_dict()["scores"], indent=1))
    for m in report.misses:
        print(f"[{m.mode}] {m.object} -> {m.got}: {m.reason}\n    {m.description}")
    if args.fit:
        import recall.engine as engine

        for w_name, w_head in ((0.6, 0.3), (0.6, 0.4), (0.7, 0.3), (0.7, 0.4), (0.5, 0.3)):
            engine.NAME_WEIGHT, engine.HEAD_WEIGHT = w_name, w_head
            r = evaluate(args.catalog, args.descriptions)
            print(
                f"NAME_WEIGHT {w_name} HEAD_WEIGHT {w_head}: hybrid top-1 {r.score('jp', False).top1_pct:.1f} %"
            )
        engine.NAME_WEIGHT, engine.HEAD_WEIGHT = NAME_WEIGHT, HEAD_WEIGHT
        a, b, k = fit_confidence(report.cases)
        print(f"confidence: a={a:.3f} b={b:.3f} over {k} results")
        close = sorted(
            c.features_only.closeness for c in report.cases if c.features_only.closeness is not None
        )
        right = sorted(
            c.features_only.closeness
            for c in report.cases
            if c.features_only.closeness is not None and c.features_only.matches[0].name == c.object
        )
        q = np.percentile(right, [50, 90, 95, 99])
        print(
            f"closeness of right first matches: p50 {q[0]:.2f} p90 {q[1]:.2f} p95 {q[2]:.2f} p99 {q[3]:.2f} max {max(right):.2f}"
        )
        print("all:", np.percentile(close, [50, 90, 99]))
        recaller = Recaller.from_csv(args.catalog)
        with OPEN_SET.open() as fh:
            for row in csv.DictReader(fh):
                res = recaller.recall_text(row["description"])
                best = res.best.name if res.best else None
                print(
                    f"open-set {res.closeness if res.closeness is not None else math.nan:.2f} {res.open_set} "
                    f"{best}: {row['description'][:60]}"
                )


if __name__ == "__main__":
    _main()
