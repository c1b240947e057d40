// examples/hdl's Verilog master, Verilated, on endatsim's bench: the few lines a Verilator user
// writes. The model runs on its 80 MHz system clock (12.5 ns) inside the bench; its ports are
// connected by name below; the bench file and the outputs come from the command line
// (cosim/main.hpp):  endat_master_verilated BENCH.json [--json FILE] [--junit FILE] ...
#include <verilated.h>

#include "Vendat_master.h"
#include "cosim/main.hpp"
#include "cosim/verilated_master.hpp"

int main(int argc, char** argv) {
  using namespace endatsim;
  return cosim::run_main(argc, argv, [](cosim::Bench& bench) {
    Vendat_master m;
    cosim::VerilatedMaster master(bench,
                                  {.sys_clk = &m.sys_clk,
                                   .clock = &m.endat_clock,
                                   .data_out = &m.data_out,
                                   .data_enable = &m.data_oe,
                                   .data_in = &m.data_in,
                                   .position_valid = [&m] { return m.position_valid != 0; },
                                   .position = [&m] { return std::uint64_t{m.position}; },
                                   .parameter_valid = [&m] { return m.param_valid != 0; },
                                   .parameter = [&m] { return std::uint64_t{m.param_value}; }},
                                  [&m] { m.eval(); }, sim::ps(12'500));
    m.rst = 1;
    master.run_cycles(8);
    m.rst = 0;
    if (master.run_until([&m] { return m.done != 0; })) master.run_for(sim::us(100));
    m.final();
  });
}
