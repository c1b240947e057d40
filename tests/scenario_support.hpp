#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vector>

#include <sstream>
#include <string>

#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"
#include "endatsim/scenarios/transaction_log.hpp"
#include "endatsim/scenarios/vcd_reader.hpp"

namespace endatsim::test_support {

// Every bundled, field and safety scenario file, in path order (the parameters of the suites
// that run them all).
inline std::vector<std::filesystem::path> scenario_files() {
  std::vector<std::filesystem::path> out;
  for (const char* folder : {"bundled", "field", "safety"})
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(ENDATSIM_SOURCE_DIR) / "scenarios" / folder))
      if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// One run with the transaction log, its JSON lines and the results file streamed into strings,
// as `endatsim run --log --log-json --json` writes them.
struct Streamed {
  scenarios::ScenarioResult result;
  std::string log, jsonl, json;
};
inline Streamed run_streamed(const scenarios::Scenario& s, scenarios::RunOptions options) {
  std::ostringstream log, jsonl, json;
  scenarios::TransactionLogWriter text(log, scenarios::TransactionLogWriter::Format::Text);
  scenarios::TransactionLogWriter lines(jsonl, scenarios::TransactionLogWriter::Format::JsonLines);
  scenarios::ResultsJsonWriter results(json, "test");
  options.sinks = {&text, &lines, &results};
  Streamed out{scenarios::run_scenario(s, options), {}, {}, {}};
  results.finish(out.result.passed(), "", {});
  out.log = log.str();
  out.jsonl = jsonl.str();
  out.json = json.str();
  return out;
}

// A parameterized test's name from its scenario file: folder and stem, alphanumeric
// ("field_09_cable_changed_while_running").
inline std::string scenario_test_name(const std::filesystem::path& file) {
  std::string name = file.parent_path().filename().string() + "_" + file.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

// A scenario built in code: an EnDat 2.2 encoder at position 104462 on `cable_m` of cable,
// a master at f_c, optional delay compensation (measured first), `reads` position reads.
inline scenarios::Scenario make_scenario(double cable_m, sim::Hertz f_c, bool compensated, unsigned reads = 3) {
  scenarios::Scenario s;
  s.name = "in-code";
  s.line.cable_length_m = cable_m;
  s.encoder.motion.start = 104462;
  s.master.f_c = f_c;
  s.master.delay_compensation = compensated;
  s.master.t_st = compensated ? sim::us(2) : sim::Time::zero();
  s.master.measurement.f_e = 8 * f_c;
  if (compensated) s.script.push_back({master::Operation::Kind::MeasureDelay, {}, {}, {}, 1, {}, {}});
  master::Operation read;
  read.command = protocol::ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  read.count = reads;
  read.cycle = sim::us(100);
  s.script.push_back(read);
  return s;
}

// A script operation that sends `command` with its 8 + 16 bits (address / MRS code / port and
// parameter / instruction / block address).
inline master::Operation op(protocol::ModeCommand command, std::uint8_t address = 0, std::uint16_t parameter = 0) {
  master::Operation o;
  o.command = command;
  o.address = address;
  o.parameter = parameter;
  return o;
}

// Puts a read with disturbed mode bits (a type I error handling) before the scenario's reads.
inline void prepend_disturbed_read(scenarios::Scenario& s, std::uint8_t mode_bits) {
  master::Operation bad = s.script.back();
  bad.mode_bits = mode_bits;
  bad.count = 1;
  s.script.insert(s.script.begin(), bad);
}

// Every VCD a test writes goes through the lint, with sigrok's restrictions.
inline void expect_clean_vcd(const std::string& text, const std::string& what) {
  const auto f = scenarios::parse_vcd(text, {.sigrok = true});
  EXPECT_TRUE(f.issues.empty()) << what << ": line " << (f.issues.empty() ? 0 : f.issues[0].line) << ": "
                                << (f.issues.empty() ? "" : f.issues[0].message);
  EXPECT_FALSE(f.variables.empty()) << what << ": no variables";
}

inline std::size_t count_ok(const scenarios::ScenarioResult& r) {
  std::size_t n = 0;
  for (const auto& f : r.frames) n += !f.measurement && f.outcome == master::FrameOutcome::Ok;
  return n;
}

inline std::size_t count_violations(const scenarios::ScenarioResult& r, std::string_view check) {
  std::size_t n = 0;
  for (const auto& v : r.violations) n += v.check == check;
  return n;
}

// Findings of `check` that count against the given verdict.
inline std::size_t count_violations(const scenarios::ScenarioResult& r, std::string_view check, checker::Verdict verdict) {
  std::size_t n = 0;
  for (const auto& v : r.violations) n += v.check == check && v.verdict == verdict;
  return n;
}

}  // namespace endatsim::test_support
