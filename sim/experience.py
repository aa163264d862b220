"""What the validation trials learned, used to choose the planner's first grasp (issue 24).

The planner ranks candidates by rules (sim/planner.py); the trials (sim/trial.py) say which held. An
:class:`Experience` keeps, per **(hand program, object class)**, how many validated candidates held and how
many were tried (a candidate holds when every seed's trial succeeded, as in sim/choice.py). The object
class is the planner's resolved ``shape`` and ``material`` (``thin/paper``, ``radial/glass``, ..., a tiny flat thing apart:
:func:`object_class`); a program, not a grasp type, because merged types run the same hand actions.

**Estimate.** The chance that program ``p`` holds an object of class ``k`` is the posterior mean of a
Beta prior (mean :data:`PRIOR_MEAN`, weight :data:`PRIOR_STRENGTH` pseudo-trials) updated with its counts:
``(held + w m) / (tried + w)``. An unseen pair estimates the prior mean.

**Choice.** The rules' order stands unless the trials clearly disagree: walking the first :data:`WINDOW`
candidates (the ones validation tries, sim.worker.DEFAULT_TOP) in the rules' order, a later candidate
becomes the pick when its estimate is at least :data:`SWITCH_MARGIN` above the current pick's. So an
unseen class, or classes with weak evidence, keep the rules' order, and the first choice changes only
where its program has mostly failed on the class and another has mostly held. Deterministic: counts,
not samples.

The margin, prior and class were chosen on the seed catalog's trials (data written here: sim/PLANNER.md,
"First choice from experience", gives the sweep and the leave-one-object-out figure it yields).
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from kb.errors import SimulationError
from sim.grasp_rules import is_tiny_flat
from sim.programs import program_for

__all__ = [
    "EXPERIENCE_JSON",
    "PRIOR_MEAN",
    "PRIOR_STRENGTH",
    "SWITCH_MARGIN",
    "TINY_SUFFIX",
    "WINDOW",
    "Experience",
    "FirstChoiceMeasure",
    "Outcome",
    "leave_one_object_out",
    "saved_experience",
    "object_class",
    "outcomes",
]

#: Beta(1, 1): before any trial a program is as likely to hold an object of a class as not.
PRIOR_MEAN = 0.5
#: The prior weighs as much as two trials: one failure alone moves a class's estimate from 0.5 to 0.33.
PRIOR_STRENGTH = 2.0
#: A later candidate replaces the pick only when its estimate is this much higher (0.4: e.g. 3 of 3 held,
#: 0.8, against 0 of 1, 0.33, is enough; 1 of 1, 0.67, against 1 of 2, 0.5, is not).
SWITCH_MARGIN = 0.4
#: Candidates the experience may reorder: those validation tries (sim.worker.DEFAULT_TOP).
WINDOW = 3
_EPS = 1e-9
#: The counts of the seed catalog's validation (written by ``benchmarks/sim_bench.py --only choice --save``).
EXPERIENCE_JSON = Path(__file__).resolve().parent / "data" / "experience.json"


#: Suffix of the class of a tiny flat thing (sim.grasp_rules ``is_tiny_flat``: coins, clips).
TINY_SUFFIX = "/tiny"


def object_class(obj: Any) -> str:
    """The class experience is kept for: ``shape/material`` of a resolved object (sim.planned_object
    ``PlannedObject``; an unknown material is ``unknown``), plus :data:`TINY_SUFFIX` for a tiny flat thing
    (at most 3.5 cm long: the planner's tip-pinch row). A coin and a key are both ``thin/metal``, but the
    thumb-index tip pinch that holds coins and clips (3 of 3 in the seed catalog, data written here) pushed
    the key and the credit card out (0 of 2), whose lateral pinch holds: lumped, the coins' trials promoted
    the tip pinch over the key's lateral pinch (sim/PLANNER.md)."""
    base = f"{obj.shape}/{obj.material or 'unknown'}"
    return base + TINY_SUFFIX if is_tiny_flat(obj) else base


@dataclass(frozen=True)
class Outcome:
    """One validated candidate of one object: did its program hold (every seed)?"""

    object_name: str
    program: str
    object_class: str
    rank: int
    holds: bool


def outcomes(rows: Iterable[Mapping[str, Any]], classes: Mapping[str, str]) -> list[Outcome]:
    """Trial rows (``object_name``, ``grasp_type``, ``rank``, ``success``, ``outcome``; any seeds) as one
    outcome per object and candidate, in order of first appearance. ``classes`` maps each object's name to
    its :func:`object_class`; an object missing from it is an error naming it (no guess)."""
    by: dict[tuple[str, str], dict[str, Any]] = {}
    for r in rows:
        name = str(r["object_name"])
        if name not in classes:
            raise SimulationError(f"no object class for {name!r}: pass its features")
        key = (name, program_for(str(r["grasp_type"])).name)
        o = by.setdefault(key, {"rank": int(r.get("rank") or 0), "holds": True})
        o["rank"] = min(o["rank"], int(r.get("rank") or 0))
        if not (r.get("success") and (r.get("outcome") or "success") == "success"):
            o["holds"] = False
    return [Outcome(n, p, classes[n], o["rank"], o["holds"]) for (n, p), o in by.items()]


@dataclass(frozen=True)
class Experience:
    """Counts ``(held, tried)`` per ``(program, object class)``; see the module docstring."""

    counts: Mapping[tuple[str, str], tuple[int, int]] = field(default_factory=dict)

    @classmethod
    def learn(cls, seen: Iterable[Outcome]) -> Experience:
        counts: dict[tuple[str, str], tuple[int, int]] = {}
        for o in seen:
            held, tried = counts.get((o.program, o.object_class), (0, 0))
            counts[(o.program, o.object_class)] = (held + o.holds, tried + 1)
        return cls(counts)

    def without(self, seen: Iterable[Outcome]) -> Experience:
        """These counts less ``seen`` (an object's own outcomes: leave-one-object-out)."""
        counts = dict(self.counts)
        for o in seen:
            held, tried = counts[(o.program, o.object_class)]
            counts[(o.program, o.object_class)] = (held - o.holds, tried - 1)
        return Experience(counts)

    def estimate(self, program: str, klass: str) -> float:
        """Posterior mean chance that ``program`` holds an object of class ``klass``."""
        held, tried = self.counts.get((program, klass), (0, 0))
        return (held + PRIOR_STRENGTH * PRIOR_MEAN) / (tried + PRIOR_STRENGTH)

    def pick(self, programs: Sequence[str], klass: str) -> int:
        """Index of the first choice among ``programs`` (the rules' order, best first): 0 unless a later
        one within :data:`WINDOW` is estimated :data:`SWITCH_MARGIN` or more above the current pick."""
        best = 0
        for j in range(1, min(WINDOW, len(programs))):
            # _EPS: a difference of exactly the margin (11/15 against 1/3) switches despite rounding
            if (
                self.estimate(programs[j], klass) - self.estimate(programs[best], klass)
                >= SWITCH_MARGIN - _EPS
            ):
                best = j
        return best

    def order(self, plans: Sequence[Any], obj: Any) -> list[Any]:
        """``plans`` (GraspPlan, the rules' order) with the experience's pick first and the rest in the
        rules' order; a promoted plan's rationale says why, with the counts."""
        import dataclasses

        klass = object_class(obj)
        programs = [program_for(p.grasp_type).name for p in plans]
        j = self.pick(programs, klass) if plans else 0
        if j == 0:
            return list(plans)
        first, displaced = plans[j], plans[0]
        held, tried = self.counts.get((programs[j], klass), (0, 0))
        held0, tried0 = self.counts.get((programs[0], klass), (0, 0))
        line = (
            f"experience: on {klass} objects the {programs[j]} program held {held} of {tried} validated "
            f"candidates, the rules' first choice's {programs[0]} {held0} of {tried0}, so it goes first "
            f"(estimates {self.estimate(programs[j], klass):.2f} vs {self.estimate(programs[0], klass):.2f}; "
            f"sim/experience.py)"
        )
        promoted = dataclasses.replace(first, rationale=(*first.rationale, line))
        return [promoted, displaced, *[p for k, p in enumerate(plans) if k not in (0, j)]]

    def to_dict(self) -> dict[str, Any]:
        rows = [
            {"program": p, "object_class": k, "held": h, "tried": t}
            for (p, k), (h, t) in sorted(self.counts.items())
        ]
        return {"prior_mean": PRIOR_MEAN, "prior_strength": PRIOR_STRENGTH, "margin": SWITCH_MARGIN,
                "window": WINDOW, "counts": rows}  # fmt: skip

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> Experience:
        """Read :meth:`to_dict`'s form; a malformed count (missing key, not a whole number, not
        0 <= held <= tried) is a SimulationError naming it."""
        counts = {}
        for row in d.get("counts", []):
            try:
                held, tried, key = (
                    int(row["held"]),
                    int(row["tried"]),
                    (str(row["program"]), str(row["object_class"])),
                )
            except (KeyError, TypeError, ValueError) as e:
                raise SimulationError(f"experience count {row!r} is malformed: {e}") from e
            if not 0 <= held <= tried:
                raise SimulationError(f"experience count {row!r}: held must be between 0 and tried")
            counts[key] = (held, tried)
        return cls(counts)

    def save(self, path: str | Path = EXPERIENCE_JSON) -> Path:
        path = Path(path)
        path.write_text(json.dumps(self.to_dict(), indent=1) + "\n")
        return path

    @classmethod
    def load(cls, path: str | Path = EXPERIENCE_JSON) -> Experience:
        """The saved counts; a missing file is an empty experience (the rules' order); a file that is not
        JSON is a SimulationError naming it."""
        path = Path(path)
        if not path.exists():
            return cls()
        try:
            data = json.loads(path.read_text())
        except json.JSONDecodeError as e:
            raise SimulationError(f"{path}: not an experience file ({e})") from e
        return cls.from_dict(data)


_SAVED: dict[Path, tuple[float, Experience]] = {}


def saved_experience(path: str | Path = EXPERIENCE_JSON) -> Experience:
    """The saved experience the service's planning uses (CLI ``grasp``, HTTP ``/grasp/plan``), read once
    per change of the file; see :meth:`Experience.load`."""
    path = Path(path)
    stamp = path.stat().st_mtime if path.exists() else -1.0
    cached = _SAVED.get(path)
    if cached is None or cached[0] != stamp:
        cached = (stamp, Experience.load(path))
        _SAVED[path] = cached
    return cached[1]


@dataclass(frozen=True)
class FirstChoiceMeasure:
    """First choice measured leave-one-object-out: each object's pick is made by the experience of every
    other object's trials (its own never rank its own candidates), among its validated candidates."""

    objects: int
    with_hold: int  # objects with a validated candidate that holds
    rules_first_holds: int  # the rules' first choice holds
    first_holds: int  # the experience's pick holds
    changed: tuple[tuple[str, str, str, bool], ...]  # (object, rules' first, pick, pick holds)

    def to_dict(self) -> dict[str, Any]:
        return {
            "objects": self.objects, "with_hold": self.with_hold, "rules_first_holds": self.rules_first_holds,
            "first_holds": self.first_holds, "share_of_with_hold": round(self.first_holds / self.with_hold, 4)
            if self.with_hold else None, "changed": [list(c) for c in self.changed],
        }  # fmt: skip


def leave_one_object_out(seen: Sequence[Outcome]) -> FirstChoiceMeasure:
    """Measure the experience's first choice on ``seen`` (every object's validated candidates)."""
    everything = Experience.learn(seen)
    by_object: dict[str, list[Outcome]] = {}
    for o in seen:
        by_object.setdefault(o.object_name, []).append(o)
    with_hold = rules = picked = 0
    changed = []
    for name, own in by_object.items():
        own = sorted(own, key=lambda o: o.rank)
        j = everything.without(own).pick([o.program for o in own], own[0].object_class)
        if any(o.holds for o in own):
            with_hold += 1
            rules += own[0].holds
            picked += own[j].holds
        if j:
            changed.append((name, own[0].program, own[j].program, own[j].holds))
    return FirstChoiceMeasure(len(by_object), with_hold, rules, picked, tuple(changed))
