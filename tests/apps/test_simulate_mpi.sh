#!/usr/bin/env bash
# `mpirun -n 2 craterkit simulate` runs one simulation over two processes (docs/parallel.md): process 0 alone
# prints the summary and writes the files, and the snapshots hold what the serial run's hold, bit for bit
# (the Sedov blast with lists rebuilt at every step, skin 0, as the distributed run's are; particles matched
# by id). An impact runs to the end of its crater's growth as the serial one
# does, and a bad key is said once, with status 2. A process killed mid-run ends the job with an error that says so, and
# the run resumed from its last checkpoint ends where the uninterrupted run ends, bit for bit.
# Usage: test_simulate_mpi.sh /path/to/craterkit /path/to/data mpiexec
set -u
CK="$1"
DATA="$2"
MPIEXEC="$3"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. "$(dirname "$0")/../study/tiny_study.sh"  # $WORK/tiny.toml; fail() and the failure count
two() { "$MPIEXEC" -n 2 --oversubscribe --bind-to none "$@"; }

sed -e 's/^particles_per_side = 50/particles_per_side = 14/' -e 's/^end_time = 0.05/end_time = 0.01/' \
  -e 's/^snapshot_times = .*/snapshot_times = [0.0, 0.005]/' -e 's/^\[neighbours\]/[neighbours]\nskin = 0.0/' \
  "$DATA/examples/sedov.toml" >"$WORK/sedov.toml"
grep -q '^skin = 0.0' "$WORK/sedov.toml" || fail "the test's sedov.toml has no [neighbours] skin = 0.0"
"$CK" simulate "$WORK/sedov.toml" --out "$WORK/serial" --threads 1 --json >"$WORK/serial.json" 2>"$WORK/err" ||
  fail "serial run exited $? ($(cat "$WORK/err"))"
two "$CK" simulate "$WORK/sedov.toml" --out "$WORK/two" --threads 1 --json >"$WORK/two.json" 2>"$WORK/err" ||
  fail "two-process run exited $? ($(cat "$WORK/err"))"
cat >"$WORK/same.py" <<'PYEOF'
import sys
import h5py, numpy as np
def datasets(path):
    out = {}
    def visit(name, item):
        if isinstance(item, h5py.Dataset):
            out[name] = item[()]
    with h5py.File(path) as f:
        f.visititems(visit)
    return out
def same_particles(path_a, path_b):
    """Every per-particle dataset equal, particles matched by id."""
    a, b = datasets(path_a), datasets(path_b)
    assert sorted(a) == sorted(b), (path_a, sorted(a), sorted(b))
    ids = [k for k in a if k.split("/")[-1] == "id"][0]
    order_a, order_b = np.argsort(a[ids]), np.argsort(b[ids])
    n = len(order_a)
    assert len(order_b) == n, (path_a, n, len(order_b))
    for key in a:
        if a[key].ndim >= 1 and len(a[key]) == n:
            assert np.array_equal(a[key][order_a], b[key][order_b]), (path_a, key)
if __name__ == "__main__":
    same_particles(sys.argv[1], sys.argv[2])
PYEOF
$PY - "$WORK" <<'PYEOF' || fail "the two-process run differs from the serial one"
import json, sys
sys.path.insert(0, sys.argv[1])
from same import same_particles
work = sys.argv[1]
serial = json.load(open(f"{work}/serial.json"))
two = json.load(open(f"{work}/two.json"))  # one JSON object: process 0 alone prints
assert two["particles"] == serial["particles"] == 14**3, (two["particles"], serial["particles"])
assert two["steps"] == serial["steps"], (two["steps"], serial["steps"])
assert [s.split("/")[-1] for s in two["snapshots"]] == [s.split("/")[-1] for s in serial["snapshots"]]
assert abs(two["relative_energy_error"] - serial["relative_energy_error"]) < 1e-12
for name in ["snap_000001.h5", "snap_000002.h5", "checkpoint.h5"]:
    same_particles(f"{work}/serial/{name}", f"{work}/two/{name}")
PYEOF

# The tiny quarter-domain impact of the sweep tests, with its block time steps, to the end of its crater's growth
# (182 blocks): the late-stage switch, the crater samples and the end-of-growth decision (process 0 measures on
# the gathered particles and decides for all), the final crater. The same blocks, switch and end of growth as
# the serial run; crater radius and depth within 1e-4: the pair sums add in each process's order, and over the
# impact the 1e-16 differences grow to 1.3e-5 in the depth (measured); a lost halo differs by percents.
"$CK" simulate "$WORK/tiny.toml" --out "$WORK/impact1" --threads 1 --json --quiet >"$WORK/impact1.json" 2>"$WORK/err" ||
  fail "the serial impact exited $? ($(cat "$WORK/err"))"
two "$CK" simulate "$WORK/tiny.toml" --out "$WORK/impact2" --threads 1 --json --quiet >"$WORK/impact2.json" \
  2>"$WORK/impact2.err" || fail "the two-process impact exited $? ($(cat "$WORK/impact2.err"))"
[ "$(grep -c "^crater: radius" "$WORK/impact2.err")" -eq 1 ] ||
  fail "the two-process impact should report its crater once: $(cat "$WORK/impact2.err")"
$PY - "$WORK" <<'PYEOF' || fail "the two-process impact differs from the serial one"
import csv, json, sys
work = sys.argv[1]
serial = json.load(open(f"{work}/impact1.json"))
two = json.load(open(f"{work}/impact2.json"))
print("impact over two processes: steps", two["steps"], "crater radius", two["crater_radius"], "(serial",
      serial["crater_radius"], ") depth", two["crater_depth"], "(serial", serial["crater_depth"], ")")
assert two["processes"] == 2 and serial["processes"] == 1
assert two["steps"] == serial["steps"], (two["steps"], serial["steps"])
assert two["particles"] == serial["particles"] and two["ejected_particles"] == serial["ejected_particles"]
assert serial["crater_growth_ended"] and two["crater_growth_ended"]
assert serial["late_stage"]["switched"] and two["late_stage"]["switched"]
assert abs(two["crater_growth_end_time"] / serial["crater_growth_end_time"] - 1) < 1e-4
for key in ["crater_radius", "crater_depth"]:
    assert abs(two[key] / serial[key] - 1) < 1e-4, (key, two[key], serial[key])
rows = [list(csv.reader(open(f"{work}/{run}/crater_growth.csv"))) for run in ["impact1", "impact2"]]
assert len(rows[0]) == len(rows[1]) > 5, [len(r) for r in rows]
for name in ["crater.json", "crater_profile.csv", "ejecta.csv", "checkpoint.h5"]:
    open(f"{work}/impact2/{name}", "rb").close()
PYEOF

sed 's/^courant = 0.3/courant = -1/' "$WORK/sedov.toml" >"$WORK/bad.toml"
two "$CK" simulate "$WORK/bad.toml" --out "$WORK/bad" >"$WORK/out" 2>"$WORK/err"
status=$?
[ "$status" -eq 2 ] || fail "a bad time_step.courant over two processes exited $status, expected 2"
[ "$(grep -c "time_step.courant" "$WORK/err")" -eq 1 ] ||
  fail "the error should name time_step.courant once: $(cat "$WORK/err")"

# A process killed mid-run, after its first checkpoint (every 5 steps; about 90 steps in all); skin 0, so that
# the serial run it is compared with rebuilds its lists at every step as the distributed one does.
sed -e 's/^particles_per_side = 50/particles_per_side = 20/' -e 's/^sort_interval = 20/skin = 0.0\nsort_interval = 5/' \
  -e 's/^checkpoint_interval_seconds = 300/checkpoint_interval_steps = 5/' -e 's/^snapshot_times = .*/snapshot_times = [0.0]/' \
  "$DATA/examples/sedov.toml" >"$WORK/long.toml"
"$CK" simulate "$WORK/long.toml" --out "$WORK/whole" --threads 1 --quiet >/dev/null 2>"$WORK/err" ||
  fail "the uninterrupted run exited $? ($(cat "$WORK/err"))"
two "$CK" simulate "$WORK/long.toml" --out "$WORK/killed" --threads 1 --quiet >/dev/null 2>"$WORK/killed.err" &
job=$!
for _ in $(seq 1 400); do [ -e "$WORK/killed/checkpoint.h5" ] && break; sleep 0.025; done
victim=""
for pid in $(pgrep -x craterkit); do  # this job's processes only (ctest may run other craterkit tests)
  grep -qa "$WORK/killed" "/proc/$pid/cmdline" 2>/dev/null && victim=$pid
done
if [ -z "$victim" ]; then
  fail "no process of the two-process run to kill (it ended before its first checkpoint?)"
  wait "$job"
else
  kill -KILL "$victim"
  wait "$job"
  status=$?
  echo "killed process $victim of the two-process run after its first checkpoint: the job exited $status"
  grep -iE "signal 9|killed" "$WORK/killed.err" | head -2
  [ "$status" -ne 0 ] || fail "the job with a killed process exited 0"
  grep -qiE "signal 9|killed" "$WORK/killed.err" || fail "the job does not say a process was killed: $(cat "$WORK/killed.err")"
  two "$CK" simulate "$WORK/long.toml" --out "$WORK/killed" --threads 1 --quiet --resume >/dev/null 2>"$WORK/err" ||
    fail "the resume exited $? ($(cat "$WORK/err"))"
  $PY "$WORK/same.py" "$WORK/whole/checkpoint.h5" "$WORK/killed/checkpoint.h5" ||
    fail "the killed and resumed run ends elsewhere than the uninterrupted one"
fi

[ "$failures" -eq 0 ] && echo "test_simulate_mpi: all checks passed"
exit "$failures"
