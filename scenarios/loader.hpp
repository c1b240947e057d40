#pragma once

#include <stdexcept>
#include <string>

#include "scenarios/scenario.hpp"

namespace endatsim::scenarios {

// Bad input: the message names the file, the JSON path and what was expected.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Scenario load_scenario_file(const std::string& path);
Scenario load_scenario_text(const std::string& text, const std::string& file_name);

}  // namespace endatsim::scenarios
