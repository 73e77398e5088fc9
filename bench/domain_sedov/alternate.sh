#!/usr/bin/env bash
# Alternates 1 process x 2 threads and 2 processes x 1 thread (bound to cores) of bench_domain_sedov, K pairs,
# so that a drift of the machine's speed hits both alike; prints every line, then the minimum and median s/step
# of each. Usage: bench/domain_sedov/alternate.sh [N=46] [K=5] [STEPS=10] [BUILD=build/release]
set -u
N=${1:-46}
K=${2:-5}
STEPS=${3:-10}
B=${4:-build/release}/bench/domain_sedov/bench_domain_sedov
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for _ in $(seq 1 "$K"); do
  "$B" "$N" --threads 2 --steps "$STEPS"
  mpirun -n 2 --bind-to "${BIND:-core}" "$B" "$N" --threads 1 --steps "$STEPS"
done | tee "$out"
for conf in "1 x 2" "2 x 1"; do
  grep "| $conf |" "$out" | awk -F'|' '{print $4}' | sort -n |
    awk -v c="$conf" '{a[NR] = $1} END {printf "%s: min %.3f median %.3f s/step (%d runs)\n", c, a[1], a[int((NR + 1) / 2)], NR}'
done
