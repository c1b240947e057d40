// libFuzzer target: scenario files that load are run through master, line, encoder and checker
// for at most 2 ms of simulated time within the default limits. The run must end (no exception
// other than a ScenarioError for a scenario beyond the limits, crash, UB or leak).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"

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
  scenarios::ScenarioResult r;
  try {
    r = scenarios::run_scenario(s);  // within the default limits
  } catch (const scenarios::ScenarioError& e) {
    if (std::string(e.what()).rfind("fuzz.json: at /", 0) != 0) {
      std::fprintf(stderr, "a limit error that does not name the file and place: %s\n", e.what());
      std::abort();
    }
    return -1;  // beyond the limits: refused before the run
  }
  if (!r.incomplete.empty() && r.passed()) {
    std::fprintf(stderr, "an incomplete run passed: %s\n", r.incomplete.c_str());
    std::abort();
  }
  if (r.simulated > s.max_time + sim::ms(1)) {
    std::fprintf(stderr, "ran past max_time: %s\n", sim::format_time(r.simulated).c_str());
    std::abort();
  }
  return 0;
}
