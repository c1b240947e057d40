#!/bin/sh
# The bridge and a Verilated master's program refuse bad configuration with a message that names
# what is wrong and exit status 2, and a master that never lets the run end fails (status 1):
#   bad_input.sh VPI_DIR VERILATED_PROGRAM SOURCE_DIR
set -eu
vpi=$1 verilated=$2 src=$3
hdl=$src/examples/hdl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
iverilog -g2012 -s tb_endatsim -o tb.vvp "$hdl/verilog/endat_master.v" "$hdl/verilog/tb_endatsim.v"
failures=0
# expect STATUS MESSAGE-FRAGMENT COMMAND...
expect() {
  want_status=$1 want_text=$2
  shift 2
  status=0
  "$@" > out.txt 2>&1 || status=$?
  if [ "$status" -ne "$want_status" ] || ! grep -qF -- "$want_text" out.txt; then
    echo "FAILED: $* -> exit $status (expected $want_status with \"$want_text\"):"
    cat out.txt
    failures=$((failures + 1))
  else
    echo "ok: exit $status, \"$want_text\""
  fi
}
pins="+endatsim_clock=tb_endatsim.endat_clock +endatsim_data_out=tb_endatsim.data_out +endatsim_data_enable=tb_endatsim.data_oe +endatsim_data_in=tb_endatsim.data_in_from_line"
bench="+endatsim_bench=$hdl/bench_8mhz_50m.json"
# shellcheck disable=SC2086
{
  expect 2 "missing +endatsim_bench" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $pins
  expect 2 "unknown plusarg +endatsim_clk=x" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins +endatsim_clk=x
  expect 2 "+endatsim_clock=tb_endatsim.no_such_pin: no such signal" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins \
    +endatsim_clock=tb_endatsim.no_such_pin
  echo '{"name": "b", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"}}' > with_master.json
  expect 2 "with_master.json: at /master: a co-simulation bench has no \"master\"" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $pins +endatsim_bench=with_master.json
  echo '{"bench": "x.json", "clock": 5}' > bad_config.json
  expect 2 "bad_config.json: at /clock: expected a string" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp +endatsim_config=bad_config.json
  expect 2 "give one or the other" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins +endatsim_data=tb_endatsim.data_out
  expect 2 "+endatsim_clock=tb_endatsim.position: a pin of one bit, got 64 bits" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp \
    $bench $pins +endatsim_clock=tb_endatsim.position
  expect 2 "+endatsim_verbose: expected nothing, 1/0 or true/false" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins \
    +endatsim_verbose=maybe
  # A bench whose max_time ends before the master is done: stopped there, and a failure.
  sed 's/"max_time": "20 ms"/"max_time": "1 ms"/' "$hdl/bench_8mhz_50m.json" > short.json
  expect 1 "FAIL ended before max_time: still running at the bench's max_time 1 ms" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $pins +endatsim_bench=short.json
  expect 1 "FAIL ended before max_time" "$verilated" short.json
  expect 2 "unknown option --jsn" "$verilated" "$hdl/bench_8mhz_50m.json" --jsn x
  expect 2 "no bench file given" "$verilated"
  expect 2 "nope.json: cannot open the file" "$verilated" nope.json
}
[ "$failures" -eq 0 ]
