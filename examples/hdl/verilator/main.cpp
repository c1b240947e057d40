// examples/hdl's Verilog master, Verilated, on endatsim's bench: the few lines a Verilator user
// writes. The model runs on its 80 MHz system clock (12.5 ns) inside the bench; its ports are
// connected by name in endat_master_run.hpp; the bench file and the outputs come from the
// command line (cosim/main.hpp):  endat_master_verilated BENCH.json [--json FILE] [--junit FILE] ...
#include <verilated.h>

#include "endatsim/cosim/main.hpp"
#include "endat_master_run.hpp"

int main(int argc, char** argv) { return endatsim::cosim::run_main(argc, argv, &run_endat_master); }
