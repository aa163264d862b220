"""Regenerate the README's figure tables from measured results, so the README says what the commands print.

Tables live between marker comments in README.md::

    <!-- figures:recall-accuracy -->   ... generated ...   <!-- /figures:recall-accuracy -->
    <!-- figures:benchmarks -->        ... generated ...   <!-- /figures:benchmarks -->
    <!-- figures:extraction-corpus --> ... generated ...   <!-- /figures:extraction-corpus -->

Sources (committed, so the README can be checked without re-measuring):

* ``benchmarks/results/evaluate.json``: ``objrecall evaluate --json`` on the development set and on the
  hold-out set (``--evaluate`` re-runs it, about a minute);
* ``benchmarks/results/*.json`` with ``benchmark`` and ``result`` keys, one per benchmark table row,
  written by a benchmark run through :func:`benchmarks.results.save` (``order`` sorts the rows);
* ``benchmarks/results/corpus_bench.json``'s per-language and per-layout counts, for the extraction table.

Usage::

    python scripts/readme_figures.py              # rewrite README.md's tables from the saved results
    python scripts/readme_figures.py --evaluate   # re-run objrecall evaluate first, then rewrite
    python scripts/readme_figures.py --check      # exit 1 if README.md differs from the saved results
    python scripts/readme_figures.py --adopt      # save benchmark rows edited in README.md by hand as results
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
RESULTS = REPO / "benchmarks" / "results"
EVALUATE_JSON = RESULTS / "evaluate.json"
#: The evaluation sets of the recall-accuracy table: (key, catalog CSV, descriptions CSV).
EVALUATION_SETS = (
    ("dev", "kb/data/seed_catalog.csv", "recall/data/dev_descriptions.csv"),
    ("holdout", "kb/data/seed_catalog.csv", "tests/data/holdout/holdout_descriptions.csv"),
)
#: Rows of the recall-accuracy table: (metric, features_only, label, bold top-1).
RECALL_ROWS = (
    ("jp", True, "Joint Probability (the paper's, features only)", True),
    ("euclidean", True, "Euclidean", False),
    ("minkowski", True, "Minkowski p=4", False),
    ("cosine", True, "Cosine", False),
    ("kdtree", True, "k-d tree", False),
    ("jplog", True, "jplog: JP on relative differences (features only)", False),
    ("jp", False, "JP + names (hybrid)", False),
    ("jplog", False, "**jplog + names (hybrid, the default)**", True),
)


class FiguresError(Exception):
    """A results file or a README marker is missing or malformed."""


def run_evaluate(repo: Path = REPO) -> dict:
    """``objrecall evaluate --json`` on each evaluation set (a real subprocess, as a person runs it)."""
    out = {}
    env = {**os.environ, "PYTHONPATH": str(repo)}
    for key, catalog, descriptions in EVALUATION_SETS:
        proc = subprocess.run(
            [sys.executable, "-m", "kb.service.cli", "evaluate", "--catalog", catalog, "--descriptions",
             descriptions, "--json"],
            cwd=repo, env=env, capture_output=True, text=True, check=False,
        )  # fmt: skip
        if proc.returncode != 0:
            raise FiguresError(f"objrecall evaluate on {descriptions} failed: {proc.stderr.strip()[-500:]}")
        data = json.loads(proc.stdout.strip().splitlines()[-1])
        out[key] = {"n": data["n"], "scores": data["scores"], "descriptions": descriptions}
    return out


def _pct(value: float | None) -> str:
    if value is None:
        return "–"
    return f"{value:g} %" if value != 100 else "100 %"


def _score(scores: list[dict], metric: str, features_only: bool) -> dict:
    for s in scores:
        if s["metric"] == metric and bool(s["features_only"]) == features_only:
            return s
    raise FiguresError(f"no score for metric {metric!r} (features_only={features_only}) in evaluate.json")


def render_recall_table(evaluate: dict) -> str:
    """The recall-accuracy table (paper vs dev vs hold-out, top-1 and top-3) from evaluate.json."""
    dev, hold = evaluate["dev"]["scores"], evaluate["holdout"]["scores"]
    lines = [
        "| metric | paper top-1 | dev top-1 | dev top-3 | hold-out top-1 | hold-out top-3 |",
        "|---|---|---|---|---|---|",
    ]
    for metric, features_only, label, bold in RECALL_ROWS:
        d, h = _score(dev, metric, features_only), _score(hold, metric, features_only)
        paper = d.get("paper_top1_pct")
        top1 = (lambda v: f"**{_pct(v)}**") if bold else _pct
        lines.append(
            f"| {label} | {paper if paper is not None else '–'} | {top1(d['top1_pct'])} | {_pct(d['top3_pct'])} "
            f"| {top1(h['top1_pct'])} | {_pct(h['top3_pct'])} |"
        )
    return "\n".join(lines)


def load_benchmark_rows(results: Path = RESULTS) -> list[dict]:
    """Benchmark result files (``benchmark`` and ``result`` keys), ordered by ``order`` then file name."""
    rows = []
    for path in sorted(results.glob("*.json")):
        if path == results / EVALUATE_JSON.name:
            continue
        data = json.loads(path.read_text(encoding="utf-8"))
        if not {"benchmark", "result"} <= set(data):
            raise FiguresError(f"{path}: a benchmark result needs 'benchmark' and 'result' keys")
        rows.append({**data, "_file": path.name})
    return sorted(rows, key=lambda r: (r.get("order", 1000), r["_file"]))


def render_benchmark_table(rows: list[dict]) -> str:
    lines = ["| benchmark | result |", "|---|---|"]
    lines += [f"| {r['benchmark']} | {r['result']} |" for r in rows]
    return "\n".join(lines)


def adopt_benchmark_rows(text: str, results: Path = RESULTS) -> int:
    """Save the README's benchmark rows as result files (a row edited by hand replaces the saved one, a new
    row gets a file, a saved row the README no longer has is removed); returns how many files changed."""
    block = _block(text, "benchmarks")
    rows = [[c.strip() for c in line.strip().strip("|").split("|", 1)] for line in block.splitlines()[2:] if line.strip()]
    saved = {r["benchmark"]: r for r in load_benchmark_rows(results)}
    changed = 0
    for i, (bench, result) in enumerate(rows):
        old = saved.pop(bench, None)
        name = old["_file"] if old else re.sub(r"[^a-z0-9]+", "_", bench.lower()).strip("_")[:40] + ".json"
        record = {k: v for k, v in (old or {}).items() if k != "_file"}
        if old and old["result"] == result and old.get("order") == (i + 1) * 10:
            continue
        if not old or old["result"] != result:
            record["source"] = "written in README.md by hand (adopted by readme_figures --adopt)"
        record.update(benchmark=bench, result=result, order=(i + 1) * 10)
        (results / (name if name.endswith(".json") else name + ".json")).write_text(
            json.dumps(record, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        changed += 1
    for gone in saved.values():
        (results / gone["_file"]).unlink()
        changed += 1
    return changed


def _block(text: str, name: str) -> str:
    match = re.search(rf"<!-- figures:{re.escape(name)} -->\n(.*?)<!-- /figures:{re.escape(name)} -->", text, re.S)
    if match is None:
        raise FiguresError(f"README has no <!-- figures:{name} --> block")
    return match.group(1)


def replace_block(text: str, name: str, content: str) -> str:
    """``text`` with the lines between ``<!-- figures:name -->`` and ``<!-- /figures:name -->`` replaced."""
    pattern = re.compile(rf"(<!-- figures:{re.escape(name)} -->\n)(.*?)(<!-- /figures:{re.escape(name)} -->)", re.S)
    if len(pattern.findall(text)) != 1:
        raise FiguresError(f"README needs exactly one <!-- figures:{name} --> ... <!-- /figures:{name} --> block")
    return pattern.sub(lambda m: m.group(1) + content.rstrip("\n") + "\n" + m.group(3), text)


def _merged(groups: dict, key=lambda g: g) -> dict:
    out: dict = {}
    for g, c in groups.items():
        m = out.setdefault(key(g), {"pages": 0, "dims": 0, "mass": 0})
        for k in m:
            m[k] += c[k]
    return out


def render_corpus_table(results: Path = RESULTS) -> str:
    """The extraction figures per language (primary subtag: ``en-US`` counts as ``en``) and per layout
    class, held-out stores beside development stores, from ``corpus_bench.json`` (``--held-out --save``)."""
    path = results / "corpus_bench.json"
    if not path.exists():
        raise FiguresError(f"{path} is missing: run benchmarks/corpus_bench.py --held-out --save")
    data = json.loads(path.read_text(encoding="utf-8"))["data"]
    held, dev = data["held_out"], data["development"]

    def cell(c: dict | None, k: str) -> str:
        return f"{c[k]}/{c['pages']} ({c[k] / c['pages']:.2f})" if c and c["pages"] else "–"

    lines = ["| group | held-out dims | held-out mass | development dims | development mass |", "|---|---|---|---|---|"]
    lines.append(f"| **all** ({held['stores']} + {dev['stores']} stores) | {cell(held['all'], 'dims')} | "
                 f"{cell(held['all'], 'mass')} | {cell(dev['all'], 'dims')} | {cell(dev['all'], 'mass')} |")
    for kind, key in (("language", lambda g: g.split("-")[0].lower()), ("layout", lambda g: g)):
        h, d = _merged(held[kind], key), _merged(dev[kind], key)
        for g in sorted(set(h) | set(d), key=lambda g: (-(h.get(g, {}).get("pages", 0) + d.get(g, {}).get("pages", 0)), g)):
            lines.append(f"| {kind} {g} | {cell(h.get(g), 'dims')} | {cell(h.get(g), 'mass')} | "
                         f"{cell(d.get(g), 'dims')} | {cell(d.get(g), 'mass')} |")
    return "\n".join(lines) + "\n"


def render_readme(text: str, results: Path = RESULTS) -> str:
    """The README ``text`` with every figure table regenerated from the saved results."""
    evaluate = json.loads((results / EVALUATE_JSON.name).read_text(encoding="utf-8"))
    text = replace_block(text, "recall-accuracy", render_recall_table(evaluate))
    text = replace_block(text, "benchmarks", render_benchmark_table(load_benchmark_rows(results)))
    return replace_block(text, "extraction-corpus", render_corpus_table(results))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--evaluate", action="store_true", help="re-run objrecall evaluate first")
    parser.add_argument("--check", action="store_true", help="exit 1 if README.md is not up to date")
    parser.add_argument("--adopt", action="store_true", help="save README.md's benchmark rows as results first")
    args = parser.parse_args(argv)
    readme = REPO / "README.md"
    try:
        if args.evaluate:
            RESULTS.mkdir(parents=True, exist_ok=True)
            EVALUATE_JSON.write_text(json.dumps(run_evaluate(), indent=1) + "\n", encoding="utf-8")
        text = readme.read_text(encoding="utf-8")
        if args.adopt:
            print(f"readme_figures: {adopt_benchmark_rows(text)} benchmark result files changed", file=sys.stderr)
        new = render_readme(text)
    except FiguresError as err:
        print(f"readme_figures: {err}", file=sys.stderr)
        return 1
    if args.check:
        if new != text:
            print("readme_figures: README.md's figures differ from benchmarks/results; run "
                  "python scripts/readme_figures.py --adopt (rows edited by hand) or --evaluate", file=sys.stderr)
            return 1
        return 0
    if new != text:
        readme.write_text(new, encoding="utf-8")
        print("readme_figures: README.md updated", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
