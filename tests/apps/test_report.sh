#!/usr/bin/env bash
# craterkit report on the shipped radii tables and on a small table of its own: it writes report.md,
# report.json, the fit files and the figures; its numbers are those of craterkit fit, scale, rates and age on
# the same input; the cohesion of the observed SCI crater is the linear interpolation in the table ("none in
# range" when there is none); without its plotting script the numbers are still written and the skipped
# figures named; bad input exits with status 2, names the problem and writes nothing.
# usage: test_report.sh CRATERKIT DATA
set -u
CK="$1"
DATA="$2"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
CS="$DATA/radii/cohesion_size_coarse.csv"
FP="$DATA/radii/friction_porosity_coarse.csv"
HAVE_MPL=1
$PY -c "import matplotlib" 2>/dev/null || HAVE_MPL=0

# 1. The shipped tables together.
"$CK" report --radii "$CS" --radii "$FP" --out "$WORK/r" >"$WORK/stdout" 2>"$WORK/err" ||
  fail "report on the shipped tables exited $?: $(tail -5 "$WORK/err")"
for f in report.md report.json fit_cohesion_size_coarse.json fit_friction_porosity_coarse.json; do
  [ -s "$WORK/r/$f" ] || fail "report did not write $f"
done
if [ "$HAVE_MPL" -eq 1 ]; then
  for f in scaled_radius.png sci_cohesion.png friction.png rates.png ages.png; do
    [ -s "$WORK/r/$f" ] || fail "report did not draw $f: $(cat "$WORK/err")"
    grep -q "($f)" "$WORK/r/report.md" || fail "report.md does not show $f"
  done
fi
grep -q "report: fitting" "$WORK/err" || fail "no progress messages on stderr"
head -c "$(stat -c %s "$WORK/r/report.md")" "$WORK/stdout" | cmp -s - "$WORK/r/report.md" ||
  fail "the printed report is not report.md"
for section in "## Scaling constants" "## The SCI crater under the fitted laws" \
  "## The SCI crater in the engine, against cohesion" "## The SCI crater in the engine, against friction" \
  "## Crater-formation rates on Ryugu" "## Model ages of the Ryugu counts"; do
  grep -qF "$section" "$WORK/r/report.md" || fail "report.md lacks '$section'"
done

# The fit of each table is craterkit fit's on the table without its sigma column (same lines, same JSON).
$PY - "$CS" "$WORK/cs_unweighted.csv" "$FP" "$WORK/fp_unweighted.csv" <<'PYEOF' || fail "cannot cut the sigma column"
import sys
for source, target in zip(sys.argv[1::2], sys.argv[2::2]):
    out, column = [], None
    for line in open(source):
        if line.startswith("#"):
            out.append(line)
            continue
        cells = line.rstrip("\n").split(",")
        if column is None:
            column = cells.index("crater_radius_sigma")
        del cells[column]
        out.append(",".join(cells) + "\n")
    open(target, "w").write("".join(out))
PYEOF
for t in cs fp; do
  "$CK" fit "$WORK/${t}_unweighted.csv" --form hh2011 --fix nu=0.4 --out "$WORK/fit_$t.json" --quiet >/dev/null 2>"$WORK/err" ||
    fail "craterkit fit on $t exited $?: $(cat "$WORK/err")"
done
$PY - "$WORK" <<'PYEOF' || fail "the report's fits are not craterkit fit's"
import json, sys
w = sys.argv[1]
for mine, single in (("fit_cohesion_size_coarse.json", "fit_cs.json"), ("fit_friction_porosity_coarse.json", "fit_fp.json")):
    a = json.load(open(f"{w}/r/{mine}"))
    b = json.load(open(f"{w}/{single}"))
    assert a == b, (mine, a, b)
report = json.load(open(f"{w}/r/report.json"))
assert [t["fit_file"] for t in report["tables"]] == ["fit_cohesion_size_coarse.json", "fit_friction_porosity_coarse.json"]
fitted = [g for g in report["groups"] if g["fitted"]]
assert fitted, "no group fitted"
single = json.load(open(f"{w}/fit_cs.json"))["groups"]
for g in fitted:
    if g["table"].endswith("cohesion_size_coarse.csv"):
        same = [s for s in single if s["group"] == g["group"]][0]
        assert g["fit"] == same["fit"], g["group"]
PYEOF

# Rates, ages and the SCI crater of a fitted group against craterkit rates, age and scale on the same fit.
GROUP=$($PY -c "
import json, sys
r = json.load(open(sys.argv[1]))
g = [g for g in r['groups'] if 'rates' in g][0]
print(','.join(f'{k}={v}' for k, v in g['group'].items()))" "$WORK/r/report.json") || fail "no group with rates"
FIT="$WORK/r/fit_cohesion_size_coarse.json"
"$CK" rates --fit "$FIT" --group "$GROUP" --cohesion 1,0.05,0.5 --diameters 20,100 --json >"$WORK/rates.json" \
  2>/dev/null || fail "rates --fit on the report's fit exited $?"
"$CK" age "$DATA/craters/ryugu_global_hirata2020.csv" --fit "$FIT" --group "$GROUP" --body ryugu --cohesion 0.5 \
  --json >"$WORK/age0.json" 2>/dev/null || fail "age --fit exited $?"
"$CK" age "$DATA/craters/ryugu_global_hirata2020_20_100m.csv" --fit "$FIT" --group "$GROUP" --body ryugu \
  --cohesion 0.05 --max-diameter 99 --json >"$WORK/age1.json" 2>/dev/null || fail "age --max-diameter 99 exited $?"
"$CK" age "$DATA/craters/ryugu_global_hirata2020_20_100m.csv" --fit "$FIT" --group "$GROUP" --body ryugu \
  --cohesion 2 --min-diameter 100 --json >"$WORK/age2.json" 2>/dev/null || fail "age --min-diameter 100 exited $?"
RHO=$($PY -c "
import json, sys
r = json.load(open(sys.argv[1]))
print(repr([g for g in r['groups'] if 'rates' in g][0]['sci']['target_density']))" "$WORK/r/report.json")
A=$($PY -c "import math; print(repr((3 * 2.0 / (4 * math.pi * 2700.0)) ** (1 / 3)))")
"$CK" scale --fit "$FIT" --group "$GROUP" --impactor-radius "$A" --impactor-density 2700 --velocity 2000 \
  --gravity 1.4e-4 --target-density "$RHO" --strength 0.2 --json >"$WORK/scale.json" 2>/dev/null ||
  fail "scale --fit exited $?"
$PY - "$WORK" <<'PYEOF' || fail "the report's rates, ages or SCI crater disagree with rates/age/scale"
import json, math, sys
w = sys.argv[1]
r = json.load(open(f"{w}/r/report.json"))
g = [g for g in r["groups"] if "rates" in g][0]
rates = json.load(open(f"{w}/rates.json"))["rows"]
for d in (20.0, 100.0):
    for y in (0.05, 0.5):
        single = [x["relative_rate"] for x in rates if x["crater_diameter"] == d and x["cohesion"] == y][0]
        mine = [x["relative_rate"] for x in g["rates"]["rows"] if x["crater_diameter"] == d and x["cohesion"] == y][0]
        assert math.isclose(single, mine, rel_tol=1e-12), (d, y, single, mine)
for k, y in ((0, 0.5), (1, 0.05), (2, 2.0)):
    single = json.load(open(f"{w}/age{k}.json"))["ages"][0]
    unit = g["ages"]["units"][k]
    mine = [x for x in unit["rows"] if x["cohesion"] == y][0]
    assert math.isclose(single["median_yr"], mine["median_yr"], rel_tol=1e-12), (k, single["median_yr"], mine["median_yr"])
assert [u["craters"] for u in g["ages"]["units"]] == [77, 66, 11], [u["craters"] for u in g["ages"]["units"]]
sci = [x["crater_radius"] for x in g["sci"]["cohesions"] if x["cohesion"] == 0.2][0]
scale = json.load(open(f"{w}/scale.json"))["crater_radius"]
assert math.isclose(sci, scale, rel_tol=1e-12), (sci, scale)
PYEOF

# The engine's SCI craters: every SCI row of the tables, and the cohesion of 7.25 m by linear interpolation.
$PY - "$WORK/r/report.json" "$CS" "$FP" <<'PYEOF' || fail "the engine's SCI series are not the tables' rows"
import csv, json, math, sys
report = json.load(open(sys.argv[1]))
a_sci = (3 * 2.0 / (4 * math.pi * 2700.0)) ** (1 / 3)
known = {"impactor_radius", "impactor_density", "velocity", "target_density", "gravity", "strength",
         "crater_radius", "crater_radius_sigma", "run", "growth_ended"}
def crossings(points, level):
    out = []
    for (x0, r0), (x1, r1) in zip(points, points[1:]):
        if (r0 - level) * (r1 - level) < 0:
            out.append(x0 + (level - r0) * (x1 - x0) / (r1 - r0))
    out += [x for x, r in points if r == level]
    return sorted(set(out))
expected = {}
for table in sys.argv[2:]:
    for row in csv.DictReader(l for l in open(table) if not l.startswith("#")):
        sci = (math.isclose(float(row["impactor_radius"]), a_sci, rel_tol=1e-9) and float(row["velocity"]) == 2000
               and math.isclose(float(row["gravity"]), 1.4e-4, rel_tol=1e-9))
        if not sci:
            continue
        key = (table, tuple(sorted((k, v) for k, v in row.items() if k not in known)))
        expected.setdefault(key, []).append((float(row["strength"]), float(row["crater_radius"])))
series = report["sci_engine"]["series"]
assert len(series) == len(expected), (len(series), len(expected))
for s in series:
    key = (s["table"], tuple(sorted(s["target"].items())))
    points = sorted(expected[key])
    assert [(p["cohesion"], p["crater_radius"]) for p in s["points"]] == points, key
    best = crossings(points, 7.25)
    got = s["cohesion_for_observed_radius"]
    if best:
        assert math.isclose(got, best[0], rel_tol=1e-12), (key, got, best)
    else:
        assert got is None and s["summary"].startswith("none in range"), (key, s["summary"])
friction = report["friction"]["series"]
rows = sum(len(s["points"]) for s in friction)
zero = sum(1 for pts in expected.values() for y, r in pts if y == 0.0)
assert rows == zero, (rows, zero)
PYEOF

# 2. A sweep folder, and a small table of its own: a crossing at a known cohesion, one with none in range.
mkdir -p "$WORK/sweep"
cp "$CS" "$WORK/sweep/radii.csv"
"$CK" report "$WORK/sweep" --out "$WORK/s" --quiet >/dev/null 2>"$WORK/err" || fail "report DIR exited $?: $(cat "$WORK/err")"
[ -s "$WORK/s/fit.json" ] || fail "report DIR did not write fit.json"
[ -s "$WORK/err" ] && fail "--quiet still wrote: $(cat "$WORK/err")"
A=$($PY -c "import math; print(repr((3 * 2.0 / (4 * math.pi * 2700.0)) ** (1 / 3)))")
{
  echo "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,friction,porosity"
  for row in 0:8.0:0.4 0.1:7.0:0.4 0.3:6.0:0.4 0:5.0:0.55 0.1:4.5:0.55 0.5:4.0:0.55; do
    IFS=: read -r y r f <<<"$row"
    echo "$A,2700,2000,1300,1.4e-4,$y,$r,$f,0.5"
  done
} >"$WORK/small.csv"
"$CK" report --radii "$WORK/small.csv" --out "$WORK/small" --json >"$WORK/small.json" 2>"$WORK/err" ||
  fail "report on the small table exited $?: $(cat "$WORK/err")"
cmp -s "$WORK/small.json" "$WORK/small/report.json" || fail "--json does not print report.json"
$PY - "$WORK/small/report.json" <<'PYEOF' || fail "the small table's SCI cohesions are wrong"
import json, math, sys
r = json.load(open(sys.argv[1]))
s = {x["target"]["friction"]: x for x in r["sci_engine"]["series"]}
# R = 8, 7, 6 m at 0, 0.1, 0.3 Pa: 7.25 m at 0.075 Pa; within 6.45-8.05 m from 0 to 0.21 Pa.
assert math.isclose(s["0.4"]["cohesion_for_observed_radius"], 0.075, rel_tol=1e-12), s["0.4"]
assert all(math.isclose(a, b, rel_tol=1e-12) for a, b in zip(s["0.4"]["cohesion_band_1sigma"], [0.0, 0.21]))
assert s["0.55"]["cohesion_for_observed_radius"] is None and s["0.55"]["cohesion_band_1sigma"] is None
assert s["0.55"]["summary"].startswith("none in range: smaller at every cohesion"), s["0.55"]["summary"]
assert [p["friction"] for p in r["friction"]["series"][0]["points"]] == [0.4, 0.55]
assert not any(g["fitted"] for g in r["groups"])  # 3 rows per group: not fitted
PYEOF
grep -q "| 0.075 Pa |" "$WORK/small/report.md" || fail "report.md does not give 0.075 Pa"
grep -q "none in range" "$WORK/small/report.md" || fail "report.md does not say none in range"

# 3. Without its plotting script the numbers are written and the skipped figures named.
CRATERKIT_PLOT_REPORT_SCRIPT="$WORK/missing.py" "$CK" report --radii "$CS" --out "$WORK/noplot" >/dev/null \
  2>"$WORK/err" || fail "report without its script exited $?"
grep -q "figures skipped (scaled_radius.png, sci_cohesion.png, friction.png, rates.png, ages.png)" "$WORK/err" ||
  fail "no message naming the skipped figures: $(cat "$WORK/err")"
grep -q "Figures skipped" "$WORK/noplot/report.md" || fail "report.md does not say the figures were skipped"
grep -qF "## Model ages" "$WORK/noplot/report.md" || fail "report.md without figures lacks its numbers"
ls "$WORK/noplot" | grep -q png && fail "figures written without their script"
printf 'import sys\nsys.stderr.write("no matplotlib here\\n")\nsys.exit(3)\n' >"$WORK/fake.py"
CRATERKIT_PLOT_REPORT_SCRIPT="$WORK/fake.py" "$CK" report --radii "$CS" --out "$WORK/fake" >/dev/null 2>"$WORK/err" ||
  fail "report with a failing script exited $?"
grep -q "exit status 3" "$WORK/fake/report.md" || fail "report.md does not say why the figures are missing"

# 4. --overwrite replaces the report's files and leaves others alone; without it a non-empty folder is refused.
echo keep >"$WORK/r/notes.txt"
"$CK" report --radii "$CS" --out "$WORK/r" >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--out.*not empty.*--overwrite" "$WORK/err" || fail "a non-empty --out: $(cat "$WORK/err")"
"$CK" report --radii "$CS" --out "$WORK/r" --overwrite --quiet >/dev/null 2>"$WORK/err" || fail "--overwrite exited $?"
[ -e "$WORK/r/fit_friction_porosity_coarse.json" ] && fail "--overwrite left the earlier report's fit file"
[ -s "$WORK/r/fit.json" ] && [ -s "$WORK/r/notes.txt" ] || fail "--overwrite: fit.json missing or notes.txt removed"

# 5. Bad input: status 2, the problem named, nothing written.
expect_refusal() {  # WHAT PATTERN ARGS...
  local what="$1" pattern="$2"
  shift 2
  "$CK" report "$@" --out "$WORK/never" >/dev/null 2>"$WORK/err"
  local status=$?
  [ "$status" -eq 2 ] || fail "$what: exit status $status, not 2 ($(cat "$WORK/err"))"
  grep -q -- "$pattern" "$WORK/err" || fail "$what: the message does not say '$pattern': $(cat "$WORK/err")"
  [ -e "$WORK/never" ] && fail "$what: the refused report wrote its folder" && rm -rf "$WORK/never"
}
expect_refusal "no input" "no input"
mkdir -p "$WORK/empty_sweep"
expect_refusal "a folder without radii.csv" "holds no radii.csv" "$WORK/empty_sweep"
expect_refusal "a missing table" "missing.csv: no such file" --radii "$WORK/missing.csv"
expect_refusal "a file as DIR" "is a file" "$CS"
grep -v "^[0-9]" "$WORK/small.csv" >"$WORK/header_only.csv"
expect_refusal "a table without rows" "header_only.csv: no data rows" --radii "$WORK/header_only.csv"
sed 's/,strength,/,cohesion,/' "$WORK/small.csv" >"$WORK/no_strength.csv"
expect_refusal "a table without strength" "strength" --radii "$WORK/no_strength.csv"
expect_refusal "a table given twice" "given twice" --radii "$CS" --radii "$CS"
expect_refusal "an unknown grouping column" "frction" --radii "$CS" --group-by frction

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all report checks passed"
