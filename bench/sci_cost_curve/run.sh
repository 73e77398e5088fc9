#!/usr/bin/env bash
# The SCI crater's cost against resolution: data/examples/sci.toml at each outer spacing DX (impact.particle_spacing)
# run to the end of growth, one after the other, then the cost model of curve.py (bench/RESULTS.md, "Cost curve of
# the SCI crater"). Runs take minutes (1.0 m) to hours (0.25 m): run on a quiet machine, in a folder outside the
# repository.
#
# Usage: bench/sci_cost_curve/run.sh CRATERKIT OUT_DIR THREADS DX [DX ...]
# Example: bench/sci_cost_curve/run.sh build/release/apps/craterkit /tmp/cost 2 1.0 0.5 0.35
set -euo pipefail
if [ $# -lt 4 ]; then sed -n '2,9p' "$0"; exit 2; fi
program=$(realpath "$1") out=$2 threads=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
config=$here/../../data/examples/sci.toml
export CRATERKIT_DATA_DIR=${CRATERKIT_DATA_DIR:-$here/../../data}
mkdir -p "$out"
for dx in "$@"; do
  sed -E "s/^particle_spacing = [0-9.]+ /particle_spacing = $dx /" "$config" > "$out/sci-$dx.toml"
  grep -q "^particle_spacing = $dx " "$out/sci-$dx.toml" || { echo "could not set particle_spacing = $dx" >&2; exit 2; }
  rm -rf "$out/run-$dx"
  echo "dx_max $dx: $("$program" simulate "$out/sci-$dx.toml" --dry-run 2>&1 | grep 'particles [0-9]')" >&2
  "$program" simulate "$out/sci-$dx.toml" --out "$out/run-$dx" --threads "$threads" --json --quiet \
    > "$out/run-$dx.json.part"
  mv "$out/run-$dx.json.part" "$out/run-$dx.json"  # only a finished run leaves its summary
done
python3 "$here/curve.py" "$out" "$@"
