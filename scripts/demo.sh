#!/usr/bin/env bash
# The main job on the embedded default, with no network: seed catalog -> ingest the bundled demo storefront
# (served on 127.0.0.1) -> recall sample descriptions -> validate their grasps in MuJoCo -> report.
# Arguments go to `objrecall demo` (see `objrecall demo --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export MUJOCO_GL="${MUJOCO_GL:-egl}"
exec .venv/bin/objrecall demo "$@"
