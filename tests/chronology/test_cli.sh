#!/usr/bin/env bash
# Command-line contract of `craterkit rates` and `craterkit age` with a fitted law: --fit of a grouped fit
# needs --group (the error lists the groups); the fit's covariance is carried into the outputs (percentiles
# beside the central values, seeded and reproducible); a law without a covariance changes nothing.
# Usage: test_cli.sh /path/to/craterkit
set -u
CK="$1"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_status STATUS PATTERN ARGS... : runs craterkit, checks the exit status and that stderr matches PATTERN
expect_status() {
  local want=$1 pattern=$2
  shift 2
  "$CK" "$@" >"$WORK/out" 2>"$WORK/err"
  local got=$?
  [ "$got" -eq "$want" ] || fail "craterkit $* exited $got, expected $want ($(cat "$WORK/err"))"
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$WORK/err"; then
    fail "craterkit $*: stderr lacks '$pattern': $(cat "$WORK/err")"
  fi
}

EXAMPLES="$CRATERKIT_DATA_DIR/examples"
COUNTS="$CRATERKIT_DATA_DIR/craters/ryugu_global_hirata2020.csv"
expect_status 0 "" fit "$EXAMPLES/radii_groups_example.csv" --form hh2011 --fix nu=0.4 --out "$WORK/groups.json"
RATES=(--cohesion 0,0.05,1 --diameters 20,100)

# rates: a group's law with its uncertainty
expect_status 0 "" rates --fit "$WORK/groups.json" --group friction=0.55 "${RATES[@]}" --json
cp "$WORK/out" "$WORK/rates.json"
$PY - "$WORK/rates.json" <<'PYEOF' || fail "rates --fit --group JSON lacks the scaling-law uncertainty"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["scaling_law"]["group"] == {"friction": "0.55", "porosity": "0.5", "resolution": "18"}
u = d["scaling_law_uncertainty"]
assert u["samples"] == 1000 and u["seed"] == 1 and u["drawn"] == ["H1", "H2", "mu"] and u["fixed"] == ["nu"]
for row in d["rows"]:
    s = row["scaling_law_uncertainty"]
    for key in ("impactor_radius", "relative_rate", "production_rate_per_km2_per_yr"):
        p = s[key]
        assert p["p16"] <= p["p50"] <= p["p84"], (key, p)
    a = s["impactor_radius"]
    assert a["p16"] < row["impactor_radius"] < a["p84"], row
    if row["cohesion"] == 0:
        assert s["relative_rate"] == {"p16": 1.0, "p50": 1.0, "p84": 1.0}
    else:
        assert s["relative_rate"]["p16"] < s["relative_rate"]["p84"]
PYEOF
expect_status 0 "" rates --fit "$WORK/groups.json" --group friction=0.55 "${RATES[@]}" --json
cmp -s "$WORK/out" "$WORK/rates.json" || fail "rates with the same seed differ"
expect_status 0 "" rates --fit "$WORK/groups.json" --group friction=0.55 "${RATES[@]}" --json --seed 2
cmp -s "$WORK/out" "$WORK/rates.json" && fail "rates with another seed are identical"
expect_status 0 "" rates --fit "$WORK/groups.json" --group friction=0.55 "${RATES[@]}"
grep -q "^# scaling-law uncertainty: 15.87-84.13 % range over 1000 draws of the fitted H1, H2, mu" "$WORK/out" ||
  fail "rates text lacks the uncertainty comment"
grep -q "relative_rate_law_range" "$WORK/out" || fail "rates text lacks the law-range columns"

# without --group, or with a group that is not there, the error lists the groups
expect_status 2 "friction=0.55,porosity=0.5,resolution=18; friction=0.8,porosity=0.5,resolution=18" \
  rates --fit "$WORK/groups.json" "${RATES[@]}"
expect_status 2 "matches no group" rates --fit "$WORK/groups.json" --group friction=0.6 "${RATES[@]}"
expect_status 2 "--group" rates --params jutzi2022_ryugu --group friction=0.55 "${RATES[@]}"
expect_status 2 "--samples" rates --fit "$WORK/groups.json" --group friction=0.55 "${RATES[@]}" --samples 10

# --samples 0, a constant set, or a constant overriding the fit: no uncertainty in the output
for args in "--fit $WORK/groups.json --group friction=0.55 --samples 0" "--params jutzi2022_ryugu" \
  "--fit $WORK/groups.json --group friction=0.55 --mu 0.45"; do
  # shellcheck disable=SC2086
  expect_status 0 "" rates $args "${RATES[@]}" --json
  grep -q "scaling_law_uncertainty" "$WORK/out" && fail "rates $args reports a scaling-law uncertainty"
done
grep -q "covariance is not propagated" "$WORK/err" || fail "overriding a fitted constant does not say so"

# age: counting and law uncertainty side by side
expect_status 0 "" age "$COUNTS" --fit "$WORK/groups.json" --group friction=0.8 --cohesion 0,0.05 --json
$PY - "$WORK/out" <<'PYEOF' || fail "age --fit JSON lacks the two uncertainties"
import json, sys
d = json.load(open(sys.argv[1]))
assert set(d["scaling_law_uncertainty"]["reported"]) == {"counting", "scaling_law", "total"}
for a in d["ages"]:
    law = a["scaling_law_uncertainty"]["median_yr"]
    assert law["p16"] < a["median_yr"] < law["p84"], (law, a["median_yr"])
    total = a["total_uncertainty"]
    lo, hi = a["sigma1_yr"]
    assert total["sigma1_yr"][1] - total["sigma1_yr"][0] > hi - lo
    assert total["sigma2_yr"][0] < total["sigma1_yr"][0] < total["median_yr"] < total["sigma1_yr"][1]
PYEOF
expect_status 0 "" age "$COUNTS" --fit "$WORK/groups.json" --group friction=0.8 --cohesion 0,0.05
grep -q "counting_1-sigma_Myr" "$WORK/out" && grep -q "law_1-sigma_Myr" "$WORK/out" &&
  grep -q "total_1-sigma_Myr" "$WORK/out" || fail "age text does not label the counting, law and total columns"
expect_status 0 "" age "$COUNTS" --params jutzi2022_ryugu --cohesion 0,0.05 --json
grep -q "total_uncertainty" "$WORK/out" && fail "age with a constant set reports a scaling-law uncertainty"

# age of the real two-size count (docs/chronology.md, Real counts): both bins date as N(>=20 m) = 77 alone (the
# binned likelihood depends on the age only through the total), and the fit range splits them into 66 + 11
TWO="$CRATERKIT_DATA_DIR/craters/ryugu_global_hirata2020_20_100m.csv"
for range in "" "--max-diameter 99" "--min-diameter 100"; do
  # shellcheck disable=SC2086
  expect_status 0 "" age "$TWO" --params jutzi2022_ryugu --cohesion 0,1 --json $range
  cp "$WORK/out" "$WORK/two${range// /}.json"
done
expect_status 0 "" age "$COUNTS" --params jutzi2022_ryugu --cohesion 0,1 --json
$PY - "$WORK/out" "$WORK/two.json" "$WORK/two--max-diameter99.json" "$WORK/two--min-diameter100.json" <<'PYEOF' ||
import json, sys
one, both, small, large = (json.load(open(f))["ages"] for f in sys.argv[1:])
for a, b in zip(one, both):
    assert abs(a["median_yr"] / b["median_yr"] - 1) < 1e-9, (a["median_yr"], b["median_yr"])
    assert b["craters_in_range"] == 77
for s, l in zip(small, large):
    assert s["craters_in_range"] == 66 and l["craters_in_range"] == 11, (s["craters_in_range"], l["craters_in_range"])
    assert l["median_yr"] > 10 * s["median_yr"], (s["median_yr"], l["median_yr"])  # the small-crater deficit
# a stronger target narrows the gap between the sizes
assert large[1]["median_yr"] / small[1]["median_yr"] < large[0]["median_yr"] / small[0]["median_yr"]
PYEOF
  fail "age of ryugu_global_hirata2020_20_100m.csv: bins, fit ranges or the size contrast are not as documented"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
