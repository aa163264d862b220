"""One unit of grasp-validation work and its stored row: a trial, a render, or both, run in a worker
process (sim/worker.py hands these to an executor, sim/executors.py).

The trial function is named as "module:function" (resolved inside the worker) or is any picklable
module-level callable ``fn(obj, plan, *, seed) -> result``, where ``result`` is a TrialResult-like object
(``to_dict()``) or a dict.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib
import json
import re
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from kb.errors import SimulationError
from kb.features import ObjectRecord
from sim.grasps import GraspPlan
from sim.planner import PLANNER_VERSION

__all__ = [
    "row_details","DEFAULT_RENDER", "DEFAULT_TRIAL", "Trial", "TrialTask", "current_hand_version", "image_name", "run_task"]

#: The trial function, as "module:function", resolved inside each worker process.
DEFAULT_TRIAL = "sim.trial:run_trial"
DEFAULT_RENDER = "sim.render:render_trial"
#: Rendered image size (pixels) for reports.
IMAGE_SIZE = (480, 360)

Trial = Callable[..., Any] | str


def resolve(fn: Trial) -> Callable[..., Any]:
    if callable(fn):
        return fn
    module, _, name = str(fn).partition(":")
    return getattr(importlib.import_module(module), name)


def current_hand_version() -> str:
    """The simulated hand's version string (stored with every result; a new hand re-runs the trials)."""
    try:
        hand = importlib.import_module("sim.hand")
    except ModuleNotFoundError:
        return ""
    for attr in ("HAND_VERSION", "VERSION", "__version__"):
        if hasattr(hand, attr):
            return str(getattr(hand, attr))
    return ""


def image_name(object_name: str, grasp_type: str) -> str:
    """A safe file name for an object's grasp image (names may hold any text from scraped pages)."""
    slug = re.sub(r"[^a-z0-9]+", "-", object_name.lower()).strip("-")[:40] or "object"
    digest = hashlib.sha1(f"{object_name}\x00{grasp_type}".encode()).hexdigest()[:10]
    return f"{slug}-{grasp_type}-{digest}.png"


@dataclass(frozen=True)
class TrialTask:
    """One unit of work for a worker process: a trial, a render, or both."""

    obj: ObjectRecord
    plan: GraspPlan
    rank: int
    seed: int
    features_hash: str
    object_id: int | None = None
    trial: Trial | None = DEFAULT_TRIAL  # None: render only (the trial is stored already)
    render: Trial | None = None
    image_path: str | None = None
    hand_version: str = ""


def _result_dict(result: Any) -> dict[str, Any]:
    if isinstance(result, dict):
        return dict(result)
    if hasattr(result, "to_dict"):
        return dict(result.to_dict())
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        return dataclasses.asdict(result)
    raise SimulationError(f"trial returned {type(result).__name__}, not a result record")


def _num(value: Any) -> float | None:
    try:
        out = float(value)
    except (TypeError, ValueError):
        return None
    return None if out != out else out  # NaN -> None


def run_task(task: TrialTask) -> dict[str, Any]:
    """Run one task (in a worker process) and return its ``grasp_validations`` row.

    A :class:`SimulationError` from the trial is a result (outcome ``error``) and is stored; any other
    exception is a bug or a missing dependency: the row gets ``store = False`` so a rerun tries again.
    """
    row: dict[str, Any] = {
        "object_name": task.obj.name,
        "object_id": task.object_id,
        "features_hash": task.features_hash,
        "grasp_type": task.plan.grasp_type,
        "family": task.plan.family,
        "rank": task.rank,
        "seed": task.seed,
        "planner_version": PLANNER_VERSION,
        "hand_version": task.hand_version,
        "store": task.trial is not None,
    }
    details: dict[str, Any] = {"plan": task.plan.to_dict()}
    if task.trial is not None:
        start, cpu_start = time.perf_counter(), time.process_time()
        try:
            res = _result_dict(resolve(task.trial)(task.obj, task.plan, seed=task.seed))
        except SimulationError as err:
            res = {"outcome": "error", "success": False, "reason": str(err)}
        except Exception as err:  # noqa: BLE001 - reported, not stored
            res = {"outcome": "error", "success": False, "reason": f"{type(err).__name__}: {err}"}
            row["store"] = False
        outcome = res.get("outcome") or ("success" if res.get("success") else "failure")
        row.update(
            outcome=outcome,
            success=bool(res.get("success")) and outcome == "success",
            reason=res.get("reason"),
            slip_cm=_num(res.get("slip_cm")),
            rotation_deg=_num(res.get("rotation_deg")),
            grip_force_n=_num(res.get("grip_force_n", task.plan.grip_force_n)),
            max_contact_force_n=_num(res.get("max_contact_force_n")),
            simulator=res.get("simulator"),
        )
        if res.get("hand_version") and str(res["hand_version"]) != task.hand_version:
            details["trial_hand_version"] = str(res["hand_version"])  # the key keeps the planned version
        for key in (
            "program", "lifted", "perturbation", "closed_posture", "sim_time_s", "wall_time_s", "protocol",
            "failed_directions",
        ):
            if key in res:
                details[key] = res[key]
        details.setdefault("wall_time_s", round(time.perf_counter() - start, 4))
        details["cpu_time_s"] = round(time.process_time() - cpu_start, 4)
    if task.render is not None and task.image_path:
        try:
            png = resolve(task.render)(
                task.obj, task.plan, seed=task.seed, width=IMAGE_SIZE[0], height=IMAGE_SIZE[1]
            )
            path = Path(task.image_path)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(png)
            details["image"] = path.name
        except Exception as err:  # noqa: BLE001 - a report without one image is still a report
            details["image_error"] = f"{type(err).__name__}: {err}"
    row["details"] = json.dumps(details, default=str)
    return row


def row_details(row: Mapping[str, Any]) -> dict[str, Any]:
    """The ``details`` JSON of a stored grasp-validation row as a dict ({} when absent or malformed)."""
    raw = row.get("details")
    if isinstance(raw, Mapping):
        return dict(raw)
    try:
        out = json.loads(raw) if raw else {}
    except (TypeError, ValueError):
        return {}
    return out if isinstance(out, dict) else {}
