"""The trial's world: a table, the object resting on it and the pre-shaped hand at its start pose.

:func:`build_world` places the object for the plan (grasped dimension along world y, the hand's opposition
axis; flat objects lie overhanging a table edge and are grasped there), pre-shapes the hand and backs it off
along the approach; :class:`TrialWorld` holds the compiled model and the indices a trial reads
(sim/trial.py runs the protocol on it; sim/render.py draws it). sim/PHYSICS.md explains the placement.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import mujoco
import numpy as np

from kb.errors import SimulationError
from kb.features import ObjectRecord
from sim import hand as H
from sim.grasps import GRASP_TYPES, GraspPlan, edge_grip_in_cm, edge_overhang_cm
from sim.objects import ObjectModel, add_object, add_table, object_model
from sim.placement import HOLD_HANDLE, layout
from sim.programs import program_for
from sim.sheet import add_sheet, is_sheet

__all__ = ["APPROACH_M", "HOLD_HANDLE", "PENETRATION_TOL_M", "TrialWorld", "build_world"]

#: The hand starts this far back along the approach direction.
APPROACH_M = 0.06
#: Gap between the palm face and the object above it in pinches (cm); a wrap's gap is its hand program's
#: ``palm_gap_cm`` (sim/programs.py: 0.4 cm pressed to the palm, 1 cm held in the fingers).
PRECISION_PALM_CLEARANCE_CM = 1.0
#: A rod lying on the table is pinched this fraction of its radius below its centre line ...
ROD_BELOW_FRACTION = 0.25
#: ... but never with the contact lower than this above the table (a pad's radius: its centre stays clear).
ROD_PAD_CLEAR_CM = 0.9
#: Deeper overlap than this at the pre-grasp pose means the hand starts inside the object.
PENETRATION_TOL_M = 0.002


@dataclass
class TrialWorld:
    """A compiled world for one (object, plan) and the indices the trial reads."""

    model: mujoco.MjModel
    data: mujoco.MjData
    obj: ObjectModel
    plan: GraspPlan
    targets: H.GraspTargets
    approach_dir: np.ndarray
    object_body: int
    palm_body: int
    is_hand: np.ndarray  # per geom: does it belong to the hand
    object_geom: int  # the object's main part (a vessel's cylinder); is_object marks all its geoms
    wrist_act: np.ndarray
    digit_act: np.ndarray
    wrist_qpos: np.ndarray
    approach: str = "top"  # as built: the plan's, or "edge" for a flat object grasped at a table edge
    geom_digit: dict[int, str] = field(default_factory=dict)  # hand geom id -> digit it belongs to
    digit_qpos: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))  # qpos index per digit joint
    is_object: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))  # per geom: the object's

    @cached_property
    def touches(self) -> np.ndarray:
        """Per geom pair (either order): is one the object's and the other the hand's (taken once)."""
        obj, hand = self.is_object, self.is_hand
        return (obj[:, None] & hand[None, :]) | (hand[:, None] & obj[None, :])

    def _contact_rows(self) -> np.ndarray:
        """Indices of the active hand-object contacts (the trial reads them every control tick)."""
        d = self.data
        n = d.ncon
        if n == 0:
            return _EMPTY_IDX
        c = d.contact
        mask = self.touches[c.geom1[:n], c.geom2[:n]] & (c.efc_address[:n] >= 0)
        return np.flatnonzero(mask)

    def object_contacts(self) -> tuple[np.ndarray, np.ndarray]:
        """Indices of the active hand-object contacts, and for each the hand geom it involves."""
        idx = self._contact_rows()
        if not idx.size:
            return idx, _EMPTY_IDX
        c = self.data.contact
        g1, g2 = c.geom1[idx], c.geom2[idx]
        return idx, np.where(self.is_object[g1], g2, g1)

    def palm_pose(self) -> tuple[np.ndarray, np.ndarray]:
        return self.data.xpos[self.palm_body].copy(), self.data.xmat[self.palm_body].reshape(3, 3).copy()

    def object_in_palm(self) -> tuple[np.ndarray, np.ndarray]:
        """Object position and orientation matrix in the palm frame."""
        p, r = self.palm_pose()
        po = self.data.xpos[self.object_body]
        ro = self.data.xmat[self.object_body].reshape(3, 3)
        return r.T @ (po - p), r.T @ ro

    def digit_forces(self) -> dict[str, float]:
        """Total normal force (N) each digit presses on the object with (its fingertip sensors)."""
        d = self.data
        out = dict.fromkeys(H.DIGITS, 0.0)
        idx, hand_geoms = self.object_contacts()
        for k, g in zip(idx, hand_geoms, strict=True):
            digit = self.geom_digit.get(int(g))
            if digit is not None:
                out[digit] += float(d.efc_force[d.contact.efc_address[k]])
        return out

    def hand_contacts(self) -> tuple[np.ndarray, np.ndarray]:
        """Normal forces (N) and distances (m) of the active hand-object contacts.

        With elliptic cones a contact's first constraint row is its normal force (what
        ``mj_contactForce`` returns as force[0]); reading ``efc_force`` directly avoids a Python loop.
        """
        idx = self._contact_rows()
        if not idx.size:
            return _EMPTY, _EMPTY
        d = self.data
        return d.efc_force[d.contact.efc_address[idx]], d.contact.dist[idx]

    def contact_forces(self) -> np.ndarray:
        """The normal forces of :meth:`hand_contacts` alone (what the trial measures every control tick)."""
        idx = self._contact_rows()
        if not idx.size:
            return _EMPTY
        d = self.data
        return d.efc_force[d.contact.efc_address[idx]]


_EMPTY = np.zeros(0)
_EMPTY_IDX = np.zeros(0, dtype=int)


def _compile_failure(obj: ObjectModel, exc: Exception) -> str:
    """Why the trial model did not compile, in the object's terms (never MuJoCo's raw text alone): an object
    at kb's plausibility limits (kb/plausibility.py) can still have parts under MuJoCo's minimum mass or
    inertia (mjMINVAL, 1e-15 in SI units), e.g. a 5 m thread 10 µm thick."""
    size = " x ".join(f"{d:g}" for d in obj.dims_cm)
    what = f"{obj.name!r} ({size} cm, {obj.mass_kg * 1000:g} g)"
    if "mjMINVAL" in str(exc):
        return (
            f"{what} is too small or too light for MuJoCo to simulate: a part's mass or inertia is under its "
            "minimum (mjMINVAL, 1e-15 kg m²)"
        )
    return f"could not build the trial model for {what}: {' '.join(str(exc).split())}"


def build_world(obj: ObjectRecord | ObjectModel, plan: GraspPlan, *, seed: int = 0) -> TrialWorld:
    """Compile the trial's world with the hand at its start pose (pre-shaped, backed off the object)."""
    if plan.grasp_type not in GRASP_TYPES:
        raise SimulationError(f"unknown grasp type {plan.grasp_type!r}")
    if plan.approach not in H.APPROACH_QUAT:
        raise SimulationError(f"unknown approach {plan.approach!r}: expected top or side")
    model_obj = obj if isinstance(obj, ObjectModel) else object_model(obj)
    rng = np.random.default_rng(seed)
    lay = layout(model_obj, plan)
    approach, axes, signs, flat = lay.approach, lay.axes, lay.signs, lay.flat
    ext, grip_centre, grip_ext, width = lay.ext, lay.grip_centre, lay.grip_ext, lay.width
    program = program_for(plan.grasp_type)
    ball = model_obj.kind == "sphere" and plan.params.get("hold") is None
    targets = H.grasp_targets(
        plan, width, align_pads=not flat, overshoot_cm=_overshoot_cm(program, model_obj), ball=ball
    )
    wrap = program.control == "wrap"

    depth = grip_ext[2] if approach == "top" else grip_ext[0]  # the grasped body's extent along the approach
    # Over the table's edge as far as the pads reach in (up to 6 cm), never by so much that the object's
    # centre of mass leaves the table (sim/grasps.py, shared with the planner's force).
    overhang = edge_overhang_cm(depth) if flat else 0.0
    lying = (
        approach == "top" and model_obj.kind == "cylinder" and model_obj.axis_dim is not None
        and axes.get(model_obj.axis_dim) != 2 and plan.params.get("hold") is None
    )  # fmt: skip
    lead = float(plan.params.get(H.FINGER_LEAD_PARAM, 0.0)) if flat else 0.0
    center_cm, grip_depth = _object_in_hand_cm(program, targets, depth, flat, lead, rod=lying)
    center_h = center_cm * H.CM

    obj_pos = np.array([0.0, 0.0, ext[2] / 2.0 * H.CM])
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, np.array(H.APPROACH_QUAT[approach]))
    rot = rot.reshape(3, 3)
    palm_pos = obj_pos + grip_centre * H.CM - rot @ center_h
    if approach == "side":
        # Keep the palm's lower edge above the table: the fingers spread vertically from its centre.
        palm_pos[2] = max(palm_pos[2], (H.PALM_HALF_CM[0] + 0.3) * H.CM)
    approach_dir = np.array([0.0, 0.0, 1.0]) if approach == "top" else np.array([1.0, 0.0, 0.0])

    spec = mujoco.MjSpec()
    spec.modelname = "grasp_trial"
    H.configure_options(spec)
    _add_scenery(spec)
    add_table(spec, (grip_centre[0] + depth / 2.0 - overhang) * H.CM if flat else None)
    if is_sheet(model_obj, flat):  # floppy: a chain of strips that droops behind the held one (sim/sheet.py)
        add_sheet(spec, model_obj, ext, obj_pos, overhang)
    else:
        add_object(spec, model_obj, axes, obj_pos, signs)
    H.add_hand(spec, approach=approach, mount_m=palm_pos, torque_limits=targets.closing_limits)
    try:
        model = spec.compile()
    except Exception as exc:
        raise SimulationError(_compile_failure(model_obj, exc)) from exc
    world = _trial_world(model, model_obj, plan, targets, approach, approach_dir)
    data = world.data

    noise = np.array([rng.normal(0, 0.001), rng.normal(0, 0.001), 0.0])
    open_q = targets.open + rng.normal(0, 0.01, size=targets.open.shape)
    data.qpos[world.digit_qpos] = open_q
    if not wrap:
        # Round objects bulge above their equator into the fingers that reach down to it: pinch higher,
        # in 5 mm steps up to 1 cm below the top, until the pre-shaped hand clears the object.
        backoff = _precision_backoff_m(
            model, data, world.is_hand, world.is_object, world.wrist_qpos, approach_dir, grip_depth - 1.0
        )
        noise = noise + backoff * approach_dir
    data.qpos[world.wrist_qpos] = noise
    data.ctrl[world.digit_act] = open_q
    data.ctrl[world.wrist_act] = noise
    return world


#: How far past a floppy object's surface a lateral pinch closes (cm; other pinches: sim/hand.py
#: ``PRECISION_OVERSHOOT_CM``, 1 cm). A soft contact takes up the 1 cm (a cloth's 10 mm impedance ramp and
#: 0.03 s time constant): the straight fingers stopped on the cloth's face, pressing at a third of their
#: limit, and the held strip turned out (16-22 deg) under its hanging weight. Closing 2 cm past, the thumb
#: and the index and middle fingers gather the cloth's edge along the fingers (sim/PHYSICS.md, floppy sheets).
LATERAL_GATHER_OVERSHOOT_CM = 2.0


def _overshoot_cm(program, obj: ObjectModel) -> float:
    """How far past the object's surface the pinch's closing targets lie (sim/hand.py grasp_targets)."""
    if program.name == "lateral_pinch" and obj.rigidity == "floppy":
        return LATERAL_GATHER_OVERSHOOT_CM
    return H.PRECISION_OVERSHOOT_CM


def _trial_world(model, obj: ObjectModel, plan: GraspPlan, targets, approach: str, approach_dir) -> TrialWorld:
    """The compiled model with fresh data and the indices a trial reads."""
    object_body = model.body("object").id
    scenery = np.zeros(model.nbody, dtype=bool)  # the world (the table) and a sheet's draping strips
    scenery[0] = True
    scenery[[b for b in range(model.nbody) if model.body(b).name.startswith("sheet_")]] = True
    return TrialWorld(
        model=model,
        data=mujoco.MjData(model),
        obj=obj,
        plan=plan,
        targets=targets,
        approach_dir=approach_dir,
        object_body=object_body,
        palm_body=model.body("palm").id,
        # Hand geoms: every geom on a body other than the world (the table), the object and a sheet's strips.
        is_hand=~scenery[model.geom_bodyid] & (model.geom_bodyid != object_body),
        object_geom=model.geom("object_geom").id,
        is_object=model.geom_bodyid == object_body,
        wrist_act=np.array([model.actuator(n).id for n in H.WRIST_ACTUATOR_NAMES]),
        digit_act=np.array([model.actuator(n).id for n in H.ACTUATOR_NAMES]),
        wrist_qpos=np.array([model.jnt_qposadr[model.joint(n).id] for n in H.WRIST_JOINT_NAMES]),
        digit_qpos=np.array([model.jnt_qposadr[model.joint(n).id] for n in H.JOINT_NAMES]),
        approach=approach,
        geom_digit={
            g: model.geom(g).name.split("_")[0]
            for g in range(model.ngeom)
            if model.geom(g).name.split("_")[0] in H.DIGITS
        },
    )


def _add_scenery(spec: mujoco.MjSpec) -> None:
    """Lights and a sky for the pictures (sim/render.py); nothing here touches the physics."""
    spec.worldbody.add_light(pos=[0.3, -0.3, 0.8], dir=[-0.3, 0.3, -0.8], diffuse=[0.6, 0.6, 0.6])
    spec.worldbody.add_light(pos=[-0.4, 0.4, 0.6], dir=[0.4, -0.4, -0.6], diffuse=[0.35, 0.35, 0.35])
    spec.visual.headlight.ambient = [0.35, 0.35, 0.35]
    spec.visual.headlight.diffuse = [0.45, 0.45, 0.45]
    spec.add_texture(
        name="sky",
        type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
        builtin=mujoco.mjtBuiltin.mjBUILTIN_GRADIENT,
        rgb1=[0.92, 0.94, 0.97],
        rgb2=[0.55, 0.6, 0.68],
        width=64,
        height=64,
    )


def _object_in_hand_cm(
    program, targets: H.GraspTargets, depth: float, flat: bool, lead: float = 0.0, rod: bool = False
) -> tuple[np.ndarray, float]:
    """Where the object's centre sits in the hand frame (cm) at the grasp pose, and how far below its near
    face the pads meet it (pinches; 0 for wraps). ``depth``: its extent along the approach axis."""
    palm_face = -H.PALM_HALF_CM[2]
    if program.control == "wrap":  # pressed to the palm, or held in the fingers by the program's gap
        return np.array([0.0, targets.center_y_cm, palm_face - program.palm_gap_cm - depth / 2.0]), 0.0
    x_c = float(np.mean([H.FINGER_BY_NAME[f].x_cm for f in targets.fingers]))
    # Pads meet the object's sides at its centre (no gravity torque about the pinch axis) when they reach
    # that far, else 3 cm below its near face; flat objects as near their centre of mass as the pads
    # reach under the overhang.
    grip_depth = edge_grip_in_cm(depth) if flat else min(depth / 2.0, 3.0)
    if lead:  # an edge lever hold: the finger pads at the usual depth, the thumb ``lead`` nearer the edge
        grip_depth = max(lead / 2.0, grip_depth - lead / 2.0)
    if rod and depth / 2.0 <= 3.0:  # below a lying rod's centre line, as far as the pads clear the table
        grip_depth += max(0.0, min(ROD_BELOW_FRACTION * depth / 2.0, depth / 2.0 - ROD_PAD_CLEAR_CM))
    z_c = min(
        targets.contact_z_cm - depth / 2.0 + grip_depth,
        palm_face - PRECISION_PALM_CLEARANCE_CM - depth / 2,
    )
    return np.array([x_c, targets.center_y_cm, z_c]), grip_depth


def _precision_backoff_m(model, data, is_hand, is_object, wrist_qpos, approach_dir, max_cm: float) -> float:
    """Smallest back-off (m, along the approach, 5 mm steps up to ``max_cm``) at which the pre-shaped hand
    does not overlap the object; 0 if none does (the trial then fails as starting inside)."""
    steps = int(max(0.0, max_cm) // 0.5)
    for k in range(steps + 1):
        offset = k * 0.005
        data.qpos[wrist_qpos] = offset * approach_dir
        mujoco.mj_forward(model, data)
        n = data.ncon
        g1, g2 = data.contact.geom1[:n], data.contact.geom2[:n]
        mine = (is_object[g1] & is_hand[g2]) | (is_object[g2] & is_hand[g1])
        if not (data.contact.dist[:n][mine] < -PENETRATION_TOL_M).any():
            return offset
    return 0.0
