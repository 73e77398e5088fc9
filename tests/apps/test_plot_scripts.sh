#!/usr/bin/env bash
# The plotting scripts users run on impact output (scripts/plot_crater_runs.py, plot_impact_section.py,
# plot_impact_plan.py, plot_energy_error.py) on a real run: a tiny impact to 0.3 s with snapshots; each
# script must exit 0 and write a PNG, and reject a bad argument with a message.
# Usage: test_plot_scripts.sh /path/to/craterkit /path/to/scripts
set -u
CK="$1"
SCRIPTS="$2"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

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
[run]
end_time = 0.3
gravity = [0.0, 0.0, -1.0]
[kernel]
max_smoothing_length = 1.8
[crater]
check_interval = 0.05
[output]
snapshot_times = [0.0, 0.1, 0.3]
TOMLEOF
"$CK" simulate "$WORK/tiny.toml" --out "$WORK/run" --threads 1 --quiet >/dev/null 2>"$WORK/err" ||
  fail "tiny impact exited $? ($(cat "$WORK/err"))"

$PY "$SCRIPTS/plot_crater_runs.py" "$WORK/growth.png" "tiny=$WORK/run" >"$WORK/out" 2>&1 ||
  fail "plot_crater_runs.py exited $? ($(cat "$WORK/out"))"
is_png "$WORK/growth.png" || fail "plot_crater_runs.py wrote no PNG"
$PY "$SCRIPTS/plot_impact_section.py" "$WORK/section.png" "tiny=$WORK/run@0.3" --width 0.5 >"$WORK/out" 2>&1 ||
  fail "plot_impact_section.py exited $? ($(cat "$WORK/out"))"
is_png "$WORK/section.png" || fail "plot_impact_section.py wrote no PNG"
$PY "$SCRIPTS/plot_impact_plan.py" "$WORK/plan.png" "$WORK/run" >"$WORK/out" 2>&1 ||
  fail "plot_impact_plan.py exited $? ($(cat "$WORK/out"))"
is_png "$WORK/plan.png" || fail "plot_impact_plan.py wrote no PNG"
$PY "$SCRIPTS/plot_energy_error.py" "$WORK/energy.png" "tiny=$WORK/run" >"$WORK/out" 2>&1 ||
  fail "plot_energy_error.py exited $? ($(cat "$WORK/out"))"
is_png "$WORK/energy.png" || fail "plot_energy_error.py wrote no PNG"

# A bad argument: a clear message, a non-zero exit, no figure.
$PY "$SCRIPTS/plot_energy_error.py" "$WORK/bad.png" "tiny=$WORK/nowhere" >"$WORK/out" 2>&1 &&
  fail "plot_energy_error.py accepted a run folder that does not exist"
grep -q "nowhere" "$WORK/out" || fail "plot_energy_error.py: the message does not name the folder: $(cat "$WORK/out")"
[ -e "$WORK/bad.png" ] && fail "plot_energy_error.py wrote a figure for a bad argument"

[ "$failures" -eq 0 ] && echo "all plotting-script checks passed"
exit "$failures"
