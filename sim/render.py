"""Offscreen pictures of a grasp trial (PNG bytes), for the validation reports.

MuJoCo renders with OpenGL. Without a display, choose a headless backend *before mujoco is imported*:
``MUJOCO_GL=egl`` (Debian packages libegl1 libegl-mesa0 libgl1-mesa-dri: Mesa's software rasteriser
behind EGL, no GPU needed) or ``MUJOCO_GL=osmesa`` (libosmesa6). Importing this module first sets
``MUJOCO_GL=egl`` when no backend is chosen and there is no X display.
"""

from __future__ import annotations

import io
import os
import sys

if "MUJOCO_GL" not in os.environ and sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    os.environ["MUJOCO_GL"] = "egl"

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from kb.errors import SimulationError  # noqa: E402
from kb.features import ObjectRecord  # noqa: E402
from sim.grasps import GraspPlan  # noqa: E402
from sim.trial import run_trial  # noqa: E402
from sim.world import TrialWorld, build_world  # noqa: E402

__all__ = ["encode_png", "grasp_camera", "render_trial", "render_world", "visible_fractions"]

#: Camera azimuth (degrees) per approach.
VIEW_AZIMUTH_DEG = {"top": 155.0, "side": 240.0, "edge": 110.0}
#: Camera distance: this many times the object's largest side, within these limits (m).
VIEW_DISTANCE_FACTOR = 2.0
VIEW_DISTANCE_M = (0.35, 0.6)
#: Table-edge grasps are seen from 25 degrees above: the thumb on top, the fingers under the overhang and a
#: pan's inside and handle all show (nearly level, -8, hid the pan's inside and handle).
EDGE_ELEVATION = -25.0
#: The camera aims this fraction of the way from the hand's contacts towards the object's centre.
VIEW_OBJECT_WEIGHT = 0.3

GL_HINT = (
    "offscreen rendering needs an OpenGL backend: set MUJOCO_GL=egl (apt install libegl1 libegl-mesa0 "
    "libgl1-mesa-dri) or MUJOCO_GL=osmesa (apt install libosmesa6) before Python starts"
)


def _headless_backend() -> None:
    """Use EGL/OSMesa even when mujoco was imported (with its default GLFW backend) before this module.

    MuJoCo binds its OpenGL backend at import time; on a Linux machine without a display that default
    (GLFW) cannot work. If ``MUJOCO_GL`` asks for egl or osmesa, or is unset without a display, swap the
    renderer's context class for the headless one (what ``MUJOCO_GL`` would have chosen at import).
    """
    if not sys.platform.startswith("linux"):
        return
    wanted = os.environ.get("MUJOCO_GL", "").lower() or ("" if os.environ.get("DISPLAY") else "egl")
    if wanted not in ("egl", "osmesa"):
        return
    from mujoco.rendering.classic import gl_context

    current = getattr(gl_context, "GLContext", None)
    if current is not None and getattr(current, "__module__", "").endswith(wanted):
        return
    try:
        if wanted == "egl":
            os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
            from mujoco.egl import GLContext
        else:
            os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
            from mujoco.osmesa import GLContext
    except Exception as exc:  # missing system libraries
        raise SimulationError(f"cannot load the {wanted} OpenGL backend ({exc}); {GL_HINT}") from exc
    gl_context.GLContext = GLContext


def _contact_centre(world: TrialWorld) -> np.ndarray:
    """Where the camera aims: the mean position of the hand's contacts with the object, else between the
    object and the palm."""
    data = world.data
    n = data.ncon
    if n:
        g1, g2 = data.contact.geom1[:n], data.contact.geom2[:n]
        mask = (world.is_object[g1] & world.is_hand[g2]) | (world.is_object[g2] & world.is_hand[g1])
        if mask.any():
            return data.contact.pos[:n][mask].mean(axis=0)
    return 0.5 * data.xpos[world.object_body] + 0.5 * data.xpos[world.palm_body]


def grasp_camera(world: TrialWorld) -> mujoco.MjvCamera:
    """The free camera of the pictures: aimed at the grasp, framed on the object (sim/PHYSICS.md)."""
    data = world.data
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    # Aimed at the grasp, with some of the object: a 45 cm pan seen whole leaves the hand a few pixels.
    centre = data.xipos[world.object_body]
    cam.lookat[:] = (1.0 - VIEW_OBJECT_WEIGHT) * _contact_centre(world) + VIEW_OBJECT_WEIGHT * centre
    lo, hi = VIEW_DISTANCE_M
    cam.distance = min(hi, max(lo, VIEW_DISTANCE_FACTOR * max(world.obj.dims_cm) * 0.01))
    # Look across the opposition axis so both the thumb and the fingers show: for a top grasp from the
    # index side, for a side grasp from the fingers' side of the object.
    cam.azimuth = VIEW_AZIMUTH_DEG.get(world.approach, 155.0)
    cam.elevation = EDGE_ELEVATION if world.approach == "edge" else -22.0
    return cam


def render_world(
    world: TrialWorld, *, width: int = 480, height: int = 360, segmentation: bool = False
) -> np.ndarray:
    """An RGB image (height x width x 3, uint8) of the world's current state from :func:`grasp_camera`.
    With ``segmentation``, instead the MuJoCo object id and type of every pixel (height x width x 2)."""
    model, data = world.model, world.data
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
    model.vis.global_.offheight = max(model.vis.global_.offheight, height)
    cam = grasp_camera(world)
    _headless_backend()
    try:
        renderer = mujoco.Renderer(model, height=height, width=width)
    except Exception as exc:
        raise SimulationError(f"could not start MuJoCo's renderer ({exc}); {GL_HINT}") from exc
    try:
        if segmentation:
            renderer.enable_segmentation_rendering()
        renderer.update_scene(data, camera=cam)
        return renderer.render().copy()
    except Exception as exc:
        raise SimulationError(f"MuJoCo rendering failed ({exc}); {GL_HINT}") from exc
    finally:
        renderer.close()


def visible_fractions(world: TrialWorld, *, width: int = 240, height: int = 180) -> dict[str, float]:
    """Fractions of the picture's pixels showing the hand and the object (a segmentation render with the
    pictures' camera): what a test asks of a picture in which the grasp is visible."""
    seg = render_world(world, width=width, height=height, segmentation=True)
    ids, types = seg[..., 0], seg[..., 1]
    geoms = np.where(types == int(mujoco.mjtObj.mjOBJ_GEOM), ids, -1)
    valid = geoms >= 0
    hand = np.zeros(geoms.shape, dtype=bool)
    obj = np.zeros(geoms.shape, dtype=bool)
    hand[valid] = world.is_hand[geoms[valid]]
    obj[valid] = world.is_object[geoms[valid]]
    return {"hand": float(hand.mean()), "object": float(obj.mean())}


def encode_png(image: np.ndarray) -> bytes:
    """PNG bytes of an RGB uint8 image (matplotlib's writer: no extra dependency)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.image

    buf = io.BytesIO()
    matplotlib.image.imsave(buf, image, format="png")
    return buf.getvalue()


def render_trial(
    obj: ObjectRecord, plan: GraspPlan, *, seed: int = 0, width: int = 480, height: int = 360
) -> bytes:
    """PNG of ``plan`` on ``obj`` at the end of the hold phase (the object lifted in the hand), or at the
    moment the trial stopped if the grasp failed before. Same seed, same picture as :func:`run_trial`'s
    trial. Raises :class:`SimulationError` (with a hint about ``MUJOCO_GL``) if rendering is unavailable."""
    world = build_world(obj, plan, seed=seed)
    run_trial(obj, plan, seed=seed, stop_after="hold", world=world)
    return encode_png(render_world(world, width=width, height=height))
