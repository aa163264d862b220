"""Saving a benchmark's README row beside its printed output (``benchmarks/results/NAME.json``).

A benchmark calls :func:`save_result` at the end of a full-size run with the one-line summary the README's
benchmark table shows and the numbers it came from; ``scripts/readme_figures.py`` renders the table from
these files (and a test checks the README matches them).
"""

from __future__ import annotations

import json
import platform
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

RESULTS = Path(__file__).resolve().parent / "results"

__all__ = ["RESULTS", "save_result"]


def save_result(name: str, *, benchmark: str, result: str, data: dict[str, Any] | None = None,
                order: int = 1000, source: str = "measured by the benchmark") -> Path:
    """Write ``results/NAME.json``: the README row (``benchmark``, ``result``), its ``data`` and context."""
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / f"{name}.json"
    record = {
        "benchmark": benchmark, "result": result, "order": order, "source": source, "data": data or {},
        "measured_at": datetime.now(UTC).isoformat(timespec="seconds"), "machine": platform.machine(),
    }  # fmt: skip
    path.write_text(json.dumps(record, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return path
