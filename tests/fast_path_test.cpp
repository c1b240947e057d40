// The frame-level fast path (scenarios/frame_replay.hpp) against the event level: for every
// bundled, field and safety scenario and for three hundred generated ones (mixed versions, clock
// rates, cables, compensation, additional data that stay, roll or carry a time, jitter, moving
// axes, continuous clocks, parameter reads and waits between reads, the power-on sequence, the
// safety functions, events at a time, at a frame and at a clock edge, everything kept or three
// of each), every output is the same byte for
// byte: the transaction log, its JSON lines, the results file, the JUnit XML, the summary and
// the VCD, and the kernel events counted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include <unistd.h>

#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"

#include "scenario_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace scenarios = endatsim::scenarios;
namespace sim = endatsim::sim;

// Every output of one run: the streamed ones, JUnit, the summary and the VCD.
struct Outputs : endatsim::test_support::Streamed {
  std::string junit, summary, vcd;
};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Outputs run_with(const scenarios::Scenario& s, scenarios::Engine engine, const std::string& tag,
                 scenarios::RunOptions options) {
  // A name of its own: ctest runs each test in a process of its own, side by side.
  const fs::path vcd = fs::temp_directory_path() / ("endatsim_fast_path_" + std::to_string(::getpid()) + "_" + tag + ".vcd");
  options.engine = engine;
  options.vcd_path = vcd.string();
  options.vcd_decoded = true;
  Outputs out{endatsim::test_support::run_streamed(s, options), {}, {}, {}};
  std::ostringstream summary;
  scenarios::write_summary(summary, out.result, true);
  out.junit = scenarios::junit_xml({out.result});
  out.summary = summary.str();
  out.vcd = read_file(vcd);
  fs::remove(vcd);
  return out;
}

// Runs `s` both ways with `options` and requires the same outputs; returns the frames the fast
// path played.
std::uint64_t expect_same_outputs(const scenarios::Scenario& s, const std::string& what, scenarios::RunOptions options = {}) {
  const Outputs event = run_with(s, scenarios::Engine::Event, "event", options);
  const Outputs fast = run_with(s, scenarios::Engine::Auto, "auto", options);
  EXPECT_EQ(event.result.frames_replayed, 0U) << what;
  EXPECT_EQ(fast.result.events, event.result.events) << what << ": kernel events";
  EXPECT_EQ(fast.log, event.log) << what << ": transaction log";
  EXPECT_EQ(fast.jsonl, event.jsonl) << what << ": JSON lines";
  EXPECT_EQ(fast.json, event.json) << what << ": results file";
  EXPECT_EQ(fast.junit, event.junit) << what << ": JUnit";
  EXPECT_EQ(fast.summary, event.summary) << what << ": summary";
  EXPECT_TRUE(fast.vcd == event.vcd) << what << ": VCD (" << fast.vcd.size() << " against " << event.vcd.size() << " bytes)";
  return fast.result.frames_replayed;
}

class FastPathScenario : public ::testing::TestWithParam<fs::path> {};

TEST_P(FastPathScenario, GivesTheOutputsOfTheEventLevel) {
  const auto s = scenarios::load_scenario_file(GetParam().string());
  expect_same_outputs(s, GetParam().filename().string());
}

INSTANTIATE_TEST_SUITE_P(Scenarios, FastPathScenario, ::testing::ValuesIn(endatsim::test_support::scenario_files()),
                         [](const auto& param_info) { return endatsim::test_support::scenario_test_name(param_info.param); });

// ---- generated scenarios ----------------------------------------------------------------------

// A scenario drawn at random, as its JSON text (the loader checks it like any file).
class ScenarioDraw {
 public:
  explicit ScenarioDraw(std::uint64_t seed) : rng_(seed) {}

  std::string json(std::uint64_t index) {
    const bool v22 = coin(0.8);
    const unsigned mhz_list[] = {1, 2, 4, 8, 16};
    const unsigned mhz = mhz_list[pick(v22 ? 5 : 4)];
    const bool compensated = mhz >= 4 ? coin(0.8) : coin(0.3);
    const unsigned cable = 1 + static_cast<unsigned>(pick(mhz >= 8 ? 40 : 100));
    const unsigned bits = coin(0.5) ? 25 : 13 + static_cast<unsigned>(pick(20));
    const char* cycles[] = {"50 us", "62.5 us", "100 us", "200 us"};
    std::ostringstream j;
    j << "{ \"name\": \"drawn_" << index << "\", \"seed\": " << pick(1000) << ", \"max_time\": \"30 ms\",\n";
    j << "  \"line\": { \"cable_length_m\": " << cable << " },\n";
    j << "  \"encoder\": { \"version\": \"" << (v22 ? "2.2" : "2.1") << "\", \"position_bits\": " << bits
      << ", \"motion\": { \"start\": " << pick(1u << 12) << ", \"counts_per_s\": " << (coin(0.2) ? 1000 + pick(100000) : 0)
      << " }" << (coin(0.3) ? ", \"t_m_short\": \"2 us\"" : "")
      << ", \"sensors\": { \"temperature_1\": 3000, \"temperature_2\": 3100, \"operating_status_error_sources\": \"0x0000\" } },\n";
    j << "  \"master\": { \"f_c\": \"" << mhz << " MHz\", \"t_st\": \"" << (mhz == 16 ? "1 us" : "2 us") << "\", \"position_bits\": " << bits
      << ", \"delay_compensation\": " << (compensated ? "true" : "false")
      << (coin(0.15) ? ", \"jitter\": \"2 ns\"" : "") << (coin(0.2) ? ", \"safety\": { \"error_messages\": true }" : "")
      << ", \"delay_measurement\": { \"f_c\": \"200 kHz\", \"f_e\": \"128 MHz\", \"count\": 3 } },\n";
    j << "  \"script\": [\n";
    if (coin(0.1)) j << "    { \"op\": \"power_on_sequence\" },\n";
    if (compensated) j << "    { \"op\": \"measure_delay\" },\n";
    std::string command = "encoder_send_position_values";
    if (v22) {
      const double r = uniform();
      if (r < 0.6) {
        command = "encoder_send_position_values_with_additional_data";
        const char* staying[] = {"temperature_1", "temperature_2", "operating_status_error_sources"};
        const char* moving[] = {"timestamp", "additional_sensors", "position_value_2_word_1", "diagnosis"};
        j << "    { \"op\": \"select_additional_data\", \"additional_data\": \""
          << (coin(0.7) ? staying[pick(3)] : moving[pick(4)]) << "\" },\n";
        if (coin(0.5)) j << "    { \"op\": \"select_additional_data\", \"additional_data\": \"" << staying[pick(3)] << "\" },\n";
      } else if (r < 0.8) {
        command = "encoder_send_position_values_with_additional_data";  // none selected: the 2.2 position alone
      }
    }
    const bool continuous = command == "encoder_send_position_values" && coin(0.2);
    j << "    { \"op\": \"read_position\", \"command\": \"" << command << "\", \"count\": " << 8 + pick(40)
      << ", \"cycle\": \"" << (continuous ? "500 us" : cycles[pick(4)]) << "\""
      << (continuous ? ", \"continuous_words\": 2" : "") << " }";
    if (coin(0.2))
      j << ",\n    { \"op\": \"wait\", \"duration\": \"" << 10 + pick(200) << " us\" }";
    if (coin(0.2))
      j << ",\n    { \"op\": \"select_memory_area\", \"mrs\": \"operating_parameters\" },"
        << "\n    { \"op\": \"read_parameter\", \"address\": " << pick(4) << " }";
    if (coin(0.3)) j << ",\n    { \"op\": \"read_position\", \"count\": " << 5 + pick(20) << ", \"cycle\": \"100 us\" }";
    if (coin(0.25)) j << ",\n    " << repeated_frames(v22);
    j << "\n  ]";
    if (coin(0.4)) j << ",\n  \"events\": [ " << event() << " ]";
    j << "\n}\n";
    return j.str();
  }

 private:
  // Frames of a mode command with 8 + 16 bits, over and over (none is played: what the encoder
  // does with the bits is not), with a cycle above or below t_b.
  std::string repeated_frames(bool v22) {
    const char* cycles[] = {"200 us", "2 ms"};
    const char* v21[] = {"encoder_send_parameters", "encoder_send_test_values"};
    const char* v22_commands[] = {"encoder_send_position_values_and_receive_error_reset",
                                  "encoder_send_position_values_and_send_parameter", "encoder_send_parameters"};
    const std::string command = v22 ? v22_commands[pick(3)] : v21[pick(2)];
    std::ostringstream f;
    f << "{ \"op\": \"frame\", \"command\": \"" << command << "\"";
    if (command != "encoder_send_test_values") f << ", \"address\": " << pick(4);  // no 8 + 16 bits
    f << ", \"count\": " << 5 + pick(25) << ", \"cycle\": \"" << cycles[pick(2)] << "\" }";
    return f.str();
  }
  std::string event() {
    std::ostringstream e;
    const unsigned at_us = 200 + static_cast<unsigned>(pick(2000));
    switch (pick(5)) {
      case 0: e << "{ \"at\": \"" << at_us << " us\", \"set_cable\": { \"cable_length_m\": " << 1 + pick(30) << " } }"; break;
      case 1: e << "{ \"at\": \"" << at_us << " us\", \"error_sources\": { \"errors\": \"0x0001\" } }"; break;
      case 2: e << "{ \"frame\": " << 3 + pick(20) << ", \"clock\": " << 10 + pick(20) << ", \"bit_flip\": { \"wire\": \"data\", \"end\": \"master\" } }"; break;
      case 3: e << "{ \"frame\": " << 3 + pick(20) << ", \"slip\": { \"steps\": 5 } }"; break;
      default: e << "{ \"at\": \"" << at_us << " us\", \"slip\": { \"steps\": 7 } }"; break;
    }
    return e.str();
  }
  bool coin(double p) { return uniform() < p; }
  double uniform() { return std::uniform_real_distribution<double>(0, 1)(rng_); }
  std::uint64_t pick(std::uint64_t n) { return std::uniform_int_distribution<std::uint64_t>(0, n - 1)(rng_); }
  std::mt19937_64 rng_;
};

TEST(FastPathDrawn, ThreeHundredDrawnScenariosGiveTheOutputsOfTheEventLevel) {
  constexpr std::uint64_t kScenarios = 300;
  ScenarioDraw draw(20261127);
  std::uint64_t played = 0, playing = 0;
  for (std::uint64_t i = 0; i < kScenarios; ++i) {
    const std::string text = draw.json(i);
    scenarios::Scenario s;
    try {
      s = scenarios::load_scenario_text(text, "drawn_" + std::to_string(i) + ".json");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "the draw made a scenario the loader refuses: " << e.what() << "\n" << text;
      continue;
    }
    // Every third keeps three of each (a long run's outputs, streamed).
    scenarios::RunOptions options;
    if (i % 3 == 0) options.kept = 3;
    const std::uint64_t n = expect_same_outputs(s, "drawn scenario " + std::to_string(i) + ":\n" + text, options);
    played += n;
    playing += n != 0 ? 1 : 0;
    if (::testing::Test::HasFailure()) break;  // one scenario's differences are enough to read
  }
  // The draws exercise the fast path, not only the fall-back to the event level.
  EXPECT_GT(playing, kScenarios / 4);
  EXPECT_GT(played, 1000U);
}

// Frames whose 8 + 16 bits make the encoder do something are run, never played: 2.1 parameter
// reads at a cycle below t_b (the master waits t_b before each), and error resets whose effect on
// word 0 shows when max_time ends the run between two frames.
TEST(FastPathCommands, FramesWithAPayloadOrASupplementGiveTheOutputsOfTheEventLevel) {
  const char* reads = R"({"name": "t_b_reads", "max_time": "200 ms", "line": {"cable_length_m": 2},
    "encoder": {"version": "2.2"}, "master": {"f_c": "1 MHz"},
    "script": [{"op": "select_memory_area", "mrs": "operating_parameters"},
               {"op": "frame", "command": "encoder_send_parameters", "address": 1, "count": 60}]})";
  const char* resets = R"({"name": "error_resets_cut", "max_time": "5.15 ms", "line": {"cable_length_m": 2},
    "encoder": {"version": "2.2", "error_sources": "0x0001"}, "master": {"f_c": "1 MHz"},
    "script": [{"op": "frame", "command": "encoder_send_position_values_and_receive_error_reset", "count": 40,
                "cycle": "200 us"}],
    "expect": {"memory": [{"area": "operating_status", "address": "0x00", "value": "0x0000"}]}})";
  for (const char* text : {reads, resets}) {
    const scenarios::Scenario s = scenarios::load_scenario_text(text, "commands.json");
    EXPECT_EQ(expect_same_outputs(s, s.name), 0U) << s.name;
  }
}

// A moving axis: frames are played while the position stands between two measuring steps, and run
// from the first frame that latches the next one; an axis that steps every frame or two is not
// recorded at all.
TEST(FastPathMotion, AMovingAxisPlaysTheFramesBetweenItsStepsAndGivesTheOutputsOfTheEventLevel) {
  const auto loop = [](int counts_per_s) {
    return R"({"name": "moving_)" + std::to_string(counts_per_s) + R"(", "max_time": "40 ms", "line": {"cable_length_m": 5},
      "encoder": {"version": "2.2", "position_bits": 25, "motion": {"start": 33554400, "counts_per_s": )" +
           std::to_string(counts_per_s) + R"(}},
      "master": {"f_c": "8 MHz", "position_bits": 25},
      "script": [{"op": "read_position", "count": 600, "cycle": "50 us"}]})";
  };
  // 2 000 counts/s: a step every 10 frames, and the position wraps past 2^25 - 1 on the way.
  const scenarios::Scenario slow = scenarios::load_scenario_text(loop(2000), "slow.json");
  const Outputs fast = run_with(slow, scenarios::Engine::Auto, "slow", {});
  ASSERT_FALSE(fast.result.frames.empty());
  EXPECT_EQ(fast.result.frames.front().position, 33554400U);
  EXPECT_LT(fast.result.frames.back().position, 100U);  // about 60 steps on, past 2^25 - 1
  std::set<std::uint64_t> positions;
  for (const auto& f : fast.result.frames) positions.insert(f.position);
  EXPECT_GE(positions.size(), 55U);
  const std::uint64_t played = expect_same_outputs(slow, "slow axis");
  EXPECT_GT(played, 400U);
  EXPECT_LT(played, 540U);  // the first frames after each step run
  // 30 000 counts/s: a step every frame or two.
  const scenarios::Scenario quick = scenarios::load_scenario_text(loop(30000), "quick.json");
  EXPECT_EQ(expect_same_outputs(quick, "quick axis"), 0U);
}

// Events that change nothing (no errors set, a slip of no steps) at the same point of two
// consecutive frames: each recording then holds one event more than its frame runs once the
// events are over, and the two agree with each other. A frame is recorded only while no event acts
// in it, so the frames after them play with the kernel events they run.
TEST(FastPathEvents, EventsThatChangeNothingInConsecutiveFramesKeepTheKernelEventsCounted) {
  const char* text = R"({"name": "no_op_events", "max_time": "1 s", "line": {"cable_length_m": 10},
    "encoder": {"version": "2.2", "position_bits": 25}, "master": {"f_c": "1 MHz", "position_bits": 25},
    "script": [{"op": "read_position", "count": 200, "cycle": "100 us"}],
    "events": [{"at": "5.0501 ms", "error_sources": {"errors": "0x0000"}},
               {"at": "5.1501 ms", "error_sources": {"errors": "0x0000"}},
               {"at": "10.0501 ms", "slip": {"steps": 0}}, {"at": "10.1501 ms", "slip": {"steps": 0}},
               {"at": "15.0001 ms", "slip": {"steps": 0}}, {"at": "15.2001 ms", "slip": {"steps": 0}}]})";
  const scenarios::Scenario s = scenarios::load_scenario_text(text, "no_op_events.json");
  EXPECT_GT(expect_same_outputs(s, s.name), 150U);
}

// A run that a limit ends ends where the event level ends it: a frame is played only when no
// limit can be reached inside it.
TEST(FastPathLimits, ARunEndedByALimitEndsAtTheSameEventWithTheSameOutputs) {
  scenarios::Scenario s = scenarios::load_scenario_file(ENDATSIM_SOURCE_DIR "/bench/scenarios/additional_data_loop_1s.json");
  s.script.back().count = 600;
  s.max_time = sim::ms(40);
  s.expect = {};
  struct Case {
    const char* what;
    scenarios::Limits limits;
  };
  std::vector<Case> cases(4);
  cases[0] = {"kernel events", {}};
  cases[0].limits.kernel_events = 400'000;
  cases[1] = {"records", {}};
  cases[1].limits.records = 700;
  cases[2] = {"max_time", {}};
  cases[2].limits.max_time = sim::us(21'031);
  cases[3] = {"none", {}};
  for (const Case& c : cases) {
    scenarios::RunOptions options;
    options.limits = c.limits;
    const Outputs fast = run_with(s, scenarios::Engine::Auto, "limits", options);
    EXPECT_GT(fast.result.frames_replayed, 100U) << c.what;
    EXPECT_EQ(fast.result.incomplete.empty(), std::string(c.what) == "none") << c.what << ": " << fast.result.incomplete;
    expect_same_outputs(s, std::string("limit ") + c.what, options);
  }
}

}  // namespace
