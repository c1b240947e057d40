#!/bin/sh
# Builds and runs the example EnDat master against its own behavioural encoder stub, in Verilog
# (Icarus) and VHDL (GHDL), lints the Verilog master with Verilator, and checks that the two
# endatsim co-simulation testbenches compile. Everything is built in a temporary directory.
#
#   examples/hdl/run_stub.sh [DEFECT [RTD_NS]]     defaults: 0 and 700 (50 m at t_D max)
#
# Exit status 0 when every step passes. With DEFECT 1..3 the stub still answers (it checks no
# timing), so those runs show what a stub alone does not catch.
set -eu

defect=${1:-0}
rtd=${2:-700}
here=$(cd "$(dirname "$0")" && pwd)
v=$here/verilog
h=$here/vhdl
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0

now() { date +%s.%N; }
elapsed() { echo "$1 $2" | awk '{ printf "%.2f s", $2 - $1 }'; }

echo "== verilator --lint-only -Wall endat_master.v"
verilator --lint-only -Wall "$v/endat_master.v" || status=1

echo "== Verilog: tb_stub DEFECT=$defect RTD=$rtd ns (iverilog + vvp)"
iverilog -g2012 -s tb_stub -P tb_stub.DEFECT="$defect" -P tb_stub.T_RTD_NS="$rtd" \
  -o "$tmp/tb_stub.vvp" "$v/tb_stub.v" "$v/encoder_stub.v" "$v/endat_master.v"
t0=$(now)
vvp -n "$tmp/tb_stub.vvp" || status=1
echo "   vvp wall time $(elapsed "$t0" "$(now)")"

echo "== VHDL: tb_stub DEFECT=$defect RTD=$rtd ns (ghdl)"
ghdl -a --std=08 --workdir="$tmp" "$h/endat_master.vhd" "$h/encoder_stub.vhd" "$h/tb_stub.vhd"
ghdl -e --std=08 --workdir="$tmp" -o "$tmp/tb_stub_vhdl" tb_stub
t0=$(now)
ghdl -r --std=08 --workdir="$tmp" tb_stub -gDEFECT="$defect" -gT_RTD_NS="$rtd" || status=1
echo "   ghdl -r wall time $(elapsed "$t0" "$(now)")"

echo "== tb_endatsim.v compiles; only the bridge's system tasks are missing"
iverilog -g2012 -s tb_endatsim -o "$tmp/tb_endatsim.vvp" "$v/tb_endatsim.v" "$v/endat_master.v"
out=$(vvp -n "$tmp/tb_endatsim.vvp" 2>&1 || true)
if echo "$out" | grep -q 'endatsim_position' && \
   [ -z "$(echo "$out" | grep -i 'error' | grep -v 'endatsim_position\|endatsim_parameter\|not runnable')" ]; then
  echo "   ok: vvp names only \$endatsim_position and \$endatsim_parameter"
else
  echo "$out"
  status=1
fi

echo "== tb_endatsim.vhd analyses and elaborates"
ghdl -a --std=08 --workdir="$tmp" "$h/tb_endatsim.vhd"
if ghdl -e --std=08 --workdir="$tmp" -o "$tmp/tb_endatsim_vhdl" tb_endatsim; then echo "   ok"; else status=1; fi

[ "$status" -eq 0 ] && echo "ALL PASS" || echo "SOMETHING FAILED"
exit "$status"
