#!/usr/bin/env bash
# The test suite, offline: NLTK_DATA points at an empty folder (nothing may need downloaded NLTK data).
# Arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
OBJRECALL_EXTRAS=test,ray bash scripts/setup.sh
export MUJOCO_GL="${MUJOCO_GL:-egl}"
NLTK_DATA="$(mktemp -d)"
export NLTK_DATA
trap 'rm -rf "$NLTK_DATA"' EXIT  # the empty folder goes with the run
.venv/bin/python -m pytest -q "$@"
