#!/usr/bin/env bash
# craterkit run (the main job) on a tiny study of its own: the whole chain runs (sweep, fit, SCI cohesion,
# rates, ages: `craterkit report`'s code), its numbers are those the single commands give for the same fitted law
# (rates, age, scale with --fit), a second run reuses the finished runs and gives the same report.json, and bad
# flags are refused
# before anything is written.
# usage: test_main_job.sh CRATERKIT
set -u
CK="$1"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. "$(dirname "$0")/../study/tiny_study.sh"

cat >"$WORK/chain.toml" <<'TOMLEOF'
[study]
name = "tiny-chain"
base = "tiny.toml"
[sizing]
enabled = false
[grid]
impact_speed = [40.0, 50.0, 60.0]
cohesion = [0.0, 100.0]
TOMLEOF

"$CK" run --study "$WORK/chain.toml" --out "$WORK/out" --jobs 2 --threads 1 >"$WORK/report.txt" 2>"$WORK/err" ||
  fail "the main job exited $?: $(tail -5 "$WORK/err")"
for f in report.md report.json fit.json sweep/radii.csv scaled_radius.png rates.png ages.png; do
  [ -s "$WORK/out/$f" ] || fail "the main job did not write $f"
done
grep -q "## Model ages" "$WORK/report.txt" || fail "the printed report has no ages section"

# The report's numbers against the single commands on the same fit.
"$CK" rates --fit "$WORK/out/fit.json" --cohesion 1,0.05 --diameters 20,40 --json >"$WORK/rates.json" 2>/dev/null ||
  fail "rates --fit on the main job's fit exited $?"
"$CK" age "$CK_DATA/craters/ryugu_global_hirata2020.csv" --fit "$WORK/out/fit.json" --body ryugu \
  --cohesion 0.5 --json >"$WORK/age.json" 2>/dev/null || fail "age --fit on the main job's fit exited $?"
"$CK" scale --fit "$WORK/out/fit.json" --impactor-radius 0.05613 --impactor-density 2700 --velocity 2000 \
  --gravity 1.4e-4 --target-density 1300 --strength 0.2 --json >"$WORK/scale.json" 2>/dev/null ||
  fail "scale --fit on the main job's fit exited $?"
$PY - "$WORK" <<'PYEOF' || fail "the main job's report disagrees with rates/age/scale on its own fit"
import json, math, sys
w = sys.argv[1]
report = json.load(open(w + "/out/report.json"))
assert len(report["groups"]) == 1 and report["groups"][0]["group"] == {}, "the main job fits every row at once"
s = report["groups"][0]
rates = json.load(open(w + "/rates.json"))["rows"]
for d in (20.0, 40.0):
    single = [r["relative_rate"] for r in rates if r["crater_diameter"] == d and r["cohesion"] == 0.05][0]
    chain = [r["relative_rate"] for r in s["rates"]["rows"] if r["crater_diameter"] == d and r["cohesion"] == 0.05][0]
    assert math.isclose(single, chain, rel_tol=1e-12), (d, single, chain)
age = json.load(open(w + "/age.json"))["ages"][0]["median_yr"]
chain_age = [r["median_yr"] for r in s["ages"]["units"][0]["rows"] if r["cohesion"] == 0.5][0]
assert math.isclose(age, chain_age, rel_tol=1e-12), (age, chain_age)
# SCI: the impactor radius of 2 kg of aluminium, as the main job computes it.
a = (3 * 2.0 / (4 * math.pi * 2700.0)) ** (1 / 3)
assert abs(a - 0.05613) < 5e-6
sci = [r["crater_radius"] for r in s["sci"]["cohesions"] if r["cohesion"] == 0.2][0]
scale = json.load(open(w + "/scale.json"))["crater_radius"]
assert math.isclose(sci, scale, rel_tol=1e-3), (sci, scale)
# The fit's rows are the sweep's table, and fit.json is that fit.
assert report["tables"][0]["source"].endswith("sweep/radii.csv")
assert s["fit"]["residual_summary"]["rows"] == 6 and "residuals" not in s["fit"]
fit_file = json.load(open(w + "/out/fit.json"))
assert fit_file["parameters"] == s["fit"]["parameters"], (fit_file["parameters"], s["fit"]["parameters"])
# The cohesion for the observed SCI crater, when there is one, gives that crater under the fitted law.
y = s["sci"]["cohesion_for_observed_radius"]
radii = [r["crater_radius"] for r in s["sci"]["cohesions"]]
assert radii == sorted(radii, reverse=True), radii
if y is None:
    assert radii[0] < 7.25
PYEOF

# Again: every run is reused, the report is the same.
cp "$WORK/out/report.json" "$WORK/first.json"
"$CK" run --study "$WORK/chain.toml" --out "$WORK/out" --json >"$WORK/second.json" 2>"$WORK/err" ||
  fail "the second main job exited $?"
grep -q "started" "$WORK/err" && fail "the second main job ran runs again: $(grep started "$WORK/err")"
cmp -s "$WORK/out/report.json" "$WORK/first.json" || fail "the second main job changed report.json"
cmp -s "$WORK/out/report.json" <(cat "$WORK/second.json") || fail "--json does not print report.json"

# A dry run lists the runs and writes nothing.
"$CK" run --study "$WORK/chain.toml" --out "$WORK/dry" --dry-run >"$WORK/dry.txt" 2>"$WORK/err" ||
  fail "run --dry-run exited $?: $(cat "$WORK/err")"
grep -q "impact_speed-60_cohesion-100" "$WORK/dry.txt" || fail "run --dry-run does not list the runs"
[ -e "$WORK/dry" ] && fail "run --dry-run wrote its output folder"

# The default's live runs are runs of the shipped study, found in its shipped table by name.
"$CK" sweep "$CK_DATA/studies/main_job.toml" --out "$WORK/mj" --dry-run --json >"$WORK/mj.json" 2>"$WORK/err" ||
  fail "the default study does not plan: $(cat "$WORK/err")"
"$CK" sweep "$CK_DATA/studies/cohesion_size_coarse.toml" --out "$WORK/csc" --dry-run --json >"$WORK/csc.json" \
  2>"$WORK/err" || fail "the shipped study does not plan: $(cat "$WORK/err")"
$PY - "$WORK" "$CK_DATA/radii/cohesion_size_coarse.csv" <<'PYEOF' || fail "the default's runs are not the shipped study's"
import csv, json, sys
w, table = sys.argv[1], sys.argv[2]
live = {r["name"]: r for r in json.load(open(w + "/mj.json"))}
study = {r["name"]: r for r in json.load(open(w + "/csc.json"))}
rows = list(csv.DictReader(line for line in open(table) if not line.startswith("#")))
assert len(rows) == len(study), (len(rows), len(study))
assert {r["run"] for r in rows} == set(study), "the shipped table is not the shipped study's"
for name, run in live.items():
    assert name in study, name
    assert {k: v for k, v in run.items() if k != "index"} == {k: v for k, v in study[name].items() if k != "index"}, name
PYEOF

# Bad flags: status 2, the flag named, nothing written.
"$CK" run --full --study "$WORK/chain.toml" --out "$WORK/never" >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--full" "$WORK/err" || fail "--full with --study: $(cat "$WORK/err")"
: >"$WORK/file"
"$CK" run --study "$WORK/chain.toml" --out "$WORK/file" >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--out" "$WORK/err" || fail "--out on a file: $(cat "$WORK/err")"
"$CK" run --study "$WORK/missing.toml" --out "$WORK/never" >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] || fail "a missing study file: status $?"
[ -e "$WORK/never" ] && fail "a refused main job left its output folder"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all main-job checks passed"
