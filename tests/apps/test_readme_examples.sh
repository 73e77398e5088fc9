#!/usr/bin/env bash
# Runs every `$K ...` example of README.md's quick tour as printed, in a scratch folder where data/ is the
# source tree's data, with K the built program; each must exit with status 0. The examples of
# `simulate`, `sweep` and `run` (minutes to hours of SPH) run with --dry-run appended, which reads and checks
# the configuration and the flags exactly as printed and stops before simulating.
# Also checks a few of the promises the README makes around the examples (list, JSON version, simulate's
# default output folder).
# With a fourth argument (the folder of the built Python package), the README's Python block and the Python
# blocks of docs/python.md (one script, in order) run too, with /usr/bin/python3 (```py blocks, which need the
# output of a simulation, do not).
# Usage: test_readme_examples.sh /path/to/craterkit /path/to/README.md /path/to/data [/path/to/python]
set -u
CK=$(realpath "$1")
README=$(realpath "$2")
DATA=$(realpath "$3")
PYTHON_PACKAGE="${4:-}"
[ -n "$PYTHON_PACKAGE" ] && PYTHON_PACKAGE=$(realpath -m "$PYTHON_PACKAGE")
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ln -s "$DATA" "$WORK/data"
cd "$WORK" || exit 1

# The example lines: inside the first ```sh block after "## A quick tour".
mapfile -t examples < <(awk '/^## A quick tour/ {tour = 1} tour && /^```sh/ {inside = 1; next}
                             inside && /^```/ {exit} inside && /^\$K / {print}' "$README")
[ "${#examples[@]}" -ge 8 ] || fail "found only ${#examples[@]} examples in $README"
export MPLBACKEND=Agg OMP_NUM_THREADS=1
for line in "${examples[@]}"; do
  command=${line%%#*}  # the trailing comment
  case "$command" in
    "\$K simulate "* | "\$K sweep "* | "\$K run"*) command="$command --dry-run" ;;
  esac
  echo "== $command"
  K="$CK"
  if ! eval "$command" >"$WORK/out" 2>"$WORK/err"; then
    fail "README example '$line' failed: $(cat "$WORK/err")"
  fi
done
# What the examples write (fit.json is read by the next example, age.png is the age plot, report/ the report).
[ -s fit.json ] || fail "the fit example wrote no fit.json"
[ -s age.png ] || fail "the age example wrote no age.png"
[ -s report/report.md ] || fail "the report example wrote no report/report.md"

# craterkit list: every kind, with the data directory in use.
"$CK" list >"$WORK/out" 2>"$WORK/err" || fail "craterkit list failed: $(cat "$WORK/err")"
for word in jutzi2022_ryugu ryugu basalt power_law_q4 example "citation:" "data directory:"; do
  grep -q -- "$word" "$WORK/out" || fail "craterkit list does not show '$word'"
done
"$CK" list bodies --json >"$WORK/out" 2>"$WORK/err" || fail "craterkit list bodies --json failed"
/usr/bin/python3 - "$WORK/out" <<'PYEOF' || fail "craterkit list bodies --json is not as documented"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["craterkit_version"], d
assert [b["name"] for b in d["bodies"]] == ["bennu", "ryugu"], d
assert all(b["citation"] and b["source"].endswith(".toml") for b in d["bodies"]), d
assert "constant_sets" not in d, d
PYEOF
"$CK" list planets >"$WORK/out" 2>"$WORK/err" && fail "craterkit list planets succeeded"

# scale --body takes the gravity from the body; the JSON says which version made it.
"$CK" scale --params jutzi2022_ryugu --body ryugu --impactor-radius 0.056 --impactor-density 2700 \
  --velocity 2000 --json >"$WORK/out" || fail "scale --body failed"
/usr/bin/python3 - "$WORK/out" <<'PYEOF' || fail "scale --body --json is not as documented"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["body"] == "Ryugu" and abs(d["gravity"] - 1.496e-4) < 1e-12, d
assert d["target_density"] == 1190.0, d  # the body's density, as in rates and age
assert d["craterkit_version"] and d["scaling_law"]["coefficient_1"] == 0.6, d
PYEOF

# the age figure in the other presentations and formats
for p in differential:pdf R:svg; do
  "$CK" age data/craters/ryugu_synthetic_unit.scc --params jutzi2022_ryugu --cohesion 0.05 --presentation "${p%%:*}" \
    --plot "figure.${p##*:}" >"$WORK/out" 2>"$WORK/err" || fail "age --plot figure.${p##*:} failed: $(cat "$WORK/err")"
done
head -c 5 figure.pdf | grep -q "%PDF" || fail "age --plot figure.pdf is not a PDF"
"$CK" age "$(dirname "$README")/tests/chronology/data/synthetic_lunar_unit.diam" --chronology moon_neukum2001 \
  --min-diameter 200 --max-diameter 1000 --plot moon.png --json >"$WORK/out" 2>"$WORK/err" ||
  fail "age --chronology --plot failed: $(cat "$WORK/err")"
[ -s moon.png ] || fail "age --chronology --plot wrote no figure"
grep -q "<svg" figure.svg || fail "age --plot figure.svg is not an SVG"
"$CK" age data/craters/ryugu_synthetic_unit.scc --params jutzi2022_ryugu --cohesion 0.05 --plot figure.jpg \
  >"$WORK/out" 2>"$WORK/err" && fail "age --plot figure.jpg succeeded"

# simulate without --out names the folder it writes (here a dry run writes nothing and names none).
"$CK" simulate data/examples/sod.toml --dry-run >"$WORK/out" 2>"$WORK/err" || fail "simulate --dry-run failed"
grep -q "no --out" "$WORK/err" && fail "a dry run should not announce an output folder"

if [ -n "$PYTHON_PACKAGE" ]; then
  python_blocks() { awk '/^```python/ {inside = 1; next} inside && /^```/ {inside = 0} inside {print}' "$1"; }
  python_blocks "$README" >readme.py
  [ -s readme.py ] || fail "README.md has no Python example"
  PYTHONPATH="$PYTHON_PACKAGE" /usr/bin/python3 readme.py >"$WORK/out" 2>"$WORK/err" ||
    fail "README's Python example failed: $(cat "$WORK/err")"
  python_blocks "$(dirname "$README")/docs/python.md" >python_md.py
  PYTHONPATH="$PYTHON_PACKAGE" /usr/bin/python3 python_md.py >"$WORK/out" 2>"$WORK/err" ||
    fail "docs/python.md's examples failed: $(cat "$WORK/err")"
  [ -s unit.csv ] || fail "docs/python.md's example wrote no unit.csv"
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all README examples ran"
