#pragma once

#include <stdexcept>
#include <string>

#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {

// Bad input: the message names the file, the JSON path and what was expected.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Run: line, encoders, the project's master and its script. Bench: the same without "master" and
// "script", for a master outside endatsim (co-simulation); its expectations are those that need
// no master model.
enum class ScenarioKind : std::uint8_t { Run, Bench };

Scenario load_scenario_file(const std::string& path, ScenarioKind kind = ScenarioKind::Run);
Scenario load_scenario_text(const std::string& text, const std::string& file_name,
                            ScenarioKind kind = ScenarioKind::Run);

}  // namespace endatsim::scenarios
