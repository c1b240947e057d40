#include <gtest/gtest.h>

#include <algorithm>
#include <regex>

#include "endatsim/input/json_input.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"

using namespace endatsim;
using scenarios::load_scenario_text;
using scenarios::ScenarioError;

namespace {

const char* const kValid = R"({
  "name": "ok",
  "line": {"cable_length_m": 10},
  "master": {"f_c": "1 MHz"},
  "script": [{"op": "read_position"}]
})";

// Replaces the first occurrence of `from` in the valid scenario.
std::string valid_with(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

std::string error_of(const std::string& text) {
  try {
    load_scenario_text(text, "bad.json");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(ScenarioLoader, AcceptsAMinimalScenarioWithDocumentedDefaults) {
  const auto s = load_scenario_text(kValid, "ok.json");
  EXPECT_EQ(s.name, "ok");
  EXPECT_EQ(s.master.f_c, sim::MHz(1));
  EXPECT_EQ(s.encoder.position_bits, 25U);
  EXPECT_EQ(s.line.cable_delay_per_m, sim::ns(5));
  ASSERT_EQ(s.script.size(), 1U);
  EXPECT_EQ(s.script[0].command, protocol::ModeCommand::EncoderSendPositionValues);
}

TEST(ScenarioLoader, ReadsTheDatasheetsTstAndTloMaxima) {
  const auto s = load_scenario_text(valid_with("\"master\"", "\"encoder\": {\"t_st_max\": \"3 us\", \"t_lo_max\": \"5 us\"}, \"master\""), "ok.json");
  EXPECT_EQ(s.encoder.t_st_max, sim::us(3));
  EXPECT_EQ(s.encoder.t_lo_max, sim::us(5));
  EXPECT_FALSE(load_scenario_text(kValid, "ok.json").encoder.t_st_max.has_value());
}

struct BadCase {
  const char* label;
  std::string text;
  std::vector<std::string> must_contain;
  friend void PrintTo(const BadCase& c, std::ostream* os) { *os << c.label; }
};

class ScenarioLoaderRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(ScenarioLoaderRejects, NamingFilePathAndExpectation) {
  const std::string message = error_of(GetParam().text);
  EXPECT_EQ(message.rfind("bad.json: ", 0), 0U) << message;
  for (const auto& part : GetParam().must_contain) EXPECT_NE(message.find(part), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ScenarioLoaderRejects,
    ::testing::Values(
        BadCase{"empty", "", {"not valid JSON"}},
        BadCase{"garbage", "\x01\x02\xff", {"not valid JSON"}},
        BadCase{"array", "[]", {"at /", "expected an object"}},
        BadCase{"missing_name", valid_with("\"name\": \"ok\",", ""), {"missing required key \"name\""}},
        BadCase{"misspelt_required_key", valid_with("\"cable_length_m\"", "\"cable_lenght_m\""),
                {"at /line: missing required key \"cable_length_m\" (did you mean it for \"cable_lenght_m\"?)"}},
        BadCase{"fc_number", valid_with("\"1 MHz\"", "1000000"), {"/master/f_c", "frequency string", "got number"}},
        BadCase{"fc_too_high", valid_with("\"1 MHz\"", "\"20 MHz\""), {"/master/f_c", "16 MHz"}},
        BadCase{"fc_too_low", valid_with("\"1 MHz\"", "\"50 kHz\""), {"/master/f_c", "100 kHz"}},
        BadCase{"negative_cable", valid_with("10}", "-1}"), {"/line/cable_length_m", "0 .. 300 m"}},
        BadCase{"huge_cable", valid_with("10}", "1e300}"), {"/line/cable_length_m"}},
        BadCase{"unknown_key", valid_with("\"cable_length_m\"", "\"cable_lenght_m\": 1, \"cable_length_m\""),
                {"/line", "unknown key \"cable_lenght_m\""}},
        BadCase{"bad_unit", valid_with("\"1 MHz\"", "\"1 MHZ\""), {"/master/f_c", "unit"}},
        BadCase{"bad_op", valid_with("read_position", "read_positions"), {"/script/0/op", "one of"}},
        BadCase{"bad_mode_bits", valid_with("{\"op\": \"read_position\"}", "{\"op\": \"read_position\", \"mode_bits\": \"0001\"}"),
                {"/script/0/mode_bits", "six mode bits"}},
        BadCase{"times_backwards",
                valid_with("[{\"op\": \"read_position\"}]",
                           "[{\"op\": \"read_position\", \"at\": \"2 ms\"}, {\"op\": \"wait\", \"at\": \"1 ms\", \"duration\": \"1 us\"}]"),
                {"/script/1/at", "not before"}},
        BadCase{"empty_script", valid_with("[{\"op\": \"read_position\"}]", "[]"), {"/script", "non-empty array"}},
        BadCase{"t_m_out_of_range", valid_with("\"master\"", "\"encoder\": {\"t_m\": \"5 us\"}, \"master\""),
                {"/encoder/t_m", "10 us .. 30 us"}},
        BadCase{"t_st_max_below_the_table", valid_with("\"master\"", "\"encoder\": {\"t_st_max\": \"500 ns\"}, \"master\""),
                {"/encoder/t_st_max", "1 us .. 10 ms"}},
        BadCase{"t_lo_max_below_the_table", valid_with("\"master\"", "\"encoder\": {\"t_lo_max\": \"100 ns\"}, \"master\""),
                {"/encoder/t_lo_max", "200 ns .. 10 ms"}},
        BadCase{"multiturn_without_bits", valid_with("\"master\"", "\"encoder\": {\"kind\": \"multiturn\"}, \"master\""),
                {"/encoder", "multiturn_bits"}},
        BadCase{"deep_nesting", valid_with("\"ok\",", "\"ok\", \"description\": " + std::string(100, '[') + std::string(100, ']') + ","),
                {"nested deeper"}},
        BadCase{"invalid_utf8", valid_with("\"ok\"", "\"o\xc3\x28k\""), {"not valid JSON"}},
        BadCase{"negative_count", valid_with("{\"op\": \"read_position\"}", "{\"op\": \"read_position\", \"count\": -3}"),
                {"/script/0/count", "integer 1 .. 1000000"}},
        BadCase{"bad_violation_name",
                valid_with("\"script\"", "\"expect\": {\"violations\": {\"t_foo\": 1}}, \"script\""),
                {"/expect/violations/t_foo", "unknown name"}},
        BadCase{"bad_count_text",
                valid_with("\"script\"", "\"expect\": {\"outcomes\": {\"ok\": \">= x\"}}, \"script\""),
                {"/expect/outcomes/ok", "a count"}}),
    [](const auto& param_info) { return std::string(param_info.param.label); });

TEST(ScenarioLoader, MissingFileIsNamed) {
  try {
    scenarios::load_scenario_file("/nonexistent/x.json");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.json: cannot open"), std::string::npos);
  }
}

TEST(ScenarioLoader, DuplicateKeysAreRejectedWithTheirPath) {
  const std::string text = valid_with("\"cable_length_m\": 10", "\"cable_length_m\": 10, \"cable_length_m\": 20");
  const std::string message = error_of(text);
  EXPECT_NE(message.find("bad.json: at /line/cable_length_m: duplicate key"), std::string::npos) << message;
  const std::string in_array =
      error_of(valid_with("{\"op\": \"read_position\"}", "{\"op\": \"wait\"}, {\"op\": \"read_position\", \"op\": \"wait\"}"));
  EXPECT_NE(in_array.find("at /script/1/op: duplicate key"), std::string::npos) << in_array;
}

TEST(ScenarioLoader, NumberOverflowIsReportedAsBadJsonWithItsPath) {
  const std::string message = error_of(valid_with("10}", "1e400}"));
  EXPECT_EQ(message.rfind("bad.json: at /line/cable_length_m: not valid JSON: number overflow", 0), 0U) << message;
}

TEST(ScenarioLoader, ADirectoryIsNotAScenario) {
  try {
    scenarios::load_scenario_file(ENDATSIM_SOURCE_DIR);
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(ScenarioLoader, ReadsLineEventsInTimeOrder) {
  const auto s = load_scenario_text(
      valid_with("\"script\"", "\"events\": [{\"at\": \"1 ms\", \"set_cable\": {\"cable_length_m\": 50}}], \"script\""),
      "ok.json");
  ASSERT_EQ(s.events.size(), 1U);
  EXPECT_EQ(s.events[0].at, sim::ms(1));
  EXPECT_EQ(s.events[0].cable_length_m, 50.0);
  EXPECT_EQ(s.events[0].cable_delay_per_m, sim::ns(5));
  const std::string backwards = error_of(valid_with(
      "\"script\"",
      "\"events\": [{\"at\": \"2 ms\", \"set_cable\": {\"cable_length_m\": 5}}, {\"at\": \"1 ms\", \"set_cable\": "
      "{\"cable_length_m\": 5}}], \"script\""));
  EXPECT_NE(backwards.find("at /events/1/at"), std::string::npos) << backwards;
  const std::string too_long =
      error_of(valid_with("\"script\"", "\"events\": [{\"at\": \"1 ms\", \"set_cable\": {\"cable_length_m\": 400}}], \"script\""));
  EXPECT_NE(too_long.find("at /events/0/set_cable/cable_length_m"), std::string::npos) << too_long;
}

// ---- expect.violations: "*" counts every check not named ----

namespace {
std::vector<scenarios::ExpectationResult> judged(const std::string& violations, const std::vector<std::string>& found) {
  const auto s = load_scenario_text(valid_with("\"script\"", "\"expect\": {\"violations\": " + violations + "}, \"script\""), "v.json");
  std::vector<checker::Violation> vs;
  for (const auto& check : found) {
    checker::Violation v;
    v.check = check;
    vs.push_back(v);
  }
  std::vector<scenarios::ExpectationResult> out;
  scenarios::judge_violations(s.expect, vs, out);
  return out;
}
bool all_passed(const std::vector<scenarios::ExpectationResult>& r) {
  return std::all_of(r.begin(), r.end(), [](const auto& e) { return e.passed; });
}
}  // namespace

TEST(ExpectViolations, ACheckNotNamedFailsWithoutTheWildcard) {
  const auto r = judged(R"({"t_st": 1})", {"t_st", "f_c", "f_c"});
  EXPECT_FALSE(all_passed(r));
  ASSERT_EQ(r.size(), 2U);
  EXPECT_EQ(r[1].name, "violations.f_c");
  EXPECT_EQ(r[1].detail, "2 (expected none: not listed)");
}

TEST(ExpectViolations, TheWildcardCountsEveryCheckNotNamedTogether) {
  const std::vector<std::string> found{"t_st", "f_c", "f_c", "t_lo"};
  const auto any = judged(R"({"t_st": 1, "*": ">=0"})", found);
  EXPECT_TRUE(all_passed(any));
  ASSERT_EQ(any.size(), 2U);
  EXPECT_EQ(any[1].name, "violations.*");
  EXPECT_EQ(any[1].detail, "3 of checks not named (expected >=0): f_c 2, t_lo 1");
  EXPECT_TRUE(all_passed(judged(R"({"t_st": 1, "*": 3})", found)));
  EXPECT_FALSE(all_passed(judged(R"({"t_st": 1, "*": "<=2"})", found)));
  EXPECT_FALSE(all_passed(judged(R"({"t_st": 1, "*": 4})", found)));
  // The named checks are still judged on their own.
  EXPECT_FALSE(all_passed(judged(R"({"t_st": 2, "*": ">=0"})", found)));
  // With nothing else found, "*" sees zero.
  EXPECT_FALSE(all_passed(judged(R"({"*": ">=1"})", {})));
  EXPECT_TRUE(all_passed(judged(R"({"*": 0})", {})));
}

TEST(ExpectViolations, TheWildcardIsOnlyAKeyOfViolations) {
  try {
    load_scenario_text(valid_with("\"script\"", "\"expect\": {\"outcomes\": {\"*\": 1}}, \"script\""), "v.json");
    FAIL() << "\"*\" was taken as an outcome";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("/expect/outcomes/*"), std::string::npos) << e.what();
  }
}

// The schema's pattern for keys such as A3 addresses matches a string exactly when the loader reads
// it as a number in the range: decimal or hex, either case, leading zeros up to 16 digits.
TEST(WordStringPattern, MatchesExactlyTheStringsTheLoaderReadsInTheRange) {
  const auto reads_in = [](const std::string& text, std::uint64_t min, std::uint64_t max) {
    const nlohmann::json j = text;
    try {
      return input::Node(j, "/k", "f.json").as_word(max) >= min;
    } catch (const std::exception&) {
      return false;
    }
  };
  for (const auto& [min, max] : {std::pair<std::uint64_t, std::uint64_t>{1, 64}, {0, 15}, {0, 255}, {7, 300}, {0, 0}, {16, 16}}) {
    const std::regex pattern(input::word_string_pattern(min, max));
    std::vector<std::string> texts = {"", "0x", "x1", "-1", "1 ", " 1", "0x0x1", "1e1", "0b1", "00000000000000001", "0x00000000000000001",
                                      "0000000000000001", "0x000000000000000F"};
    for (std::uint64_t v = 0; v <= 320; ++v) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(v));
      texts.push_back(buf);
      texts.push_back(std::string("00") + buf);
      std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(v));
      texts.push_back(buf);
      std::snprintf(buf, sizeof buf, "0X%03llX", static_cast<unsigned long long>(v));
      texts.push_back(buf);
    }
    for (const auto& t : texts)
      EXPECT_EQ(std::regex_match(t, pattern), reads_in(t, min, max)) << "\"" << t << "\" in " << min << " .. " << max;
  }
  EXPECT_THROW(input::word_string_pattern(5, 4), std::invalid_argument);
}
