"""Grasp taxonomy (Cutkosky 1989; Feix et al. 2016) and the plan record shared by planner and simulator.

The planner (sim/planner.py) produces :class:`GraspPlan` records; the trial runner (sim/trial.py) executes
one in MuJoCo. Grasp type names are stable identifiers stored in the knowledge base.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any, Literal

__all__ = ["FAMILIES", "GRASP_TYPES", "Family", "GraspPlan"]

Family = Literal["power", "intermediate", "precision"]

#: grasp type -> family, after Cutkosky (1989) and the Feix et al. (2016) GRASP taxonomy.
GRASP_TYPES: dict[str, Family] = {
    "heavy_wrap_large_diameter": "power",
    "heavy_wrap_small_diameter": "power",
    "medium_wrap": "power",
    "adducted_thumb": "power",
    "light_tool": "power",
    "power_disk": "power",
    "power_sphere": "power",
    "lateral_pinch": "intermediate",
    "thumb_4_finger": "precision",
    "thumb_3_finger": "precision",
    "thumb_2_finger": "precision",
    "thumb_index_finger": "precision",
    "precision_disk": "precision",
    "precision_sphere": "precision",
    "tripod": "precision",
}
FAMILIES: tuple[str, ...] = ("power", "intermediate", "precision")


@dataclass(frozen=True)
class GraspPlan:
    """One candidate grasp for an object.

    grasp_type: a key of :data:`GRASP_TYPES`; family: its family.
    grasped_dim: which object dimension lies between thumb and fingers ("a", "b" or "c").
    aperture_cm: hand opening before closing (the grasped extent plus a margin).
    approach: direction the palm approaches from, in the object frame ("top" = from +z, "side" = from +x).
    grip_force_n: the squeeze: normal force on each side of the grip, F = m g SF / (2 mu) (from mass,
    friction and fragility); the trial measures half the total hand-object normal force to compare.
    score: planner preference, higher is better (plans are ranked by it).
    rationale: the rules that chose it, in words.
    """

    grasp_type: str
    family: Family
    grasped_dim: Literal["a", "b", "c"]
    aperture_cm: float
    approach: Literal["top", "side"]
    grip_force_n: float
    score: float
    rationale: tuple[str, ...] = ()
    params: dict[str, Any] = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.grasp_type not in GRASP_TYPES:
            raise ValueError(f"unknown grasp type {self.grasp_type!r}")
        if GRASP_TYPES[self.grasp_type] != self.family:
            raise ValueError(f"{self.grasp_type} is a {GRASP_TYPES[self.grasp_type]} grasp, not {self.family}")

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["rationale"] = list(self.rationale)
        return d
