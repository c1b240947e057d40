#!/bin/sh
# SIGINT and SIGTERM stop `run`, `sweep` and `check` at the next event boundary: the exit status
# is 128 + the signal, and no output is left half-written or looking complete (an earlier run's
# "passed" results are replaced or removed).
# usage: interrupt_test.sh ENDATSIM SOURCE_DIR
set -u
exe=$1
src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "interrupt_test: $*" >&2
  exit 1
}
# Waits (at most 60 s) until the file pattern $1 matches something.
wait_for() {
  n=0
  while ! ls $1 >/dev/null 2>&1; do
    n=$((n + 1))
    [ $n -le 1200 ] || fail "timed out waiting for $1"
    sleep 0.05
  done
}

# A run that takes minutes within raised limits: 10^5 reads at 2 MHz, every edge an event (the
# fast path would play most of them in a second).
cat >"$dir/long.json" <<EOF
{"name": "long", "line": {"cable_length_m": 10}, "master": {"f_c": "2 MHz"}, "max_time": "60 s",
 "script": [{"op": "read_position", "count": 100000}]}
EOF
raise="--max-records 100000000 --max-kernel-events 100000000000 --engine event"

# --- run: SIGINT while the first of two scenarios runs --------------------------------------
echo '{"passed": true, "scenarios": []}' >"$dir/out.json"
echo '<testsuites failures="0" errors="0"/>' >"$dir/out.xml"
"$exe" run "$dir/long.json" "$src/scenarios/bundled/endat21_1mhz_10m.json" --quiet $raise \
  --json "$dir/out.json" --junit "$dir/out.xml" --vcd "$dir/vcd" --log "$dir/out.log" >"$dir/run.out" 2>"$dir/run.err" &
pid=$!
wait_for "$dir/vcd/long.vcd.part-*"
sleep 1
kill -INT $pid
wait $pid
status=$?
[ $status -eq 130 ] || fail "run: exit status $status, expected 130 (SIGINT); stderr: $(cat "$dir/run.err")"
grep -q 'interrupted by SIGINT' "$dir/run.err" || fail "run: stderr does not say it was interrupted"
grep -q '"complete": false' "$dir/out.json" || fail "run: the JSON does not say incomplete"
grep -q '"passed": false' "$dir/out.json" || fail "run: the JSON still says passed"
grep -q '"not_run"' "$dir/out.json" || fail "run: the JSON does not list the scenario not run"
grep -q 'endat21_1mhz_10m.json' "$dir/out.json" || fail "run: the scenario not run is not named"
grep -q '<error type="incomplete" message="interrupted by SIGINT' "$dir/out.xml" || fail "run: JUnit lacks the incomplete error"
grep -q '<error type="not run"' "$dir/out.xml" || fail "run: JUnit lacks the scenario not run"
tail -n 2 "$dir/out.log" | grep -q '^# incomplete: long: interrupted by SIGINT' || fail "run: the log does not end incomplete"
[ -s "$dir/vcd/long.vcd" ] || fail "run: no VCD up to the stop"
tail -n 1 "$dir/vcd/long.vcd" | grep -q '^#[0-9][0-9]*$' || fail "run: the VCD does not end with a timestamp"
ls "$dir"/*.part-* "$dir"/vcd/*.part-* >/dev/null 2>&1 && fail "run: part files left behind"

# --- sweep: SIGTERM while its points run; an earlier sweep's outputs go ----------------------
echo 'old,results' >"$dir/sweep.csv"
"$exe" sweep "$dir/long.json" --grid /seed=1,2 --jobs 2 --quiet $raise --csv "$dir/sweep.csv" >"$dir/sweep.out" 2>"$dir/sweep.err" &
pid=$!
sleep 1
kill -TERM $pid
wait $pid
status=$?
[ $status -eq 143 ] || fail "sweep: exit status $status, expected 143 (SIGTERM); stderr: $(cat "$dir/sweep.err")"
grep -q "removed $dir/sweep.csv" "$dir/sweep.err" || fail "sweep: stderr does not name the output removed"
[ -e "$dir/sweep.csv" ] && fail "sweep: an earlier sweep's CSV stays in place"

# --- check: SIGINT while captures are judged ------------------------------------------------
cat >"$dir/capture.json" <<EOF
{"name": "capture", "line": {"cable_length_m": 1}, "master": {"f_c": "16 MHz"}, "max_time": "60 s",
 "script": [{"op": "read_position", "count": 10000}]}
EOF
"$exe" run "$dir/capture.json" --quiet $raise --vcd "$dir/capture.vcd" >/dev/null 2>&1
[ -s "$dir/capture.vcd" ] || fail "check: no capture to judge"
c="$dir/capture.vcd"
"$exe" check $c $c $c $c $c $c $c $c $c $c --clock encoder_clock --data encoder_data --quiet \
  --json "$dir/check.json" --junit "$dir/check.xml" --log "$dir/check.log" >"$dir/check.out" 2>"$dir/check.err" &
pid=$!
wait_for "$dir/check.log.part-*"
kill -INT $pid
wait $pid
status=$?
[ $status -eq 130 ] || fail "check: exit status $status, expected 130 (SIGINT); stderr: $(cat "$dir/check.err")"
grep -q '"complete": false' "$dir/check.json" || fail "check: the JSON does not say incomplete"
grep -q 'interrupted by SIGINT: not judged' "$dir/check.json" || fail "check: the captures not judged are not listed"
grep -q 'interrupted by SIGINT: not judged' "$dir/check.xml" || fail "check: JUnit does not list the captures not judged"
ls "$dir"/*.part-* >/dev/null 2>&1 && fail "check: part files left behind"
echo "interrupt_test: run, sweep and check stopped cleanly"
