#!/bin/sh
# The co-simulation bridge bounded and interruptible like `endatsim run`: a limit ends the run
# incomplete (exit 3), SIGINT and SIGTERM end it with the outputs saying so (exit 128 + N) in
# Icarus and GHDL, and a limit that is not a number is bad configuration (exit 2):
#   limits_interrupt.sh VPI_DIR VERILATED_PROGRAM SOURCE_DIR
set -eu
vpi=$1 verilated=$2 src=$3
hdl=$src/examples/hdl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() {
  echo "FAILED: $1"
  cat out.txt
  failures=$((failures + 1))
}
# check STATUS WANT-STATUS INCOMPLETE-FRAGMENT JSON: the status, the summary and the JSON's "incomplete".
check() {
  if [ "$1" -ne "$2" ]; then fail "exit $1, expected $2"; return; fi
  if ! grep -qF "INCOMPLETE: $3" out.txt; then fail "no 'INCOMPLETE: $3' in the summary"; return; fi
  if ! python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); sys.exit(0 if sys.argv[2] in j.get("incomplete", "") and not j["passed"] else 1)' "$4" "$3"; then
    fail "$4 does not say incomplete: $3"; return
  fi
  echo "ok: exit $1, $3"
}
sed 's/"max_time": "20 ms"/"max_time": "60 s"/' "$hdl/bench_8mhz_50m.json" > long.json
# A master whose CLOCK runs forever: only a limit or a signal ends the run before 60 s.
cat > busy.v <<'V'
`timescale 1ns / 1ps
module busy;
  reg clk = 1'b1, dout = 1'b0, doe = 1'b0, din = 1'b1;
  always #500 clk = ~clk;
endmodule
V
iverilog -g2012 -s busy -o busy.vvp busy.v
pins="+endatsim_clock=busy.clk +endatsim_data_out=busy.dout +endatsim_data_enable=busy.doe +endatsim_data_in=busy.din"
icarus() { vvp -n -M "$vpi" -m endatsim_vpi busy.vvp +endatsim_bench=long.json $pins "$@"; }

# shellcheck disable=SC2086
{
  status=0
  icarus +endatsim_max_kernel_events=100000 +endatsim_json=limit.json > out.txt 2>&1 || status=$?
  check $status 3 "limit kernel_events reached" limit.json
  status=0
  icarus +endatsim_max_time=2ms +endatsim_json=time.json > out.txt 2>&1 || status=$?
  # A limit, as run's --max-time: incomplete (exit 3), not the bench's own max_time (exit 1).
  check $status 3 "limit max_time reached: 2 ms simulated, less than the bench's 60 s" time.json
  if grep -qF "ended before max_time" out.txt; then fail "+endatsim_max_time judged as the bench's max_time"; fi
  status=0
  icarus +endatsim_max_records=lots > out.txt 2>&1 || status=$?
  if [ $status -ne 2 ] || ! grep -qF "+endatsim_max_records=lots: --max-records expects an integer" out.txt; then fail "a bad limit"; else echo "ok: a bad limit"; fi
  for signal in INT TERM; do
    status=0
    # Not through the function: $! must be the simulator's process, not a subshell's.
    vvp -n -M "$vpi" -m endatsim_vpi busy.vvp +endatsim_bench=long.json $pins +endatsim_json=$signal.json \
      +endatsim_junit=$signal.xml > out.txt 2>&1 &
    pid=$!
    sleep 1
    kill -$signal $pid
    wait $pid || status=$?
    want=130
    [ $signal = TERM ] && want=143
    check $status $want "interrupted by SIG$signal" $signal.json
    grep -qF '<error type="incomplete"' $signal.xml || fail "$signal.xml does not say incomplete"
  done
  if command -v ghdl > /dev/null && [ -f "$vpi/endatsim_vpi_ghdl.so" ]; then
    # CLOCK running; with -gclocked=false CLOCK still and another clock running instead.
    cat > busy.vhd <<'V'
library ieee;
use ieee.std_logic_1164.all;
entity busy is
  generic (clocked : boolean := true);
end entity;
architecture sim of busy is
  signal clk : std_logic := '1';
  signal other : std_logic := '0';
  signal dout, doe : std_logic := '0';
  signal din : std_logic := '1';
begin
  running : if clocked generate
    clk <= not clk after 500 ns;
  end generate;
  other <= not other after 10 ns;
end architecture;
V
    ghdl -a --std=08 busy.vhd && ghdl -e --std=08 busy
    status=0
    ghdl -r --std=08 busy --vpi="$vpi/endatsim_vpi_ghdl.so" +endatsim_bench=long.json $pins +endatsim_json=ghdl.json \
      > out.txt 2>&1 &
    pid=$!
    sleep 2
    kill -INT $pid
    wait $pid || status=$?
    check $status 130 "interrupted by SIGINT" ghdl.json
    # A design whose watched pins never move (a master held in reset while another clock runs)
    # never calls the bridge, and GHDL's own SIGINT handler does not stop it: the bridge's look
    # now and then in simulated time does (before, it ran on until killed).
    for signal in INT TERM; do
      status=0
      ghdl -r --std=08 busy -gclocked=false --vpi="$vpi/endatsim_vpi_ghdl.so" +endatsim_bench=long.json $pins \
        +endatsim_json=quiet_$signal.json > out.txt 2>&1 &
      pid=$!
      sleep 1
      kill -$signal $pid
      # Stopped within 10 s, or killed and failed.
      for _ in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do kill -0 $pid 2>/dev/null || break; sleep 0.5; done
      if kill -0 $pid 2>/dev/null; then kill -9 $pid; fail "GHDL with quiet pins still runs 10 s after SIG$signal"; fi
      wait $pid || status=$?
      want=130
      [ $signal = TERM ] && want=143
      check $status $want "interrupted by SIG$signal" quiet_$signal.json
    done
  fi
  status=0
  "$verilated" "$hdl/bench_8mhz_50m.json" --max-kernel-events 2000 --json verilated.json > out.txt 2>&1 || status=$?
  check $status 3 "limit kernel_events reached" verilated.json
  status=0
  "$verilated" "$hdl/bench_8mhz_50m.json" --max-records 0 > out.txt 2>&1 || status=$?
  if [ $status -ne 2 ] || ! grep -qF -- "--max-records expects an integer 1 .." out.txt; then fail "--max-records 0"; else echo "ok: --max-records 0"; fi
}
[ "$failures" -eq 0 ]
