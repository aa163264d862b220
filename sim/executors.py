"""Where grasp trials run: one small interface, a local process pool, and Ray for clusters.

An :class:`Executor` maps a picklable, module-level function over items and yields the results **as they
complete** (not in input order: every result names its own object and grasp). The validation worker
(sim/worker.py) only talks to this interface, so a trial function can be swapped in (tests inject a
trivial one) and the same worker runs on one core, on all local cores, or on a Ray cluster.

- :class:`SerialExecutor`: in this process, one item at a time (debugging, ``--workers 1``).
- :class:`LocalProcessExecutor`: ``concurrent.futures.ProcessPoolExecutor`` with the ``forkserver``
  (Linux) or ``spawn`` start method: each worker process imports MuJoCo itself, never a forked copy of a
  parent that may hold an OpenGL context or a DuckDB connection.
- :class:`RayExecutor`: Ray tasks on a cluster (``address``) or a local Ray; Ray is an optional extra
  (``pip install 'objrecall[ray]'``) imported only when this executor is made.
"""

from __future__ import annotations

import itertools
import multiprocessing
import os
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any, Protocol, TypeVar

from kb.errors import SimulationError

__all__ = [
    "EXECUTORS",
    "Executor",
    "LocalProcessExecutor",
    "RayExecutor",
    "SerialExecutor",
    "default_workers",
    "make_executor",
]

T = TypeVar("T")
R = TypeVar("R")



def _bounded_map(
    items: Iterable[T],
    limit: int,
    submit: Callable[[T], Any],
    wait_some: Callable[[list[Any]], tuple[Iterable[Any], list[Any]]],
    result: Callable[[Any], R],
    cancel: Callable[[Any], Any],
) -> Iterator[R]:
    """Keep at most ``limit`` tasks in flight, yield each result as its task finishes, and cancel the
    tasks still pending when the consumer stops early (shared by the process-pool and Ray executors)."""
    pending: list[Any] = []
    it = iter(items)
    try:
        while True:
            pending.extend(submit(item) for item in itertools.islice(it, limit - len(pending)))
            if not pending:
                return
            done, pending = wait_some(pending)
            for task in done:
                yield result(task)
    finally:
        for task in pending:
            cancel(task)

class Executor(Protocol):
    """Runs ``fn`` over ``items``; results come back in completion order. Use as a context manager."""

    workers: int

    def map(self, fn: Callable[[T], R], items: Iterable[T]) -> Iterator[R]: ...

    def close(self) -> None: ...

    def __enter__(self) -> Executor: ...

    def __exit__(self, *exc: object) -> None: ...


def default_workers() -> int:
    """Cores this process may use (the scheduler affinity), at least 1."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)


class _Base:
    workers = 1

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class SerialExecutor(_Base):
    """Runs every item in this process, in order."""

    def map(self, fn: Callable[[T], R], items: Iterable[T]) -> Iterator[R]:
        for item in items:
            yield fn(item)


class LocalProcessExecutor(_Base):
    """A pool of ``workers`` local processes (forkserver where available, else spawn).

    At most ``2 * workers`` items are in flight, so a huge item list is not pickled up front and an
    interrupted run (Ctrl-C, or a consumer that stops early) leaves little queued work behind.
    """

    def __init__(self, workers: int | None = None, *, start_method: str | None = None):
        self.workers = int(workers) if workers else default_workers()
        if self.workers < 1:
            raise ValueError(f"workers must be at least 1, not {workers}")
        methods = multiprocessing.get_all_start_methods()
        self.start_method = start_method or ("forkserver" if "forkserver" in methods else "spawn")
        self._pool: ProcessPoolExecutor | None = None

    def _get_pool(self) -> ProcessPoolExecutor:
        if self._pool is None:
            ctx = multiprocessing.get_context(self.start_method)
            self._pool = ProcessPoolExecutor(max_workers=self.workers, mp_context=ctx)
        return self._pool

    def map(self, fn: Callable[[T], R], items: Iterable[T]) -> Iterator[R]:
        def first_done(pending: list[Future]) -> tuple[Iterable[Future], list[Future]]:
            done, rest = wait(pending, return_when=FIRST_COMPLETED)
            return done, list(rest)

        return _bounded_map(
            items, 2 * self.workers, lambda item: self._get_pool().submit(fn, item), first_done, Future.result, Future.cancel
        )

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None


class RayExecutor(_Base):
    """Ray tasks: on the cluster at ``address`` (``"auto"``, ``"ray://host:10001"``), or a local Ray.

    ``workers`` caps the tasks in flight (default: the cluster's CPUs). If Ray is already initialised in
    this process (a test's ``ray.init(...)``), it is used as it is and left running on close.
    """

    def __init__(self, address: str | None = None, *, workers: int | None = None, **init_kwargs: Any):
        try:
            import ray
        except ImportError:
            raise SimulationError(
                "the Ray executor needs Ray: pip install 'objrecall[ray]' (or use --executor local)"
            ) from None
        self._ray = ray
        self._owns = False
        if not ray.is_initialized():
            init_kwargs.setdefault("include_dashboard", False)
            init_kwargs.setdefault("log_to_driver", False)
            ray.init(address=address, **init_kwargs)
            self._owns = True
        cpus = int(ray.cluster_resources().get("CPU", 1))
        self.workers = int(workers) if workers else max(1, cpus)

    def map(self, fn: Callable[[T], R], items: Iterable[T]) -> Iterator[R]:
        ray = self._ray
        remote = ray.remote(num_cpus=1)(fn)
        return _bounded_map(
            items, 2 * self.workers, remote.remote, lambda pending: ray.wait(pending, num_returns=1), ray.get, ray.cancel
        )

    def close(self) -> None:
        if self._owns and self._ray.is_initialized():
            self._ray.shutdown()
            self._owns = False


#: Names accepted by ``--executor``.
EXECUTORS = ("local", "serial", "ray")


def make_executor(kind: str = "local", *, workers: int | None = None, address: str | None = None) -> Executor:
    """An executor by name: ``local`` (processes; ``workers=1`` runs serially in this process),
    ``serial`` or ``ray`` (``address`` of the cluster, else a local Ray)."""
    if kind == "local":
        if workers == 1:
            return SerialExecutor()
        return LocalProcessExecutor(workers)
    if kind == "serial":
        return SerialExecutor()
    if kind == "ray":
        return RayExecutor(address, workers=workers)
    raise SimulationError(f"unknown executor {kind!r}; expected one of {', '.join(EXECUTORS)}")
