#!/usr/bin/env bash
# `craterkit simulate` killed with SIGKILL at random moments and resumed with --resume until done ends with
# every file of its folder byte for byte equal to an uninterrupted run's (crater.json, the growth history,
# ejecta, conservation log, snapshots, XDMF, the final checkpoint), and nothing else left in it (no
# temporary files). The quarter-domain tiny impact of tests/study/tiny_study.sh (536 particles, 1-3 s a run),
# whose loose end-of-growth rule makes the crater-growth monitor end the run. The seed of the kill moments is
# printed (KILL_TEST_SEED repeats a sequence).
# Usage: test_kill_resume.sh /path/to/craterkit
set -u
CK="$1"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. "$(dirname "$0")/../study/tiny_study.sh"
sed -i 's/^checkpoint_interval_steps = 40/checkpoint_interval_steps = 15\nsnapshot_times = [0.05, 0.2, 0.4]/' "$WORK/tiny.toml"

"$CK" simulate "$WORK/tiny.toml" --out "$WORK/whole" --threads 1 --quiet >/dev/null 2>"$WORK/err" ||
  fail "the uninterrupted run exited $? ($(cat "$WORK/err"))"
start=$(date +%s%N)
"$CK" simulate "$WORK/tiny.toml" --out "$WORK/timing" --threads 1 --quiet >/dev/null 2>&1
run_ms=$((($(date +%s%N) - start) / 1000000))
echo "one run takes $run_ms ms"

seed=${KILL_TEST_SEED:-$$}
RANDOM=$seed
echo "kill moments from seed $seed"
kills=0
for chain in 1 2 3; do
  dir="$WORK/killed$chain"
  for attempt in $(seq 1 12); do
    "$CK" simulate "$WORK/tiny.toml" --out "$dir" --threads 1 --quiet --resume >/dev/null 2>>"$WORK/killed.err" &
    pid=$!
    if [ "$attempt" -le 4 ]; then
      delay_ms=$((RANDOM % (3 * run_ms / 4 + 1) + 20))
      sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
      if kill -KILL "$pid" 2>/dev/null; then
        kills=$((kills + 1))
        echo "chain $chain: killed after $delay_ms ms"
      fi
    fi
    wait "$pid" 2>/dev/null
    status=$?
    [ "$attempt" -gt 4 ] && { [ "$status" -eq 0 ] || fail "chain $chain: the last resume exited $status ($(tail -3 "$WORK/killed.err"))"; break; }
  done
  (cd "$WORK/whole" && ls -A) >"$WORK/files.whole"
  (cd "$dir" && ls -A) >"$WORK/files.killed"
  cmp -s "$WORK/files.whole" "$WORK/files.killed" ||
    fail "chain $chain: other files than the uninterrupted run's: $(diff "$WORK/files.whole" "$WORK/files.killed" | tr '\n' ' ')"
  for file in $(cat "$WORK/files.whole"); do
    cmp -s "$WORK/whole/$file" "$dir/$file" || fail "chain $chain: $file differs from the uninterrupted run's"
  done
done
[ "$kills" -ge 4 ] || fail "only $kills kills happened (the runs ended before the kills)"

[ "$failures" -eq 0 ] && echo "all kill-and-resume checks passed ($kills kills)"
exit "$failures"
