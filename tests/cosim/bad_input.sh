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
  # Configuration the bridge refuses before anything runs.
  expect 2 "+endatsim_position_valid=tb_endatsim.param_value: a pin of one bit, got 16 bits" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins +endatsim_position=tb_endatsim.position \
    +endatsim_position_valid=tb_endatsim.param_value
  expect 2 "+endatsim_position=tb_endatsim.dut: names a vpiModule, not a signal" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins +endatsim_position=tb_endatsim.dut \
    +endatsim_position_valid=tb_endatsim.position_valid
  expect 2 "endatsim writes DATA into a reg the testbench declares for it" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins +endatsim_data_in=tb_endatsim.endat_clock
  expect 2 "+endatsim_enable_active_low inverts +endatsim_data_enable, which is not given" \
    vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench +endatsim_clock=tb_endatsim.endat_clock \
    +endatsim_data_out=tb_endatsim.data_out +endatsim_data_in=tb_endatsim.data_in_from_line +endatsim_enable_active_low
  expect 2 "+endatsim_json: cannot write '/nonexistent/x.json'" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $bench $pins \
    +endatsim_json=/nonexistent/x.json
  # Outputs checked before the run as `endatsim run` checks its own: none overwrites the bench or
  # another output (before, the bench file was replaced by the JUnit XML, or by the VCD).
  cp "$hdl/bench_8mhz_50m.json" victim.json
  expect 2 "+endatsim_junit victim.json: that is the bench file" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp $pins \
    +endatsim_bench=victim.json +endatsim_junit=victim.json
  expect 2 "+endatsim_json out.json and +endatsim_junit out.json: the same file" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp \
    $bench $pins +endatsim_json=out.json +endatsim_junit=out.json
  expect 2 "--vcd victim.json: that is the bench file" "$verilated" victim.json --vcd victim.json
  expect 2 "--json /nonexistent/x.json: cannot open the file for writing" "$verilated" victim.json --json /nonexistent/x.json
  if ! cmp -s victim.json "$hdl/bench_8mhz_50m.json"; then
    echo "FAILED: the bench file was overwritten"
    failures=$((failures + 1))
  fi
  expect 2 "unknown plusarg +endatsimjson=x.json (the prefix is +endatsim_)" vvp -n -M "$vpi" -m endatsim_vpi tb.vvp \
    $bench $pins +endatsimjson=x.json
  # A testbench in which nothing happens on the pins still ends at the bench's max_time, failing.
  cat > quiet.v <<'V'
`timescale 1ns / 1ps
module quiet;
  reg clk = 1'b1, dout = 1'b0, doe = 1'b0, din = 1'b1, other = 1'b0;
  always #10 other = ~other;  // a free-running clock elsewhere: the simulation never runs out of events
endmodule
V
  iverilog -g2012 -s quiet -o quiet.vvp quiet.v
  expect 1 "FAIL ended before max_time: still running at the bench's max_time 1 ms" \
    vvp -n -M "$vpi" -m endatsim_vpi quiet.vvp +endatsim_bench=short.json +endatsim_clock=quiet.clk \
    +endatsim_data_out=quiet.dout +endatsim_data_enable=quiet.doe +endatsim_data_in=quiet.din
  # CLOCK going unknown fails the run, not only a note.
  sed 's/always #10 other = ~other;/initial #5000 clk = 1'"'"'bx;/' quiet.v > x_clock.v
  iverilog -g2012 -s quiet -o x_clock.vvp x_clock.v
  expect 1 "FAIL pins at known levels: 1 time(s) unknown" \
    vvp -n -M "$vpi" -m endatsim_vpi x_clock.vvp +endatsim_bench=short.json +endatsim_clock=quiet.clk \
    +endatsim_data_out=quiet.dout +endatsim_data_enable=quiet.doe +endatsim_data_in=quiet.din
  # CLOCK unknown from time 0 and never changed: no call ever came, yet it is no known level; and
  # with no frame at all nothing was judged (before, both passed and the verdict read "conforms").
  sed 's/reg clk = 1.b1, dout = 1.b0, doe = 1.b0/reg clk = 1'"'"'bz, dout = 1'"'"'bx, doe = 1'"'"'bx/' quiet.v > z_pins.v
  iverilog -g2012 -s quiet -o z_pins.vvp z_pins.v
  expect 1 "FAIL pins at known levels: 2 time(s) unknown" \
    vvp -n -M "$vpi" -m endatsim_vpi z_pins.vvp +endatsim_bench=short.json +endatsim_clock=quiet.clk \
    +endatsim_data_out=quiet.dout +endatsim_data_enable=quiet.doe +endatsim_data_in=quiet.din
  expect 1 "FAIL frames: no frame began at the encoder's connector" \
    vvp -n -M "$vpi" -m endatsim_vpi z_pins.vvp +endatsim_bench=short.json +endatsim_clock=quiet.clk \
    +endatsim_data_out=quiet.dout +endatsim_data_enable=quiet.doe +endatsim_data_in=quiet.din
  # A master that hangs mid-frame with CLOCK LOW until the testbench's $finish: the cut frame is
  # named, and with the encoder's t_LO maximum declared the LOW phase that outlasts it fails t_lo
  # (before, both passed without a word).
  cat > hung.v <<'V'
`timescale 1ns / 1ps
module hung;
  reg clk = 1'b1, dout = 1'b0, doe = 1'b0, din = 1'b1;
  integer i;
  initial begin
    #50000;
    for (i = 0; i < 5; i = i + 1) begin clk = 1'b0; #500; clk = 1'b1; #500; end
    clk = 1'b0;  // and never again
    #500000 $finish;
  end
endmodule
V
  iverilog -g2012 -s hung -o hung.vvp hung.v
  hung_pins="+endatsim_clock=hung.clk +endatsim_data_out=hung.dout +endatsim_data_enable=hung.doe +endatsim_data_in=hung.din"
  # 1 m of cable and no expectations: the master's undriven mode bits fail floating_data (exit 1).
  echo '{"name": "hung", "max_time": "1 ms", "line": {"cable_length_m": 1}, "encoder": {"version": "2.2"}}' > hung.json
  expect 1 "the simulation ended inside frame #0: its clock count and start-bit polling not judged; CLOCK LOW at the encoder's connector since 55.045 us (499.955 us before the end)" \
    vvp -n -M "$vpi" -m endatsim_vpi hung.vvp +endatsim_bench=hung.json $hung_pins +endatsim_json=hung_out.json
  if grep -qF "violation t_lo" out.txt; then echo "FAILED: t_lo judged without a declared maximum"; failures=$((failures + 1)); fi
  if ! python3 -c 'import json, sys; c = json.load(open("hung_out.json"))["frame_cut_by_end"]; sys.exit(0 if c == {"frame": 0, "clock": 0, "clock_since_ps": 55045000} else 1)'; then
    echo "FAILED: hung_out.json's frame_cut_by_end"; failures=$((failures + 1))
  fi
  echo '{"name": "hung", "max_time": "1 ms", "line": {"cable_length_m": 1}, "encoder": {"version": "2.2", "t_lo_max": "30 us"}}' > datasheet.json
  expect 1 "measured >= 499.955 us, limit <= 30 us (this encoder's t_LO maximum) - CLOCK LOW phase longer than this encoder's datasheet allows (1 pulse(s) in this frame; worst shown: still LOW where the run or capture ended inside the frame)" \
    vvp -n -M "$vpi" -m endatsim_vpi hung.vvp +endatsim_bench=datasheet.json $hung_pins
  # A data_out that follows data_in combinationally while released: Icarus carries endatsim's write
  # through at once, back into the bridge, which must finish one call before the next.
  cat > loop.v <<'V'
module tb_loop;
  tb_endatsim t ();
  wire dout_w = t.data_oe ? t.data_out : t.data_in_from_line;
endmodule
V
  iverilog -g2012 -s tb_loop -o loop.vvp "$hdl/verilog/endat_master.v" "$hdl/verilog/tb_endatsim.v" loop.v
  expect 0 "PASS hdl_master_8mhz_50m" vvp -n -M "$vpi" -m endatsim_vpi loop.vvp $bench +endatsim_clock=tb_loop.t.endat_clock \
    +endatsim_data_out=tb_loop.dout_w +endatsim_data_enable=tb_loop.t.data_oe +endatsim_data_in=tb_loop.t.data_in_from_line
  expect 2 "--vcd /nonexistent/x.vcd: cannot open the file for writing: its directory '/nonexistent' does not exist" "$verilated" "$hdl/bench_8mhz_50m.json" --vcd /nonexistent/x.vcd
  expect 2 "unknown option --jsn" "$verilated" "$hdl/bench_8mhz_50m.json" --jsn x
  expect 2 "no bench file given" "$verilated"
  expect 2 "nope.json: cannot open the file" "$verilated" nope.json
}
[ "$failures" -eq 0 ]
