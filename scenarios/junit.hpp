// JUnit XML for CI servers (Jenkins, GitLab, GitHub test reporters): one <testsuite> for a
// run, one <testcase> per scenario (or per group of its expectations), a <failure> per test case
// whose expectations do not all hold, carrying the violated expectations and the timing violations. No wall-clock times or
// host names: the same run gives the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// A scenario that did not run because the run was interrupted before it: an error test case.
struct NotRun {
  std::string file, name, reason;
};
// What a <testcase> is: a scenario (its class the scenario's folder: "endatsim.field"), or one
// group of a scenario's expectations ("outcomes", "violations", "positions_match_encoder"...;
// its class the folder and the scenario: "endatsim.field.09_cable_changed_while_running"), so
// that a CI server lists which expectation broke.
enum class JunitCases : std::uint8_t { Scenario, Expectation };
std::string junit_xml(const std::vector<ScenarioResult>& results, const std::string& suite_name = "endatsim",
                      const std::vector<NotRun>& not_run = {}, JunitCases cases = JunitCases::Scenario);

// The document around a run's test cases (one <testsuites> holding one <testsuite>): what
// junit_xml writes before the first and after the last, for `endatsim merge` to write the same.
std::string junit_head(const std::string& suite_name, std::size_t tests, std::size_t failures, std::size_t errors);
std::string junit_tail();

// `endatsim check`: one <testsuite> per capture, one <testcase> per row of the timing table; a
// row with violations or undecided findings fails, a row not applicable or not observable in
// that capture is skipped with the reason.
// A capture that could not be read is a <testsuite> of its own with one errored <testcase>, so
// that a CI server never shows it as green or leaves it out.
struct CaptureReadError {
  std::string file;
  std::string message;
};
std::string junit_xml(const std::vector<CaptureCheckResult>& captures,
                      const std::vector<CaptureReadError>& unreadable = {});

// Escapes text for XML attributes and character data; drops characters XML 1.0 forbids.
std::string xml_escape(const std::string& text);

}  // namespace endatsim::scenarios
