"""The cost model by which :class:`recall.search.JPIndex` picks a plan per query: estimated CPU time
in ns of each plan, from counts taken before scoring, and the rules that compare them.

The figures were fitted on this machine to each plan and each step forced on the same synthetic
descriptions at 100k and 1M objects (CPU time, load < 2; ``recall/RECALL.md``, "Plans"). m = the
stated features.

* **scan**: :data:`SCAN_NS` per row for each stated number, for the stated categories together (one
  gather over the category combinations) and for the selection; the first of each pair up to
  :data:`CACHE_ROWS` rows, the second above (the columns outgrow the cache);
* **window**: :data:`WINDOW_NS` per row-feature of its lead window (scattered reads; likewise by size;
  the fit gave 6.5 above the cache, 8.0 was faster in an interleaved A/B at 1M: 5 % on described
  descriptions, 14 % on sizes only, the window's time varying more than its rows);
* **probe** (the cells' bounds, then the rows of the nearest cells scored): :data:`PROBE_NS` + m ×
  (:data:`PROBE_FEATURE_NS` + :data:`BOUND_CELL_NS` per cell);
* **cells** after the probe: :data:`CELLS_FIXED_NS` + :data:`CELL_NS` per cell (their order) + m ×
  :data:`CELLS_FEATURE_NS` + :data:`CELLS_NS` per row-feature of the cells within the bound (an upper
  bound of its work: the bound only tightens; in the cache the batches' fixed costs count more);
* every plan but the scan: :data:`PLAN_FIXED_NS`.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PlanCosts", "after_probe", "before_probe"]

SCAN_NS = {"numeric": (0.8, 1.0), "categories": (1.0, 2.25), "row": (0.9, 0.6)}
WINDOW_NS = (4.0, 8.0)
CACHE_ROWS = 1 << 18
PROBE_NS, PROBE_FEATURE_NS, BOUND_CELL_NS = 80_000.0, 11_000.0, 1.8
CELLS_FIXED_NS, CELL_NS, CELLS_FEATURE_NS, CELLS_NS = 40_000.0, 20.0, 15_000.0, (3.5, 2.5)
PLAN_FIXED_NS = 50_000.0
#: The scan's estimate is within ~10 % of its time; the others' vary 2-4x with the bound (in the cache
#: their p99 made the engine's p99 at 100k 0.9-1.0x the plain float32 scan's under load), so they run
#: only when estimated below this fraction of the scan (up to / above CACHE_ROWS rows; interleaved A/B
#: on 200 described descriptions, synthetic: 0.5 against 1.0 at 100k, 28 % less CPU in all and p99 0.78
#: against 1.44 ms; 0.7 against 1.0 at 1M, 5 % less).
SCAN_TRUST = (0.5, 0.7)
#: Above CACHE_ROWS rows, when the cell plan's estimate exceeds the scan's by at most this factor, the
#: cell plan is tried first: it gives up for the scan once it has read a quarter of the rows the scan's
#: time would pay for and the rows it has read and has left within the bound are still more (at most
#: 1.25 scans in all). Below, its cost per row varies too much with the bound for a trial to pay.
CELLS_TRIAL = 2.0


@dataclass(frozen=True)
class PlanCosts:
    """Estimated CPU time (ns) of each plan for one query on one index: its ``rows`` and ``cells``, the
    stated ``numbers`` and ``features`` (m), whether any category is stated."""

    rows: int
    cells: int
    numbers: int
    features: int
    categories: bool

    @property
    def big(self) -> bool:
        """Above CACHE_ROWS rows: the second figure of each pair."""
        return self.rows > CACHE_ROWS

    @property
    def scan(self) -> float:
        big = self.big
        per_row = SCAN_NS["numeric"][big] * self.numbers + SCAN_NS["row"][big]
        return self.rows * (per_row + (SCAN_NS["categories"][big] if self.categories else 0.0))

    @property
    def trusted_scan(self) -> float:
        """The scan's estimate as the comparisons see it (:data:`SCAN_TRUST`)."""
        return self.scan * SCAN_TRUST[self.big]

    def window(self, rows_read: float) -> float:
        return PLAN_FIXED_NS + WINDOW_NS[self.big] * rows_read * self.features

    @property
    def probe(self) -> float:
        return PROBE_NS + self.features * (PROBE_FEATURE_NS + BOUND_CELL_NS * self.cells)

    @property
    def cells_fixed(self) -> float:
        return CELLS_FIXED_NS + CELL_NS * self.cells + self.features * CELLS_FEATURE_NS

    def cell_search(self, rows_within: int) -> float:
        return self.cells_fixed + CELLS_NS[self.big] * rows_within * self.features

    @property
    def give_up_rows(self) -> float:
        """Rows of cells that cost as much as the scan (a trial's limit)."""
        return self.scan / (CELLS_NS[self.big] * self.features)


def before_probe(costs: PlanCosts, window_rows: int) -> str | None:
    """The plan to run before probing the cells, given the lead window's rows at the first bound:
    "window" when it costs at most the probe and the scan, "scan" when the scan costs at most the probe
    and the cell plan's fixed part (then no plan after the probe can be cheaper), else None (probe)."""
    scan = costs.trusted_scan
    if costs.window(window_rows) <= min(costs.probe, scan):
        return "window"
    if scan <= costs.probe + costs.cells_fixed:
        return "scan"
    return None


def after_probe(
    costs: PlanCosts, window_rows: int, cell_rows: int, zero_rows: float | None
) -> tuple[str, bool]:
    """(plan, trial) after the probe: the cheapest of window, cells, scan and, when the bound is 0
    (``zero_rows`` not None: the rows the zero plan reads), zero; the scan at a bound of 0 is the zero
    plan (the k lowest rows at 0). ``trial``: the cell plan is tried before the scan (:data:`CELLS_TRIAL`)."""
    cost = {
        "window": costs.window(window_rows),
        "cells": costs.cell_search(cell_rows),
        "scan": costs.trusted_scan,
    }
    if zero_rows is not None:
        cost["zero"] = costs.window(min(zero_rows, costs.rows))
    plan = min(cost, key=cost.__getitem__)
    if plan == "scan" and zero_rows is not None:
        return "zero", False
    if plan == "scan" and costs.big and cost["cells"] <= CELLS_TRIAL * costs.scan:
        return "cells", True
    return plan, False
