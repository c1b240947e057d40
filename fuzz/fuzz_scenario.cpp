// libFuzzer target: scenario files that load are run through master, line, encoder and checker
// for at most 2 ms of simulated time. The run must end (no exception, crash, UB or leak).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scenarios/loader.hpp"
#include "scenarios/runner.hpp"

using namespace endatsim;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  scenarios::Scenario s;
  try {
    s = scenarios::load_scenario_text(text, "fuzz.json");
  } catch (const scenarios::ScenarioError&) {
    return -1;  // not a scenario: keep it out of the corpus
  }
  s.max_time = std::min(s.max_time, sim::ms(2));
  const auto r = scenarios::run_scenario(s);
  if (r.simulated > s.max_time + sim::ms(1)) {
    std::fprintf(stderr, "ran past max_time: %s\n", sim::format_time(r.simulated).c_str());
    std::abort();
  }
  return 0;
}
