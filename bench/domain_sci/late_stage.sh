#!/usr/bin/env bash
# The SCI example's late stage over 1 process x 2 threads and 2 processes x 1 thread (bound to cores),
# alternately, K pairs: each resumes the same checkpoint (RUN/checkpoint.h5 of a run of data/examples/sci.toml
# stopped in its late stage, e.g. with run.end_time = 1.0) and runs BLOCKS more blocks (run.max_steps = STEP +
# BLOCKS, STEP the checkpoint's step). Prints per run the wall time, the simulated time reached, particle
# updates per second and the phases' share of the wall time (process 0's), and the crater radius reached.
# Usage: bench/domain_sci/late_stage.sh RUN STEP [BLOCKS=50] [K=2] [BUILD=build/release]
set -u
RUN=${1:?usage: late_stage.sh RUN STEP [BLOCKS] [K] [BUILD]}
STEP=${2:?usage: late_stage.sh RUN STEP [BLOCKS] [K] [BUILD]}
BLOCKS=${3:-50}
K=${4:-2}
CK=${5:-build/release}/apps/craterkit
DATA=$(cd "$(dirname "$0")/../../data" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
[ -f "$RUN/checkpoint.h5" ] || { echo "no checkpoint.h5 in $RUN" >&2; exit 1; }
sed "s/^end_time = 500.0 .*/end_time = 500.0\nmax_steps = $((STEP + BLOCKS))/" "$DATA/examples/sci.toml" >"$WORK/sci.toml"
grep -q "^max_steps = " "$WORK/sci.toml" || { echo "could not set run.max_steps" >&2; exit 1; }
report() {
  /usr/bin/python3 -c '
import json, os, sys
d = json.load(open(sys.argv[1]))
crater_file = os.path.join(sys.argv[3], "crater.json")
radius = json.load(open(crater_file))["crater_radius"] if os.path.exists(crater_file) else float("nan")
wall = d["wall_seconds"]
phases = sorted(d["phase_seconds"].items(), key=lambda kv: -kv[1])
shares = ", ".join(f"{k} {100 * v / wall:.0f} %" for k, v in phases if v / wall >= 0.01)
row = (sys.argv[2], d["steps_this_run"], d["time"], wall, d["particle_updates_per_second"], shares, radius)
print("| %s | %d | %.4g | %.1f | %.3g | %s | %.14g |" % row)
' "$1" "$2" "$3"
}
echo "| processes x threads | blocks | t reached (s) | wall (s) | particle updates/s | phases | crater radius (m) |"
for k in $(seq 1 "$K"); do
  for mode in a b; do
    cp -r "$RUN" "$WORK/$mode$k"
    if [ $mode = a ]; then
      CRATERKIT_DATA_DIR="$DATA" "$CK" simulate "$WORK/sci.toml" --out "$WORK/$mode$k" --resume --threads 2 \
        --json --quiet >"$WORK/$mode$k.json" 2>"$WORK/$mode$k.err" || { cat "$WORK/$mode$k.err" >&2; exit 1; }
      report "$WORK/$mode$k.json" "1 x 2" "$WORK/$mode$k"
    else
      CRATERKIT_DATA_DIR="$DATA" mpirun -n 2 --bind-to core "$CK" simulate "$WORK/sci.toml" --out "$WORK/$mode$k" \
        --resume --threads 1 --json --quiet >"$WORK/$mode$k.json" 2>"$WORK/$mode$k.err" ||
        { cat "$WORK/$mode$k.err" >&2; exit 1; }
      report "$WORK/$mode$k.json" "2 x 1" "$WORK/$mode$k"
    fi
    rm -rf "$WORK/$mode$k"
  done
done
