// examples/hdl's Verilated master on a bench: its ports connected by name, and its whole sequence
// run (reset, then until `done`, then 100 us for the last frame's recovery). Shared by
// main.cpp and the co-simulation benchmark.
#pragma once

#include <cstdint>

#include "Vendat_master.h"
#include "endatsim/cosim/verilated_master.hpp"

inline void run_endat_master(endatsim::cosim::Bench& bench) {
  using namespace endatsim;
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
                                [&m] { m.eval(); }, sim::ps(12'500));  // 80 MHz system clock
  m.rst = 1;
  master.run_cycles(8);
  m.rst = 0;
  if (master.run_until([&m] { return m.done != 0; })) master.run_for(sim::us(100));
  m.final();
}
