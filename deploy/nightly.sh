#!/bin/sh
# Run one command once a night, at a fixed UTC time, for ever: the scheduler of the compose services
# `ingest` and `sim-worker` (docker-compose.yml). The command is exactly what a person would type.
#
#   deploy/nightly.sh [--at HH:MM] [--now] [--init-db PATH] -- COMMAND [ARGS...]
#
#   --at HH:MM      time of day (UTC) to run at (default $NIGHTLY_AT, else 02:00)
#   --now           also run once right away, at start-up
#   --init-db PATH  before anything, create the catalog with the seed objects if PATH does not exist
#                   (its folder, then `objrecall init --seed --db PATH`)
#   --once          run the command once (after --now/--init-db handling) and exit: for tests and cron
#
# A failing run is logged and the loop goes on to the next night; SIGTERM stops the loop.
set -eu

at="${NIGHTLY_AT:-02:00}"
now=0
once=0
init_db=""
while [ $# -gt 0 ]; do
  case "$1" in
    --at) at="$2"; shift 2 ;;
    --now) now=1; shift ;;
    --once) once=1; shift ;;
    --init-db) init_db="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "nightly.sh: unknown option $1 (usage: nightly.sh [--at HH:MM] [--now] [--init-db PATH] -- COMMAND...)" >&2; exit 2 ;;
  esac
done
if [ $# -eq 0 ]; then
  echo "nightly.sh: no command given after --" >&2
  exit 2
fi
case "$at" in
  [0-2][0-9]:[0-5][0-9]) ;;
  *) echo "nightly.sh: --at wants HH:MM (UTC), got '$at'" >&2; exit 2 ;;
esac
hh=${at%%:*}
mm=${at##*:}
target=$(( ${hh#0} * 3600 + ${mm#0} * 60 ))
if [ "$target" -ge 86400 ]; then
  echo "nightly.sh: --at $at is not a time of day" >&2
  exit 2
fi

log() { echo "nightly.sh $(date -u +%Y-%m-%dT%H:%M:%SZ): $*" >&2; }

if [ -n "$init_db" ] && [ ! -e "$init_db" ]; then
  log "no catalog at $init_db: objrecall init --seed --db $init_db"
  mkdir -p "$(dirname "$init_db")"  # the deployment's own data folder (init never creates folders)
  objrecall init --seed --db "$init_db"
fi

run() {
  log "running: $*"
  if "$@"; then log "done: $1 $2"; else log "failed with exit code $?: $*"; fi
}

trap 'log "stopping"; exit 0' TERM INT

if [ "$once" = 1 ]; then
  "$@"
  exit $?
fi
if [ "$now" = 1 ]; then
  run "$@"
fi
while :; do
  secs=$(( $(date -u +%s) % 86400 ))
  wait_s=$(( (target - secs + 86400) % 86400 ))
  [ "$wait_s" -eq 0 ] && wait_s=86400
  log "next run at $at UTC, in $wait_s s"
  sleep "$wait_s" &
  wait $!
  run "$@"
done
