"""The main job (``objrecall demo``): seed catalog -> ingest the demo storefront -> recall sample
descriptions -> validate their grasps in MuJoCo -> report. Runs with no network: the demo storefront is
served on 127.0.0.1 by this process.

Like the CLI and the HTTP service, this module is part of the service face and may import every package.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console

from kb.catalog import KnowledgeBase

__all__ = ["DemoResult", "run_demo"]


@dataclass
class DemoResult:
    db: Path
    out_dir: Path
    steps: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {"db": str(self.db), "out_dir": str(self.out_dir), "steps": self.steps}


def run_demo(db: Path, out_dir: Path, *, console: Console | None = None, workers: int = 2) -> DemoResult:
    from kb.commands import init_db

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
    return result
