// Determinism and replay through the real CLI: the same scenario and seed give byte-identical
// VCD and JSON; the JSON results name the scenario file and seed, and `endatsim run FILE --seed N`
// with those values replays the run byte for byte; a sweep gives the same bytes on any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "scenario_support.hpp"

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A directory of its own per test process (ctest runs tests of this file in parallel).
class Replay : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("endatsim_replay_" + std::to_string(getpid()) + "_" +
            testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }

  int cli(const std::string& args) const {
    const std::string cmd = "timeout 300 " + std::string(ENDATSIM_EXE) + " " + args + " >'" +
                            path("stdout").string() + "' 2>'" + path("stderr").string() + "'";
    const int raw = std::system(cmd.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  }

  // A scenario whose trace depends on the seed: clock jitter and a free-running delay counter.
  fs::path jittery_scenario() const {
    const fs::path p = path("jittery.json");
    std::ofstream(p) << R"({"name": "jittery", "seed": 11, "line": {"cable_length_m": 60},
      "encoder": {"motion": {"start": 5000, "counts_per_s": 200000}},
      "master": {"f_c": "4 MHz", "t_st": "2 us", "jitter": "7 ns", "delay_compensation": true,
                 "delay_measurement": {"f_c": "200 kHz", "counter_phase": "free_running"}},
      "script": [{"op": "measure_delay"},
                 {"op": "read_position", "command": "encoder_send_position_values_with_additional_data",
                  "count": 20, "cycle": "60 us"},
                 {"op": "read_position", "mode_bits": "000101"},
                 {"op": "read_position", "count": 5, "cycle": "60 us"}],
      "events": [{"at": "900 us", "set_cable": {"cable_length_m": 90}}]})";
    return p;
  }

  fs::path dir_;
};

const std::string kBundled = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/";

TEST_F(Replay, SameScenarioAndSeedGiveByteIdenticalVcdAndJson) {
  for (const std::string& scenario : {kBundled + "endat22_2mhz_100m_compensated.json", jittery_scenario().string()}) {
    ASSERT_LE(cli("run " + scenario + " --quiet --vcd " + path("a.vcd").string() + " --json " + path("a.json").string()), 1);
    ASSERT_LE(cli("run " + scenario + " --quiet --vcd " + path("b.vcd").string() + " --json " + path("b.json").string()), 1);
    const std::string vcd = slurp(path("a.vcd")), json = slurp(path("a.json"));
    endatsim::test_support::expect_clean_vcd(vcd, scenario);
    ASSERT_GT(vcd.size(), 10'000U) << scenario;
    ASSERT_GT(json.size(), 1'000U) << scenario;
    EXPECT_TRUE(vcd == slurp(path("b.vcd"))) << scenario << ": VCD differs between two runs";
    EXPECT_TRUE(json == slurp(path("b.json"))) << scenario << ": JSON differs between two runs";
  }
}

TEST_F(Replay, JsonResultsNameFileAndSeedAndReplayTheRun) {
  const fs::path scenario = jittery_scenario();
  ASSERT_LE(cli("run " + scenario.string() + " --seed 987654321 --quiet --vcd " + path("first.vcd").string() +
                " --json " + path("first.json").string()),
            1);
  const auto results = nlohmann::json::parse(slurp(path("first.json")));
  const auto& recorded = results.at("scenarios").at(0);
  EXPECT_EQ(recorded.at("seed").get<std::uint64_t>(), 987654321U);
  EXPECT_EQ(recorded.at("file").get<std::string>(), scenario.string());
  // Replay from what the report recorded.
  ASSERT_LE(cli("run " + recorded.at("file").get<std::string>() + " --seed " +
                std::to_string(recorded.at("seed").get<std::uint64_t>()) + " --quiet --vcd " +
                path("replay.vcd").string() + " --json " + path("replay.json").string()),
            1);
  EXPECT_TRUE(slurp(path("first.vcd")) == slurp(path("replay.vcd")));
  endatsim::test_support::expect_clean_vcd(slurp(path("replay.vcd")), "replay.vcd");
  EXPECT_TRUE(slurp(path("first.json")) == slurp(path("replay.json")));
  // The seed matters: another one gives another trace, so the comparison above can fail.
  ASSERT_LE(cli("run " + scenario.string() + " --seed 987654322 --quiet --vcd " + path("other.vcd").string()), 1);
  EXPECT_FALSE(slurp(path("first.vcd")) == slurp(path("other.vcd")));
}

TEST_F(Replay, SweepGivesTheSameBytesOnAnyNumberOfThreads) {
  const fs::path scenario = jittery_scenario();
  const std::string grid = " --grid /line/cable_length_m=0:120:30 --grid '/master/jitter=0 ps,7 ns,12 ns'"
                           " --grid /seed=1,2 --quiet";
  std::string csv1, json1;
  for (const unsigned jobs : {1U, 2U, 3U, 8U}) {
    const std::string tag = std::to_string(jobs);
    ASSERT_EQ(cli("sweep " + scenario.string() + grid + " --jobs " + tag + " --csv " + path(tag + ".csv").string() +
                  " --json " + path(tag + ".json").string()),
              0)
        << slurp(path("stderr"));
    const std::string csv = slurp(path(tag + ".csv")), json = slurp(path(tag + ".json"));
    if (jobs == 1) {
      csv1 = csv;
      json1 = json;
      ASSERT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 5 * 3 * 2) << csv;
      continue;
    }
    EXPECT_TRUE(csv == csv1) << "--jobs " << jobs << " changed the CSV";
    EXPECT_TRUE(json == json1) << "--jobs " << jobs << " changed the JSON";
  }
}

}  // namespace
