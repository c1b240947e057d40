#!/bin/sh
# One co-simulation of examples/hdl's EnDat master through the VPI bridge, as ctest runs it:
#   run_hdl.sh SIMULATOR DEFECT EXPECTED VPI_DIR SOURCE_DIR [BENCH]
# SIMULATOR: icarus | ghdl | verilator (then VPI_DIR is the Verilated program, built with DEFECT), or
# icarus-inout | ghdl-inout: the testbench with DATA as one inout net. DEFECT: the master's generic (0: none). EXPECTED: "pass", or the rows of
# the timing table that must be broken (comma-separated, nothing else broken) with the run failing;
# either may be followed by ";positions=N", the number of positions the master must report (each
# equal to the one the encoder latched). BENCH: another bench file than the configuration's.
set -eu
sim=$1 defect=$2 expected=$3 vpi=$4 src=$5
bench=${6:+"+endatsim_bench=$6"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
hdl=$src/examples/hdl
status=0
case "$sim" in
  icarus | icarus-inout)
    tb=tb_endatsim config=cosim.json
    [ "$sim" = icarus-inout ] && tb=tb_endatsim_inout config=cosim_inout.json
    iverilog -g2012 -s $tb -P $tb.DEFECT="$defect" -o "$work/tb.vvp" \
      "$hdl/verilog/endat_master.v" "$hdl/verilog/$tb.v"
    (cd "$work" && vvp -n -M "$vpi" -m endatsim_vpi tb.vvp +endatsim_config="$hdl/verilog/$config" \
      +endatsim_json=result.json +endatsim_junit=result.xml $bench) > "$work/out.txt" 2>&1 || status=$?
    ;;
  ghdl | ghdl-inout)
    tb=tb_endatsim config=cosim.json
    [ "$sim" = ghdl-inout ] && tb=tb_endatsim_inout config=cosim_inout.json
    (cd "$work" && ghdl -a --std=08 "$hdl/vhdl/endat_master.vhd" "$hdl/vhdl/$tb.vhd" &&
      ghdl -e --std=08 $tb &&
      ghdl -r --std=08 $tb -gDEFECT="$defect" --vpi="$vpi/endatsim_vpi_ghdl.so" \
        +endatsim_config="$hdl/vhdl/$config" +endatsim_json=result.json +endatsim_junit=result.xml $bench) \
      > "$work/out.txt" 2>&1 || status=$?
    ;;
  verilator)
    (cd "$work" && "$vpi" "${6:-$hdl/bench_8mhz_50m.json}" --json result.json --junit result.xml) \
      > "$work/out.txt" 2>&1 || status=$?
    ;;
  *) echo "run_hdl.sh: unknown simulator $sim" >&2; exit 2 ;;
esac
cat "$work/out.txt"
# Not exec: the shell stays to remove $work when python is done.
python3 - "$work/result.json" "$status" "$expected" <<'PY'
import json, sys
path, status, expected = sys.argv[1], int(sys.argv[2]), sys.argv[3]
try:
    r = json.load(open(path))
except OSError:
    sys.exit(f"no result written (simulator exit {status})")
broken = sorted(c["check"] for c in r["conformance"] if c["violations"] > 0)
matched = all(p["matches"] for p in r["positions"]) and len(r["positions"]) > 0
rows, _, extra = expected.partition(";")
count = int(extra.split("=")[1]) if extra.startswith("positions=") else None
counted = count is None or len(r["positions"]) == count
if rows == "pass":
    ok = status == 0 and r["passed"] and not broken and matched and counted
    print(f"expected a clean pass: exit {status}, broken {broken}, positions match {matched}")
else:
    want = sorted(rows.split(","))
    ok = status == 1 and not r["passed"] and broken == want and matched and counted
    print(f"expected exit 1 with {want} broken: exit {status}, broken {broken}, positions match {matched}")
if count is not None:
    print(f"expected {count} positions reported: {len(r['positions'])}")
sys.exit(0 if ok else 1)
PY
