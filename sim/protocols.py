"""The named validation protocols a grasp trial can be judged by (sim/trial.py runs them; sim/PHYSICS.md).

* ``lift_push`` (today's, the default): lift 10 cm, hold, then push the object with its weight along
  +x, -x, +y, -y, +z, -z **in turn**; the trial stops at the first moment the object has moved 5 cm or
  turned 15 degrees relative to the palm since closing.
* ``six_direction`` (the dexterous-grasp benchmarks' test): lift and hold as above, then the held state
  is saved and each of the six directions is tested **on its own from that state**: a force of the
  object's weight along the direction for the push's duration, gravity on (the benchmark's table-top
  setting lifts the object 10 cm first). The wrist first rises a further 10 cm (``raise_m``), so that an
  object slipping out of the hand falls more than the 10 cm threshold before it meets the table (lifted
  only 10 cm, a bottle that slid out landed at 9.9-10.2 cm: the table, not the grasp, decided). A grasp passes when every direction leaves the object's
  translation under ``max_translation_cm`` and its rotation under ``max_rotation_deg`` relative to the
  palm, measured from the end of closing. The thresholds are DexGraspBench's
  (github.com/JYChen18/DexGraspBench, ``config/task/eval.yaml``, ``simulation_metrics``:
  ``trans_thre: 0.10`` m, ``angle_thre: 180`` degrees; Chen et al., "BODex", ICRA 2025,
  arXiv:2412.16490), which judges grasps in MuJoCo by external force in six directions after DexGraspNet
  (Wang et al., ICRA 2023). Its 180 degree angle threshold means rotation is, in effect, not judged.

Differences kept on purpose (both protocols share them): the hand starts inside the object when it
overlaps by more than 2 mm (DexGraspBench: ``max_pene`` 1 cm); the object's mass and friction are the
catalog's (DexGraspBench sets every object to 30 g and friction 0.6); displacement is the largest over
the push, not the value at its end; the pushes last 0.2 s each, as today's.
"""

from __future__ import annotations

from dataclasses import dataclass

from kb.errors import SimulationError

__all__ = ["DEFAULT_PROTOCOL", "LIFT_PUSH", "PROTOCOLS", "SIX_DIRECTION", "Protocol", "protocol_named"]


@dataclass(frozen=True)
class Protocol:
    """A success rule and how its pushes are applied. ``independent``: each direction starts again from
    the state after the hold (else the pushes follow one another and the first violation ends the
    trial). ``version_tag`` is appended to the hand version of stored results (empty for the default),
    so the two protocols' results are kept apart and neither is mistaken for the other."""

    name: str
    max_translation_cm: float
    max_rotation_deg: float
    independent: bool
    version_tag: str
    source: str
    raise_m: float = 0.0  # a second rise of the wrist after the hold, before the pushes

    def beyond(self, slip_cm: float, turn_deg: float) -> bool:
        """Has the object moved ``max_translation_cm`` or more, or turned ``max_rotation_deg`` or more?"""
        return slip_cm >= self.max_translation_cm or turn_deg >= self.max_rotation_deg


LIFT_PUSH = Protocol(
    name="lift_push",
    max_translation_cm=5.0,
    max_rotation_deg=15.0,
    independent=False,
    version_tag="",
    source="this project (sim/PHYSICS.md, Trial protocol): pushes of its weight in turn, 5 cm / 15 deg",
)
SIX_DIRECTION = Protocol(
    name="six_direction",
    max_translation_cm=10.0,
    max_rotation_deg=180.0,
    independent=True,
    version_tag="+six_direction",
    raise_m=0.10,
    source="DexGraspBench config/task/eval.yaml simulation_metrics (trans_thre 0.10 m, angle_thre 180 deg); "
    "BODex, arXiv:2412.16490",
)
PROTOCOLS: dict[str, Protocol] = {p.name: p for p in (LIFT_PUSH, SIX_DIRECTION)}
DEFAULT_PROTOCOL = LIFT_PUSH.name


def protocol_named(name: str | Protocol) -> Protocol:
    """The protocol called ``name``; a :class:`SimulationError` naming the known ones otherwise."""
    if isinstance(name, Protocol):
        return name
    try:
        return PROTOCOLS[str(name)]
    except KeyError:
        known = ", ".join(PROTOCOLS)
        raise SimulationError(f"unknown validation protocol {name!r}: known protocols are {known}") from None
