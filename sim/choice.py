"""Closed-loop grasp choice: the planner's first choice beside the validated choice.

The planner ranks candidate grasps from features (sim/planner.py); the trials (sim/trial.py) say which
of them hold. The **validated choice** of an object is its best-ranked candidate that holds in every seed
it was run with; the **first choice** is the planner's rank 0, whatever the trials said. Both stay
visible (never silently swapped): a :class:`GraspChoice` names both, whether they differ, and why the
first choice failed when it did; when no candidate holds, the validated choice is ``None`` and the
reasons of every candidate are kept.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

__all__ = ["ChoiceSummary", "GraspChoice", "choose", "simulate_plans", "summarize_choices"]


@dataclass(frozen=True)
class GraspChoice:
    """One object's first and validated choice (grasp types; ranks are the planner's, 0 = best)."""

    object_name: str
    first: str
    first_holds: bool
    first_reason: str
    validated: str | None
    validated_rank: int | None
    candidates: int
    reasons: tuple[tuple[str, str], ...]  # (grasp type, reason) of every candidate tried, in rank order

    @property
    def differs(self) -> bool:
        """Does the validated choice differ from the first choice (including: nothing holds)?"""
        return self.validated != self.first

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["differs"] = self.differs
        d["reasons"] = [list(x) for x in self.reasons]
        return d


@dataclass(frozen=True)
class ChoiceSummary:
    objects: int
    first_holds: int
    validated: int
    differs: int

    def to_dict(self) -> dict[str, int]:
        return asdict(self)

    def describe(self) -> str:
        """One line; ``differs`` counts the objects where nothing holds too, so they are said apart (with
        ``--top 1`` and no hold, "differs for 1" read as if another grasp had held)."""
        none_holds = self.objects - self.validated
        other = self.differs - none_holds
        return (
            f"first choice holds for {self.first_holds} of {self.objects} objects; a validated grasp "
            f"(best-ranked that holds) for {self.validated}; the validated choice is another candidate "
            f"for {other}, and no candidate holds for {none_holds}"
        )


def choose(rows: Iterable[Mapping[str, Any]]) -> list[GraspChoice]:
    """Group trial rows (``object_name``, ``grasp_type``, ``rank``, ``success``, ``reason``; any seeds)
    by object, in the order objects first appear, and pick each one's first and validated choice.

    A candidate holds when every one of its trials succeeded; an ``error`` trial does not hold.
    """
    by_object: dict[str, dict[str, dict[str, Any]]] = {}
    for r in rows:
        cands = by_object.setdefault(str(r["object_name"]), {})
        c = cands.setdefault(
            str(r["grasp_type"]), {"rank": int(r.get("rank") or 0), "holds": True, "reason": ""}
        )
        c["rank"] = min(c["rank"], int(r.get("rank") or 0))
        if not (r.get("success") and (r.get("outcome") or "success") == "success"):
            c["holds"] = False
            c["reason"] = c["reason"] or str(r.get("reason") or r.get("outcome") or "failed")
    out = []
    for name, cands in by_object.items():
        ranked: Sequence[tuple[str, dict[str, Any]]] = sorted(cands.items(), key=lambda kv: kv[1]["rank"])
        first_type, first = ranked[0]
        holding = [(t, c) for t, c in ranked if c["holds"]]
        out.append(
            GraspChoice(
                object_name=name,
                first=first_type,
                first_holds=first["holds"],
                first_reason=first["reason"],
                validated=holding[0][0] if holding else None,
                validated_rank=holding[0][1]["rank"] if holding else None,
                candidates=len(ranked),
                reasons=tuple((t, c["reason"] or "held") for t, c in ranked),
            )
        )
    return out


def summarize_choices(choices: Sequence[GraspChoice]) -> ChoiceSummary:
    return ChoiceSummary(
        objects=len(choices),
        first_holds=sum(c.first_holds for c in choices),
        validated=sum(c.validated is not None for c in choices),
        differs=sum(c.differs for c in choices),
    )


def simulate_plans(obj: Any, plans: Sequence[Any], *, seed: int = 0) -> tuple[list[Any], GraspChoice]:
    """Run one trial of each of ``plans`` (ranked, best first) on ``obj``; return the trial results and
    the object's first and validated choice. Each plan's program runs once (the planner lists a merged
    program once)."""
    from sim.trial import run_trial

    results = [run_trial(obj, p, seed=seed) for p in plans]
    rows = [
        {"object_name": obj.name, "grasp_type": p.grasp_type, "rank": k, **r.to_dict()}
        for k, (p, r) in enumerate(zip(plans, results, strict=True))
    ]
    return results, choose(rows)[0]
