// libFuzzer target for the VCD lint's reader (endatsim-vcdlint FILE, frame diagrams): any bytes are
// parsed without an exception; at most 100 issues, each with a line within the text; every
// variable's changes in time order when the file is clean. Anything else (an exception, a crash,
// UB, a leak, a hang) is a bug.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "endatsim/scenarios/vcd_reader.hpp"

namespace scenarios = endatsim::scenarios;

namespace {

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "fuzz_vcdlint: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (const bool sigrok : {false, true}) {
    scenarios::VcdFile f;
    try {
      f = scenarios::parse_vcd(text, {.sigrok = sigrok});
    } catch (const std::exception& e) {
      bug(std::string("parse_vcd threw: ") + e.what());
    }
    if (f.issues.size() > 100) bug("more than 100 issues");
    for (const auto& issue : f.issues)
      if (issue.line > lines) bug("an issue at line " + std::to_string(issue.line) + " of " + std::to_string(lines));
    if (!f.issues.empty()) continue;
    for (const auto& v : f.variables) {
      for (std::size_t i = 1; i < v.changes.size(); ++i)
        if (v.changes[i].time < v.changes[i - 1].time) bug("changes of " + v.name + " out of time order in a clean file");
      if (f.find(v.name) == nullptr) bug("find() misses " + v.name);
    }
  }
  return 0;
}
