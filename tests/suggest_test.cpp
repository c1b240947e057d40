// "Did you mean": the edit distance it rests on, the threshold, and the hints in the messages
// of the scenario loader (keys, enum values, check names, profiles).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "endatsim/input/suggest.hpp"
#include "endatsim/scenarios/bundled_profiles.hpp"
#include "endatsim/scenarios/loader.hpp"

using namespace endatsim;

namespace {

std::string error_of(const std::string& text) {
  try {
    scenarios::load_scenario_text(text, "bad.json");
  } catch (const scenarios::ScenarioError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string scenario_with(const std::string& encoder, const std::string& expect = "{}") {
  return R"({"name": "x", "line": {"cable_length_m": 10}, "master": {"f_c": "1 MHz"}, "encoder": )" + encoder +
         R"(, "script": [{"op": "read_position"}], "expect": )" + expect + "}";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwapsOfNeighbours) {
  EXPECT_EQ(input::edit_distance("json", "json"), 0U);
  EXPECT_EQ(input::edit_distance("jsn", "json"), 1U);        // insertion
  EXPECT_EQ(input::edit_distance("jsoon", "json"), 1U);      // deletion
  EXPECT_EQ(input::edit_distance("jsan", "json"), 1U);       // substitution
  EXPECT_EQ(input::edit_distance("rnu", "run"), 1U);         // swap of neighbours
  EXPECT_EQ(input::edit_distance("JSON", "json"), 0U);       // letters without case
  EXPECT_EQ(input::edit_distance("", "abc"), 3U);
  EXPECT_EQ(input::edit_distance("kitten", "sitting"), 3U);
}

TEST(ClosestMatch, SuggestsOnlyNearNamesAndTheFirstOfEquallyNearOnes) {
  const std::vector<std::string> names{"run", "sweep", "validate", "diagram", "check", "checks"};
  EXPECT_EQ(input::closest_match("rnu", names), "run");
  EXPECT_EQ(input::closest_match("chek", names), "check");  // check and checks: check is nearer
  EXPECT_EQ(input::closest_match("valdate", names), "validate");
  EXPECT_EQ(input::closest_match("simulate", names), std::nullopt);  // far from all
  EXPECT_EQ(input::closest_match("run", names), std::nullopt);       // itself a name
  EXPECT_EQ(input::closest_match("", names), std::nullopt);
  EXPECT_EQ(input::closest_match(std::string(100000, 'r'), names), std::nullopt);
  // A third of the word's length: 9 letters allow 3 edits, 8 letters 2.
  const std::vector<std::string> long_names{"sample_rate"};
  EXPECT_EQ(input::closest_match("smpel_rat", long_names), "sample_rate");  // 3 edits
  EXPECT_EQ(input::closest_match("smpel_rt", long_names), std::nullopt);    // 4 edits
  const std::vector<std::string> tied{"ab1", "ab2"};
  EXPECT_EQ(input::closest_match("ab3", tied), "ab1");
}

TEST(DidYouMean, NamesTheNearKeyBeforeTheListOfKeys) {
  const auto e = error_of(R"({"name": "x", "line": {"cable_length_m": 10, "cable_lenght_m": 10}, "master": {"f_c": "1 MHz"},
                            "script": [{"op": "read_position"}]})");
  EXPECT_TRUE(contains(e, "bad.json: at /line: unknown key \"cable_lenght_m\" (did you mean \"cable_length_m\"? "
                          "expected one of: ")) << e;
  const auto far = error_of(R"({"name": "x", "line": {"cable_length_m": 10, "colour": 10}, "master": {"f_c": "1 MHz"}, "script": []})");
  EXPECT_TRUE(contains(far, "unknown key \"colour\" (expected one of: ")) << far;
}

TEST(DidYouMean, NamesTheNearValueOfAnEnum) {
  const auto e = error_of(scenario_with(R"({"kind": "multiturm"})"));
  EXPECT_TRUE(contains(e, "bad.json: at /encoder/kind: expected one of \"singleturn\", \"multiturn\", \"linear\", "
                          "\"touch_probe\", \"eib\", got string \"multiturm\" (did you mean \"multiturn\"?)")) << e;
  const auto far = error_of(scenario_with(R"({"kind": "rotary"})"));
  EXPECT_FALSE(contains(far, "did you mean")) << far;
}

TEST(DidYouMean, NamesTheNearCheckInExpectViolations) {
  const auto e = error_of(scenario_with("{}", R"({"violations": {"t_sT": 1}})"));
  EXPECT_TRUE(contains(e, "at /expect/violations/t_sT: unknown name \"t_sT\" (did you mean ")) << e;
}

TEST(DidYouMean, NamesTheNearBundledProfileAndListsThemAll) {
  const auto e = error_of(scenario_with(R"({"profile": "rotary_singleturn_52bit"})"));
  EXPECT_TRUE(contains(e, "bad.json: at /encoder/profile: no bundled profile \"rotary_singleturn_52bit\" (did you mean "
                          "\"rotary_singleturn_25bit\"? the bundled profiles are ")) << e;
  for (const auto& name : scenarios::bundled_profile_names()) EXPECT_TRUE(contains(e, name)) << name;
  EXPECT_EQ(scenarios::bundled_profile_names().size(), 7U);
}
