#!/usr/bin/env bash
# Idempotent set-up on a fresh Debian machine: system packages (as root), a virtualenv in .venv, and the
# project with its test extras. Safe to run again: it installs only what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

# MuJoCo's offscreen renderer on the CPU (EGL/OSMesa from Mesa), Chromium for the web page's browser test.
# (OBJRECALL_APT_PACKAGES replaces the list; empty skips this step.)
APT_PACKAGES="${OBJRECALL_APT_PACKAGES-libegl1 libgl1 libgl1-mesa-dri libegl-mesa0 libosmesa6 chromium}"
say() { echo "setup: $*" >&2; }

missing=""
for pkg in $APT_PACKAGES; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing="$missing $pkg"
done
if [ -n "$missing" ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    say "installing Debian packages:$missing"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
  else
    echo "setup: please install these Debian packages first: sudo apt-get install$missing" >&2
  fi
fi

PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
  say "creating the virtualenv .venv"
  "$PYTHON" -m venv .venv
fi
# Extras to install: "test" for the test suite, "ray" for the Ray executor (the test command adds it).
EXTRAS="${OBJRECALL_EXTRAS:-test}"
stamp=".venv/.objrecall-installed-${EXTRAS//,/-}"
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
  start=$SECONDS
  # pip: progress bars on a terminal; otherwise quiet, with its output kept to show if it fails
  if [ -t 2 ]; then pipq=(); else pipq=(-q); fi
  log=$(mktemp)
  run_pip() {
    if [ -t 2 ]; then .venv/bin/python -m pip "${pipq[@]}" "$@" >&2; else .venv/bin/python -m pip "${pipq[@]}" "$@" >>"$log" 2>&1; fi
  }
  say "1/2 upgrading pip"
  if run_pip install --upgrade pip; then
    say "2/2 installing objrecall and its dependencies [$EXTRAS] (about a minute the first time)"
    run_pip install -e ".[$EXTRAS]" || failed=1
  else
    failed=1
  fi
  if [ -n "${failed:-}" ]; then
    grep -v '^WARNING: Location' "$log" | tail -30 >&2
    say "pip install failed"
    exit 1
  fi
  rm -f "$log"
  touch "$stamp"
  say "environment ready in $((SECONDS - start)) s"
fi
