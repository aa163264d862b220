"""Agreement with real people: the grasp families recorded in the Yale human grasping dataset.

``../shared/human-grasps/human_grasp_families_dev.csv`` (relative to the repository root; never copied
into the repository) lists 126 household objects with the share of recorded human grasps in each family
(power, intermediate, precision) and the majority family (Bullock, Feix & Dollar, IJRR 2015). Its features
are coarse size and mass classes, a rigidity and a roundness code; :func:`planner_features` maps them onto
the planner's features (no object names, no per-object choices).

**Blind split.** The shared file is split once more, by a rule fixed before looking at any result: an
object is *blind* when the first 8 hex digits of ``sha1(name.strip().lower())``, read as an integer, are
``< 30`` modulo 100 (:func:`is_blind`; 46 of the 126 objects). Rules are checked only against the other 80
(*check* part); the blind part is scored once, at the end of a change (``--blind``), and reported as such.
The other 129 objects of the dataset are held back by the project and scored by someone else.
"""

from __future__ import annotations

import csv
import hashlib
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from kb.errors import InvalidFeature
from sim.grasps import FAMILIES
from sim.planner import PLANNER_VERSION, plan_grasps

__all__ = [
    "YALE_DEV_CSV",
    "FamilyAgreement",
    "YaleObject",
    "evaluate_families",
    "is_blind",
    "planner_features",
    "read_yale_families",
]

#: The shared real data: ``../shared/human-grasps`` next to the repository root, or the directory named by
#: ``OBJRECALL_HUMAN_GRASPS`` (tests skip when it is absent).
YALE_DEV_CSV = (
    Path(os.environ.get("OBJRECALL_HUMAN_GRASPS", Path(__file__).resolve().parents[1].parent / "shared" / "human-grasps"))
    / "human_grasp_families_dev.csv"
)
#: Percentage of the shared objects kept blind (see the module docstring).
BLIND_PERCENT = 30


def is_blind(name: str) -> bool:
    """Is ``name`` in the blind part of the shared human data? (sha1 rule, module docstring.)"""
    digest = hashlib.sha1(name.strip().lower().encode("utf-8")).hexdigest()
    return int(digest[:8], 16) % 100 < BLIND_PERCENT


@dataclass(frozen=True)
class YaleObject:
    """One object of the Yale data: its recorded features, family shares and majority family."""

    object: str
    a_cm: float
    b_cm: float
    c_cm: float
    mass_g: float
    rigidity: str
    roundness: str
    n_grasps: int
    shares: dict[str, float]
    majority: str


def planner_features(o: YaleObject) -> dict:
    """The planner's features for a Yale object.

    Roundness ``abc`` (round about every axis) is ``radial``; ``c`` (round about the smallest axis: a
    disk or a squat cylinder) is ``radial`` when its thickness is under 0.6 of its diameter (a disk, as
    the planner's disk rule reads it), else ``prism``; ``a`` (round about the long axis: a cylinder) is
    ``long`` when ``b <= 0.35 a`` and ``prism`` otherwise; ``non-round`` leaves the shape to the planner's
    dimension-ratio inference. Rigidity ``fragile`` becomes fragility fragile (rigidity rigid); material
    and texture are not recorded (the planner assumes hard plastic, medium texture).
    """
    a, b, c = sorted((o.a_cm, o.b_cm, o.c_cm), reverse=True)
    shape: str | None = None
    if o.roundness == "abc":
        shape = "radial"
    elif o.roundness == "c":
        shape = "radial" if c < 0.6 * b else "prism"
    elif o.roundness == "a":
        shape = "long" if b <= 0.35 * a else "prism"
    fragile = o.rigidity == "fragile"
    return {
        "a_cm": a,
        "b_cm": b,
        "c_cm": c,
        "mass_g": o.mass_g,
        "shape": shape,
        "rigidity": "rigid" if fragile else o.rigidity,
        "fragility": "fragile" if fragile else None,
    }


def read_yale_families(path: str | Path = YALE_DEV_CSV) -> list[YaleObject]:
    """The objects of a Yale family file. Raises InvalidFeature naming the row for a bad value."""
    out = []
    with open(path, newline="", encoding="utf-8") as fh:
        for line, row in enumerate(csv.DictReader(fh), start=2):
            where = f"{path}:{line}"
            try:
                nums = {k: float(row[k]) for k in ("a_cm", "b_cm", "c_cm", "mass_g", *FAMILIES)}
                n = int(row["n_grasps"])
            except (KeyError, TypeError, ValueError):
                raise InvalidFeature("row", row.get("object"), f"{where}: a number is missing or bad") from None
            if row.get("majority") not in FAMILIES:
                raise InvalidFeature("majority", row.get("majority"), f"{where}: not a grasp family")
            out.append(
                YaleObject(
                    object=row["object"],
                    a_cm=nums["a_cm"],
                    b_cm=nums["b_cm"],
                    c_cm=nums["c_cm"],
                    mass_g=nums["mass_g"],
                    rigidity=row.get("rigidity") or "rigid",
                    roundness=row.get("roundness") or "non-round",
                    n_grasps=n,
                    shares={f: nums[f] for f in FAMILIES},
                    majority=row["majority"],
                )
            )
    return out


@dataclass(frozen=True)
class FamilyAgreement:
    """How often the planner's first choice is in the family most people used."""

    part: str  # "check", "blind" or "all"
    n: int
    family_agreement: float
    always_power: float
    expected_agreement: float  # mean people's share of the planner's family (honest where majorities are 1 grasp)
    expected_always_power: float
    planner_version: str
    misses: tuple[tuple[str, str, str], ...]  # (object, people's majority, planner's family)

    def summary(self) -> dict:
        return {
            "part": self.part,
            "n": self.n,
            "family_agreement": self.family_agreement,
            "always_power": self.always_power,
            "expected_agreement": self.expected_agreement,
            "expected_always_power": self.expected_always_power,
            "planner_version": self.planner_version,
        }


def evaluate_families(objects: Iterable[YaleObject], part: str = "check") -> FamilyAgreement:
    """Score the planner on ``part`` of ``objects``: ``check`` (not blind), ``blind`` or ``all``.

    ``family_agreement`` counts the objects whose majority family the planner's first choice is in;
    ``expected_agreement`` is the mean share of the object's recorded grasps in the planner's family (the
    agreement expected with one of its recorded grasps drawn at random): the honest measure where a majority
    rests on one grasp or a tie.
    """
    if part not in ("check", "blind", "all"):
        raise ValueError(f"part must be check, blind or all, not {part!r}")
    chosen: Sequence[YaleObject] = [
        o for o in objects if part == "all" or is_blind(o.object) == (part == "blind")
    ]
    hits, power, misses = 0, 0, []
    share, power_share = 0.0, 0.0
    for o in chosen:
        family = plan_grasps(planner_features(o), top=1)[0].family
        hits += family == o.majority
        power += o.majority == "power"
        share += o.shares[family]
        power_share += o.shares["power"]
        if family != o.majority:
            misses.append((o.object, o.majority, family))
    n = len(chosen)
    return FamilyAgreement(
        part=part,
        n=n,
        family_agreement=round(hits / n, 3) if n else 0.0,
        always_power=round(power / n, 3) if n else 0.0,
        expected_agreement=round(share / n, 3) if n else 0.0,
        expected_always_power=round(power_share / n, 3) if n else 0.0,
        planner_version=PLANNER_VERSION,
        misses=tuple(misses),
    )
