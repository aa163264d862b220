"""Timing helpers the benchmarks share (imported as ``timing`` from the benchmark scripts' folder)."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

__all__ = ["median_cpu_s"]


def median_cpu_s(func: Callable[[], object], repeat: int) -> float:
    """Median CPU seconds of ``func`` over ``repeat`` calls (process time: the machine's 2 cores are shared,
    and wall time under load says more about the neighbours than about the code measured)."""
    times = []
    for _ in range(repeat):
        start = time.process_time()
        func()
        times.append(time.process_time() - start)
    return statistics.median(times)
