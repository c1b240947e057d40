// Scenario events: faults of the line and the encoder at a time, at a frame or at a
// clock edge of a frame, as a field engineer scripts them; each shows on the wire the way the
// real fault would.
#include <gtest/gtest.h>

#include <sstream>

#include "scenario_support.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using K = scenarios::Event::Kind;
using line::ObservationPoint;
using MC = protocol::ModeCommand;
using test_support::count_violations;

namespace {

scenarios::Event at(Time t, K kind) {
  scenarios::Event e;
  e.kind = kind;
  e.at = t;
  return e;
}

scenarios::Event at_frame(std::uint64_t frame, unsigned clock, K kind) {
  scenarios::Event e;
  e.kind = kind;
  e.frame = frame;
  e.clock = clock;
  return e;
}

// Ten reads of "Encoder send position values with additional data", 100 us apart, 1 MHz, 10 m.
scenarios::Scenario reads(unsigned n = 10) { return test_support::make_scenario(10, MHz(1), false, n); }

std::vector<master::FrameOutcome> outcomes(const scenarios::ScenarioResult& r) {
  std::vector<master::FrameOutcome> v;
  for (const auto& f : r.frames)
    if (!f.measurement) v.push_back(f.outcome);
  return v;
}

}  // namespace

TEST(FaultBitFlip, DataFlippedAtTheMasterInOneFrameIsOneCrcError) {
  // Frame 3, the 20th rising edge at the master's pins: a position bit of the answer.
  auto s = reads();
  auto e = at_frame(3, 20, K::BitFlip);
  e.wire = line::Wire::Data;
  e.end = ObservationPoint::MasterPins;
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  const auto o = outcomes(r);
  for (std::size_t i = 0; i < o.size(); ++i)
    EXPECT_EQ(o[i], i == 3 ? master::FrameOutcome::CrcError : master::FrameOutcome::Ok) << "frame " << i;
  EXPECT_EQ(r.encoder_frames[3].position, r.encoder_frames[2].position) << "the encoder sent the right value";
}

TEST(FaultBitFlip, AFlippedModeBitAtTheEncoderIsATypeIError) {
  // Half a period after RE3 at the encoder's pins, for one period: a mode bit (2.3).
  auto s = reads(3);
  auto e = at_frame(1, 3, K::BitFlip);
  e.offset = ns(500);
  e.wire = line::Wire::Data;
  e.end = ObservationPoint::EncoderPins;
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(outcomes(r), (std::vector{master::FrameOutcome::Ok, master::FrameOutcome::Type1Error,
                                      master::FrameOutcome::Ok}));
  ASSERT_GE(r.encoder_frames.size(), 2U);
  EXPECT_TRUE(r.encoder_frames[1].type1_error);
}

TEST(FaultGlitch, AClockGlitchAtTheEncoderShiftsItsBitsAndTheCrcCatchesIt) {
  auto s = reads(3);
  auto e = at_frame(1, 15, K::Glitch);
  e.wire = line::Wire::Clock;
  e.end = ObservationPoint::EncoderPins;
  e.width = ns(50);
  e.offset = ns(200);  // inside the HIGH half of the 1 MHz clock: one extra pulse
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  const auto o = outcomes(r);
  ASSERT_EQ(o.size(), 3U);
  EXPECT_EQ(o[0], master::FrameOutcome::Ok);
  EXPECT_NE(o[1], master::FrameOutcome::Ok);
  EXPECT_EQ(o[2], master::FrameOutcome::Ok);
}

TEST(FaultRandomBitErrors, SeededErrorsAreReproducibleAndCaughtByTheCrc) {
  auto s = reads(200);
  auto e = at(Time::zero(), K::RandomBitErrors);
  e.end = ObservationPoint::MasterPins;
  e.rate = 0.01;
  s.events.push_back(e);
  const auto a = scenarios::run_scenario(s);
  const auto b = scenarios::run_scenario(s);
  std::size_t errors = 0;
  for (auto o : outcomes(a)) errors += o != master::FrameOutcome::Ok;
  EXPECT_GT(errors, 10U) << "about 40 % of frames at 1 % per bit";
  EXPECT_LT(errors, 150U);
  EXPECT_EQ(outcomes(a), outcomes(b)) << "same seed, same errors";
  EXPECT_TRUE(scenarios::compare_positions_with_encoder(s, a).match) << "no bad position passes as good";
  scenarios::RunOptions other;
  other.seed = 2;
  EXPECT_NE(outcomes(scenarios::run_scenario(s, other)), outcomes(a));
}

TEST(FaultRandomBitErrors, TheyStopAfterTheirDuration) {
  auto s = reads(40);
  auto e = at(Time::zero(), K::RandomBitErrors);
  e.end = ObservationPoint::EncoderPins;
  e.rate = 1.0;
  e.duration = us(1000);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  std::size_t late_errors = 0;
  for (const auto& f : r.frames) late_errors += f.start > us(1100) && f.outcome != master::FrameOutcome::Ok;
  EXPECT_EQ(late_errors, 0U);
  EXPECT_NE(r.frames.front().outcome, master::FrameOutcome::Ok);
}

TEST(FaultStuck, ClockStuckHighAtTheEncoderSpoilsTheFrameUntilReleased) {
  // The encoder never sees the frame begin: it keeps driving its idle LOW against the master's
  // mode bits, and the master polls for the start bit until the clock comes through again.
  auto s = reads(6);
  auto e = at(us(250), K::Stuck);
  e.wire = line::Wire::Clock;
  e.end = ObservationPoint::EncoderPins;
  e.level = true;
  e.duration = us(300);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 6U);
  for (const auto& f : r.frames) {
    const bool hit = f.start > us(250) && f.start < us(550);
    EXPECT_EQ(f.outcome != master::FrameOutcome::Ok, hit) << "frame at " << format_time(f.start);
  }
  EXPECT_GE(count_violations(r, checker::check::kContention), 1U);
  EXPECT_GE(count_violations(r, checker::check::kPulseHigh), 1U) << "30 us without an edge at the encoder";
}

TEST(FaultLateDriverRelease, TheMastersLateReleaseCollidesWithTheEncoder) {
  auto s = reads(3);
  auto e = at(Time::zero(), K::LateDriverRelease);
  e.end = ObservationPoint::MasterPins;
  e.width = us(3);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  EXPECT_GE(count_violations(r, checker::check::kContention), 3U);
}

TEST(FaultEncoder, AnErrorSourceSetsF1FromTheNextFrame) {
  auto s = reads(4);
  auto e = at(us(150), K::ErrorSources);
  e.errors = 0x0002;  // 3.4.1: signal amplitude
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 4U);
  EXPECT_FALSE(r.frames[1].error1);
  EXPECT_TRUE(r.frames[2].error1);
  EXPECT_FALSE(r.frames[2].error2) << "F2 is low-active";
}

TEST(FaultEncoder, TCalBeyondTheStartBitTimeoutLeavesTheMasterWithoutStartBit) {
  auto s = reads(3);
  auto e = at(us(150), K::TCal);
  e.t_cal = ms(2);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 3U);
  for (const auto& f : r.frames)
    EXPECT_EQ(f.outcome, f.start < us(150) ? master::FrameOutcome::Ok : master::FrameOutcome::NoStartBit)
        << "frame at " << format_time(f.start);
}

TEST(FaultEncoder, ABusyLongerThanTheMastersPollingIsABusyTimeout) {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.script.clear();
  master::Operation poll;
  poll.kind = master::Operation::Kind::AwaitNotBusy;
  poll.count = 50;
  poll.cycle = us(100);
  s.script = {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
              op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA9), poll};
  auto e = at(Time::zero(), K::MemoryAccessTime);
  e.t_ac_read = ms(20);
  e.t_ac_write = ms(20);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(r.busy_timeouts, 1U) << "50 polls x 100 us < 20 ms";
}

// ---- power interruption ----------------------------------------------------------------------

TEST(FaultPowerInterruption, FramesDuringItFailThenTheEncoderIsBack) {
  // Unpowered, the encoder's driver is off: the fail-safe HIGH on DATA never shows the LOW a
  // careful master waits for, so the master takes it for a type I error handling.
  auto s = reads(20);
  s.encoder.startup_time = us(300);
  auto e = at(us(520), K::PowerInterruption);
  e.duration = us(500);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  const auto o = outcomes(r);
  ASSERT_EQ(o.size(), 20U);
  std::size_t silent = 0;
  for (const auto& f : r.frames) {
    // Running up after switching on (300 us), or overlapping the interruption and the run-up.
    const bool off = f.start < us(300) || (f.start + us(70) > us(520) && f.start < us(1320));
    EXPECT_EQ(f.outcome != master::FrameOutcome::Ok, off) << "frame at " << format_time(f.start);
    silent += off;
  }
  EXPECT_GE(silent, 7U);
}

namespace {

// 2.2 write of BEEFh into OEM area 1 address 10h while t_ac_write = 3 ms; the supply fails at
// `cut` and is back after 1 ms; then a 2.1 read of the word.
scenarios::Scenario interrupted_write(Time cut, slave::InterruptedNvmWrite policy, std::uint8_t address = 0x10,
                                      std::uint8_t mrs = 0xA9, std::uint16_t value = 0xBEEF) {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.encoder.t_ac_read = us(100);
  s.encoder.t_ac_write = ms(3);
  s.encoder.interrupted_nvm_write = policy;
  master::Operation wait;
  wait.kind = master::Operation::Kind::Wait;
  wait.duration = ms(6);
  s.script = {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, mrs),
              wait,
              op(MC::EncoderSendPositionValuesAndReceiveParameter, address, value),
              wait,
              op(MC::SelectionOfMemoryArea, mrs),
              op(MC::EncoderSendParameters, address)};
  auto e = at(cut, K::PowerInterruption);
  e.duration = ms(1);
  s.events.push_back(e);
  return s;
}

std::uint16_t word_read_back(const scenarios::ScenarioResult& r) {
  EXPECT_TRUE(r.finished);
  EXPECT_EQ(r.frames.back().outcome, master::FrameOutcome::Ok);
  return r.frames.back().echo_parameter;
}

}  // namespace

TEST(FaultPowerInterruption, AWriteCutShortKeepsTheOldWord) {
  // The write frame starts at about 6.1 ms; its t_ac ends about 3 ms later.
  const auto r = scenarios::run_scenario(interrupted_write(ms(7), slave::InterruptedNvmWrite::KeepOld));
  EXPECT_EQ(word_read_back(r), 0x0000);
}

TEST(FaultPowerInterruption, AWriteCutShortIsTornWhenTheNvmProgramsByteByByte) {
  const auto r = scenarios::run_scenario(interrupted_write(ms(7), slave::InterruptedNvmWrite::Torn));
  EXPECT_EQ(word_read_back(r), 0xBE00);
}

TEST(FaultPowerInterruption, AWriteWhoseAccessTimeHadRunOutSurvives) {
  const auto r = scenarios::run_scenario(interrupted_write(ms(10), slave::InterruptedNvmWrite::Torn));
  EXPECT_EQ(word_read_back(r), 0xBEEF);
}

TEST(FaultPowerInterruption, ATornWriteOfWord2NeverClearsAWriteProtection) {
  // Word 2 holds 0039h (manufacturer and compensation areas protected, 3.4.3); a write of
  // 003Dh (OEM protection added) torn by a power cut stores 0039h | 0000h: nothing is lost.
  const auto r = scenarios::run_scenario(interrupted_write(ms(7), slave::InterruptedNvmWrite::Torn, 0x02, 0xB9, 0x003D));
  EXPECT_EQ(word_read_back(r), 0x0039);
  const auto done = scenarios::run_scenario(interrupted_write(ms(10), slave::InterruptedNvmWrite::Torn, 0x02, 0xB9, 0x003D));
  EXPECT_EQ(word_read_back(done), 0x003D);
}

TEST(FaultCorruptWord, ACorruptedChecksumReadsBackChanged) {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.script = {op(MC::SelectionOfMemoryArea, 0xA5), op(MC::EncoderSendParameters, 0x0F)};  // word 47
  const std::uint16_t good = scenarios::run_scenario(s).frames.back().echo_parameter;
  auto e = at(Time::zero(), K::CorruptWord);
  e.selection.area = protocol::MemoryArea::Manufacturer3;
  e.address = 0x0F;
  e.xor_mask = 0x0100;
  s.events.push_back(e);
  EXPECT_EQ(scenarios::run_scenario(s).frames.back().echo_parameter, good ^ 0x0100);
}

TEST(FaultEvents, ASetCableEventAtAFrameChangesTheLineThere) {
  auto s = test_support::make_scenario(10, MHz(1), false, 3);
  auto e = scenarios::cable_change(Time::zero(), 120, ns(5));
  e.at.reset();
  e.frame = 1;
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 3U);
  EXPECT_EQ(r.true_round_trip, ns(200) + ns(10) * 120) << "the line at the end of the run";
  EXPECT_EQ(r.frames[0].outcome, master::FrameOutcome::Ok);
  EXPECT_GE(count_violations(r, checker::check::kSamplingWindow), 1U) << "1 MHz over 120 m uncompensated";
}

TEST(FaultLossOfFailsafe, AnUnpoweredEncoderThenLooksLikeNoStartBitInsteadOfTypeI) {
  // With the bias the undriven line reads HIGH (the master reports an error handling); without
  // it, LOW: the master polls in vain for the start bit.
  const auto outcome_during_power_cut = [](bool lose_failsafe) {
    auto s = reads(6);
    auto cut = at(us(150), K::PowerInterruption);
    cut.duration = ms(3);  // longer than the master's start-bit polling (1 ms)
    s.events.push_back(cut);
    if (lose_failsafe) {
      auto e = at(us(100), K::LossOfFailsafe);
      e.level = false;
      s.events.insert(s.events.begin(), e);
    }
    return outcomes(scenarios::run_scenario(s)).at(2);
  };
  EXPECT_EQ(outcome_during_power_cut(false), master::FrameOutcome::Type1Error);
  EXPECT_EQ(outcome_during_power_cut(true), master::FrameOutcome::NoStartBit);
}

TEST(FaultEvents, AProbeTriggerShowsInTheTriggerStatusAndTheTimestamp) {
  auto s = test_support::make_scenario(5, MHz(1), false, 4);
  s.encoder.kind = slave::EncoderKind::TouchProbe;
  s.encoder.position_bits = 16;
  s.master.position_bits = 16;
  s.encoder.motion.start = 0;
  s.script.back().command = MC::EncoderSendPositionValues;
  auto e = at(us(150), K::ProbeTrigger);
  e.duration = us(100);
  s.events.push_back(e);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 4U);
  EXPECT_EQ(r.frames[1].position, 0U);
  EXPECT_EQ(r.frames[2].position, 1U) << "deflected from 150 to 250 us";
  EXPECT_EQ(r.frames[3].position, 0U);
}

TEST(FaultEvents, AProbeTriggerNeedsATouchProbe) {
  const std::string text = R"({"name": "x", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"},
    "script": [{"op": "read_position"}],
    "events": [{"at": "1 ms", "probe_trigger": {"duration": "1 ms"}}]})";
  try {
    scenarios::load_scenario_text(text, "probe.json");
    FAIL() << "accepted";
  } catch (const scenarios::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("probe.json: at /events/0: probe_trigger needs an encoder of kind"),
              std::string::npos)
        << e.what();
  }
}

// An event the run ends before (a frame past the last, a time after it, a clock edge the frame
// never reaches) is named in the summary and the results file, never dropped without a word.
TEST(FaultEvents, AnEventTheRunEndsBeforeIsNamedInTheSummaryAndTheJson) {
  auto s = reads(10);
  s.events.push_back(at_frame(2, 0, K::Slip));  // acts
  s.events.push_back(at_frame(500, 0, K::Slip));
  s.events.push_back(at_frame(9, 200, K::Slip));  // a frame of 10 clocks has no 200th
  s.events.push_back(at(sim::ms(499), K::Slip));  // its offset puts it after max_time
  s.events.push_back(at(sim::ms(499), K::Slip));  // and this one at max_time itself, where it acts
  s.max_time = sim::ms(500);
  for (auto& e : s.events) e.steps = 1;
  s.events[3].offset = sim::ms(1) + sim::ps(1);
  s.events[4].offset = sim::ms(1);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(r.simulated, sim::ms(500));
  const std::vector<scenarios::EventNotActed> want{
      {1, "slip", "frame 500"}, {2, "slip", "frame 9, clock 200"}, {3, "slip", "at 499 ms + 1.000000001 ms"}};
  EXPECT_EQ(r.events_not_acted, want);
  std::ostringstream summary;
  scenarios::write_summary(summary, r, false);
  EXPECT_NE(summary.str().find("  warning: event #1 (slip, frame 500) never acted: the run ended before it\n"),
            std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find("  warning: event #3 (slip, at 499 ms + 1.000000001 ms) never acted"), std::string::npos)
      << summary.str();
  EXPECT_EQ(summary.str().find("event #0"), std::string::npos) << summary.str();
  const auto j = scenarios::to_json(r);
  ASSERT_EQ(j.at("events_not_acted").size(), 3U);
  EXPECT_EQ(j["events_not_acted"][2]["when"], "at 499 ms + 1.000000001 ms");
  // Every event acted: no key, no line.
  s.events.resize(1);
  const auto all = scenarios::run_scenario(s);
  EXPECT_TRUE(all.events_not_acted.empty());
  EXPECT_FALSE(scenarios::to_json(all).contains("events_not_acted"));
}
