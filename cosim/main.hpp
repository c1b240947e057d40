// The command line of a co-simulation program the user builds around a Verilated master:
//   PROGRAM BENCH.json [--json FILE] [--junit FILE] [--log FILE] [--vcd FILE] [--seed N] [--verbose]
// run_main loads the bench, hands it to `drive` (which steps the model), and reports as the VPI
// bridge does. Its exit status: 0 every expectation held, 1 one failed, 2 bad input.
#pragma once

#include <functional>

#include "endatsim/cosim/bench.hpp"

namespace endatsim::cosim {

int run_main(int argc, const char* const* argv, const std::function<void(Bench&)>& drive);

}  // namespace endatsim::cosim
