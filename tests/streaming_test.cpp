// Results written while a run goes (run_recorder.hpp, streamed_outputs.hpp): for every bundled,
// field and safety scenario, the streamed log, JSON lines and results object equal what the
// complete result gives, whatever RunOptions::kept holds back; a run that keeps little still
// judges every expectation, counts every frame and finding, and keeps no more than it may.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"
#include "endatsim/scenarios/transaction_log.hpp"

#include "scenario_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace scenarios = endatsim::scenarios;
namespace master = endatsim::master;

using endatsim::test_support::Streamed;

// One run with every output streamed, keeping `kept` frames and findings of each check.
Streamed run_streamed(const scenarios::Scenario& s, std::size_t kept) {
  scenarios::RunOptions options;
  options.kept = kept;
  return endatsim::test_support::run_streamed(s, options);
}

std::vector<std::string> expectation_lines(const scenarios::ScenarioResult& r) {
  std::vector<std::string> v;
  for (const auto& e : r.expectations) v.push_back(e.name + (e.passed ? " ok: " : " FAIL: ") + e.detail);
  return v;
}

class Streaming : public ::testing::TestWithParam<fs::path> {};

TEST_P(Streaming, OutputsEqualTheCompleteResultsAndDoNotDependOnWhatIsKept) {
  const auto s = scenarios::load_scenario_file(GetParam().string());
  const Streamed all = run_streamed(s, SIZE_MAX);
  const auto& r = all.result;
  EXPECT_EQ(r.late_findings, 0U) << "a finding came after its frame was written out";
  EXPECT_EQ(all.log, scenarios::transaction_log_text(r));
  EXPECT_EQ(all.jsonl, scenarios::transaction_log_jsonl(r));
  const auto parsed = nlohmann::json::parse(all.json);
  ASSERT_EQ(parsed["scenarios"].size(), 1U);
  EXPECT_EQ(parsed["scenarios"][0], scenarios::to_json(r)) << "the streamed results object differs";
  EXPECT_EQ(r.tally.results, r.frames.size());

  // Keeping three frames and three findings per check (the summary shows three): the same files, byte for byte (but for the
  // count of findings not kept), the same verdicts.
  const Streamed few = run_streamed(s, 3);
  EXPECT_EQ(few.result.late_findings, 0U);
  EXPECT_EQ(few.log, all.log);
  EXPECT_EQ(few.jsonl, all.jsonl);
  auto few_json = nlohmann::json::parse(few.json);
  auto& scenario = few_json["scenarios"][0];
  EXPECT_EQ(scenario["frames"], parsed["scenarios"][0]["frames"]);
  EXPECT_EQ(scenario["expectations"], parsed["scenarios"][0]["expectations"]);
  EXPECT_EQ(scenario["conformance"], parsed["scenarios"][0]["conformance"]);
  EXPECT_EQ(scenario["verdict"], parsed["scenarios"][0]["verdict"]);
  EXPECT_EQ(expectation_lines(few.result), expectation_lines(r));
  EXPECT_EQ(few.result.passed(), r.passed());
  EXPECT_LE(few.result.frames.size(), 3U);
  EXPECT_LE(few.result.encoder_frames.size(), 128U);
  std::map<std::string, std::size_t> per_check;
  for (const auto& v : few.result.violations) EXPECT_LE(++per_check[v.check], 3U) << v.check;
  const std::uint64_t counted = r.violations.size();
  EXPECT_EQ(few.result.violations.size() + scenario.value("violations_not_kept", std::uint64_t{0}), counted);
  std::ostringstream a, b;
  scenarios::write_summary(a, r, false);
  scenarios::write_summary(b, few.result, false);
  EXPECT_EQ(b.str(), a.str()) << "the summary depends on what was kept";
}

INSTANTIATE_TEST_SUITE_P(Scenarios, Streaming, ::testing::ValuesIn(endatsim::test_support::scenario_files()), [](const auto& param_info) { return endatsim::test_support::scenario_test_name(param_info.param); });

TEST(ResultsJsonWriter, ResultsFileOfNoScenarioAndOfAnIncompleteRunIsValidJson) {
  std::ostringstream out;
  scenarios::ResultsJsonWriter writer(out, "1.2.3");
  writer.finish(false, "interrupted by SIGINT", {"a.json", "b.json"});
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["endatsim"], "1.2.3");
  EXPECT_TRUE(j["scenarios"].empty());
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(j["not_run"], nlohmann::json::array({"a.json", "b.json"}));
  EXPECT_EQ(out.str().find("\"scenarios\": []"), out.str().find("\"scenarios\""));
}

}  // namespace

// A master that measures the delay again and again (a careful one on a noisy line) kept every
// measurement in memory, about 2 KB each: a long run grew without bound. The first
// RunOptions::kept are kept, every one is counted, and the last (what the expectations judge) is
// kept apart; the results list the kept ones and count the others.
TEST(ResultsKept, DelayMeasurementsAreCountedAndTheFirstFewKept) {
  const auto s = scenarios::load_scenario_text(R"({
    "name": "remeasure", "seed": 1, "line": { "cable_length_m": 10 },
    "encoder": { "version": "2.2", "position_bits": 25 },
    "master": { "f_c": "8 MHz", "t_st": "2 us", "delay_compensation": true },
    "script": [ { "op": "measure_delay" }, { "op": "measure_delay" }, { "op": "measure_delay" },
                { "op": "measure_delay" }, { "op": "measure_delay" },
                { "op": "read_position", "count": 2, "cycle": "100 us" } ],
    "expect": { "delay_measurement": { "accepted": true } } })", "remeasure.json");
  const Streamed all = run_streamed(s, SIZE_MAX);
  const Streamed two = run_streamed(s, 2);
  EXPECT_EQ(all.result.measurements.size(), 5U);
  EXPECT_EQ(two.result.measurements.size(), 2U);
  EXPECT_EQ(two.result.measurements_count, 5U);
  ASSERT_TRUE(two.result.last_measurement.has_value());
  EXPECT_EQ(two.result.last_measurement->t_d, all.result.measurements.back().t_d);
  EXPECT_TRUE(two.result.passed());
  const auto j = nlohmann::json::parse(two.json)["scenarios"][0];
  EXPECT_EQ(j["delay_measurements"].size(), 2U);
  EXPECT_EQ(j["delay_measurements_not_kept"], 3);
  EXPECT_FALSE(nlohmann::json::parse(all.json)["scenarios"][0].contains("delay_measurements_not_kept"));
}
