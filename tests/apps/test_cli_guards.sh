#!/usr/bin/env bash
# What `craterkit simulate` refuses, and how it protects an output folder: thread counts out of bounds, a new
# run into a non-empty folder (unless --overwrite), a resume with a changed configuration, a damaged
# checkpoint, a truncated or missing side log; a bad input leaves no folder behind, an unusable output path is
# found before any work, temporary files of killed runs are removed. Every refusal is status 2 with a message
# naming the flag, key or file. On a short Sod tube (a few steps).
# Usage: test_cli_guards.sh /path/to/craterkit /path/to/data
set -u
CK="$1"
DATA="$2"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# expect_refusal WHAT PATTERN COMMAND...: status 2 and PATTERN (grep -F) in stderr.
expect_refusal() {
  local what="$1" pattern="$2"
  shift 2
  "$@" >"$WORK/out" 2>"$WORK/err"
  local status=$?
  [ "$status" -eq 2 ] || fail "$what: exited $status, expected 2 ($(cat "$WORK/err"))"
  grep -qF -- "$pattern" "$WORK/err" || fail "$what: the message lacks '$pattern': $(cat "$WORK/err")"
}

sed -e 's/^end_time = 0.2/end_time = 0.2\nmax_steps = 4/' -e 's/^snapshot_times = .*/snapshot_times = [0.0]\ncheckpoint_interval_steps = 2/' \
  "$DATA/examples/sod.toml" >"$WORK/sod.toml"
run() { "$CK" simulate "$@" --threads 1 --quiet >"$WORK/out" 2>"$WORK/err"; }

# --- Threads.
expect_refusal "--threads 100000" "--threads 100000: allowed 1 to" "$CK" simulate "$WORK/sod.toml" --threads 100000
expect_refusal "--threads -1" "--threads -1" "$CK" simulate "$WORK/sod.toml" --threads -1
expect_refusal "sweep --threads 100000" "--threads 100000" "$CK" sweep "$WORK/none.toml" --out "$WORK/sw" --threads 100000
[ -e "$WORK/sw" ] && fail "a refused sweep created its folder"

# --- A new run into a non-empty folder.
run "$WORK/sod.toml" --out "$WORK/a" || fail "the Sod run exited $? ($(cat "$WORK/err"))"
[ -e "$WORK/a/checkpoint.h5" ] || fail "the Sod run wrote no checkpoint"
cp "$WORK/a/conservation.csv" "$WORK/conservation.before"
expect_refusal "a new run into a used folder" "--overwrite" "$CK" simulate "$WORK/sod.toml" --out "$WORK/a" --threads 1 --quiet
cmp -s "$WORK/a/conservation.csv" "$WORK/conservation.before" || fail "a refused run changed the folder"
touch "$WORK/a/snap_000099.h5" "$WORK/a/notes.txt"
run "$WORK/sod.toml" --out "$WORK/a" --overwrite || fail "--overwrite exited $? ($(cat "$WORK/err"))"
[ -e "$WORK/a/snap_000099.h5" ] && fail "--overwrite left an old snapshot"
[ -e "$WORK/a/notes.txt" ] || fail "--overwrite removed a file that is not a run output"
cmp -s "$WORK/a/conservation.csv" "$WORK/conservation.before" || fail "the overwritten run differs from the first"
expect_refusal "--resume --overwrite" "exclude each other" "$CK" simulate "$WORK/sod.toml" --out "$WORK/a" --resume --overwrite

# --- Resume with a changed configuration: refused, naming the key and both values; an end-time change is fine.
sed 's/^left_density = 1.0/left_density = 1.1/' "$WORK/sod.toml" >"$WORK/changed.toml"
expect_refusal "a resume with another left_density" "sod.left_density: 1.1000000000000001 now, 1 in the checkpoint" \
  "$CK" simulate "$WORK/changed.toml" --out "$WORK/a" --resume --threads 1 --quiet
sed 's/^max_steps = 4/max_steps = 6/' "$WORK/sod.toml" >"$WORK/longer.toml"
cp -r "$WORK/a" "$WORK/b"
run "$WORK/longer.toml" --out "$WORK/a" --resume || fail "a resume with a larger max_steps exited $? ($(cat "$WORK/err"))"
[ "$(tail -n 1 "$WORK/a/conservation.csv" | cut -d, -f2)" = 6 ] || fail "the resumed run did not reach step 6"

# --- Side logs: truncated or missing is refused; a stale temporary file of a killed run is removed.
cp -r "$WORK/b" "$WORK/c"
head -n 3 "$WORK/b/conservation.csv" >"$WORK/b/cut" && mv "$WORK/b/cut" "$WORK/b/conservation.csv"
expect_refusal "a truncated conservation.csv" "conservation.csv: holds 2 rows" \
  "$CK" simulate "$WORK/longer.toml" --out "$WORK/b" --resume --threads 1 --quiet
rm "$WORK/b/conservation.csv"
expect_refusal "a missing conservation.csv" "conservation.csv: missing" \
  "$CK" simulate "$WORK/longer.toml" --out "$WORK/b" --resume --threads 1 --quiet
touch "$WORK/c/.checkpoint.h5.tmp.999999999"
run "$WORK/longer.toml" --out "$WORK/c" --resume || fail "the resume exited $? ($(cat "$WORK/err"))"
[ -e "$WORK/c/.checkpoint.h5.tmp.999999999" ] && fail "a stale temporary checkpoint was left"
cmp -s "$WORK/a/conservation.csv" "$WORK/c/conservation.csv" || fail "the two resumed runs differ"

# --- A damaged checkpoint: refused, naming it.
cp -r "$WORK/c" "$WORK/d"
size=$(stat -c %s "$WORK/d/checkpoint.h5")
printf '\x5a\x5a\x5a\x5a' | dd of="$WORK/d/checkpoint.h5" bs=1 seek=$((size / 2)) conv=notrunc status=none
expect_refusal "a damaged checkpoint" "$WORK/d/checkpoint.h5" \
  "$CK" simulate "$WORK/longer.toml" --out "$WORK/d" --resume --threads 1 --quiet

# --- Bad input leaves no folder; an unusable output path is found before any work.
sed 's/^material = .*/material = "no_such_material"/' "$WORK/sod.toml" >"$WORK/bad.toml"
expect_refusal "an unknown material" "no_such_material" "$CK" simulate "$WORK/bad.toml" --out "$WORK/e" --threads 1 --quiet
[ -e "$WORK/e" ] && fail "a run refused for its material left its folder"
touch "$WORK/file"
expect_refusal "--out below a file" "--out $WORK/file/run" "$CK" simulate "$WORK/sod.toml" --out "$WORK/file/run" --quiet
expect_refusal "--out a file" "exists and is not a folder" "$CK" simulate "$WORK/sod.toml" --out "$WORK/file" --quiet
expect_refusal "sweep --out below a file" "--out $WORK/file/sweep" "$CK" sweep "$DATA/studies/example.toml" \
  --out "$WORK/file/sweep"
expect_refusal "fit --out in a missing folder" "--out $WORK/none/fit.json" \
  "$CK" fit "$DATA/examples/radii_example.csv" --out "$WORK/none/fit.json"

# --- Values that must not get through.
expect_refusal "scale overflowing" "(the numbers overflow)" "$CK" scale --params jutzi2022_ryugu --impactor-radius 1e300 --gravity 1e-4 --target-density 1200 \
  --impactor-density 2700 --velocity 2000 --strength 0.05
expect_refusal "rates with an empty list element" "--cohesion 0,,1: an empty element" "$CK" rates --params jutzi2022_ryugu \
  --body ryugu --cohesion 0,,1 --q -4 --diameters 22,36
expect_refusal "rates with a trailing comma" "--diameters 22,36,: an empty element" "$CK" rates --params jutzi2022_ryugu \
  --body ryugu --cohesion 0,1 --q -4 --diameters 22,36,
sed 's/^Total_area = 0.8 <km^2>/Total_area = 800000 <m^2>/' "$DATA/craters/ryugu_synthetic_unit.scc" >"$WORK/m2.scc"
expect_refusal "an .scc area in m^2" "the unit must be <km^2>" "$CK" age "$WORK/m2.scc" --params jutzi2022_ryugu \
  --body ryugu --cohesion 0.05
sed 's/^0.11955\t/119.55\t/' "$DATA/craters/ryugu_synthetic_unit.scc" >"$WORK/big.scc"
expect_refusal "a crater larger than the body" "m is larger than" "$CK" age "$WORK/big.scc" --params jutzi2022_ryugu \
  --body ryugu --cohesion 0.05
printf '\xef\xbb\xbf' >"$WORK/bom.csv" && cat "$DATA/examples/radii_example.csv" >>"$WORK/bom.csv"
"$CK" fit "$WORK/bom.csv" --form hh2011 --fix nu=0.4 --json >"$WORK/bom.json" 2>"$WORK/err" ||
  fail "a radii table with a UTF-8 byte-order mark exited $? ($(cat "$WORK/err"))"
"$CK" fit "$DATA/examples/radii_example.csv" --form hh2011 --fix nu=0.4 --json >"$WORK/plain.json" 2>/dev/null
cmp -s <(grep -v '\.csv' "$WORK/bom.json") <(grep -v '\.csv' "$WORK/plain.json") || fail "the byte-order mark changed the fit"
expect_refusal "measure with a tiny radial step" "radial_step 1e-12 m: 5e+10 samples per ray" "$CK" measure \
  "$WORK/a/snap_000000.h5" --rho-initial 1 --spacing 0.01 --max-radius 0.05 --radial-step 1e-12
expect_refusal "measure with too many azimuths" "--azimuths 100000" "$CK" measure "$WORK/a/snap_000000.h5" \
  --rho-initial 1 --spacing 0.01 --azimuths 100000
# The DEM late stage refuses before it writes anything (a Sod snapshot is no impact run).
expect_refusal "dem-late-stage with a negative grain" "grain_diameter" "$CK" dem-late-stage \
  "$WORK/a/snap_000000.h5" --out "$WORK/dem" --grain-diameter -0.5
expect_refusal "dem-late-stage with f = 2" "--friction 2 is not allowed" "$CK" dem-late-stage \
  "$WORK/a/snap_000000.h5" --out "$WORK/dem" --friction 2
expect_refusal "dem-late-stage on a Sod snapshot" "not the snapshot of an impact run" "$CK" dem-late-stage \
  "$WORK/a/snap_000000.h5" --out "$WORK/dem" --no-stop-when-grown
[ -e "$WORK/dem" ] && fail "a refused dem-late-stage created its folder"

[ "$failures" -eq 0 ] && echo "all guard checks passed"
exit "$failures"
