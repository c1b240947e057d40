// The command line of a co-simulation program the user builds around a Verilated master:
//   PROGRAM BENCH.json [--json FILE] [--junit FILE] [--log FILE] [--vcd FILE] [--seed N] [--verbose]
// run_main loads the bench, hands it to `drive` (which steps the model), and reports as the VPI
// bridge does. Its exit status: 0 every expectation held, 1 one failed, 2 bad input.
#pragma once

#include <functional>

#include "endatsim/cosim/bench.hpp"
#include "endatsim/scenarios/bundled_profiles.hpp"

namespace endatsim::cosim {

int run_bench_program(int argc, const char* const* argv, const std::function<void(Bench&)>& drive);

// Inline, so that a program built against the installed package finds that package's profiles
// (ENDATSIM_PACKAGE_PROFILES_DIR, from its CMake config) wherever it was installed.
inline int run_main(int argc, const char* const* argv, const std::function<void(Bench&)>& drive) {
#ifdef ENDATSIM_PACKAGE_PROFILES_DIR
  scenarios::set_package_profiles_dir(ENDATSIM_PACKAGE_PROFILES_DIR);
#endif
  return run_bench_program(argc, argv, drive);
}

}  // namespace endatsim::cosim
