#!/usr/bin/env bash
# Command-line contract of `craterkit simulate` that does not need a run: --dry-run reports the set-up of
# the shipped SCI example (particle counts that tests/sph_core/test_graded_target.cpp also checks through the
# library) and writes nothing; a bad key exits with status 2 and names the key, also with --dry-run.
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

[ "$failures" -eq 0 ] && echo "all simulate CLI checks passed"
exit "$failures"
