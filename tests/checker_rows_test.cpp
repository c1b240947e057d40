// Rows of table 2.3.2 judged at their limits: t_b, the delay measurement's
// clock and counter (2.1.2), t_HI maximum, the recovery time t_m + t_R, the wait after an error,
// f_c (also for the cable) and the pulse widths, each just inside (no violation) and just outside
// (a violation) by one picosecond, one count or one hertz, whichever is the quantity's step.
// The clock's phases are set to the picosecond with a hand-driven clock (HandClock below).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "scenario_support.hpp"
#include "endatsim/scenarios/loader.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using MC = protocol::ModeCommand;
using test_support::count_violations;
using test_support::make_scenario;

namespace {

std::size_t count(const scenarios::ScenarioResult& r, std::string_view check) { return count_violations(r, check); }

}  // namespace

TEST(CheckerTimeBetweenCycles, OneMillisecondIsTooShortOnePicosecondMoreIsEnough) {
  // 2.3.2 "t_b > 1 ms" between EnDat 2.1 memory frames; the master starts the next one
  // t_b_wait after the previous frame's last rising edge, the same gap at the encoder's pins.
  auto s = make_scenario(5, MHz(1), false, 1);
  s.encoder.t_ac_read = us(100);
  s.script = {op(MC::SelectionOfMemoryArea, 0xA1), op(MC::EncoderSendParameters, 0x0D)};
  s.master.t_b_wait = ms(1);
  const auto at_limit = scenarios::run_scenario(s);
  ASSERT_EQ(count(at_limit, checker::check::kTimeBetweenCycles), 1U);
  const auto& v = *std::find_if(at_limit.violations.begin(), at_limit.violations.end(),
                                [](const auto& x) { return x.check == checker::check::kTimeBetweenCycles; });
  EXPECT_EQ(v.measured, "1 ms");
  EXPECT_NE(v.message.find("other readings"), std::string::npos) << "the uncertain row names its alternatives";
  s.master.t_b_wait = ms(1) + ps(1);
  EXPECT_EQ(count(scenarios::run_scenario(s), checker::check::kTimeBetweenCycles), 0U);
}

TEST(CheckerTimeBetweenCycles, PositionReadsAndEnDat22FramesAreNotConcerned) {
  auto s = make_scenario(5, MHz(1), false, 5);
  s.script.back().command = MC::EncoderSendPositionValues;  // 2.1, every 100 us
  EXPECT_EQ(count(scenarios::run_scenario(s), checker::check::kTimeBetweenCycles), 0U);
  auto s22 = make_scenario(5, MHz(1), false, 1);
  s22.master.t_b_wait = Time::zero();
  s22.script = {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
                op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA1)};
  EXPECT_EQ(count(scenarios::run_scenario(s22), checker::check::kTimeBetweenCycles), 0U);
}

TEST(CheckerBoundaries, MeasurementClockAt100And200KilohertzByOneHertz) {
  // 2.1.2: the delay is measured at 100 .. 200 kHz.
  const auto violations = [](Hertz measurement_f_c) {
    auto s = make_scenario(10, MHz(2), true, 1);
    s.checker.f_c_tolerance_ppm = 0;
    s.master.measurement.f_c = measurement_f_c;
    return count(scenarios::run_scenario(s), checker::check::kMeasurementClock);
  };
  EXPECT_EQ(violations(kHz(100)), 0U);
  EXPECT_EQ(violations(kHz(200)), 0U);
  EXPECT_EQ(violations(kHz(100) - 1), 3U);
  EXPECT_EQ(violations(kHz(200) + 1), 3U);
}

TEST(CheckerBoundaries, CounterClockAtEightTimesFcLessTenPercentByOneHertz) {
  // 2.1.2: f_e at least eight times f_c, within +/-10 %: 7.2 x 2 MHz = 14.4 MHz.
  const auto violations = [](Hertz f_e) {
    auto s = make_scenario(10, MHz(2), true, 1);
    s.master.measurement.f_e = f_e;
    return count(scenarios::run_scenario(s), checker::check::kMeasurementProcedure);
  };
  EXPECT_EQ(violations(Hertz{14'400'000}), 0U);
  EXPECT_EQ(violations(Hertz{14'399'999}), 1U);
}

TEST(CheckerBoundaries, HighPhaseOfTenMicrosecondsAtTheClocksResolution) {
  // 2.3.2 t_HI maximum 10 us. The clock generator's step is one hertz: 50 kHz gives a HIGH phase
  // of exactly 10 us, 49 999 Hz one 0.2 ns longer (the nearest settable value above the limit).
  const auto violations = [](Hertz measurement_f_c) {
    auto s = make_scenario(1, MHz(1), true, 1);
    s.master.measurement.f_c = measurement_f_c;
    s.master.measurement.count = 3;
    return count(scenarios::run_scenario(s), checker::check::kPulseHigh);
  };
  EXPECT_EQ(violations(kHz(50)), 0U);
  EXPECT_EQ(violations(Hertz{49'999}), 3U);
}

TEST(CheckerBoundaries, MemoryAccessTimeOfTwelveMillisecondsByOneClockPeriod) {
  // 2.3.2 t_ac maximum 12 ms: the acknowledgment's start bit rides on a clock edge, so the
  // measured time moves in whole periods (1 us here) and the checker allows 12 ms + T; an access
  // one period longer is caught.
  const auto violations = [](Time t_ac) {
    auto s = make_scenario(5, MHz(1), false, 1);
    s.encoder.t_ac_read = us(100);
    s.script = {op(MC::SelectionOfMemoryArea, 0xA9), op(MC::EncoderReceiveParameters, 0x01, 0x1234)};
    scenarios::Event slow;
    slow.kind = scenarios::Event::Kind::MemoryAccessTime;
    slow.at = Time::zero();
    slow.t_ac_read = us(100);
    slow.t_ac_write = t_ac;
    s.events.push_back(slow);
    const auto r = scenarios::run_scenario(s);
    EXPECT_EQ(r.frames.back().outcome, master::FrameOutcome::Ok);
    return count(r, checker::check::kMemoryAccess);
  };
  EXPECT_EQ(violations(ms(12) + us(1)), 0U);
  EXPECT_EQ(violations(ms(12) + us(2)), 1U);
}

TEST(CheckerBoundaries, OnOffRatioWithCompensationByOnePermille) {
  // 2.3.2 on-off ratio error +/-10 % with delay compensation: HIGH 40 .. 60 % of the period.
  const auto violations = [](unsigned high_permille) {
    auto s = make_scenario(10, MHz(4), true, 2);
    s.master.high_permille = high_permille;
    const auto r = scenarios::run_scenario(s);
    // With compensation the 0.2 us minimum of t_HI and t_LO does not apply: the ratio's row says it.
    EXPECT_EQ(count(r, checker::check::kPulseHigh) + count(r, checker::check::kPulseLow), 0U) << high_permille;
    return count(r, checker::check::kOnOffRatio);
  };
  EXPECT_EQ(violations(400), 0U);
  EXPECT_EQ(violations(600), 0U);
  EXPECT_EQ(violations(399), 2U);  // one per frame, its worst phase
  EXPECT_EQ(violations(601), 2U);
}

TEST(CheckerBoundaries, ShortRecoveryTimeNeedsOneMegahertzByOneHertz) {
  auto s = make_scenario(1, MHz(1), false, 1);
  s.encoder.t_m_short = us(2);
  s.encoder.short_t_m_selected = true;
  s.checker.f_c_tolerance_ppm = 0;
  EXPECT_EQ(count(scenarios::run_scenario(s), checker::check::kShortRecoveryClock), 0U);
  s.master.f_c = MHz(1) - 1;
  EXPECT_EQ(count(scenarios::run_scenario(s), checker::check::kShortRecoveryClock), 1U);
}

TEST(CheckerBoundaries, EnDat22BusyLongerThanTwelveMilliseconds) {
  // 2.3.2 t_ac maximum 12 ms, seen through the busy bit of additional data 1 (2.6.1): polls every
  // 100 us after a 2.2 write; an access of 12 ms ends in time, one of 12.5 ms does not.
  const auto violations = [](Time t_ac) {
    auto s = make_scenario(5, MHz(1), false, 1);
    master::Operation poll;
    poll.kind = master::Operation::Kind::AwaitNotBusy;
    poll.count = 200;
    poll.cycle = us(100);
    s.script = {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
                op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA9), poll,
                op(MC::EncoderSendPositionValuesAndReceiveParameter, 0x01, 0x1234), poll};
    scenarios::Event slow;
    slow.kind = scenarios::Event::Kind::MemoryAccessTime;
    slow.at = Time::zero();
    slow.t_ac_read = us(200);
    slow.t_ac_write = t_ac;
    s.events.push_back(slow);
    const auto r = scenarios::run_scenario(s);
    EXPECT_EQ(r.busy_timeouts, 0U);
    return count(r, checker::check::kMemoryAccess);
  };
  EXPECT_EQ(violations(ms(12)), 0U);
  EXPECT_EQ(violations(us(12'500)), 1U);
}

// ---- a clock driven by hand, to the picosecond ---------------------------------------------

namespace {

// CLOCK at the master logic edge by edge, for one frame announced to the checker as the master
// announces its frames: phases to the picosecond, which the master's clock generator (a period
// from whole hertz, a duty cycle in permille) cannot set.
class HandClock {
 public:
  HandClock(Kernel& k, line::Line& line) : k_(k), clock_(line.master().clock_out) {}
  // FE1 at `start`, then LOW and HIGH phases alternately (the last one HIGH).
  void frame(Time start, const std::vector<Time>& phases) {
    Time t = start;
    std::uint64_t level = 0;
    k_.schedule_at(t, bind<&HandClock::set>(this, level));
    for (Time phase : phases) {
      t += phase;
      level ^= 1U;
      k_.schedule_at(t, bind<&HandClock::set>(this, level));
    }
  }

 private:
  void set(std::uint64_t level) { clock_.write(level != 0); }
  Kernel& k_;
  Signal& clock_;
};

std::size_t hand_clocked(const checker::DeclaredFrame& frame, const std::vector<Time>& phases, std::string_view check,
                         double cable_m = 0) {
  Kernel k;
  line::LineParams line_params;
  line_params.cable_length_m = cable_m;
  line::Line line(k, line_params);
  checker::CheckerParams params;
  params.f_c_tolerance_ppm = 0;
  checker::TimingChecker checker(k, line, checker::EncoderDeclaration{}, checker::MasterDeclaration{}, params);
  HandClock clock(k, line);
  checker.on_frame_start(frame);
  clock.frame(us(1), phases);
  k.run();
  checker.finish();
  const auto& v = checker.violations();
  return static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [&](const auto& x) { return x.check == check; }));
}

// `n` clock pulses of `low` and `high`; pulse `odd` gets a HIGH phase of `odd_high`.
std::vector<Time> pulses(unsigned n, Time low, Time high, unsigned odd = 0, Time odd_high = {}) {
  std::vector<Time> phases;
  for (unsigned k = 1; k <= n; ++k) {
    phases.push_back(low);
    phases.push_back(k == odd ? odd_high : high);
  }
  return phases;
}

checker::DeclaredFrame frame_at(Hertz f_c, bool measurement, bool compensated = false) {
  checker::DeclaredFrame f;
  f.f_c = f_c;
  f.measurement = measurement;
  f.compensated = compensated;
  f.command = MC::EncoderSendPositionValues;
  f.mode_bits = protocol::info(f.command).bits;
  return f;
}

}  // namespace

TEST(CheckerBoundaries, HighPhaseOfTenMicrosecondsByOnePicosecond) {
  // 2.3.2 t_HI maximum 10 us, on the fifth of twelve pulses of a 100 kHz clock.
  const auto t_hi = [](Time high) {
    return hand_clocked(frame_at(kHz(100), false), pulses(12, us(5), us(5), 5, high), checker::check::kPulseHigh);
  };
  EXPECT_EQ(t_hi(us(10)), 0U);
  EXPECT_EQ(t_hi(us(10) + ps(1)), 1U);
}

TEST(CheckerBoundaries, OnOffRatioWithCompensationByOnePicosecond) {
  // 2.3.2 on-off ratio error +/-10 % with delay compensation: at 4 MHz (T = 250 ns) every phase
  // after t_ST at least 100 ns. The third pulse's phases move by a picosecond, T unchanged.
  const auto ratio = [](Time high) {
    std::vector<Time> phases = pulses(20, ns(125), ns(125));
    phases[0] = us(2);                  // t_ST
    phases[5] = high;                   // HIGH 3
    phases[6] = ns(250) - high;         // LOW 4
    return hand_clocked(frame_at(MHz(4), false, true), phases, checker::check::kOnOffRatio);
  };
  EXPECT_EQ(ratio(ns(100)), 0U);
  EXPECT_EQ(ratio(ns(150)), 0U);
  EXPECT_EQ(ratio(ns(100) - ps(1)), 1U);  // HIGH 3 short
  EXPECT_EQ(ratio(ns(150) + ps(1)), 1U);  // LOW 4 short
  EXPECT_EQ(hand_clocked(frame_at(MHz(4), false, true), pulses(20, ns(125), ns(99)), checker::check::kPulseHigh), 0U)
      << "with compensation t_HI's 0.2 us minimum does not apply";
}

TEST(CheckerBoundaries, OnOffRatioWithoutCompensationTheShorterPhaseAgainstTheCableByOnePicosecond) {
  // 2.1.1: another duty cycle gives f_c = 1/(2 t_min) on Figure 2. Over 100 m t_D max is 1.2 us:
  // a 400 kHz clock (T = 2.5 us, the f_c row content) needs each phase of at least 1.2 us.
  const auto ratio = [](Time high, double cable_m = 100) {
    return hand_clocked(frame_at(kHz(400), false), pulses(20, ns(2500) - high, high), checker::check::kOnOffRatio,
                        cable_m);
  };
  EXPECT_EQ(ratio(ns(1200)), 0U);
  EXPECT_EQ(ratio(ns(1300)), 0U);
  EXPECT_EQ(ratio(ns(1200) - ps(1)), 1U);
  EXPECT_EQ(ratio(ns(1300) + ps(1)), 1U);  // the LOW phase short
  EXPECT_EQ(ratio(ns(600), 5), 0U) << "over 5 m 2 MHz, not the cable, bounds f_c: t_HI and t_LO's 0.2 us apply";
  EXPECT_EQ(hand_clocked(frame_at(kHz(400), false), pulses(20, ns(1300), ns(1200) - ps(1)),
                         checker::check::kClockFrequency, 100),
            0U)
      << "the period is within the cable's limit";
}

TEST(CheckerBoundaries, MeasurementClockAt100And200KilohertzByOnePicosecondOfPeriod) {
  // 2.1.2: the delay is measured at 100 .. 200 kHz; periods 10 us and 5 us, one picosecond longer
  // and shorter respectively.
  const auto outside = [](Hertz nominal, Time low, Time high) {
    return hand_clocked(frame_at(nominal, true), pulses(12, low, high), checker::check::kMeasurementClock);
  };
  EXPECT_EQ(outside(kHz(100), us(5), us(5)), 0U);
  EXPECT_EQ(outside(kHz(100), us(5), us(5) + ps(1)), 1U);
  EXPECT_EQ(outside(kHz(200), ns(2500), ns(2500)), 0U);
  EXPECT_EQ(outside(kHz(200), ns(2500), ns(2500) - ps(1)), 1U);
}

// 2.5.1, 2.6.1: after a 2.2 write, the next access must follow a frame that shows Busy = 0. The
// bundled busy-polling scenario waits for it (clean, and the row is judged); without the wait the
// read right after the write is reported, from the wires and from the run alike.
TEST(CheckerAccessWhileBusy, AnAccessBeforeBusyZeroIsReportedAfterItIsNot) {
  auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                         "/scenarios/bundled/parameters_endat22_busy_polling.json");
  const auto clean = scenarios::run_scenario(s);
  EXPECT_EQ(count(clean, checker::check::kAccessWhileBusy), 0U);
  const auto row = std::find_if(clean.conformance.begin(), clean.conformance.end(),
                                [](const auto& c) { return c.check == checker::check::kAccessWhileBusy; });
  ASSERT_NE(row, clean.conformance.end());
  EXPECT_GE(row->judged, 2U);  // the write and the read after the selection
  ASSERT_EQ(s.script[5].kind, master::Operation::Kind::AwaitNotBusy);
  s.script.erase(s.script.begin() + 5);  // the wait after the write
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count(r, checker::check::kAccessWhileBusy), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kAccessWhileBusy) {
      EXPECT_EQ(v.field, "command supplement");
      EXPECT_NE(v.limit.find("Busy = 0"), std::string::npos) << v.limit;
    }
}

// 2.3.1 note 1: an EnDat 2.1 access while Busy is set is as wrong as a 2.2 one. The 2.2 write
// followed at once by a 2.1 read of the same word (no wait for Busy = 0) is reported.
TEST(CheckerAccessWhileBusy, AnEnDat21ReadRightAfterAnEnDat22WriteIsReported) {
  auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                         "/scenarios/bundled/parameters_endat22_busy_polling.json");
  ASSERT_EQ(s.script[5].kind, master::Operation::Kind::AwaitNotBusy);
  ASSERT_EQ(s.script[6].command, protocol::ModeCommand::EncoderSendPositionValuesAndSendParameter);
  s.script.erase(s.script.begin() + 5);  // the wait after the write
  s.script[5].command = protocol::ModeCommand::EncoderSendParameters;  // the read, as a 2.1 mode command
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count(r, checker::check::kAccessWhileBusy), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kAccessWhileBusy) {
      EXPECT_NE(v.limit.find("Busy = 0"), std::string::npos) << v.limit;
    }

}

// 3.4.4: word 3 selects recovery time I; "Encoder receive reset" activates it. The checker follows
// the activation on the wires in both directions, and with it note 3's f_c >= 1 MHz condition.
namespace {

scenarios::Scenario word3_scenario(const std::string& f_c, const std::string& word3, bool reset, const std::string& wait) {
  const std::string text = R"({
    "name": "word3", "seed": 1, "line": { "cable_length_m": 2 },
    "encoder": { "version": "2.2", "t_m": "20 us", "t_m_short": "2 us" },
    "master": { "f_c": ")" + f_c + R"(", "t_m_wait": ")" + wait + R"(" },
    "checker": { "f_c_tolerance_ppm": 0 },
    "script": [
      { "op": "select_memory_area", "mrs": "operating_status" },
      { "op": "write_parameter", "address": 3, "value": ")" + word3 + R"(" },)" +
                           (reset ? R"({ "op": "reset" },)" : R"({ "op": "wait", "duration": "50 ms" },)") + R"(
      { "op": "read_position", "command": "encoder_send_position_values_with_additional_data", "count": 3, "cycle": "1 us" }
    ] })";
  return scenarios::load_scenario_text(text, "word3.json");
}

}  // namespace

TEST(CheckerShortRecoveryTime, FollowsWordThreeOnlyOnceAResetHasActivatedIt) {
  // Selected and activated: 4.5 us between 2.2 frames is enough (short t_m 2 us + t_R; envelope 3.75 us + t_R).
  EXPECT_EQ(count_violations(scenarios::run_scenario(word3_scenario("2 MHz", "0x0001", true, "3750 ns")),
                             checker::check::kRecovery),
            0U);
  // One picosecond less than the envelope's 3.75 us + t_R: this encoder (2 us) is still suited.
  const auto short_by_1ps = scenarios::run_scenario(word3_scenario("2 MHz", "0x0001", true, "3749999 ps"));
  EXPECT_EQ(count_violations(short_by_1ps, checker::check::kRecovery, checker::Verdict::SpecEnvelope), 2U);
  // Written but not activated: the long t_m still holds.
  EXPECT_GE(count_violations(scenarios::run_scenario(word3_scenario("2 MHz", "0x0001", false, "3750 ns")),
                             checker::check::kRecovery, checker::Verdict::Both),
            1U);
  // Selected back to the long t_m and activated: the short wait breaks it again.
  EXPECT_GE(count_violations(scenarios::run_scenario(word3_scenario("2 MHz", "0x0002", true, "3750 ns")),
                             checker::check::kRecovery, checker::Verdict::Both),
            1U);
}

// Short, then back to the long t_m (bits 2^0 = 0, 2^1 = 1), each activated by a reset: after the
// second reset the envelope's 30 us + t_R holds again, to the picosecond, while this encoder's
// 20 us + t_R is still met one picosecond short of it.
TEST(CheckerShortRecoveryTime, SwitchedBackTheLongRecoveryTimeHoldsToThePicosecond) {
  const auto run = [](const std::string& wait) {
    const std::string text = R"({
      "name": "word3_back", "seed": 1, "line": { "cable_length_m": 2 },
      "encoder": { "version": "2.2", "t_m": "20 us", "t_m_short": "2 us" },
      "master": { "f_c": "2 MHz", "t_m_wait": ")" + wait + R"(" },
      "script": [
        { "op": "select_memory_area", "mrs": "operating_status" },
        { "op": "write_parameter", "address": 3, "value": "0x0001" },
        { "op": "reset" },
        { "op": "read_position", "command": "encoder_send_position_values_with_additional_data", "count": 2, "cycle": "1 us" },
        { "op": "select_memory_area", "mrs": "operating_status" },
        { "op": "write_parameter", "address": 3, "value": "0x0002" },
        { "op": "reset" },
        { "op": "read_position", "command": "encoder_send_position_values_with_additional_data", "count": 3, "cycle": "1 us" }
      ] })";
    return scenarios::run_scenario(scenarios::load_scenario_text(text, "word3_back.json"));
  };
  const auto exact = run("30 us");
  EXPECT_EQ(count_violations(exact, checker::check::kRecovery), 0U);
  const auto short_by_1ps = run("29999999 ps");
  // The gaps between the three reads after the second reset, and none before it: the master
  // waits over 1 ms (t_b) before each 2.1 parameter frame, and between the first two reads the
  // short t_m is active.
  EXPECT_EQ(count_violations(short_by_1ps, checker::check::kRecovery, checker::Verdict::SpecEnvelope), 2U);
  EXPECT_EQ(count_violations(short_by_1ps, checker::check::kRecovery, checker::Verdict::Both), 0U);
  EXPECT_EQ(count_violations(short_by_1ps, checker::check::kRecovery, checker::Verdict::ThisEncoder), 0U);
}

TEST(CheckerShortRecoveryTime, NeedsOneMegahertzToTheHertzOnceActivated) {
  const auto at = [](const std::string& f_c) {
    return count_violations(scenarios::run_scenario(word3_scenario(f_c, "0x0001", true, "30 us")), checker::check::kShortRecoveryClock);
  };
  EXPECT_EQ(at("1 MHz"), 0U);
  EXPECT_EQ(at("999999 Hz"), 3U);
  // Not activated: the rule does not apply.
  EXPECT_EQ(count_violations(scenarios::run_scenario(word3_scenario("999999 Hz", "0x0001", false, "30 us")),
                             checker::check::kShortRecoveryClock),
            0U);
}

TEST(CheckerBoundaries, RecoveryTimeByOnePicosecond) {
  auto s = make_scenario(1, MHz(1), false, 2);
  s.script.back().cycle = Time::zero();
  using checker::Verdict;
  // This encoder: gap = t_m_wait + t_r_wait = 20.5 us = its t_m + t_R; the envelope wants 30.5 us.
  s.master.t_m_wait = us(20);
  auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kRecovery), 1U);
  EXPECT_EQ(count_violations(r, checker::check::kRecovery, Verdict::SpecEnvelope), 1U);
  EXPECT_TRUE(checker::conclude(r.violations).this_encoder);
  EXPECT_FALSE(checker::conclude(r.violations).spec_envelope);
  s.master.t_m_wait = us(20) - ps(1);
  r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kRecovery, Verdict::Both), 1U);
  EXPECT_FALSE(checker::conclude(r.violations).this_encoder);
  // The envelope: t_m 30 us + t_R 500 ns.
  s.master.t_m_wait = us(30);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kRecovery), 0U);
  s.master.t_m_wait = us(30) - ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kRecovery, Verdict::SpecEnvelope), 1U);
}

TEST(CheckerBoundaries, WaitAfterErrorHandlingByOnePicosecond) {
  auto s = make_scenario(1, MHz(1), false, 1);
  test_support::prepend_disturbed_read(s, 0b000101);
  s.master.error_wait = ns(29'500);  // + t_r_wait 0.5 us = 30 us
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kErrorRecovery), 0U);
  s.master.error_wait = ns(29'500) - ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kErrorRecovery), 1U);
}

TEST(CheckerBoundaries, ClockFrequencyByOnePicosecondOfPeriod) {
  auto s = make_scenario(1, MHz(2), false, 1);  // period 500000 ps
  s.checker.f_c_tolerance_ppm = 0;
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockFrequency), 0U);
  s.master.f_c = Hertz{2'000'004};  // period 499999 ps
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockFrequency), 1U);
}

TEST(CheckerBoundaries, ClockFrequencyForTheCableByOnePicosecondOfPeriod) {
  // 30 m without compensation: 2 t_D max = 2 x (0.2 + 0.01 x 30) us = 1 us (2.3.2 note 4 and 2.1.1).
  auto s = make_scenario(30, MHz(1), false, 1);
  s.checker.f_c_tolerance_ppm = 0;
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockFrequency), 0U);
  s.master.f_c = Hertz{1'000'001};  // period 999999 ps
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kClockFrequency), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kClockFrequency) {
      EXPECT_EQ(v.limit, "period >= 2 t_D = 1 us");
      EXPECT_EQ(v.measured, "1.000001 MHz over 30 m");
      EXPECT_NE(v.spec.find("2.3.2 note 4 and 2.1.1"), std::string::npos) << v.spec;
    }
}

TEST(CheckerBoundaries, PulseWidthByOnePicosecond) {
  auto s = make_scenario(1, kHz(2500), false, 1);  // 400000 ps: HIGH and LOW 200000 ps = 0.2 us
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kPulseHigh), 0U);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kPulseLow), 0U);
  s.master.f_c = Hertz{2'500'007};  // 399999 ps: HIGH 199999 ps
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kPulseHigh), 1U);
}
