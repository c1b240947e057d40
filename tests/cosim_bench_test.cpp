// The co-simulation bench as an outside simulator drives it: a loop here owns time, moves the
// bench to each of its instants, drives the master's pins and reads DATA back as the bench
// delivers it, the way the VPI bridge does for an HDL simulator. No master model is involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <sstream>
#include <string>
#include <vector>

#include "endatsim/cosim/bench.hpp"
#include "endatsim/cosim/report.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/scenarios/exit_status.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "test_support.hpp"

namespace {

using namespace endatsim;
using namespace endatsim::sim;
using cosim::MasterPin;

constexpr std::uint8_t k21Position = 0b000111;  // "Encoder send position values" (2.3.1)

// A 2.1 position read at 1 MHz whose master samples DATA at its falling edges: on a 10 m cable
// the round trip (300 ns) is inside half a period. FE1 at `start`.
struct PinChange {
  Time at;
  MasterPin pin;
  bool level;
};

std::vector<PinChange> position_read_21(Time start, unsigned clocks = 11 + 32) {
  std::vector<PinChange> out;
  const Time half = ns(500);
  Time t = start;
  const std::string drive = "-0" + test_support::bits_msb(k21Position, 6);
  for (unsigned n = 1; n <= clocks; ++n) {
    out.push_back({t, MasterPin::Clock, false});
    const char c = n <= drive.size() ? drive[n - 1] : '-';
    if (c == '0' || c == '1') out.push_back({t, MasterPin::DataOut, c == '1'});
    out.push_back({t, MasterPin::DataEnable, c == '0' || c == '1'});
    t += half;
    out.push_back({t, MasterPin::Clock, true});
    t += half;
  }
  return out;
}

struct Outside {
  std::vector<Time> rising;                   // the master's rising edges, at its logic
  std::vector<std::pair<Time, bool>> data_in;  // DATA at its receiver, as delivered
  std::string sampled;                         // DATA at each falling edge
};

// Runs the pin changes, in lockstep with the bench, and reports a position after each frame
// from what this master sampled (F1, 25 position bits LSB first).
Outside drive(cosim::Bench& bench, const std::vector<std::vector<PinChange>>& frames) {
  Outside o;
  bench.on_data_in([&](Time t, bool level) { o.data_in.emplace_back(t, level); });
  for (const auto& frame : frames) {
    std::string bits;
    for (const auto& c : frame) {
      while (bench.next_event_time() && *bench.next_event_time() < c.at) bench.advance_to(*bench.next_event_time());
      bench.advance_to(c.at);
      if (c.pin == MasterPin::Clock && !c.level) bits += bench.data_in() ? '1' : '0';
      if (c.pin == MasterPin::Clock && c.level) o.rising.push_back(c.at);
      bench.drive(c.pin, c.level);
    }
    bench.advance_to(frame.back().at + us(1));
    const auto start = bits.find('1', 10);  // the start bit, after the turnaround
    std::uint64_t position = 0;
    for (unsigned i = 0; i < 25 && start != std::string::npos && start + 2 + i < bits.size(); ++i)
      position |= std::uint64_t{bits[start + 2 + i] == '1'} << i;
    bench.report_position(position);
    o.sampled += bits;
  }
  return o;
}

const char* kBench = R"({
  "name": "bench_1mhz_10m",
  "line": { "cable_length_m": 10 },
  "encoder": { "version": "2.2", "position_bits": 25, "t_cal": "1 us", "motion": { "start": 1000, "counts_per_s": 1000000 } },
  "expect": { "positions_match_encoder": true, "violations": {} }
})";

std::vector<std::vector<PinChange>> three_reads() {
  return {position_read_21(us(20)), position_read_21(us(120)), position_read_21(us(220))};
}

TEST(CosimBench, DataReachesTheOutsideMasterOneRoundTripAfterEachRisingEdgeToThePicosecond) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  const auto o = drive(bench, three_reads());
  // Every change of DATA during an answer follows a rising edge by exactly the line's round trip:
  // master driver 40 + cable 50 + encoder receiver 20, logic 20, driver 20 + cable 50 + master receiver 100 ns.
  ASSERT_FALSE(o.data_in.empty());
  Kernel k;
  const line::Line cable(k, s.line);
  const Time round_trip = cable.round_trip(s.encoder.output_delay);
  EXPECT_EQ(round_trip, ns(300));
  unsigned answer_edges = 0;
  for (const auto& [t, level] : o.data_in) {
    const auto after = std::upper_bound(o.rising.begin(), o.rising.end(), t - round_trip);
    if (after == o.rising.begin() || *(after - 1) != t - round_trip) continue;
    ++answer_edges;
  }
  EXPECT_GE(answer_edges, 3U * 2U);  // at least each start bit's rise and the fall after the CRC
  const auto r = bench.finish();
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.frames_decoded, 3U);
  EXPECT_EQ(r.frames_clean, 3U);
  ASSERT_EQ(r.positions.size(), 3U);
  for (const auto& p : r.positions) EXPECT_TRUE(p.matches()) << p.value << " vs " << p.truth.value_or(0);
  EXPECT_TRUE(r.violations.empty());
}

TEST(CosimBench, AMasterThatReportsAPositionItDidNotReadFailsTheExpectation) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  drive(bench, {position_read_21(us(20))});
  bench.report_position(12345);
  const auto r = bench.finish();
  EXPECT_FALSE(r.passed());
  const auto e = std::find_if(r.expectations.begin(), r.expectations.end(),
                              [](const auto& x) { return x.name == "positions_match_encoder"; });
  ASSERT_NE(e, r.expectations.end());
  EXPECT_FALSE(e->passed);
  EXPECT_NE(e->detail.find("reported 12345"), std::string::npos) << e->detail;
  const auto j = cosim::to_json(r);
  EXPECT_FALSE(j["passed"].get<bool>());
  EXPECT_FALSE(j["positions"][1]["matches"].get<bool>());
  EXPECT_NE(cosim::junit_xml(r).find("<failure type=\"expectation\""), std::string::npos);
}

// Too few clocks: the checker finds it on the wires, with no word from the master.
TEST(CosimBench, AFrameCutShortIsFoundOnTheWires) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  drive(bench, {position_read_21(us(20)), position_read_21(us(120), 30), position_read_21(us(220))});
  const auto r = bench.finish();
  const auto count = std::count_if(r.violations.begin(), r.violations.end(),
                                   [](const checker::Violation& v) { return v.check == checker::check::kClockCount; });
  EXPECT_EQ(count, 1);
  EXPECT_FALSE(r.passed());
}

// Events at a frame need no master model: the bench finds the master's frames on the wires.
TEST(CosimBench, AFrameIndexedBitFlipHitsThatFrameOnly) {
  std::string text = kBench;
  text.replace(text.find("\"expect\""), 0,
               R"("events": [ { "frame": 1, "clock": 20, "bit_flip": { "wire": "data", "end": "master", "width": "1 us" } } ], )");
  const auto s = scenarios::load_scenario_text(text, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  drive(bench, three_reads());
  const auto r = bench.finish();
  // The flip is at the master's connector: the encoder sent every frame cleanly, and this master,
  // which does not check the CRC, misreads frame 1 only.
  ASSERT_EQ(r.frames.size(), 3U);
  EXPECT_EQ(r.frames_clean, 3U);
  ASSERT_EQ(r.positions.size(), 3U);
  EXPECT_TRUE(r.positions[0].matches());
  EXPECT_FALSE(r.positions[1].matches());
  EXPECT_TRUE(r.positions[2].matches());
}

// An event at a frame the master never clocks did nothing: the report names it.
TEST(CosimBench, AnEventAtAFrameTheMasterNeverBeganIsNamed) {
  std::string text = kBench;
  text.replace(text.find("\"expect\""), 0,
               R"("events": [ { "frame": 1, "clock": 20, "bit_flip": { "wire": "data", "end": "master", "width": "1 us" } },
                              { "frame": 7, "bit_flip": { "wire": "data", "end": "master", "width": "1 us" } } ], )");
  const auto s = scenarios::load_scenario_text(text, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  drive(bench, three_reads());
  const auto r = bench.finish();
  const std::vector<scenarios::EventNotActed> want{{1, "bit_flip", "frame 7"}};
  EXPECT_EQ(r.events_not_acted, want);
  std::ostringstream summary;
  cosim::write_summary(summary, r, false);
  EXPECT_NE(summary.str().find("warning: event #1 (bit_flip, frame 7) never acted: the run ended before it"),
            std::string::npos) << summary.str();
  EXPECT_EQ(cosim::to_json(r).at("events_not_acted").size(), 1U);
}

TEST(CosimBench, TheSameBenchAndSeedGiveTheSameReport) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  const auto once = [&] {
    cosim::Bench bench(s);
    drive(bench, three_reads());
    return cosim::to_json(bench.finish()).dump();
  };
  EXPECT_EQ(once(), once());
}

// What a run ended early reports: an "INCOMPLETE" line, JSON and JUnit that say so, the status.
void expect_incomplete_report(const cosim::BenchResult& r, const std::string& reason, int status) {
  EXPECT_FALSE(r.passed());
  EXPECT_NE(r.incomplete.find(reason), std::string::npos) << r.incomplete;
  const auto j = cosim::to_json(r);
  EXPECT_FALSE(j["passed"].get<bool>());
  EXPECT_EQ(j["incomplete"].get<std::string>(), r.incomplete);
  EXPECT_NE(cosim::junit_xml(r).find("<error type=\"incomplete\""), std::string::npos);
  std::ostringstream out, err;
  EXPECT_EQ(cosim::report(r, {}, false, out, err), status);
  EXPECT_NE(out.str().find("INCOMPLETE: " + r.incomplete), std::string::npos) << out.str();
}

TEST(CosimBenchLimits, KernelEventsEndTheRunAndTheBenchStandsStill) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::BenchOptions options;
  options.limits.kernel_events = 200;  // one frame takes about a thousand
  cosim::Bench bench(s, options);
  EXPECT_FALSE(bench.should_stop());
  drive(bench, three_reads());
  EXPECT_TRUE(bench.should_stop());
  const Time stopped_at = bench.now();
  EXPECT_LT(stopped_at, us(120));
  bench.advance_to(us(400));
  bench.drive(MasterPin::Clock, false);
  EXPECT_EQ(bench.now(), stopped_at);
  const auto r = bench.finish();
  EXPECT_GE(r.events, 200U);
  EXPECT_LT(r.events, 200U + 4096U);
  expect_incomplete_report(r, "limit kernel_events reached", 3);
  EXPECT_NE(r.incomplete.find("--max-kernel-events or limits.kernel_events"), std::string::npos) << r.incomplete;
  EXPECT_EQ(r.interrupted, 0);
}

TEST(CosimBenchLimits, RecordsBoundWhatAMasterReports) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::BenchOptions options;
  options.limits.records = 50;
  cosim::Bench bench(s, options);
  drive(bench, {position_read_21(us(20))});
  for (int i = 0; i < 1000 && !bench.should_stop(); ++i) bench.report_position(1);
  const auto r = bench.finish();
  EXPECT_LE(r.positions.size(), 50U);
  expect_incomplete_report(r, "limit records reached: 50 ", 3);
}

TEST(CosimBenchLimits, MaxTimeCapsTheBenchsOwnAndABenchAskingForMoreIsRefused) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::BenchOptions options;
  options.limits.max_time = us(100);
  cosim::Bench bench(s, options);
  EXPECT_EQ(bench.max_time(), us(100));
  bench.advance_to(us(99));
  EXPECT_FALSE(bench.should_stop());
  bench.advance_to(us(100));
  EXPECT_TRUE(bench.should_stop());
  const auto r = bench.finish();
  // A limit reached, as `endatsim run --max-time` says: incomplete (exit 3), not the bench's own
  // max_time's failure "ended before max_time".
  EXPECT_EQ(r.incomplete, "limit max_time reached: 100 us simulated, less than the bench's 1 s (--max-time changes it); "
                          "the run ended at 100 us");
  EXPECT_FALSE(r.passed());
  for (const auto& e : r.expectations) EXPECT_NE(e.name, "ended before max_time");
  std::ostringstream out, err;
  EXPECT_EQ(cosim::report(r, {}, false, out, err), scenarios::exit_status::kIncomplete);
  // The bench's own max_time reached: the failure, complete.
  cosim::Bench whole(s);
  whole.advance_to(whole.max_time());
  const auto own = whole.finish();
  EXPECT_TRUE(own.incomplete.empty());
  const auto ended = std::find_if(own.expectations.begin(), own.expectations.end(),
                                  [](const auto& e) { return e.name == "ended before max_time"; });
  ASSERT_NE(ended, own.expectations.end());
  EXPECT_FALSE(ended->passed);
  cosim::BenchOptions few_events;
  few_events.limits.kernel_events = 10;
  std::string text = kBench;
  text.replace(text.find("\"expect\""), 0, R"("limits": {"kernel_events": 11}, )");
  const auto asks_more = scenarios::load_scenario_text(text, "bench.json", scenarios::ScenarioKind::Bench);
  EXPECT_THROW(cosim::Bench(asks_more, few_events), scenarios::ScenarioError);
}

TEST(CosimBenchLimits, SigintEndsTheRunMarkedInterrupted) {
  const auto s = scenarios::load_scenario_text(kBench, "bench.json", scenarios::ScenarioKind::Bench);
  cosim::Bench bench(s);
  drive(bench, {position_read_21(us(20))});
  EXPECT_FALSE(bench.should_stop());
  scenarios::request_interrupt(SIGINT);
  EXPECT_TRUE(bench.should_stop());
  scenarios::request_interrupt(0);
  const Time stopped_at = bench.now();
  bench.advance_to(us(300));
  EXPECT_EQ(bench.now(), stopped_at);
  const auto r = bench.finish();
  EXPECT_EQ(r.interrupted, SIGINT);
  expect_incomplete_report(r, "interrupted by SIGINT", 128 + SIGINT);
  EXPECT_EQ(cosim::to_json(r)["interrupted"], "SIGINT");
}

void expect_bench_error(const std::string& text, const std::string& fragment) {
  try {
    scenarios::load_scenario_text(text, "bench.json", scenarios::ScenarioKind::Bench);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const scenarios::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CosimBenchLoader, RefusesWhatNeedsTheProjectsMasterModelNamingThePlace) {
  expect_bench_error(R"({"name": "b", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"}})", "bench.json: at /master: a co-simulation bench has no \"master\"");
  expect_bench_error(R"({"name": "b", "line": {"cable_length_m": 1}, "script": []})", "at /script:");
  expect_bench_error(R"({"name": "b", "line": {"cable_length_m": 1}, "expect": {"outcomes": {"ok": 3}}})",
                     "at /expect/outcomes: \"outcomes\" needs the project's master model");
  expect_bench_error(R"({"name": "b", "line": {"cable_length_m": 1}, "events": [{"at": "1 us", "random_bit_errors": {"end": "master", "rate": 0.1}}]})",
                     "at /events/0/random_bit_errors:");
  expect_bench_error(R"({"name": "b", "line": {"cable_length_m": 1}, "events": [{"at": "1 us", "bit_flip": {"wire": "data", "end": "master"}}]})",
                     "at /events/0/bit_flip: a bench's bit_flip needs a \"width\"");
  // A run scenario still needs its master.
  EXPECT_THROW(scenarios::load_scenario_text(R"({"name": "b", "line": {"cable_length_m": 1}})", "run.json"), scenarios::ScenarioError);
}

}  // namespace
