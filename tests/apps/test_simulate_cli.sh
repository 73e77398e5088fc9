#!/usr/bin/env bash
# Command-line contract of `craterkit simulate` and `craterkit measure`: --dry-run reports the set-up of the
# shipped SCI example (particle counts that tests/impact/test_graded_target.cpp also checks through the
# library) and writes nothing; a bad key exits with status 2 and names the key, also with --dry-run; a run
# killed at a checkpoint resumes to the crater of an uninterrupted run; `measure` on a run's last snapshot
# gives the run's own crater and writes only where --out says.
# Usage: test_simulate_cli.sh /path/to/craterkit /path/to/data
set -u
CK="$1"
DATA="$2"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$CK" simulate "$DATA/examples/sci.toml" --out "$WORK/run" --dry-run --json >"$WORK/out" 2>"$WORK/err" ||
  fail "simulate --dry-run sci.toml exited $? ($(cat "$WORK/err"))"
$PY - "$WORK/out" <<'PYEOF' || fail "simulate --dry-run --json: unexpected summary: $(cat "$WORK/out")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["setup"] == "impact", d
assert d["particles"] == d["target_particles"] + d["projectile_particles"], d
assert d["projectile_particles"] == 8, d  # a quarter of the 32-particle sphere at dx0 = a/2
assert 0 < d["fixed_particles"] < d["target_particles"], d
assert abs(d["t_transition"] - 0.1) < 1e-12, d  # 10 R_dom / c = 10 x 15 m / 1500 m/s
assert d["end_time"] == 500.0, d
assert (d["domain_radius"], d["particle_spacing"], d["inner_spacing"]) == (15.0, 0.5, 0.028), d
PYEOF
[ -e "$WORK/run" ] && fail "simulate --dry-run created the output directory"

"$CK" simulate "$DATA/examples/sci.toml" --dry-run >"$WORK/out" 2>"$WORK/err" || fail "text --dry-run exited $?"
grep -q "graded target" "$WORK/out" || fail "text --dry-run lacks the set-up description: $(cat "$WORK/out")"
grep -q "dry run, nothing simulated or written" "$WORK/out" || fail "text --dry-run lacks its last line"

sed 's/^grading = 0.1 /grading = 7.0 /' "$DATA/examples/sci.toml" >"$WORK/bad.toml"
"$CK" simulate "$WORK/bad.toml" --dry-run >"$WORK/out" 2>"$WORK/err"
status=$?
[ "$status" -eq 2 ] || fail "a bad impact.grading exited $status, expected 2"
grep -q "impact.grading" "$WORK/err" || fail "the error does not name impact.grading: $(cat "$WORK/err")"

# Kill and resume: the tiny impact of tests/impact/test_impact_run.cpp (2,144 particles, 1 s),
# once uninterrupted and once killed with SIGKILL as soon as its first checkpoint exists, then resumed with
# --resume: the resumed run ends with the same crater (crater.json), the same growth history and ejecta
# as the uninterrupted one, bit for bit.
cat >"$WORK/tiny.toml" <<'TOMLEOF'
[problem]
name = "tiny-impact"
setup = "impact"
[impact]
projectile_model = "resolved"
projectile_density = 1300.0
projectile_mass = 5450.0
impact_speed = 50.0
A_low = 0.27e6
domain_radius = 5.0
particle_spacing = 0.5
t_transition = 0.01
escape_speed = 1.0
[run]
end_time = 1.0
gravity = [0.0, 0.0, -1.0]
[kernel]
max_smoothing_length = 1.8
[crater]
check_interval = 0.1
[output]
checkpoint_interval_steps = 40
checkpoint_interval_seconds = 0
TOMLEOF
"$CK" simulate "$WORK/tiny.toml" --out "$WORK/whole" --threads 1 --quiet >/dev/null 2>"$WORK/err" ||
  fail "tiny impact exited $? ($(cat "$WORK/err"))"
"$CK" simulate "$WORK/tiny.toml" --out "$WORK/killed" --threads 1 --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -e "$WORK/killed/checkpoint.h5" ] && break
  sleep 0.05
done
if kill -0 "$pid" 2>/dev/null; then
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  [ -e "$WORK/killed/crater.json" ] && fail "a killed run left a crater.json"
  "$CK" simulate "$WORK/tiny.toml" --out "$WORK/killed" --threads 1 --quiet --resume >/dev/null 2>"$WORK/err" ||
    fail "resumed tiny impact exited $? ($(cat "$WORK/err"))"
  for file in crater.json crater_growth.csv ejecta.csv conservation.csv; do
    cmp -s "$WORK/whole/$file" "$WORK/killed/$file" || fail "resumed run: $file differs from the uninterrupted run's"
  done
else
  fail "the tiny impact ended before its first checkpoint could be killed"
fi

# measure: the run's last snapshot, measured with its run record, is the run's crater, byte for byte; without
# --out nothing is written (the run's crater.json stays as it was).
last=$(ls "$WORK/whole"/snap_*.h5 | tail -n 1)
cp "$WORK/whole/crater.json" "$WORK/crater.before"
touch -d '2000-01-01' "$WORK/whole/crater.json"
"$CK" measure "$last" --json >"$WORK/measured.json" 2>"$WORK/err" || fail "measure exited $? ($(cat "$WORK/err"))"
cmp -s "$WORK/measured.json" "$WORK/whole/crater.json" || fail "measure on the last snapshot differs from the run's crater.json"
[ "$(stat -c %Y "$WORK/whole/crater.json")" = "$(date -d '2000-01-01' +%s)" ] ||
  fail "measure without --out rewrote the run's crater.json"
"$CK" measure "$last" --out "$WORK/measured" >/dev/null 2>"$WORK/err" || fail "measure --out exited $? ($(cat "$WORK/err"))"
cmp -s "$WORK/measured/crater.json" "$WORK/whole/crater.json" || fail "measure --out DIR: crater.json differs from the run's"
"$CK" measure "$last" --spacing -1 >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--spacing" "$WORK/err" || fail "measure --spacing -1: no status-2 error naming the flag"

[ "$failures" -eq 0 ] && echo "all simulate CLI checks passed"
exit "$failures"
