"""Grasp planning and MuJoCo grasp validation."""

import os as _os
import sys as _sys

# MuJoCo picks its OpenGL backend when it is first imported. Without a display, default to EGL (Mesa's
# software renderer, headless) so sim/render.py can draw offscreen; a MUJOCO_GL set by the user wins.
if "MUJOCO_GL" not in _os.environ and _sys.platform.startswith("linux") and not _os.environ.get("DISPLAY"):
    _os.environ["MUJOCO_GL"] = "egl"
