#!/usr/bin/env bash
# The SCI example (data/examples/sci.toml, block time steps) over 1 process x 2 threads and 2 processes x 1
# thread (bound to cores), alternately, K pairs, each its first BLOCKS blocks from t = 0 (the shock stage);
# prints per run the wall time, the simulated time reached, particle updates per second and the phases' share
# of the wall time (process 0's). Usage: bench/domain_sci/compare.sh [BLOCKS=400] [K=2] [BUILD=build/release]
set -u
BLOCKS=${1:-400}
K=${2:-2}
CK=${3:-build/release}/apps/craterkit
DATA=$(cd "$(dirname "$0")/../../data" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
sed "s/^end_time = 500.0 .*/end_time = 500.0\nmax_steps = $BLOCKS/" "$DATA/examples/sci.toml" >"$WORK/sci.toml"
grep -q "^max_steps = $BLOCKS" "$WORK/sci.toml" || { echo "could not set run.max_steps" >&2; exit 1; }
report() {
  /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
wall = d["wall_seconds"]
phases = sorted(d["phase_seconds"].items(), key=lambda kv: -kv[1])
shares = ", ".join(f"{k} {100 * v / wall:.0f} %" for k, v in phases if v / wall >= 0.01)
row = (sys.argv[2], d["steps"], d["time"], wall, d["particle_updates_per_second"], shares)
print("| %s | %d | %.4g | %.1f | %.3g | %s |" % row)
' "$1" "$2"
}
echo "| processes x threads | blocks | t reached (s) | wall (s) | particle updates/s | phases |"
for k in $(seq 1 "$K"); do
  CRATERKIT_DATA_DIR="$DATA" "$CK" simulate "$WORK/sci.toml" --out "$WORK/a$k" --threads 2 --json --quiet \
    >"$WORK/a$k.json" 2>"$WORK/a$k.err" || { cat "$WORK/a$k.err" >&2; exit 1; }
  report "$WORK/a$k.json" "1 x 2"
  CRATERKIT_DATA_DIR="$DATA" mpirun -n 2 --bind-to core "$CK" simulate "$WORK/sci.toml" --out "$WORK/b$k" \
    --threads 1 --json --quiet >"$WORK/b$k.json" 2>"$WORK/b$k.err" || { cat "$WORK/b$k.err" >&2; exit 1; }
  report "$WORK/b$k.json" "2 x 1"
done
