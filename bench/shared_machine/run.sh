#!/usr/bin/env bash
# A run beside another program: the same stretch of an impact run, resumed from a run folder's checkpoint, with
# THREADS threads alone and then beside one single-threaded busy process in its own session (as a user's
# long fit or build beside a simulation). Prints wall time and particle updates per second of each.
#
# Usage: bench/shared_machine/run.sh CRATERKIT CONFIG RUN_DIR MAX_STEPS [THREADS]
#   CRATERKIT  the program
#   CONFIG     the run's configuration (run.max_steps set to MAX_STEPS, which --resume allows)
#   RUN_DIR    a run folder with checkpoint.h5 (copied; not changed), or - for a new run from the start
#   MAX_STEPS  the step to stop at (past the checkpoint's)
# Example (the SCI run's end-of-growth checkpoint, 300 late-stage steps):
#   bench/shared_machine/run.sh build/release/apps/craterkit sci.toml sci_run 4558 2
# and the shock stage, the first 150 steps of a new run:
#   bench/shared_machine/run.sh build/release/apps/craterkit sci.toml - 150 2
set -euo pipefail
if [ $# -lt 4 ]; then sed -n '2,15p' "$0"; exit 2; fi
program=$1 config=$2 run_dir=$3 max_steps=$4 threads=${5:-2}
if [ "$run_dir" != - ] && [ ! -f "$run_dir/checkpoint.h5" ]; then echo "no checkpoint.h5 in $run_dir" >&2; exit 2; fi
work=$(mktemp -d)
competitor=
cleanup() {
  if [ -n "$competitor" ]; then kill -- "-$competitor" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
if grep -q "^max_steps *=" "$config"; then
  sed -E "s/^max_steps *=.*/max_steps = $max_steps/" "$config" > "$work/config.toml"
else
  sed -E "s/^\[run\]/[run]\nmax_steps = $max_steps/" "$config" > "$work/config.toml"
fi
grep -q "^max_steps = $max_steps" "$work/config.toml" || { echo "$config has no [run] table" >&2; exit 2; }

one_run() {  # $1: label
  rm -rf "$work/run"
  local resume=()
  if [ "$run_dir" != - ]; then cp -r "$run_dir" "$work/run" && resume=(--resume); fi
  "$program" simulate "$work/config.toml" --out "$work/run" "${resume[@]}" --threads "$threads" --json \
    > "$work/$1.json" 2> "$work/$1.err"
  grep -v "^t " "$work/$1.err" | sed "s/^/    $1: /" || true
  /usr/bin/python3 - "$work/$1.json" "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:>16}: {r['wall_seconds']:8.2f} s wall, {r['particle_updates_per_second']:10.4g} particle updates/s, "
      f"step {r['steps']}")
PY
}

echo "$(nproc) processors; $threads threads; load $(cut -d' ' -f1-3 /proc/loadavg)"
one_run alone
setsid bash -c 'while :; do :; done' &
competitor=$!
sleep 1
one_run "beside one busy"
