#!/usr/bin/env bash
# The SCI example (data/examples/sci.toml, block time steps) over 1 process x 2 threads and 2 processes x 1
# thread (bound to cores), alternately, K pairs, each BLOCKS blocks: from t = 0 (the shock stage), or with
# --from RUN STEP resumed from RUN/checkpoint.h5 (a run of sci.toml stopped at step STEP, e.g. in its late
# stage with run.end_time = 1.0; run.max_steps = STEP + BLOCKS). Prints per run the wall time, the simulated
# time reached, particle updates per second, the phases' share of the wall time (process 0's) and the crater
# radius reached.
# Usage: bench/domain_sci/compare.sh [--from RUN STEP] [BLOCKS=400] [K=2] [BUILD=build/release]
set -u
RUN=
STEP=0
if [ "${1:-}" = "--from" ]; then
  RUN=${2:?usage: compare.sh [--from RUN STEP] [BLOCKS] [K] [BUILD]}
  STEP=${3:?usage: compare.sh [--from RUN STEP] [BLOCKS] [K] [BUILD]}
  shift 3
  [ -f "$RUN/checkpoint.h5" ] || { echo "no checkpoint.h5 in $RUN" >&2; exit 1; }
fi
BLOCKS=${1:-400}
K=${2:-2}
CK=${3:-build/release}/apps/craterkit
DATA=$(cd "$(dirname "$0")/../../data" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
LAST=$((STEP + BLOCKS))
sed "s/^end_time = 500.0 .*/end_time = 500.0\nmax_steps = $LAST/" "$DATA/examples/sci.toml" >"$WORK/sci.toml"
grep -q "^max_steps = $LAST" "$WORK/sci.toml" || { echo "could not set run.max_steps" >&2; exit 1; }
report() {
  /usr/bin/python3 -c '
import json, os, sys
d = json.load(open(sys.argv[1]))
crater_file = os.path.join(sys.argv[3], "crater.json")
radius = json.load(open(crater_file)).get("crater_radius") if os.path.exists(crater_file) else None
radius = float("nan") if radius is None else radius  # no crater measured yet
wall = d["wall_seconds"]
phases = sorted(d["phase_seconds"].items(), key=lambda kv: -kv[1])
shares = ", ".join(f"{k} {100 * v / wall:.0f} %" for k, v in phases if v / wall >= 0.01)
row = (sys.argv[2], d["steps_this_run"], d["time"], wall, d["particle_updates_per_second"], shares, radius)
print("| %s | %d | %.4g | %.1f | %.3g | %s | %.14g |" % row)
' "$1" "$2" "$3"
}
# One run: LABEL OUT, then the command that runs it (the output folder, --resume when resuming, appended).
run() {
  local label=$1 out=$2
  shift 2
  local resume=()
  if [ -n "$RUN" ]; then
    cp -r "$RUN" "$out"
    resume=(--resume)
  fi
  CRATERKIT_DATA_DIR="$DATA" "$@" --out "$out" "${resume[@]}" --json --quiet >"$out.json" 2>"$out.err" ||
    { cat "$out.err" >&2; exit 1; }
  report "$out.json" "$label" "$out"
  rm -rf "$out"
}
echo "| processes x threads | blocks | t reached (s) | wall (s) | particle updates/s | phases | crater radius (m) |"
for k in $(seq 1 "$K"); do
  run "1 x 2" "$WORK/a$k" "$CK" simulate "$WORK/sci.toml" --threads 2
  run "2 x 1" "$WORK/b$k" mpirun -n 2 --bind-to core "$CK" simulate "$WORK/sci.toml" --threads 1
done
