#!/usr/bin/env bash
# Command-line contract of `craterkit sweep` on a 2 x 2 grid of tiny impacts (tiny_study.sh): a bad study exits
# with status 2 naming the key and writes nothing; --dry-run lists the runs with their particle counts; a sweep
# runs every run and writes radii.csv whose rows are the runs' crater.json; a second sweep runs nothing; a run
# that fails is recorded in failed.json while the others finish, is skipped by the next sweep and run again by
# --retry-failed; two sweeps started together on one folder run each run exactly once.
# Usage: test_sweep_cli.sh /path/to/craterkit
set -u
CK="$1"
PY=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. "$(dirname "$0")/tiny_study.sh"

# attempts RUN_FOLDER: the number of children started for the run
attempts() { [ -e "$1/attempts.log" ] && wc -l <"$1/attempts.log" || echo 0; }

# --- A bad study: status 2, the key named, nothing written.
sed 's/^cohesion = .*/cohesion = [0.0, -1.0]/' "$WORK/study.toml" >"$WORK/bad.toml"
"$CK" sweep "$WORK/bad.toml" --out "$WORK/bad" >/dev/null 2>"$WORK/err"
status=$?
[ "$status" -eq 2 ] || fail "a negative cohesion exited $status, expected 2"
grep -q "grid.cohesion" "$WORK/err" && grep -q -- "-1" "$WORK/err" || fail "the error does not name grid.cohesion: $(cat "$WORK/err")"
[ -e "$WORK/bad" ] && fail "a rejected study wrote its output folder"
"$CK" sweep "$WORK/study.toml" >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--out" "$WORK/err" || fail "a sweep without --out: no status-2 error naming --out"

# --- --dry-run: the runs and their particle counts, nothing written.
"$CK" sweep "$WORK/study.toml" --out "$WORK/a/out" --dry-run --json >"$WORK/dry.json" 2>"$WORK/err" ||
  fail "--dry-run exited $? ($(cat "$WORK/err"))"
$PY - "$WORK/dry.json" <<'PYEOF' || fail "--dry-run --json: unexpected listing: $(cat "$WORK/dry.json")"
import json, sys
runs = json.load(open(sys.argv[1]))
assert [r["name"] for r in runs] == ["impact_speed-50_cohesion-0", "impact_speed-50_cohesion-100",
                                     "impact_speed-60_cohesion-0", "impact_speed-60_cohesion-100"], runs
assert all(r["particles"] == 536 for r in runs), runs
assert runs[3]["axes"] == {"impact_speed": 60.0, "cohesion": 100.0}, runs
# sizing off: each run's own sizes, from its dry run (tiny.toml's domain, spacing and end time)
assert all(not r["sized"] and r["domain_radius"] == 5.0 and r["particle_spacing"] == 0.5 and r["end_time"] == 1.0
           for r in runs), runs
PYEOF
"$CK" sweep "$WORK/study.toml" --out "$WORK/a/out" --dry-run >"$WORK/dry.txt" 2>"$WORK/err" ||
  fail "text --dry-run exited $? ($(cat "$WORK/err"))"
grep -q "(base)" "$WORK/dry.txt" && fail "text --dry-run shows (base) where the runs' own sizes are known: $(cat "$WORK/dry.txt")"
grep -Eq "impact_speed-60_cohesion-100 +[0-9.e+-]+ +5 +0.5 " "$WORK/dry.txt" ||
  fail "text --dry-run lacks a run's own R_dom and dx_max: $(cat "$WORK/dry.txt")"
[ -e "$WORK/a" ] && fail "--dry-run created the output folder"

# --- The sweep: every run, radii.csv from the runs' crater.json.
"$CK" sweep "$WORK/study.toml" --out "$WORK/a/out" --jobs 2 --threads 1 --json >"$WORK/summary.json" 2>"$WORK/err" ||
  fail "the sweep exited $? ($(tail -5 "$WORK/err"))"
grep -q "ETA" "$WORK/err" || fail "no progress lines with an ETA on stderr: $(cat "$WORK/err")"
$PY - "$WORK/a/out" "$WORK/summary.json" <<'PYEOF' || fail "radii.csv does not hold the runs' craters"
import csv, json, os, sys
out = sys.argv[1]
summary = json.load(open(sys.argv[2]))
assert summary["done"] == 4 and summary["failed"] == 0 and summary["started"] == 4, summary
lines = open(os.path.join(out, "radii.csv")).read().splitlines()
assert lines[0] == '# craterkit sweep: study "tiny-grid": 2 x 2 test grid', lines[0]
assert lines[1].startswith("# craterkit "), lines[1]
assert lines[2] == "# command: craterkit sweep study.toml --out out", lines[2]
assert lines[3] == ("impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,"
                    "crater_radius_sigma,friction,porosity,resolution,run,growth_ended"), lines[3]
rows = list(csv.DictReader(lines[3:]))
plan = json.load(open(os.path.join(out, "sweep.json")))
assert [r["run"] for r in rows] == plan["runs"], (rows, plan)
for row in rows:
    crater = json.load(open(os.path.join(out, "runs", row["run"], "crater.json")))
    assert float(row["crater_radius"]) == crater["crater_radius"], (row, crater["crater_radius"])
    assert float(row["crater_radius_sigma"]) == crater["crater_radius_uncertainty"], row
    assert float(row["target_density"]) == crater["settings"]["rho_initial"], row
    result = json.load(open(os.path.join(out, "runs", row["run"], "result.json")))
    assert row["growth_ended"] == ("true" if result["simulate"]["crater_growth_ended"] else "false"), row
    speed, cohesion = row["run"].split("_cohesion-")
    assert float(row["velocity"]) == float(speed.split("-")[1]) and float(row["strength"]) == float(cohesion), row
    assert float(row["gravity"]) == 1.0 and float(row["impactor_density"]) == 1300.0, row
    assert float(row["friction"]) == 0.55 and float(row["porosity"]) == 0.5, row
    assert row["impactor_radius"] == "1.0002798344485166", row
runs = open(os.path.join(out, "runs.csv")).read().splitlines()
assert runs[0].startswith("run,status,attempts,"), runs[0]
assert all(",done,1," in line for line in runs[1:]) and len(runs) == 5, runs
PYEOF
for run in $RUNS; do
  dir="$WORK/a/out/runs/$run"
  for file in config.toml run.json target.toml result.json crater.json simulate.out.json simulate.log; do
    [ -e "$dir/$file" ] || fail "$run lacks $file"
  done
done
cp "$WORK/a/out/radii.csv" "$WORK/radii.first"

# --- Again: nothing runs, the table stays byte for byte.
"$CK" sweep "$WORK/study.toml" --out "$WORK/a/out" --threads 1 >/dev/null 2>"$WORK/err" || fail "the second sweep exited $?"
grep -q "4 finished before" "$WORK/err" || fail "the second sweep did not skip the finished runs: $(cat "$WORK/err")"
for run in $RUNS; do
  [ "$(attempts "$WORK/a/out/runs/$run")" -eq 1 ] || fail "the second sweep started $run again"
done
cmp -s "$WORK/a/out/radii.csv" "$WORK/radii.first" || fail "radii.csv changed on a sweep that ran nothing"
"$CK" sweep --collect "$WORK/a/out" >/dev/null 2>"$WORK/err" || fail "--collect exited $? ($(cat "$WORK/err"))"
cmp -s "$WORK/a/out/radii.csv" "$WORK/radii.first" || fail "--collect wrote another radii.csv"

# --- A run that fails (its crater.json cannot be written: a folder stands in its place) is recorded, the others
# finish; the next sweep skips it, --retry-failed runs it again (resumed from its checkpoint).
broken="$WORK/b/out/runs/impact_speed-60_cohesion-0"
mkdir -p "$broken/crater.json/x"
"$CK" sweep "$WORK/study.toml" --out "$WORK/b/out" --jobs 2 --threads 1 >/dev/null 2>"$WORK/err"
status=$?
[ "$status" -eq 1 ] || fail "a sweep with a failed run exited $status, expected 1"
$PY - "$broken/failed.json" <<'PYEOF' || fail "failed.json: $(cat "$broken/failed.json")"
import json, sys
f = json.load(open(sys.argv[1]))
assert f["exit_status"] == 1 and f["description"] == "exit status 1", f
assert any("crater.json" in line for line in f["stderr_tail"]), f
PYEOF
[ -e "$broken/result.json" ] && fail "the failed run has a result.json"
for run in $RUNS; do
  [ "$run" = "impact_speed-60_cohesion-0" ] && continue
  [ -e "$WORK/b/out/runs/$run/result.json" ] || fail "$run did not finish beside the failed run"
done
[ "$(grep -c -v '^#' "$WORK/b/out/radii.csv")" -eq 4 ] || fail "radii.csv should hold the 3 finished runs"
grep -q "^impact_speed-60_cohesion-0,failed,1," "$WORK/b/out/runs.csv" || fail "runs.csv lacks the failed run"
"$CK" sweep "$WORK/study.toml" --out "$WORK/b/out" --threads 1 >/dev/null 2>"$WORK/err"
[ "$?" -eq 1 ] || fail "a sweep over a failed run should exit 1"
[ "$(attempts "$broken")" -eq 1 ] || fail "a sweep without --retry-failed ran the failed run again"
rm -r "$broken/crater.json"
"$CK" sweep "$WORK/study.toml" --out "$WORK/b/out" --threads 1 --retry-failed >/dev/null 2>"$WORK/err" ||
  fail "--retry-failed exited $? ($(tail -3 "$WORK/err"))"
[ "$(attempts "$broken")" -eq 2 ] || fail "--retry-failed did not run the failed run once more"
[ -e "$broken/failed.json" ] && fail "failed.json stayed after the run succeeded"
cmp -s "$WORK/b/out/radii.csv" "$WORK/radii.first" || fail "after the retry radii.csv differs from the first sweep's"

# --- Two sweeps started together on one folder: each run runs exactly once, both end with the whole table.
"$CK" sweep "$WORK/study.toml" --out "$WORK/c/out" --jobs 2 --threads 1 >"$WORK/c1.out" 2>"$WORK/c1.err" &
p1=$!
"$CK" sweep "$WORK/study.toml" --out "$WORK/c/out" --jobs 2 --threads 1 >"$WORK/c2.out" 2>"$WORK/c2.err" &
p2=$!
wait "$p1" || fail "the first of two concurrent sweeps exited $? ($(tail -3 "$WORK/c1.err"))"
wait "$p2" || fail "the second of two concurrent sweeps exited $? ($(tail -3 "$WORK/c2.err"))"
cat "$WORK/c1.err" "$WORK/c2.err" | grep -q "being run by another process" ||
  fail "the two sweeps never met a run the other had claimed: the test did not test concurrency"
for run in $RUNS; do
  dir="$WORK/c/out/runs/$run"
  [ "$(attempts "$dir")" -eq 1 ] || fail "two concurrent sweeps started $run $(attempts "$dir") times"
  [ "$(grep -c '^=== craterkit sweep: attempt' "$dir/simulate.log")" -eq 1 ] || fail "$run: more than one child in simulate.log"
  [ "$(grep -c '^0,0,' "$dir/conservation.csv")" -le 1 ] || fail "$run: conservation.csv started twice"
done
cmp -s "$WORK/c/out/radii.csv" "$WORK/radii.first" || fail "concurrent sweeps: radii.csv differs from a single sweep's"

[ "$failures" -eq 0 ] && echo "all sweep CLI checks passed"
exit "$failures"
