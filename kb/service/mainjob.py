"""The main job (``objrecall demo``): seed catalog -> ingest the demo storefront -> recall sample
descriptions (each looked up in the demo store's search when the catalog does not know it: one, the teapot,
is sold only there) -> validate their grasps in MuJoCo -> report. Runs with no network: the demo storefront is
served on 127.0.0.1 by this process.

Like the CLI and the HTTP service, this module is part of the service face (``kb/service/``) and may import
every package.
"""

from __future__ import annotations

import csv
import importlib.resources
import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from kb.catalog import KnowledgeBase
from kb.jsonable import to_jsonable
from kb.service.bootstrap import demo_descriptions_path, init_db

__all__ = ["DemoResult", "run_demo"]


@dataclass
class DemoResult:
    db: Path
    out_dir: Path
    steps: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {"db": str(self.db), "out_dir": str(self.out_dir), "steps": self.steps}


def run_demo(db: Path, out_dir: Path, *, console: Console | None = None, workers: int = 2) -> DemoResult:
    console = console or Console(stderr=True)
    out_dir.mkdir(parents=True, exist_ok=True)
    result = DemoResult(db=db, out_dir=out_dir)

    t0 = time.perf_counter()
    console.rule("[bold]1. seed catalog")
    kb: KnowledgeBase = init_db(db, seed=True)
    summary = kb.summary()
    result.steps["seed"] = {"objects": summary["objects"], "seconds": round(time.perf_counter() - t0, 2)}
    console.print(f"catalog {db}: {summary['objects']} objects "
                  f"({', '.join(f'{k} {v}' for k, v in summary['shape'].items())})")

    console.rule("[bold]2. ingest the demo storefront (127.0.0.1, no network)")
    result.steps["ingest"] = ing = _ingest_demo_store(kb, console)
    console.print(ingest_line(ing))

    console.rule("[bold]3. recall sample descriptions (looked up in the demo store's search when unknown)")
    recalled = _recall_samples(db, console)
    result.steps["recall"] = recalled
    console.print(f"recall: {len(recalled)} descriptions, {sum(1 for r in recalled if r['top'])} recalled, "
                  f"{sum(1 for r in recalled if r['open_set'])} open set, "
                  f"{sum(1 for r in recalled if r['looked_up'])} looked up in the store")

    console.rule("[bold]4. validate grasps of the recalled objects in MuJoCo")
    names = list(dict.fromkeys(r["top"] for r in recalled if r["top"]))
    result.steps["grasp"] = g = _validate_grasps(kb, names, out_dir, workers, progress=console.is_terminal)
    console.print(f"grasp: {g.get('objects', 0)} objects, {g.get('trials', 0)} trials "
                  f"({g.get('ran', 0)} run now: {g.get('succeeded', 0)} succeeded, {g.get('failed', 0)} failed, "
                  f"{g.get('errors', 0)} errors; {g.get('skipped', 0)} stored before); "
                  f"{_choice_line(g.get('choice_summary') or {})}")

    console.rule("[bold]5. report")
    report = result.steps["grasp"].get("report")
    console.print(f"catalog: {db}  ({kb.count_objects()} objects)")
    console.print(f"grasp validation report: [bold]{report}[/]")
    (out_dir / "demo_summary.json").write_text(json.dumps(to_jsonable(result.to_dict()), indent=2))
    result.steps["seconds"] = round(time.perf_counter() - t0, 1)
    console.print(f"main job done in {result.steps['seconds']} s")
    return result


def _ingest_demo_store(kb: KnowledgeBase, console: Console) -> dict[str, Any]:
    import requests

    from kb.service.cli.ingest import IngestProgress, print_ingest_summary
    from scrapers.demo_store import DemoStore
    from scrapers.ingest import run_ingestion
    from scrapers.sources import load_sources

    sources_file = Path(str(importlib.resources.files("scrapers") / "demo_sources.toml"))
    with DemoStore(port=0, crawl_delay=0, slow_s=3.0) as store:
        sources = load_sources(sources_file, base_url=store.base_url, delay_s=0)
        with requests.Session() as session, IngestProgress(enabled=console.is_terminal) as progress:
            report = run_ingestion(kb, sources, session=session, progress=progress)
    print_ingest_summary(report)
    out = report.to_dict()
    keys = ("pages", "fetched", "not_modified", "extracted", "rejected", "rejected_reasons", "new", "updated")
    return {k: out[k] for k in keys if k in out}


def ingest_line(ing: dict[str, Any]) -> str:
    """The ingestion step in one line whose counts add up: a rejected page may have been rejected before it
    was fetched (robots.txt, a time-out), after (no product) or after extraction (an absurd value), so the
    reasons are said with the count."""
    reasons = ing.get("rejected_reasons") or {}
    why = f" ({', '.join(f'{k} {v}' for k, v in reasons.items())})" if reasons else ""
    pages = f"{ing['pages']} pages listed, " if "pages" in ing else ""
    return (f"ingest: {pages}{ing.get('fetched', 0)} fetched, {ing.get('extracted', 0)} extracted, "
            f"{ing.get('rejected', 0)} rejected at any stage{why}; {ing.get('new', 0)} new and "
            f"{ing.get('updated', 0)} updated objects")


def _recall_samples(db: Path, console: Console) -> list[dict[str, Any]]:
    """Each demo description recalled with ``recall.lookup.recall_with_lookup`` against the demo store."""
    import requests

    from recall.lookup import recall_with_lookup
    from scrapers.demo_store import DEMO_SOURCES, DemoStore
    from scrapers.sources import load_sources

    with demo_descriptions_path().open(newline="", encoding="utf-8") as fh:
        descriptions = [row["description"] for row in csv.DictReader(fh)]
    table = Table("description", "recalled", "score", "confidence", "open set", "lookup", show_lines=True,
                  caption="score: the ranking score, lower is better: the feature distance minus the name's "
                  "evidence, so below 0 when the description names the object")
    rows = []
    with DemoStore(port=0, crawl_delay=None) as store, requests.Session() as session:
        sources = load_sources(DEMO_SOURCES, base_url=store.base_url, delay_s=0)
        for text in descriptions:
            looked = recall_with_lookup(db, text, sources=sources, session=session, top=3)
            res = looked.result
            best = res.matches[0] if res.matches else None
            rows.append({
                "description": text,
                "top": best.name if best else None,
                "distance": best.distance if best else None,
                "confidence": res.confidence,
                "open_set": res.open_set,
                "not_in_catalog": res.not_in_catalog,
                "same_kind": [m.name for m in res.same_kind],
                "alternatives": [m.name for m in res.matches[1:]],
                "looked_up": looked.looked_up,
                "lookup": looked.message if looked.why else None,
                "added": looked.stores.new_objects if looked.stores else [],
            })
            table.add_row(
                escape(text if len(text) < 90 else text[:87] + "..."),
                escape(best.name) if best else "-",
                f"{best.score:.2f}" if best else "-",
                f"{res.confidence:.2f}",
                escape(_open_set_cell(res)),
                escape(looked.message) if looked.why else "-",
            )
    console.print(table)
    return rows


def _open_set_cell(res) -> str:
    """"not in the catalog (no orange; closest fruit: apple)", "yes" (not a close match) or "no"."""
    if res.not_in_catalog and res.described is not None:
        kind = f"; closest {res.same_kind_as}: {res.same_kind[0].name}" if res.same_kind else ""
        return f"not in the catalog (no {res.described.noun}{kind})"
    return "yes" if res.open_set else "no"


def _choice_line(c: dict[str, Any]) -> str:
    """The closed-loop outcome over every trial, run now or stored before."""
    return (f"first choice holds for {c.get('first_holds', 0)} of {c.get('objects', 0)} objects, "
            f"a validated grasp for {c.get('validated', 0)}")


def _validate_grasps(
    kb: KnowledgeBase, names: list[str], out_dir: Path, workers: int, *, progress: bool
) -> dict[str, Any]:
    from sim.worker import validate

    # a progress bar only on a terminal: piped or logged output gets the one-line summary instead
    summary = validate(kb, names, workers=workers, report_dir=out_dir / "grasp-report", progress=progress)
    out = summary.to_dict() if hasattr(summary, "to_dict") else {}
    out.pop("results", None)
    out["report"] = str(out_dir / "grasp-report" / "index.html")
    return out
