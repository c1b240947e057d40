// What a co-simulation ends with, in the forms `run` and `check` give: a summary with the
// violations, the two verdicts and the conformance table; JSON; JUnit for CI; the log of the
// frames decoded at the encoder's connector.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <optional>
#include <string>

#include "endatsim/cosim/bench.hpp"

namespace endatsim::cosim {

void write_summary(std::ostream& out, const BenchResult& r, bool verbose);
nlohmann::json to_json(const BenchResult& r);
// One <testsuite> for the bench, a <testcase> per expectation (violations.<check> among them, so
// each broken row of the timing table fails a test case of its own).
std::string junit_xml(const BenchResult& r);

struct OutputPaths {
  std::optional<std::string> json, junit, log;  // "-": standard output
};
// Before the bench runs, as `endatsim run` checks its own (scenarios::check_output_paths): no
// output is the bench file or another output, and each can be written. Throws std::runtime_error
// naming the option (`prefix` + "json": "--json", "+endatsim_json"), the path and the reason.
void check_outputs(const std::string& bench, const OutputPaths& outputs, const std::optional<std::string>& vcd,
                   const std::string& prefix);
// Prints the summary to `out` and writes each output asked for (never half a file); returns the
// exit status: 0 when every expectation held, 1 when one failed, 2 when an output could not be
// written (said on `err`), 3 when a limit ended the run, 128 + N when signal N did (the outputs
// say incomplete).
int report(const BenchResult& r, const OutputPaths& outputs, bool verbose, std::ostream& out, std::ostream& err);

}  // namespace endatsim::cosim
