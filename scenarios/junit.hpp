// JUnit XML for CI servers (Jenkins, GitLab, GitHub test reporters): one <testsuite> for a
// run, one <testcase> per scenario, a <failure> per scenario whose expectations do not all
// hold, carrying the violated expectations and the timing violations. No wall-clock times or
// host names: the same run gives the same bytes.
#pragma once

#include <string>
#include <vector>

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// A scenario that did not run because the run was interrupted before it: an error test case.
struct NotRun {
  std::string file, name, reason;
};
std::string junit_xml(const std::vector<ScenarioResult>& results, const std::string& suite_name = "endatsim",
                      const std::vector<NotRun>& not_run = {});

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
