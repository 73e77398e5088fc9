#!/usr/bin/env bash
# Command-line contract of `craterkit scale`, `fit` and `run` (scripts depend on it): exit status 0 on
# success and 2 on bad arguments with a message naming the flag, JSON keys present, the inverse round
# trip, atomic output and nothing written on an error; fits per group of a sweep-style table.
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

IMPACT=(--impactor-density 2700 --velocity 5000 --target-density 1300 --gravity 1.4e-4 --strength 0.05)
HH=(--H1 0.60 --H2 0.25 --mu 0.44 --nu 0.4)

# scale: text and JSON, with the keys of the contract
expect_status 0 "" scale --impactor-radius 0.1 "${IMPACT[@]}" "${HH[@]}"
grep -q "crater radius" "$WORK/out" || fail "scale text output lacks the crater radius"
expect_status 0 "" scale --impactor-radius 0.1 "${IMPACT[@]}" "${HH[@]}" --json
cp "$WORK/out" "$WORK/hh.json"
$PY - "$WORK/hh.json" <<'PYEOF' || fail "scale --json lacks keys"
import json, sys
d = json.load(open(sys.argv[1]))
for key in ("crater_radius", "impactor_radius", "pi_R", "pi_2", "pi_3", "regime"):
    assert key in d, key
assert d["regime"] in ("gravity", "strength", "transitional")
PYEOF

# the Holsapple form with the converted constants gives the same radius
K2=$($PY -c "print(repr((0.60/0.25)**(2/0.44)))")
expect_status 0 "" scale --impactor-radius 0.1 "${IMPACT[@]}" --K1 0.60 --K2 "$K2" --mu 0.44 --nu 0.4 --json
$PY - "$WORK/hh.json" "$WORK/out" <<'PYEOF' || fail "Holsapple and HH2011 forms disagree on the CLI"
import json, sys
a, b = (json.load(open(p))["crater_radius"] for p in sys.argv[1:3])
assert abs(a / b - 1) < 1e-12, (a, b)
PYEOF

# inverse round trip through the CLI
R=$($PY -c "import json; print(repr(json.load(open('$WORK/hh.json'))['crater_radius']))")
expect_status 0 "" scale --crater-radius "$R" "${IMPACT[@]}" "${HH[@]}" --json
$PY - "$WORK/out" <<'PYEOF' || fail "scale --crater-radius does not round-trip"
import json, sys
assert abs(json.load(open(sys.argv[1]))["impactor_radius"] / 0.1 - 1) < 1e-9
PYEOF

# --params with an explicit override
expect_status 0 "" scale --params jutzi2022_ryugu --impactor-radius 0.1 --impactor-density 2700 --velocity 5000 \
  --gravity 1.4e-4 --json
expect_status 0 "" scale --params jutzi2022_ryugu --impactor-radius 0.1 --impactor-density 2700 --velocity 5000 \
  --gravity 1.4e-4 --strength 0.05 --target-density 1300 --json
$PY - "$WORK/hh.json" "$WORK/out" <<'PYEOF' || fail "--params jutzi2022_ryugu differs from the same constants as flags"
import json, sys
a, b = (json.load(open(p))["crater_radius"] for p in sys.argv[1:3])
assert abs(a / b - 1) < 1e-12, (a, b)
PYEOF

# errors: exit 2 and the flag named
expect_status 2 "cannot be mixed" scale --impactor-radius 0.1 "${IMPACT[@]}" --K1 0.6 --H2 0.25 --mu 0.44 --nu 0.4
expect_status 2 "--velocity" scale --impactor-radius 0.1 --impactor-density 2700 --velocity fast \
  --target-density 1300 --gravity 1.4e-4 --strength 0.05 "${HH[@]}"
expect_status 2 "--gravity is required" scale --impactor-radius 0.1 --impactor-density 2700 --velocity 5000 \
  --target-density 1300 --strength 0.05 "${HH[@]}"
expect_status 2 "--impactor-radius -1" scale --impactor-radius -1 "${IMPACT[@]}" "${HH[@]}"
expect_status 2 "--mu" scale --impactor-radius 0.1 "${IMPACT[@]}" --H1 0.6 --H2 0.25 --nu 0.4
expect_status 2 "not known" scale --params no_such_set --impactor-radius 0.1 "${IMPACT[@]}"
expect_status 2 "--nu -1" scale --impactor-radius 0.1 "${IMPACT[@]}" --H1 0.6 --H2 0.25 --mu 0.44 --nu -1
expect_status 0 "" scale --help

# fit: JSON contract, --out written atomically, nothing written on an error
TABLE="$CRATERKIT_DATA_DIR/examples/radii_example.csv"
expect_status 0 "" fit "$TABLE" --form hh2011 --out "$WORK/fit.json" --json
$PY - "$WORK/fit.json" "$WORK/out" <<'PYEOF' || fail "fit JSON lacks the contract keys"
import json, sys
written, printed = (json.load(open(p)) for p in sys.argv[1:3])
assert written == printed
for name in ("H1", "H2", "mu", "nu"):
    p = written["parameters"][name]
    assert "value" in p and "sigma" in p, name
for key in ("chi2", "dof", "residual_summary"):
    assert key in written, key
assert written["dof"] == 32 - 4
assert "residuals" not in written and written["residual_summary"]["rows"] == 32
PYEOF
ls -a "$WORK" | grep -q '\.tmp\.' && fail "a temporary file was left behind"

# fit --residuals: every row's residual in a CSV; the JSON does not repeat the table (its size does not grow
# with the rows: a table of ten copies of the example's rows gives a JSON of the same size)
expect_status 0 "" fit "$TABLE" --form hh2011 --out "$WORK/fit.json" --residuals "$WORK/residuals.csv" --quiet
grep -q "written: $WORK/residuals.csv" "$WORK/out" || fail "fit does not say that it wrote --residuals"
{ grep -v "^#" "$TABLE" | head -1; for k in 1 2 3 4 5 6 7 8 9 10; do grep -v '^#' "$TABLE" | tail -n +2; done; } >"$WORK/ten.csv"
expect_status 0 "" fit "$WORK/ten.csv" --form hh2011 --out "$WORK/fit10.json"
$PY - "$WORK/fit.json" "$WORK/residuals.csv" "$WORK/fit10.json" <<'PYEOF' || fail "fit --residuals or the JSON's size"
import csv, json, math, os, sys
fit = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
assert list(rows[0].keys()) == ["line", "observed", "model", "log_residual", "normalized", "regime",
                                "gravity_share", "strength_to_gravity"], list(rows[0].keys())
assert len(rows) == 32 == fit["residual_summary"]["rows"]
logs = [float(r["log_residual"]) for r in rows]
for r in rows:
    assert math.isclose(float(r["log_residual"]), math.log(float(r["model"]) / float(r["observed"])), abs_tol=1e-12)
    assert r["regime"] in ("gravity", "transitional", "strength")
s = fit["residual_summary"]
assert math.isclose(s["rms_log_residual"], math.sqrt(sum(x * x for x in logs) / 32), rel_tol=1e-12)
assert s["log_residual_quantiles"]["min"] == min(logs) and s["log_residual_quantiles"]["max"] == max(logs)
sizes = [os.path.getsize(sys.argv[1]), os.path.getsize(sys.argv[3])]
assert json.load(open(sys.argv[3]))["residual_summary"]["rows"] == 320
assert abs(sizes[1] - sizes[0]) < 200, sizes
PYEOF
expect_status 2 "--residuals" fit "$TABLE" --residuals "$WORK/no/such/folder/r.csv" --out "$WORK/never.json"
expect_status 2 "--residuals" fit "$TABLE" --residuals "$WORK/never.json" --out "$WORK/never.json"
[ -e "$WORK/never.json" ] && fail "fit wrote its output despite an error"
expect_status 0 "" fit "$TABLE" --fix nu=0.4 --json
$PY - "$WORK/out" <<'PYEOF' || fail "fixed parameter not reported with sigma 0"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["form"] == "holsapple"
assert d["parameters"]["nu"]["value"] == 0.4 and d["parameters"]["nu"]["sigma"] == 0
assert set(d["parameters"]) == {"K1", "K2", "mu", "nu"}
PYEOF
# --fix takes one NAME=VALUE per flag and never swallows the table that follows it
expect_status 0 "" fit --fix nu=0.4 "$TABLE" --json
expect_status 2 "mu=0.44" fit "$TABLE" --fix nu=0.4 mu=0.44
# the fitted law feeds back into scale with --fit
expect_status 0 "" scale --fit "$WORK/fit.json" --impactor-radius 0.1 "${IMPACT[@]}" --json

printf 'impactor_radius,impactor_density,velocity,target_density,gravity,crater_radius\n1,2,3,4,5,6\n' >"$WORK/bad.csv"
expect_status 2 "'strength'" fit "$WORK/bad.csv" --out "$WORK/never.json"
[ -e "$WORK/never.json" ] && fail "fit wrote its output despite an error"
expect_status 2 "--form" fit "$TABLE" --form cubic --out "$WORK/never.json"
expect_status 2 "--fix" fit "$TABLE" --fix nu --out "$WORK/never.json"
expect_status 2 "'zeta'" fit "$TABLE" --fix zeta=1 --out "$WORK/never.json"
[ -e "$WORK/never.json" ] && fail "fit wrote its output despite an error"
expect_status 2 "" fit
expect_status 0 "" fit --help

# fit on a sweep-style table: one fit per group, the grouped JSON, --group-by, --require-growth-ended
GROUPED="$CRATERKIT_DATA_DIR/examples/radii_groups_example.csv"
expect_status 0 "" fit "$GROUPED" --form hh2011 --fix nu=0.4 --out "$WORK/groups.json" --json
$PY - "$WORK/groups.json" "$WORK/out" <<'PYEOF' || fail "grouped fit JSON is not one fit per friction"
import json, sys
written, printed = (json.load(open(p)) for p in sys.argv[1:3])
assert written == printed
assert written["group_by"] == ["friction", "porosity", "resolution"], written["group_by"]
groups = written["groups"]
assert [g["group"]["friction"] for g in groups] == ["0.55", "0.8"]
truth = {"0.55": {"H1": 0.60, "H2": 0.25, "mu": 0.44}, "0.8": {"H1": 0.75, "H2": 0.30, "mu": 0.40}}
flagged = 0
for g in groups:
    assert g["rows"] == 30 and g["cohesions"] == 5
    for name, value in truth[g["group"]["friction"]].items():
        p = g["fit"]["parameters"][name]
        assert abs(p["value"] - value) < 2 * p["sigma"], (g["group"], name, p, value)
    assert g["fit"]["parameters"]["nu"]["fixed"]
    assert "regimes" not in g and sum(g["regime_counts"].values()) == 30
    flagged += len(g["growth_not_ended"])
assert flagged == 3 and written["excluded_rows"]["lines"] == []
PYEOF
expect_status 0 "" fit "$GROUPED" --form hh2011 --fix nu=0.4 --residuals "$WORK/group_residuals.csv"
$PY - "$WORK/group_residuals.csv" <<'PYEOF' || fail "grouped fit --residuals"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys())[:6] == ["friction", "porosity", "resolution", "line", "run", "growth_ended"]
assert len(rows) == 60 and [r["friction"] for r in rows] == ["0.55"] * 30 + ["0.8"] * 30
assert all(r["run"] and r["regime"] in ("gravity", "transitional", "strength") for r in rows)
PYEOF
grep -q "== friction=0.55, porosity=0.5, resolution=18" "$WORK/out" || fail "grouped text report lacks the group heading"
[ "$(grep -c "regimes (strength/gravity" "$WORK/out")" -eq 2 ] || fail "grouped text report lacks regime counts"
grep -q "growth_ended = false" "$WORK/out" || fail "grouped text report does not flag rows whose growth had not ended"
expect_status 0 "" fit "$GROUPED" --form hh2011 --fix nu=0.4 --group-by none --json
$PY - "$WORK/out" <<'PYEOF' || fail "--group-by none is not one single fit"
import json, sys
d = json.load(open(sys.argv[1]))
assert "groups" not in d and "parameters" in d and d["residual_summary"]["rows"] == 60
PYEOF
expect_status 0 "" fit "$GROUPED" --form hh2011 --fix nu=0.4 --group-by friction --require-growth-ended --json
$PY - "$WORK/out" <<'PYEOF' || fail "--group-by friction --require-growth-ended"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["group_by"] == ["friction"] and d["pooled"] == {"porosity": ["0.5"], "resolution": ["18"]}
assert d["excluded_rows"] == {"require_growth_ended": True, "lines": [27, 32, 33]}, d["excluded_rows"]
assert sum(g["rows"] for g in d["groups"]) == 57
assert all(not g["growth_not_ended"] for g in d["groups"])
PYEOF
expect_status 2 "'frictoin'" fit "$GROUPED" --group-by frictoin --out "$WORK/never.json"
expect_status 2 "'growth_ended'" fit "$TABLE" --require-growth-ended --out "$WORK/never.json"
sed 's/,strength,/,strenght,/' "$GROUPED" >"$WORK/misspelt.csv"
expect_status 2 "did you mean 'strength'" fit "$WORK/misspelt.csv" --out "$WORK/never.json"
[ -e "$WORK/never.json" ] && fail "fit wrote its output despite an error"
# a group's law feeds scale; without --group the error lists the groups
expect_status 0 "" scale --fit "$WORK/groups.json" --group friction=0.8 --impactor-radius 0.1 "${IMPACT[@]}" --json
expect_status 2 "friction=0.8,porosity=0.5,resolution=18" scale --fit "$WORK/groups.json" --impactor-radius 0.1 \
  "${IMPACT[@]}"
expect_status 2 "--group" scale --fit "$WORK/fit.json" --group friction=0.8 --impactor-radius 0.1 "${IMPACT[@]}"


if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all CLI checks passed"
