"""Scoring the lookup on real store pages: a description in, did the recall end with the right product?

The descriptions are data written here (``tests/data/lookup_real/``): ``descriptions.jsonl`` holds a
person's description of a product the seed catalog lacks with the corpus page that sells it (``page``), and
``catalog_descriptions.jsonl`` descriptions of seed-catalog objects (``object``), which must not search the
stores. The pages are real (:mod:`scrapers.corpus`), served by :class:`scrapers.corpus_store.CorpusStore`.

:func:`run_trial` recalls one description with :func:`recall.lookup.recall_with_lookup` into its own copy
of the seeded catalog and says (:class:`Trial`): whether it searched, whether the recall's match after the
lookup is the object written from the expected page (``right``), and whether that object's values are the
page's labelled ones within the corpus's tolerance (``values_right``: every labelled extent and the mass
within :data:`scrapers.verdicts.TOLERANCE`, 2 %, as the extraction's corpus benchmark counts).
"""

from __future__ import annotations

import json
import shutil
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["DATA_DIR", "Trial", "load_descriptions", "run_trial", "summary"]

DATA_DIR = Path(__file__).resolve().parents[1] / "tests" / "data" / "lookup_real"


def load_descriptions(name: str = "descriptions.jsonl", folder: Path = DATA_DIR) -> list[dict[str, Any]]:
    """The rows of one descriptions file (JSON Lines)."""
    lines = (Path(folder) / name).read_text(encoding="utf-8").splitlines()
    return [json.loads(line) for line in lines if line.strip()]


@dataclass
class Trial:
    """One description's lookup: what was expected (``page`` or catalog ``object``), what happened."""

    text: str
    expected: str
    held_out: bool | None = None
    written_by: str | None = None
    looked_up: bool = False
    why: str | None = None
    match: str | None = None
    right: bool = False
    values_right: bool = False
    seconds: float = 0.0
    over_budget: bool = False
    candidate: dict[str, Any] | None = None
    problems: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def _object_of_page(db: Path, url: str) -> tuple[str | None, dict[str, Any] | None]:
    """The catalog name and values of the object written from ``url`` (None when none was)."""
    from kb.catalog import KnowledgeBase
    from scrapers.outcomes import page_identity

    with KnowledgeBase.open(db).connect() as con:
        rows = con.execute("SELECT url, object_id FROM pages WHERE object_id IS NOT NULL").fetchall()
        ids = [oid for u, oid in rows if page_identity(u) == page_identity(url)]
        if not ids:
            return None, None
        cur = con.execute("SELECT * FROM objects WHERE id = ?", [ids[0]])
        row = cur.fetchone()
        values = dict(zip([d[0] for d in cur.description], row, strict=True))
    return values["name"], values


def values_problems(values: dict[str, Any], truth: dict[str, Any]) -> list[str]:
    """How the object's values differ from the page's labels (empty: right)."""
    from scrapers.labelled_pages import dims_within, within
    from scrapers.verdicts import TOLERANCE

    problems = []
    dims = [values.get(k) for k in ("a_cm", "b_cm", "c_cm") if values.get(k) is not None]
    if truth.get("dims_cm") and not dims_within(dims, truth["dims_cm"], TOLERANCE):
        problems.append(f"dims {dims} != {truth['dims_cm']}")
    mass = values.get("mass_g")
    if truth.get("mass_g") and (mass is None or not within(mass, truth["mass_g"], TOLERANCE)):
        problems.append(f"mass {mass} != {truth['mass_g']}")
    return problems


def run_trial(template: Path, workdir: Path, row: dict[str, Any], store, sources, session,
              pages: dict[str, Any], budget_s: float) -> Trial:  # fmt: skip
    """Recall ``row`` (a descriptions row) with a lookup in ``store`` into a fresh copy of ``template``."""
    from recall.lookup import recall_with_lookup

    db = workdir / "trial.duckdb"
    shutil.copy(template, db)
    expected = row.get("page") or row["object"]
    page = pages.get(row["page"]) if row.get("page") else None
    trial = Trial(row["text"], expected, held_out=page.held_out if page is not None else None,
                  written_by=row.get("written_by"))
    t0 = time.perf_counter()
    out = recall_with_lookup(db, row["text"], sources=sources, session=session, budget_s=budget_s)
    trial.seconds = time.perf_counter() - t0
    trial.over_budget = out.seconds.get("total", 0.0) > budget_s
    trial.looked_up, trial.why = out.looked_up, out.why
    best = out.result.best
    trial.match = best.name if best is not None and not out.result.open_set else None
    if page is None:  # a catalog object: right when recalled without searching
        trial.right = trial.values_right = not out.looked_up and trial.match == row["object"]
        return trial
    url = store.url_of(page.id)
    cands = [c for c in (out.stores.candidates if out.stores else []) if c.url == url]
    if cands:
        c = cands[0]
        trial.candidate = {"outcome": c.outcome, "reason": c.reason, "name": c.name, "features": c.features}
    else:
        trial.problems.append("the page was not among the results read")
    name, values = _object_of_page(db, url)
    trial.right = name is not None and trial.match == name
    if values is not None:
        trial.problems += values_problems(values, page.truth)
        trial.values_right = trial.right and not trial.problems
    return trial


def summary(trials: list[Trial]) -> dict[str, Any]:
    """Counts and shares of a list of trials."""
    n = len(trials)
    return {
        "descriptions": n,
        "right": sum(t.right for t in trials),
        "values_right": sum(t.values_right for t in trials),
        "looked_up": sum(t.looked_up for t in trials),
        "over_budget": sum(t.over_budget for t in trials),
        "right_share": round(sum(t.right for t in trials) / n, 3) if n else None,
        "values_share": round(sum(t.values_right for t in trials) / n, 3) if n else None,
        "max_s": round(max((t.seconds for t in trials), default=0.0), 2),
    }
