// libFuzzer target: any bytes given to the scenario loader either load or raise a ScenarioError
// that names the file; anything else (another exception, a crash, UB, a leak) is a bug.
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "endatsim/scenarios/loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto s = endatsim::scenarios::load_scenario_text(text, "fuzz.json");
    if (s.name.empty() || s.script.empty()) {
      std::fprintf(stderr, "loaded a scenario without a name or script\n");
      std::abort();
    }
  } catch (const endatsim::scenarios::ScenarioError& e) {
    if (std::string(e.what()).rfind("fuzz.json: ", 0) != 0) {
      std::fprintf(stderr, "error does not name the file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
