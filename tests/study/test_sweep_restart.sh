#!/usr/bin/env bash
# `craterkit sweep` killed and restarted, and run as Slurm array tasks, on the 2 x 2 grid of tiny impacts
# (tiny_study.sh): a sweep killed with SIGKILL at random moments (its children left to finish as orphans, holding
# their runs' claims) and restarted until done gives radii.csv byte for byte equal to an uninterrupted sweep's,
# and every run's crater.json equal; `--emit slurm` writes a job-array script that passes `bash -n`, whose
# tasks run locally one by one with SLURM_ARRAY_TASK_ID set, after which `--collect` gives the same radii.csv.
# Usage: test_sweep_restart.sh /path/to/craterkit
set -u
CK="$1"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. "$(dirname "$0")/tiny_study.sh"

# --- Uninterrupted.
"$CK" sweep "$WORK/study.toml" --out "$WORK/a/out" --jobs 2 --threads 1 >/dev/null 2>"$WORK/err" ||
  fail "the uninterrupted sweep exited $? ($(tail -3 "$WORK/err"))"

# --- Killed at random moments, restarted until done. The seed is printed so that a failure can be repeated.
seed=${SWEEP_TEST_SEED:-$$}
RANDOM=$seed
echo "kill moments from seed $seed"
for round in 1 2 3 4; do
  "$CK" sweep "$WORK/study.toml" --out "$WORK/b/out" --jobs 2 --threads 1 >/dev/null 2>>"$WORK/killed.err" &
  pid=$!
  delay=$(printf '0.%02d' $((RANDOM % 100)))
  [ "$round" -eq 2 ] && delay=1.$((RANDOM % 10))
  sleep "$delay"
  kill -KILL "$pid" 2>/dev/null && echo "round $round: killed the sweep after $delay s"
  wait "$pid" 2>/dev/null
done
"$CK" sweep "$WORK/study.toml" --out "$WORK/b/out" --jobs 2 --threads 1 >/dev/null 2>"$WORK/err" ||
  fail "the restarted sweep exited $? ($(tail -3 "$WORK/err"))"
cmp -s "$WORK/a/out/radii.csv" "$WORK/b/out/radii.csv" ||
  fail "radii.csv of the killed and restarted sweep differs: $(diff "$WORK/a/out/radii.csv" "$WORK/b/out/radii.csv")"
for run in $RUNS; do
  cmp -s "$WORK/a/out/runs/$run/crater.json" "$WORK/b/out/runs/$run/crater.json" || fail "$run: crater.json differs"
  [ -e "$WORK/b/out/runs/$run/failed.json" ] && fail "$run: a kill left a failed.json"
  echo "$run: $(wc -l <"$WORK/b/out/runs/$run/attempts.log") attempt(s)"
done
# No orphan outlived the restarted sweep: it waited for every claim.
for run in $RUNS; do
  flock -n "$WORK/b/out/runs/$run/lock" true || fail "$run: its claim is still held after the sweep ended"
done

# --- Slurm: the script, its tasks run by hand, then --collect.
"$CK" sweep "$WORK/study.toml" --out "$WORK/c/out" --emit slurm --threads 1 >"$WORK/emit.out" 2>"$WORK/err" ||
  fail "--emit slurm exited $? ($(cat "$WORK/err"))"
script="$WORK/c/out/sweep.slurm"
bash -n "$script" || fail "sweep.slurm does not pass bash -n"
grep -q '^#SBATCH --array=0-3$' "$script" || fail "sweep.slurm lacks --array=0-3: $(cat "$script")"
grep -q '^#SBATCH --cpus-per-task=1$' "$script" || fail "sweep.slurm lacks --cpus-per-task=1"
grep -q '^#SBATCH --job-name=tiny-grid$' "$script" || fail "sweep.slurm lacks the job name"
grep -q "sweep --collect $WORK/c/out" "$script" || fail "sweep.slurm does not say how to collect"
[ -d "$WORK/c/out/logs" ] || fail "--emit slurm did not create the logs folder"
[ -e "$WORK/c/out/runs" ] && ls "$WORK/c/out/runs"/*/attempts.log >/dev/null 2>&1 && fail "--emit slurm ran something"
for task in 3 1 0 2; do
  SLURM_ARRAY_TASK_ID=$task SLURM_CPUS_PER_TASK=1 bash "$script" >"$WORK/task.out" 2>"$WORK/task.err" ||
    fail "array task $task exited $? ($(tail -3 "$WORK/task.err"))"
done
[ -e "$WORK/c/out/radii.csv" ] && fail "the tasks wrote radii.csv (only --collect or a sweep does)"
SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=1 bash "$script" >/dev/null 2>"$WORK/task.err" || fail "a finished task exited $?"
grep -q "finished before" "$WORK/task.err" || fail "a task of a finished run did not say so: $(cat "$WORK/task.err")"
"$CK" sweep --collect "$WORK/c/out" >/dev/null 2>"$WORK/err" || fail "--collect exited $? ($(cat "$WORK/err"))"
cmp -s "$WORK/a/out/radii.csv" "$WORK/c/out/radii.csv" ||
  fail "radii.csv of the Slurm tasks differs: $(diff "$WORK/a/out/radii.csv" "$WORK/c/out/radii.csv")"
for run in $RUNS; do
  [ "$(wc -l <"$WORK/c/out/runs/$run/attempts.log")" -eq 1 ] || fail "$run ran more than once as a task"
done
"$CK" sweep "$WORK/study.toml" --out "$WORK/c/out" --task 4 >/dev/null 2>"$WORK/err"
[ "$?" -eq 2 ] && grep -q -- "--task 4" "$WORK/err" || fail "--task 4 of 4 runs: no status-2 error naming --task"

[ "$failures" -eq 0 ] && echo "all sweep restart and Slurm checks passed"
exit "$failures"
