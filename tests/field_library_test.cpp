// The field-bug library (scenarios/field/): every bug comes as a pair, NAME.json that
// reproduces what the field saw and NAME_fixed.json with the fix. Each file's own expectations
// say how it fails (ctest runs them through the CLI); this test checks the library as a whole:
// the headers, the pairs, and that a bug shows and its fix is clean.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"

using namespace endatsim;
namespace fs = std::filesystem;

namespace {

const fs::path kField = fs::path(ENDATSIM_SOURCE_DIR) / "scenarios" / "field";

std::vector<fs::path> bugs() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(kField)) {
    const auto stem = e.path().stem().string();
    if (e.path().extension() == ".json" && !stem.ends_with("_fixed")) v.push_back(e.path());
  }
  std::sort(v.begin(), v.end());
  return v;
}

fs::path fixed_twin(const fs::path& bug) { return bug.parent_path() / (bug.stem().string() + "_fixed.json"); }

bool all_frames_ok(const scenarios::ScenarioResult& r) {
  return std::all_of(r.frames.begin(), r.frames.end(),
                     [](const auto& f) { return f.measurement || f.outcome == master::FrameOutcome::Ok; });
}

// A fix may still meet a refused access (type II: e.g. the high-impedance broadcast of 2.10 is
// acknowledged inverted by design) and failed frames that a careful master repeated, but no
// frame may be lost.
bool no_frame_lost(const scenarios::ScenarioResult& r) {
  const auto failed = std::count_if(r.frames.begin(), r.frames.end(), [](const auto& f) {
    return !f.measurement && f.outcome != master::FrameOutcome::Ok && f.outcome != master::FrameOutcome::Type2Error;
  });
  return static_cast<std::uint64_t>(failed) <= r.retries;
}

std::vector<std::uint64_t> positions(const scenarios::ScenarioResult& r) {
  std::vector<std::uint64_t> v;
  for (const auto& f : r.frames)
    if (!f.measurement && f.outcome == master::FrameOutcome::Ok) v.push_back(f.position);
  return v;
}

std::size_t errors(const scenarios::ScenarioResult& r) {
  return static_cast<std::size_t>(std::count_if(r.violations.begin(), r.violations.end(), [](const auto& v) {
    return v.severity == checker::Severity::Error;
  }));
}

std::string failed_expectations(const scenarios::ScenarioResult& r) {
  std::string s;
  for (const auto& e : r.expectations)
    if (!e.passed) s += e.name + ": " + e.detail + "\n";
  return s;
}

}  // namespace

TEST(FieldLibrary, HoldsAtLeastFifteenBugsEachWithHeaderAndFixedTwin) {
  const auto all = bugs();
  EXPECT_GE(all.size(), 15U);
  for (const auto& bug : all) {
    const auto s = scenarios::load_scenario_file(bug.string());
    ASSERT_TRUE(s.field.has_value()) << bug << ": no \"field\" header";
    EXPECT_TRUE(fs::exists(fixed_twin(bug))) << bug << ": no fixed variant";
  }
  for (const auto& e : fs::directory_iterator(kField)) {
    const auto stem = e.path().stem().string();
    if (stem.ends_with("_fixed")) {
      EXPECT_TRUE(fs::exists(kField / (stem.substr(0, stem.size() - 6) + ".json"))) << e.path() << ": a fix without its bug";
    }
  }
}

class FieldBug : public ::testing::TestWithParam<fs::path> {};

TEST_P(FieldBug, TheBugShowsAndTheFixIsClean) {
  const auto bug = scenarios::run_scenario(scenarios::load_scenario_file(GetParam().string()));
  EXPECT_TRUE(bug.passed()) << "the bug no longer reproduces as described:\n" << failed_expectations(bug);
  const auto fixed = scenarios::run_scenario(scenarios::load_scenario_file(fixed_twin(GetParam()).string()));
  EXPECT_TRUE(!all_frames_ok(bug) || errors(bug) > 0 || bug.busy_timeouts > 0 || !bug.finished ||
              bug.encoder_memory.areas != fixed.encoder_memory.areas || positions(bug) != positions(fixed))
      << "nothing went wrong in the field scenario that the fix changes";
  EXPECT_TRUE(fixed.passed()) << failed_expectations(fixed);
  EXPECT_TRUE(fixed.finished);
  EXPECT_TRUE(no_frame_lost(fixed)) << "the fixed variant still loses frames";
  EXPECT_EQ(errors(fixed), 0U) << "the fixed variant still breaks a timing condition";
}

INSTANTIATE_TEST_SUITE_P(Library, FieldBug, ::testing::ValuesIn(bugs()), [](const auto& param_info) {
  std::string name = param_info.param.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
});
