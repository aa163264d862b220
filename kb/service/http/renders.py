"""The cost cap of ``GET /grasp/render``: a few renders at a time, and a cache of the ones made.

A render runs a MuJoCo trial to the end of its hold and draws it: 0.3-1 CPU-second. So the service makes
at most ``max_concurrent`` at once; a request beyond that is refused at once with
:class:`~kb.errors.RenderBusy` (HTTP 503 and ``Retry-After``) rather than queued behind them. Renders made
are kept (least recently used first out, at most ``max_entries``) under a key that changes whenever the
picture would: the object's name and features, the grasp type, the planner and hand versions. A catalog
change that leaves the object as it was keeps its renders; one that changes it makes a new key.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable

from kb.errors import RenderBusy

__all__ = ["RenderCache"]


class RenderCache:
    """Thread-safe: the routes run in worker threads. ``get_or_render(key, render)`` returns
    ``(png, hit)``."""

    def __init__(self, max_concurrent: int = 2, max_entries: int = 64, retry_after_s: int = 2):
        if max_concurrent < 1 or max_entries < 0:
            raise ValueError("max_concurrent must be at least 1 and max_entries at least 0")
        self.max_concurrent = max_concurrent
        self.max_entries = max_entries
        self.retry_after_s = retry_after_s
        self._slots = threading.BoundedSemaphore(max_concurrent)
        self._lock = threading.Lock()
        self._pngs: OrderedDict[Hashable, bytes] = OrderedDict()
        self.hits = 0
        self.misses = 0

    def __len__(self) -> int:
        with self._lock:
            return len(self._pngs)

    def get_or_render(self, key: Hashable, render: Callable[[], bytes]) -> tuple[bytes, bool]:
        """The cached PNG for ``key``, else ``render()``'s (then cached), with whether it was a hit.
        Raises :class:`RenderBusy` when ``max_concurrent`` renders are already running."""
        with self._lock:
            png = self._pngs.get(key)
            if png is not None:
                self._pngs.move_to_end(key)
                self.hits += 1
                return png, True
        if not self._slots.acquire(blocking=False):
            raise RenderBusy(
                f"{self.max_concurrent} grasp renders are running (each costs about a CPU-second): "
                f"retry in {self.retry_after_s} s",
                retry_after_s=self.retry_after_s,
            )
        try:
            png = render()
        finally:
            self._slots.release()
        with self._lock:
            self.misses += 1
            if self.max_entries:
                self._pngs[key] = png
                self._pngs.move_to_end(key)
                while len(self._pngs) > self.max_entries:
                    self._pngs.popitem(last=False)
        return png, False
