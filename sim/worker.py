"""The grasp validation worker: objects x candidate grasps x seeds, in parallel, stored, resumable.

:func:`validate` plans the ``top`` grasps of every requested object (sim/planner.py), skips the trials
already stored in the knowledge base for the same (object, grasp type, seed, hand version, features
hash), runs the rest through an :class:`~sim.executors.Executor` and stores every result in the
``grasp_validations`` table. Results are written in batches (every ``flush_every`` results or
``flush_seconds``), each through a short write connection: the database is never held while simulating,
and a run that is interrupted keeps what it finished, so running it again resumes.

The trial function runs in the worker processes (one :class:`~sim.task.TrialTask` each, sim/task.py). By
default it is ``sim.trial:run_trial`` (MuJoCo is imported there, not here); any picklable module-level
callable ``fn(obj, plan, *, seed) -> result`` can be injected instead, where ``result`` is a
TrialResult-like object (``to_dict()``) or a dict.
"""

from __future__ import annotations

import dataclasses
import json
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from kb.catalog import KnowledgeBase, features_hash
from kb.errors import ObjrecallError
from kb.features import ObjectRecord
from sim.choice import ChoiceSummary, GraspChoice, choose, summarize_choices
from sim.executors import Executor, make_executor
from sim.planner import plan_grasps
from sim.protocols import protocol_named
from sim.task import (
    DEFAULT_RENDER,
    DEFAULT_TRIAL,
    Trial,
    TrialTask,
    current_hand_version,
    image_name,
    run_task,
)
from sim.task import row_details as _details

__all__ = [
    "DEFAULT_TOP",
    "DEFAULT_TRIAL",
    "TrialTask",
    "ValidationSummary",
    "current_hand_version",
    "image_name",
    "run_task",
    "validate",
]

#: Candidate grasps validated per object.
DEFAULT_TOP = 3
#: The trial function of each protocol other than the default (sim/protocols.py).
PROTOCOL_TRIALS = {"six_direction": "sim.trial:run_six_direction_trial"}


@dataclass
class ValidationSummary:
    """What a validation run did. ``results`` holds every requested trial's row (run now or stored
    before), with the object's shape and material, ordered by object, rank and seed."""

    objects: int = 0
    trials: int = 0
    skipped: int = 0
    ran: int = 0
    succeeded: int = 0
    failed: int = 0
    errors: int = 0
    not_stored: int = 0
    wall_time_s: float = 0.0
    hand_version: str = ""
    workers: int = 1
    executor: str = ""
    report: Path | None = None
    results: list[dict[str, Any]] = field(default_factory=list)
    choices: list[GraspChoice] = field(default_factory=list)

    @property
    def choice_summary(self) -> ChoiceSummary:
        """How often the first choice holds, a validated choice exists, and they differ."""
        return summarize_choices(self.choices)

    def to_dict(self, *, with_results: bool = True) -> dict[str, Any]:
        d = dataclasses.asdict(self)
        d["report"] = str(self.report) if self.report else None
        d["choices"] = [c.to_dict() for c in self.choices]
        d["choice_summary"] = self.choice_summary.to_dict()
        if with_results:
            d["results"] = [{**r, "details": _details(r)} for r in self.results]
        else:
            d.pop("results")
        return d


def _objects(kb: KnowledgeBase, names: Sequence[str] | str | None) -> list[ObjectRecord]:
    if names is None or names == "all" or (not isinstance(names, str) and len(names) == 0):
        return kb.list_objects()
    if isinstance(names, str):
        names = [names]
    seen: dict[str, ObjectRecord] = {}
    for name in names:
        rec = kb.get_object(name)
        seen.setdefault(rec.name, rec)
    return list(seen.values())


def _object_ids(kb: KnowledgeBase) -> dict[str, int]:
    with kb.connect() as con:
        return {name: oid for oid, name in con.execute("SELECT id, name FROM objects").fetchall()}


def _stored(kb: KnowledgeBase, names: Iterable[str]) -> dict[tuple, dict[str, Any]]:
    """Stored rows keyed by (object, grasp type, seed, hand version, features hash)."""
    names = list(names)
    if not names:
        return {}
    with kb.connect() as con:
        cur = con.execute("SELECT * FROM grasp_validations WHERE list_contains(?, object_name)", [names])
        cols = [d[0] for d in cur.description]
        rows = [dict(zip(cols, r, strict=True)) for r in cur.fetchall()]
    return {
        (r["object_name"], r["grasp_type"], r["seed"], r["hand_version"], r["features_hash"]): r for r in rows
    }


def _progress(enabled: bool, total: int):
    from contextlib import nullcontext

    if not enabled or total == 0:
        return nullcontext(None)
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    return Progress(
        TextColumn("[bold]grasp trials"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("{task.fields[last]}"),
        TimeRemainingColumn(),
        console=Console(stderr=True),
        transient=False,
    )


def _tasks_for(
    objects: Sequence[ObjectRecord],
    *,
    top: int,
    seeds: Sequence[int],
    hand: str,
    ids: dict[str, int],
    stored: dict[tuple, dict[str, Any]],
    image_dir: Path | None,
    trial: Trial,
    render: Trial | None,
) -> tuple[list[TrialTask], list[tuple], int]:
    """The tasks still to run (trials not stored; a render of each object's first choice when a report
    is wanted and its image is missing), every requested result key, and how many were stored."""
    tasks: list[TrialTask] = []
    wanted: list[tuple] = []
    skipped = 0
    for obj in objects:
        fh = features_hash(obj)
        for rank, plan in enumerate(plan_grasps(obj, top=top)):
            for seed in seeds:
                key = (obj.name, plan.grasp_type, seed, hand, fh)
                wanted.append(key)
                want_image = image_dir is not None and render is not None and rank == 0 and seed == seeds[0]
                image_path = str(image_dir / image_name(obj.name, plan.grasp_type)) if want_image else None
                if key in stored:
                    skipped += 1
                    if image_path and not Path(image_path).exists():  # render only: the trial is stored
                        tasks.append(
                            TrialTask(obj, plan, rank, seed, fh, ids.get(obj.name), None, render, image_path, hand)
                        )
                    continue
                task_render = render if image_path else None
                tasks.append(
                    TrialTask(obj, plan, rank, seed, fh, ids.get(obj.name), trial, task_render, image_path, hand)
                )
    return tasks, wanted, skipped


def _row_key(row: dict[str, Any]) -> tuple:
    return (row["object_name"], row["grasp_type"], row["seed"], row["hand_version"], row["features_hash"])


class _Batches:
    """Result rows buffered and written to the knowledge base every ``every`` rows or ``seconds``."""

    def __init__(self, kb: KnowledgeBase, every: int, seconds: float, clock: Callable[[], float]):
        self.kb, self.every, self.seconds, self.clock = kb, every, seconds, clock
        self.buffer: list[dict[str, Any]] = []
        self.last = clock()

    def add(self, row: dict[str, Any]) -> None:
        self.buffer.append(row)
        if len(self.buffer) >= self.every or self.clock() - self.last >= self.seconds:
            self.flush()

    def flush(self) -> None:
        rows = [r for r in self.buffer if r.get("store")]
        if rows:
            self.kb.record_grasp_results([{k: v for k, v in r.items() if k != "store"} for r in rows])
        self.buffer.clear()
        self.last = self.clock()


def _run(
    ex: Executor, tasks: list[TrialTask], summary: ValidationSummary, batches: _Batches, progress: bool
) -> tuple[dict[tuple, dict[str, Any]], dict[tuple, dict[str, Any]]]:
    """Run ``tasks`` on ``ex``, counting outcomes into ``summary`` and storing trial rows through
    ``batches``. Returns the new trial rows and the render-only details, both by result key."""
    new_rows: dict[tuple, dict[str, Any]] = {}
    images: dict[tuple, dict[str, Any]] = {}
    try:
        with _progress(progress, len(tasks)) as bar:
            job = bar.add_task("trials", total=len(tasks), last="") if bar is not None else None
            for row in ex.map(run_task, tasks):
                key = _row_key(row)
                if "outcome" not in row:  # render-only task
                    images[key] = json.loads(row["details"])
                else:
                    summary.ran += 1
                    outcome = row["outcome"]
                    summary.succeeded += outcome == "success"
                    summary.failed += outcome == "failure"
                    summary.errors += outcome == "error"
                    summary.not_stored += not row["store"]
                    new_rows[key] = row
                    batches.add(row)
                if bar is not None:
                    bar.update(job, advance=1, last=f"{row['object_name'][:30]} {row['grasp_type']}")
    finally:
        batches.flush()
    return new_rows, images


def _with_images(row: dict[str, Any], image: dict[str, Any] | None) -> dict[str, Any]:
    row = {k: v for k, v in row.items() if k != "store"}
    if image:
        details = _details(row)
        details.update({k: v for k, v in image.items() if k in ("image", "image_error")})
        row["details"] = json.dumps(details, default=str)
    return row


def _validated_renders(
    results: list[dict[str, Any]], objects: Sequence[ObjectRecord], image_dir: Path, render: Trial, hand: str
) -> list[TrialTask]:
    """Render tasks for each validated choice that differs from the first choice (the first choice is
    rendered with its trial), so the report can show both."""
    by_name = {o.name: o for o in objects}
    tasks = []
    for c in choose(results):
        if c.validated is None or not c.differs:
            continue
        row = next(r for r in results if r["object_name"] == c.object_name and r["grasp_type"] == c.validated)
        if "image" in _details(row):
            continue
        obj = by_name[c.object_name]
        plan = next(p for p in plan_grasps(obj) if p.grasp_type == c.validated)
        path = image_dir / image_name(obj.name, plan.grasp_type)
        rank, seed, oid = int(row["rank"]), int(row["seed"]), row.get("object_id")
        tasks.append(TrialTask(obj, plan, rank, seed, row["features_hash"], oid, None, render, str(path), hand))
    return tasks


def validate(
    kb: KnowledgeBase,
    names: Sequence[str] | str | None = None,
    *,
    top: int = DEFAULT_TOP,
    seeds: Iterable[int] = (0,),
    workers: int | None = None,
    executor: Executor | str = "local",
    address: str | None = None,
    report_dir: str | Path | None = None,
    progress: bool = True,
    limit: int | None = None,
    trial: Trial = DEFAULT_TRIAL,
    render: Trial | None = DEFAULT_RENDER,
    hand_version: str | None = None,
    protocol: str | None = None,
    flush_every: int = 25,
    flush_seconds: float = 5.0,
    clock: Callable[[], float] = time.monotonic,
) -> ValidationSummary:
    """Validate the ``top`` planned grasps of ``names`` (None, ``"all"`` or [] = every object) for each
    seed, store the results and optionally write an HTML report to ``report_dir``.

    ``executor`` is an :class:`Executor` or a name (``local``, ``serial``, ``ray``; ``workers`` and
    ``address`` configure it). ``limit`` stops after that many new trials (the rest resume later).
    ``render`` renders the first choice of each object into the report, and the validated choice where
    it differs (only with ``report_dir``). ``summary.choices`` holds each object's first and validated
    choice (sim/choice.py). ``protocol`` names the success rule (sim/protocols.py; None: the default,
    ``lift_push``, with ``trial`` as given): another protocol runs its own trial function and stores its
    results under the hand version plus the protocol's tag, apart from the default's. Raises
    ObjectNotFound for an unknown name, SimulationError for an unknown protocol.
    """
    t0 = clock()
    rule = protocol_named(protocol) if protocol is not None else None
    if rule is not None and rule.version_tag:
        trial = PROTOCOL_TRIALS[rule.name]
    seeds = list(dict.fromkeys(int(s) for s in seeds))
    if top < 1:
        raise ObjrecallError(f"top must be at least 1, not {top}")
    objects = _objects(kb, names)
    hand = current_hand_version() if hand_version is None else hand_version
    if rule is not None:
        hand += rule.version_tag
    stored = _stored(kb, [o.name for o in objects])
    report_path = Path(report_dir) if report_dir is not None else None
    image_dir = report_path / "images" if report_path is not None else None
    tasks, wanted, skipped = _tasks_for(
        objects, top=top, seeds=seeds, hand=hand, ids=_object_ids(kb), stored=stored,
        image_dir=image_dir, trial=trial, render=render,
    )  # fmt: skip
    tasks = _limited(tasks, limit)
    executor_name, ex, owns = _executor(executor, workers, address)
    summary = ValidationSummary(
        objects=len(objects),
        trials=len(wanted),
        skipped=skipped,
        hand_version=hand,
        workers=getattr(ex, "workers", 1),
        executor=executor_name,
    )
    meta = {o.name: {"shape": o.shape, "material": o.material} for o in objects}
    batches = _Batches(kb, flush_every, flush_seconds, clock)
    try:
        new_rows, images = _run(ex, tasks, summary, batches, progress)
        results = []
        for key in wanted:
            row = new_rows.get(key) or stored.get(key)
            if row is not None:  # else not run (limit) or not stored
                results.append({**_with_images(row, images.get(key)), **meta.get(row["object_name"], {})})
        if image_dir is not None and render is not None:
            results = _with_validated_renders(ex, results, objects, image_dir, render, hand, summary, batches)
    finally:
        if owns:
            ex.close()
    summary.results = results
    summary.choices = choose(results)
    if report_path is not None:
        from sim.report import write_report

        summary.report = write_report(results, report_path)
    summary.wall_time_s = round(clock() - t0, 3)
    return summary


def _limited(tasks: list, limit: int | None) -> list:
    """``tasks`` with at most ``limit`` trials (render-only tasks kept): the rest resume in a later run."""
    if limit is None:
        return tasks
    keep = {id(t) for t in [t for t in tasks if t.trial is not None][: max(0, int(limit))]}
    return [t for t in tasks if t.trial is None or id(t) in keep]


def _executor(executor: Executor | str, workers: int | None, address: str | None) -> tuple[str, Executor, bool]:
    """(its name, the executor, whether this run owns it and closes it) for an executor or its name."""
    if isinstance(executor, str):
        return executor, make_executor(executor, workers=workers, address=address), True
    return type(executor).__name__, executor, False


def _with_validated_renders(ex, results, objects, image_dir, render, hand, summary, batches) -> list:
    """``results`` with a rendering of each object's validated choice where it differs from the first."""
    extra = _validated_renders(results, objects, image_dir, render, hand)
    _, more = _run(ex, extra, summary, batches, progress=False)
    return [_with_images(r, more.get(_row_key(r))) for r in results]
