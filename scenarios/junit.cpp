#include "endatsim/scenarios/junit.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/report.hpp"
#include "endatsim/scenarios/xml.hpp"

namespace endatsim::scenarios {
namespace {

std::string failure_text(const ScenarioResult& r) {
  std::string body;
  for (const auto& e : r.expectations)
    if (!e.passed) body += "expectation " + e.name + ": " + e.detail + "\n";
  std::ostringstream summary;
  write_summary(summary, r, false);
  return body + "\n" + summary.str();
}

// A property per row that a named option loosened (RowConformance::relaxed_by), "t_st: the option
// and what it accepts": every report names the options that relaxed a limit.
std::string relaxed_properties(const std::vector<checker::RowConformance>& rows, const std::string& indent) {
  std::string x;
  for (const auto& c : rows)
    if (!c.relaxed_by.empty())
      x += indent + "<property name=\"relaxed_by\" value=\"" + xml_escape(c.check + ": " + c.relaxed_by) + "\"/>\n";
  return x;
}

bool relaxed(const std::vector<checker::RowConformance>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const auto& c) { return !c.relaxed_by.empty(); });
}

// A CI server groups test cases by class: the scenario's folder ("endatsim.field" for
// scenarios/field/x.json), never the whole path, so that the same run gives the same bytes
// wherever the tree is.
std::string classname(const std::string& suite_name, const std::string& file) {
  const std::string folder = std::filesystem::path(file).parent_path().filename().string();
  return suite_name + "." + (folder.empty() || folder == "." || folder == ".." ? "scenarios" : folder);
}

}  // namespace

std::string junit_head(const std::string& suite_name, std::size_t tests, std::size_t failures, std::size_t errors) {
  const std::string counts = "\" tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
                             "\" errors=\"" + std::to_string(errors) + "\"";
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"" + xml_escape(suite_name) + counts + ">\n" +
         "  <testsuite name=\"" + xml_escape(suite_name) + counts + " skipped=\"0\">\n";
}

std::string junit_tail() { return "  </testsuite>\n</testsuites>\n"; }

namespace {

// "outcomes.ok" belongs to the group "outcomes"; "positions_match_encoder" is a group of its own.
std::string group_of(const std::string& expectation) { return expectation.substr(0, expectation.find('.')); }

// A test case per group of each scenario's expectations, in the order they were judged.
std::string expectation_cases(const std::vector<ScenarioResult>& results, const std::string& suite_name,
                              const std::vector<NotRun>& not_run) {
  struct Case {
    std::string classname, name, file, failure, text, error;
  };
  std::vector<Case> cases;
  for (const auto& r : results) {
    const std::string cls = classname(suite_name, r.file) + "." + r.name;
    if (!r.incomplete.empty()) cases.push_back({cls, "complete", r.file, "", "", r.incomplete});
    std::vector<std::string> groups;
    for (const auto& e : r.expectations)
      if (group_of(e.name) != "complete" && std::find(groups.begin(), groups.end(), group_of(e.name)) == groups.end())
        groups.push_back(group_of(e.name));
    if (groups.empty() && r.incomplete.empty()) cases.push_back({cls, "run", r.file, "", "", ""});
    for (const auto& g : groups) {
      Case c{cls, g, r.file, "", "", ""};
      for (const auto& e : r.expectations) {
        if (group_of(e.name) != g || e.passed) continue;
        if (c.failure.empty()) c.failure = e.name + ": " + e.detail;
        c.text += "expectation " + e.name + ": " + e.detail + "\n";
      }
      cases.push_back(c);
    }
  }
  for (const auto& n : not_run) cases.push_back({classname(suite_name, n.file) + "." + n.name, "run", n.file, "", "", n.reason});
  std::size_t failures = 0, errors = 0;
  for (const auto& c : cases) (c.error.empty() ? failures : errors) += c.failure.empty() && c.error.empty() ? 0 : 1;
  std::string x = junit_head(suite_name, cases.size(), failures, errors);
  for (const auto& c : cases) {
    x += "    <testcase classname=\"" + xml_escape(c.classname) + "\" name=\"" + xml_escape(c.name) + "\" file=\"" +
         xml_escape(c.file) + "\"";
    if (c.failure.empty() && c.error.empty()) {
      x += "/>\n";
      continue;
    }
    x += ">\n";
    if (!c.error.empty())
      x += "      <error type=\"" + std::string(c.name == "complete" ? "incomplete" : "not run") + "\" message=\"" +
           xml_escape(c.error) + "\"/>\n";
    else
      x += "      <failure type=\"expectation\" message=\"" + xml_escape(c.failure) + "\">" + xml_escape(c.text) + "</failure>\n";
    x += "    </testcase>\n";
  }
  return x + junit_tail();
}

}  // namespace

// Findings of every check, kept or not.
std::uint64_t total_findings(const ScenarioResult& r) {
  std::uint64_t n = 0;
  for (const auto& [check, count] : finding_counts(r.conformance)) n += count;
  return n;
}

std::string junit_xml(const std::vector<ScenarioResult>& results, const std::string& suite_name,
                      const std::vector<NotRun>& not_run, JunitCases cases) {
  if (cases == JunitCases::Expectation) return expectation_cases(results, suite_name, not_run);
  std::size_t failures = 0, errors = not_run.size();
  for (const auto& r : results) (r.incomplete.empty() ? failures : errors) += r.passed() ? 0 : 1;
  std::string x = junit_head(suite_name, results.size() + not_run.size(), failures, errors);
  for (const auto& r : results) {
    x += "    <testcase classname=\"" + xml_escape(classname(suite_name, r.file)) + "\" name=\"" + xml_escape(r.name) +
         "\" file=\"" + xml_escape(r.file) + "\" assertions=\"" + std::to_string(r.expectations.size()) + "\">\n";
    x += "      <properties>\n";
    x += "        <property name=\"seed\" value=\"" + std::to_string(r.seed) + "\"/>\n";
    x += "        <property name=\"simulated\" value=\"" + xml_escape(sim::format_time(r.simulated)) + "\"/>\n";
    x += "        <property name=\"frames\" value=\"" + std::to_string(r.tally.results) + "\"/>\n";
    x += "        <property name=\"violations\" value=\"" + std::to_string(total_findings(r)) + "\"/>\n";
    x += relaxed_properties(r.conformance, "        ");
    x += "      </properties>\n";
    if (!r.incomplete.empty()) {
      x += "      <error type=\"incomplete\" message=\"" + xml_escape(r.incomplete) + "\">" + xml_escape(failure_text(r)) +
           "</error>\n";
    } else if (!r.passed()) {
      std::string first;
      std::size_t failed = 0;
      for (const auto& e : r.expectations)
        if (!e.passed && failed++ == 0) first = e.name + ": " + e.detail;
      if (failed > 1) first += " (and " + std::to_string(failed - 1) + " more)";
      x += "      <failure type=\"expectation\" message=\"" + xml_escape(first) + "\">" + xml_escape(failure_text(r)) +
           "</failure>\n";
    }
    x += "    </testcase>\n";
  }
  for (const auto& n : not_run)
    x += "    <testcase classname=\"" + xml_escape(classname(suite_name, n.file)) + "\" name=\"" + xml_escape(n.name) +
         "\" file=\"" + xml_escape(n.file) + "\">\n      <error type=\"not run\" message=\"" + xml_escape(n.reason) +
         "\"/>\n    </testcase>\n";
  return x + junit_tail();
}

std::string junit_xml(const std::vector<CaptureCheckResult>& captures, const std::vector<CaptureReadError>& unreadable) {
  std::size_t tests = 0, failures = 0;
  const auto failed = [](const checker::RowConformance& c) { return c.violations + c.undecided != 0; };
  for (const auto& r : captures)
    for (const auto& c : r.conformance) {
      ++tests;
      failures += failed(c) ? 1 : 0;
    }
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"endatsim check\" tests=\"" + std::to_string(tests + unreadable.size()) + "\" failures=\"" +
       std::to_string(failures) + "\" errors=\"" + std::to_string(unreadable.size()) + "\">\n";
  for (const auto& e : unreadable) {
    x += "  <testsuite name=\"" + xml_escape(e.file) + "\" tests=\"1\" failures=\"0\" errors=\"1\" skipped=\"0\">\n";
    x += "    <testcase classname=\"endatsim.check\" name=\"read\" file=\"" + xml_escape(e.file) + "\">\n";
    x += "      <error type=\"bad input\" message=\"" + xml_escape(e.message) + "\"/>\n";
    x += "    </testcase>\n  </testsuite>\n";
  }
  for (const auto& r : captures) {
    std::size_t suite_failures = 0, skipped = 0;
    for (const auto& c : r.conformance) {
      suite_failures += failed(c) ? 1 : 0;
      skipped += c.status != checker::RowConformance::Status::Judged ? 1 : 0;
    }
    x += "  <testsuite name=\"" + xml_escape(r.file) + "\" tests=\"" + std::to_string(r.conformance.size()) +
         "\" failures=\"" + std::to_string(suite_failures) + "\" errors=\"0\" skipped=\"" + std::to_string(skipped) +
         "\">\n";
    if (relaxed(r.conformance))
      x += "    <properties>\n" + relaxed_properties(r.conformance, "      ") + "    </properties>\n";
    for (const auto& c : r.conformance) {
      const auto row = protocol::timing_row(c.check);
      x += "    <testcase classname=\"endatsim.check\" name=\"" + xml_escape(c.check) + "\" file=\"" + xml_escape(r.file) +
           "\" assertions=\"" + std::to_string(c.judged) + "\">\n";
      if (!c.relaxed_by.empty())
        x += "      <properties>\n        <property name=\"relaxed_by\" value=\"" + xml_escape(c.relaxed_by) +
             "\"/>\n      </properties>\n";
      if (c.status != checker::RowConformance::Status::Judged) {
        x += "      <skipped message=\"" + xml_escape(std::string(checker::to_string(c.status)) + ": " + c.reason) + "\"/>\n";
      } else if (failed(c)) {
        std::string body;
        for (const auto& v : r.violations)
          if (v.check == c.check && v.severity != checker::Severity::Warning)
            body += std::string(checker::to_string(v.severity)) + " at " + sim::format_time(v.time) + ": measured " +
                    v.measured + ", limit " + v.limit + " - " + v.message + "\n";
        const std::string message = std::to_string(c.violations) + " violation(s), " + std::to_string(c.undecided) +
                                    " undecided [" + (row ? std::string(row->section) : std::string()) + "]";
        x += "      <failure type=\"" + std::string(c.violations != 0 ? "violation" : "undecided") + "\" message=\"" +
             xml_escape(message) + "\">" + xml_escape(body) + "</failure>\n";
      }
      x += "    </testcase>\n";
    }
    x += "  </testsuite>\n";
  }
  x += "</testsuites>\n";
  return x;
}

}  // namespace endatsim::scenarios
