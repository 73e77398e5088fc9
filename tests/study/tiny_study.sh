# Sourced by the sweep CLI tests: writes $WORK/tiny.toml, the tiny impact of tests/apps/test_simulate_cli.sh on a
# quarter domain (536 particles, 1-3 s a run; with a loose end-of-growth rule, so that the runs stop when their
# crater has grown, at about 0.8 s), and $WORK/study.toml, a 2 x 2 grid of impact speed and
# cohesion on it without the sizing rule; defines fail() and the failure count.
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

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
symmetry = "quarter"
[run]
end_time = 1.0
gravity = [0.0, 0.0, -1.0]
[kernel]
max_smoothing_length = 1.8
[crater]
check_interval = 0.05
radius_tolerance = 0.05
kinetic_energy_fraction = 0.5
[output]
checkpoint_interval_steps = 40
checkpoint_interval_seconds = 0
TOMLEOF

cat >"$WORK/study.toml" <<'TOMLEOF'
[study]
name = "tiny-grid"
description = "2 x 2 test grid"
base = "tiny.toml"
[sizing]
enabled = false
[grid]
impact_speed = [50.0, 60.0]
cohesion = [0.0, 100.0]
TOMLEOF
RUNS="impact_speed-50_cohesion-0 impact_speed-50_cohesion-100 impact_speed-60_cohesion-0 impact_speed-60_cohesion-100"
