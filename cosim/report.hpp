// What a co-simulation ends with, in the forms `run` and `check` give: a summary with the
// violations, the two verdicts and the conformance table; JSON; JUnit for CI; the log of the
// frames decoded at the encoder's connector.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "cosim/bench.hpp"

namespace endatsim::cosim {

void write_summary(std::ostream& out, const BenchResult& r, bool verbose);
nlohmann::json to_json(const BenchResult& r);
// One <testsuite> for the bench, a <testcase> per expectation (violations.<check> among them, so
// each broken row of the timing table fails a test case of its own).
std::string junit_xml(const BenchResult& r);

}  // namespace endatsim::cosim
