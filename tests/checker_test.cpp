#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <memory>

#include "scenario_support.hpp"
#include "endatsim/master/functions.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/events.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "test_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::count_violations;
using endatsim::test_support::make_scenario;

TEST(CheckerClockFrequency, Above2MHzWithoutCompensationIsAViolation) {
  const auto r = scenarios::run_scenario(make_scenario(1, MHz(4), false, 2));
  ASSERT_EQ(count_violations(r, checker::check::kClockFrequency), 2U);
  for (const auto& v : r.violations) {
    if (v.check != checker::check::kClockFrequency) continue;
    EXPECT_EQ(v.limit, "100 kHz .. 2 MHz");
    EXPECT_EQ(v.measured, "4 MHz");
  }
  EXPECT_EQ(count_violations(r, checker::check::kPulseHigh), 2U);  // 125 ns < 0.2 us as well
}

TEST(CheckerClockFrequency, SixteenMHzWithCompensationIsOnlyAWarning) {
  const auto r = scenarios::run_scenario(make_scenario(10, MHz(16), true, 2));
  ASSERT_EQ(count_violations(r, checker::check::kClockFrequency), 2U);
  for (const auto& v : r.violations) EXPECT_EQ(v.severity, checker::Severity::Warning);
}

TEST(CheckerPulseWidth, HighPhaseBelow200nsWithoutCompensation) {
  auto s = make_scenario(1, MHz(1), false, 1);
  s.master.high_permille = 150;  // 150 ns HIGH at 1 MHz
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kPulseHigh), 1U);
  EXPECT_EQ(count_violations(r, checker::check::kPulseLow), 0U);
}

TEST(CheckerRecovery, NextFrameBeforeTmPlusTrIsReported) {
  auto s = make_scenario(1, MHz(1), false, 3);
  s.master.t_m_wait = us(5);  // the encoder's t_m is 20 us
  s.script.back().cycle = Time::zero();
  const auto r = scenarios::run_scenario(s);
  // The encoder is still in t_m (DATA HIGH, driver on) when the second frame begins: it takes the
  // falling edge as one more clock, the master runs into its driver (contention) and sees no LOW.
  ASSERT_EQ(count_violations(r, checker::check::kRecovery), 1U);
  EXPECT_GE(count_violations(r, checker::check::kContention), 1U);
  EXPECT_NE(r.frames[1].outcome, master::FrameOutcome::Ok);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kRecovery) {
      EXPECT_EQ(v.limit, ">= 20.5 us (this encoder), >= 30.5 us (spec envelope)");
      EXPECT_EQ(v.verdict, checker::Verdict::Both);
    }
}

TEST(CheckerSamplingWindow, CatchesAMissingDelayCompensation) {
  auto s = make_scenario(100, MHz(2), false, 2);
  s.master.start_bit_detection = master::StartBitDetection::FirstHigh;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 2U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kSamplingWindow) {
      EXPECT_EQ(v.where, line::ObservationPoint::MasterPins);
      EXPECT_EQ(v.field, "start bit");  // the fail-safe HIGH at slot 9, taken for the start bit
    }
}

TEST(CheckerSamplingWindow, ACarefulMasterWithoutCompensationStillSamplesOutsideTheWindow) {
  // It finds the start bit two slots late and reads consistently shifted bits: the data are
  // right by luck of the phase, but every sample is taken outside the bit the master means.
  const auto r = scenarios::run_scenario(make_scenario(100, MHz(2), false, 2));
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 2U);
}

TEST(CheckerMeasurementClock, DelayMeasuredAt1MHzIsReported) {
  auto s = make_scenario(10, MHz(2), true, 1);
  s.master.measurement.f_c = MHz(1);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementClock), 3U);
}

TEST(CheckerClockFrequency, EdgeJitterOnAClockAtTheLimitIsNotAViolation) {
  // 2 MHz without compensation over 1 m (over 10 m the cable allows 1.67 MHz, 2.3.2 note 4 and 2.1.1).
  for (auto [cable, f_c, jitter, seed] : {std::tuple{1, MHz(2), ns(100), 1}, std::tuple{10, MHz(8), ns(30), 2},
                                          std::tuple{10, MHz(16), ns(15), 4}}) {
    auto s = make_scenario(cable, f_c, f_c > MHz(2), 20);
    if (f_c == MHz(16)) s.master.t_st = us(1);
    s.master.jitter = jitter;
    s.seed = static_cast<std::uint64_t>(seed);
    const auto r = scenarios::run_scenario(s);
    for (const auto& v : r.violations)
      if (v.check == checker::check::kClockFrequency) {
        EXPECT_EQ(v.severity, checker::Severity::Warning) << v.measured;  // 16 MHz: special applications
        EXPECT_EQ(f_c, MHz(16)) << v.measured;
      }
  }
}

TEST(CheckerClockFrequency, AJitteredClockThatIsTooFastIsStillCaught) {
  auto s = make_scenario(1, Hertz{2'100'000}, false, 5);
  s.master.jitter = ns(20);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockFrequency), 5U);
}

TEST(CheckerClockFrequency, ALongContinuousClockIsJudgedWithoutOverflow) {
  auto s = make_scenario(10, MHz(1), false, 1);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.script.back().command = protocol::ModeCommand::EncoderSendPositionValues;
  s.script.back().continuous_words = 1500;  // 51 000 rising edges: the fit takes the first 4096
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(test_support::count_ok(r), 1501U);
  EXPECT_EQ(count_violations(r, checker::check::kClockFrequency), 0U);
}

TEST(CheckerClockFrequency, AClockHalfAPercentFastIsCaughtAndAnExactOneIsNot) {
  auto s = make_scenario(1, Hertz{2'010'000}, false, 1);  // 0.5 % fast
  auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kClockFrequency), 1U);
  s.master.f_c = MHz(2);
  s.checker.f_c_tolerance_ppm = 0;
  r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kClockFrequency), 0U);
}

// 3.9.19 word 25 and 2.1.1: what the declared encoder allows of f_c, to the hertz; it counts
// against this encoder only (the table allows up to 8 MHz with compensation, 16 MHz specially).
TEST(CheckerClockFrequency, AboveTheDeclaredEncodersMaximumToTheHertz) {
  const auto this_encoder = [](Hertz f_c, bool v21, std::optional<std::uint16_t> word25_khz) {
    auto s = make_scenario(1, f_c, f_c > MHz(2), 2);
    s.checker.f_c_tolerance_ppm = 0;
    if (v21) {
      s.encoder.version = protocol::EndatVersion::V2_1;
    }
    if (word25_khz) {
      auto image = slave::default_memory_image(s.encoder);
      image.areas.at(protocol::MemoryArea::ManufacturerEndat22).at(protocol::word::kMaxClockFrequency) = *word25_khz;
      s.encoder.memory = image;
    }
    return count_violations(scenarios::run_scenario(s), checker::check::kClockFrequency, checker::Verdict::ThisEncoder);
  };
  // At 1 MHz one picosecond of period is one hertz; at 2 MHz the nearest clock above is 2 MHz + 4 Hz.
  EXPECT_EQ(this_encoder(MHz(1), false, 1000), 0U);
  EXPECT_EQ(this_encoder(MHz(1) + 1, false, 1000), 2U);  // each of the two reads
  EXPECT_EQ(this_encoder(MHz(1) + 1, false, std::nullopt), 0U);  // the model's word 25: 16 MHz
  EXPECT_EQ(this_encoder(MHz(2), true, std::nullopt), 0U);
  EXPECT_EQ(this_encoder(MHz(2) + 4, true, std::nullopt), 2U);
}

TEST(CheckerMeasurementProcedure, SlowCounterAndTooFewMeasurementsAreReported) {
  auto s = make_scenario(10, MHz(8), true, 1);
  s.master.measurement.f_e = MHz(32);  // needs >= 64 MHz (8 x 8 MHz, -10 %)
  s.master.measurement.count = 2;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kMeasurementProcedure), 2U);
  s.master.measurement.f_e = MHz(58);  // 8 x 8 MHz - 10 % = 57.6 MHz: allowed
  s.master.measurement.count = 3;
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kMeasurementProcedure), 0U);
}

// ---- boundary tests: just inside (no violation) and just outside (violation), by 1 ps ----

TEST(CheckerDataDelay, RoundTripAtTheSpecBoundPassesOnePicosecondMoreFails) {
  auto s = make_scenario(37, MHz(1), false, 1);  // default line: t_D = 0.2 us + 0.01 us/m x L exactly
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelay), 0U);
  s.encoder.output_delay += ps(1);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kDataDelay), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kDataDelay) {
      EXPECT_EQ(v.measured, "570.001 ns");
      EXPECT_EQ(v.limit, "<= 570 ns");
      EXPECT_EQ(v.clock, 11U);
    }
}

TEST(CheckerDriverTimes, TzAndToeAgainstOneFramePeriodReading) {
  // Encoder release after FE1 and drive after FE9 both take receiver 20 + logic + driver 20 ns.
  auto s = make_scenario(1, MHz(8), true, 1);
  s.checker.t_z_per_frame_period = true;
  s.encoder.output_delay = ns(85);  // 125 ns = T at 8 MHz: just inside
  auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOff), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOn), 0U);
  s.encoder.output_delay = ns(85) + ps(1);
  r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOff), 1U);  // the 200 kHz measurement frames have T = 5 us
  EXPECT_EQ(count_violations(r, checker::check::kDriverOn), 1U);
  s.checker.t_z_per_frame_period = false;  // the literal reading: T = 1/f_c,min = 10 us
  r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOff) + count_violations(r, checker::check::kDriverOn), 0U);
}

TEST(CheckerCalculationTime, StartBitWithinOneMillisecondAndOnePeriod) {
  // At 1 MHz the rising edges lie at (k - 0.5) us after FE1; the limit is 1 ms + T = 1001 us.
  auto s = make_scenario(1, MHz(1), false, 1);
  s.master.start_bit_timeout = ms(2);
  s.encoder.t_cal = us(1001);  // start bit on RE1002 at 1001.5 us
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kCalculationTime), 1U);
  s.encoder.t_cal = ns(1'000'500);  // RE1001 at 1000.5 us
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kCalculationTime), 0U);
  s.encoder.t_cal = ns(1'000'500) + ps(1);  // one picosecond more: the next edge, 1001.5 us
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kCalculationTime), 1U);
}

TEST(CheckerCalculationTime, AStartBitBeforeRe11BreaksTheMinimumByOneCount) {
  // 2.3.2 t_cal >= 10.5/f_c: RE11 comes 10.5 periods after FE1.
  auto s = make_scenario(5, MHz(1), false, 2);
  s.encoder.t_cal = Time::zero();
  s.encoder.earliest_start_bit_clock = 11;
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kCalculationTime), 0U);
  s.encoder.earliest_start_bit_clock = 10;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kCalculationTime), 2U);
  EXPECT_EQ(r.frames.front().outcome, master::FrameOutcome::Ok) << "the master still finds the start bit";
}

TEST(CheckerStartDelay, FirstLowPhaseAgainstNote8) {
  auto s = make_scenario(100, MHz(8), true, 1);  // 2 us at 100 m for 2 .. 8 MHz
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 0U);
  s.master.t_st = us(2) - ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 1U);
  s.master.f_c = MHz(16);  // 1 us at 16 MHz
  s.master.measurement.f_e = MHz(128);
  s.master.t_st = us(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 0U);
  s.master.t_st = us(1) - ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 1U);
  s.master.f_c = MHz(12);  // linear in between: 1.5 us
  s.master.measurement.f_e = MHz(96);
  s.master.t_st = ns(1500);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 0U);
  s.master.t_st = ns(1500) - ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kStartDelay), 1U);
}

TEST(CheckerFloatingData, AMasterPollingBeforeTheEncoderDrivesIsReported) {
  // 2 MHz over 100 m without compensation: slots 9 and 10 are sampled before the encoder's LOW
  // has come back, on the fail-safe level.
  const auto r = scenarios::run_scenario(make_scenario(100, MHz(2), false, 2));
  EXPECT_EQ(count_violations(r, checker::check::kFloatingData), 2U);
  EXPECT_EQ(count_violations(scenarios::run_scenario(make_scenario(100, MHz(2), true, 2)), checker::check::kFloatingData), 0U);
}

TEST(CheckerFloatingData, AnEncoderTakingModeBitsFromAnUndrivenLineIsReported) {
  for (bool drive : {true, false}) {
    sim::Kernel k;
    line::Line l(k, line::LineParams{});
    slave::EncoderParams ep;
    slave::Encoder e(k, l, ep);
    checker::TimingChecker c(k, l, scenarios::declared_encoder(ep));
    checker::DeclaredFrame f;
    f.f_c = MHz(1);
    c.on_frame_start(f);
    test_support::ScriptedClock clock(k, l, us(1), 12, 0b000111, Time::zero(), drive);
    k.run();
    c.finish();
    std::size_t floating = 0;
    for (const auto& v : c.violations()) floating += v.check == checker::check::kFloatingData;
    EXPECT_EQ(floating, drive ? 0U : 1U);
  }
}

TEST(CheckerErrorRecovery, AfterTypeOneTheMasterWaitsThirtyMicroseconds) {
  auto s = make_scenario(1, MHz(1), false, 1);
  test_support::prepend_disturbed_read(s, 0b000101);
  s.master.error_wait = us(30);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kErrorRecovery), 0U);
  s.master.error_wait = us(25);  // t_m of the encoder (20 us) + t_R is met, A2's 30 us is not
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kErrorRecovery), 1U);
  // The same gap suits this encoder but not the envelope's t_m of 30 us.
  EXPECT_EQ(count_violations(r, checker::check::kRecovery), 1U);
  EXPECT_EQ(count_violations(r, checker::check::kRecovery, checker::Verdict::SpecEnvelope), 1U);
}

TEST(CheckerDataDelayTolerance, ASetDelayWithinATenthOfThePeriodPasses) {
  auto s = make_scenario(10, MHz(8), true, 1);  // true t_D 300 ns, T/10 = 12.5 ns
  s.script.erase(s.script.begin());             // no measurement: the master uses its fixed value
  s.master.fixed_t_d = ps(312'500);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelayTolerance), 0U);
  s.master.fixed_t_d = ps(312'501);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelayTolerance), 1U);
  s.master.fixed_t_d = ps(287'500);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelayTolerance), 0U);
  s.master.fixed_t_d = ps(287'499);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelayTolerance), 1U);
}

TEST(CheckerDataDelay, StartBitIsAttributedToItsOwnEdgeAtSixteenMegahertz) {
  // At 16 MHz the encoder's internal delay (130 ns) spans two clock periods: the start bit must
  // still be measured from the edge that carried it, not from a later one.
  auto s = make_scenario(20, MHz(16), true, 2);
  s.master.t_st = us(1);
  auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelay), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelayTolerance), 0U);
  s.encoder.output_delay += ps(1);
  r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kDataDelay), 5U);  // 3 measurement frames, 2 reads
  for (const auto& v : r.violations)
    if (v.check == checker::check::kDataDelay) {
      EXPECT_EQ(v.measured, "400.001 ns");
    }
}

// Deliberately broken masters, one for each way a master can break the timing table: each is
// caught by the row it breaks.
TEST(CheckerBrokenMasters, EachIsCaughtWithTheRightRow) {
  struct Case {
    const char* what;
    std::string_view check;
    std::function<void(scenarios::Scenario&)> apply;
  };
  const std::vector<Case> cases{
      {"t_ST too short on 100 m", checker::check::kStartDelay, [](auto& s) { s.master.t_st = us(1); }},
      {"recovery time ignored", checker::check::kRecovery,
       [](auto& s) {
         s.master.t_m_wait = us(2);
         s.script.back().cycle = Time::zero();
       }},
      {"duty cycle off by 15 %", checker::check::kOnOffRatio, [](auto& s) { s.master.high_permille = 350; }},
      {"2.5 MHz without compensation", checker::check::kClockFrequency,
       [](auto& s) {
         s.master.delay_compensation = false;
         s.master.f_c = kHz(2500);
       }},
      {"delay measured at 1 MHz", checker::check::kMeasurementClock,
       [](auto& s) { s.master.measurement.f_c = MHz(1); }},
      {"only two measurements", checker::check::kMeasurementProcedure,
       [](auto& s) { s.master.measurement.count = 2; }},
  };
  const auto clean = scenarios::run_scenario(make_scenario(100, MHz(8), true, 3));
  EXPECT_TRUE(clean.violations.empty());
  for (const auto& c : cases) {
    auto s = make_scenario(100, MHz(8), true, 3);
    c.apply(s);
    EXPECT_GE(count_violations(scenarios::run_scenario(s), c.check), 1U) << c.what;
  }
}

TEST(CheckerClockCount, TooFewPulsesAndPulsesBeyondAnEnDat22Frame) {
  // 2.2, 25 bits, start bit at RE11: last bit at RE43, one more pulse allowed.
  auto s = make_scenario(1, MHz(1), false, 1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockCount), 0U);  // 44 pulses
  s.master.extra_clock_after_last_bit = false;
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockCount), 0U);  // 43 pulses
  s.master.position_bits = 24;  // the master thinks word 13 says 24: it stops one pulse early
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kClockCount), 1U);
  s.master.position_bits = 27;  // two more than the encoder has
  s.master.extra_clock_after_last_bit = true;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kClockCount), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kClockCount) {
      EXPECT_EQ(v.severity, checker::Severity::Warning);
      EXPECT_EQ(v.measured, "46 pulses");
    }
}

// A run that stops while a frame is going on (a limit, or the scenario's max_time) cuts that
// frame: its clock pulses are not counted against 2.3.1 (the master did not stop clocking; the
// run did), as when a capture ends inside a frame. A frame the master itself ends early still is.
TEST(CheckerClockCount, AFrameTheEndOfTheRunCutsIsNotJudged) {
  auto s = make_scenario(1, MHz(1), false, 3);
  s.script.back().cycle = us(100);
  for (const Time end : {us(20), ns(30500), us(120), us(137)}) {
    s.max_time = end;
    const auto r = scenarios::run_scenario(s);
    EXPECT_FALSE(r.finished) << end;
    EXPECT_EQ(count_violations(r, checker::check::kClockCount), 0U) << end;
  }
  // The master thinks word 13 says 24 and gives no extra pulse: every frame stops one pulse early.
  // At 137 us frame #0 (0 .. 42 us) is complete and judged, frame #1 (from 100 us) is cut.
  s.max_time = us(137);
  s.master.position_bits = 24;
  s.master.extra_clock_after_last_bit = false;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_violations(r, checker::check::kClockCount), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kClockCount) {
      EXPECT_EQ(v.frame, 0U);
    }
}

TEST(CheckerLineChange, CompensatingWithADelayFromTheOldLineIsReported) {
  // Measured on 10 m (t_D 300 ns); at 2 ms the cable becomes 60 m (800 ns) while reads go on.
  auto s = make_scenario(10, MHz(8), true, 10);
  s.script.back().cycle = us(200);
  s.master.careful.remeasure_after_line_change = false;  // a careless master
  s.master.careful.remeasure_after_crc_errors = 0;
  s.events.push_back(scenarios::cable_change(ms(2), 60, ns(5)));
  auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementProcedure), 1U);
  EXPECT_GE(count_violations(r, checker::check::kDataDelayTolerance), 1U);
  // The master hunts for the start bit, so its reads stay right by a whole-bit shift, but it
  // samples outside the data-valid windows.
  EXPECT_GE(count_violations(r, checker::check::kSamplingWindow), 1U);
  // Measuring again after the change keeps every read clean.
  master::Operation again;
  again.kind = master::Operation::Kind::MeasureDelay;
  again.at = ms(2) + us(100);
  master::Operation reads = s.script.back();
  reads.count = 3;
  s.script.push_back(again);
  s.script.push_back(reads);
  s.script[1].count = 4;
  r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementProcedure), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelayTolerance), 0U);
  EXPECT_EQ(test_support::count_ok(r), 7U);
}

TEST(CheckerTypeOne, AnAnswerThatDrivesHighAtOnceIsNoStartBit) {
  // Fail-safe LOW and an encoder driver that turns on before its level settles: the HIGH of a
  // type I answer must not be taken for a start bit (no t_D, clock-count or t_cal report).
  auto s = make_scenario(10, MHz(1), false, 1);
  s.line.failsafe_level = false;
  s.line.encoder.driver_delay = ns(30);
  s.line.encoder.enable_delay = ns(10);
  s.encoder.output_delay = ns(10);  // keeps the round trip at the t_D bound
  test_support::prepend_disturbed_read(s, 0b001111);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 2U);
  EXPECT_EQ(r.frames[0].outcome, master::FrameOutcome::Type1Error);
  EXPECT_TRUE(r.violations.empty()) << r.violations.front().check << ": " << r.violations.front().message;
}

TEST(CheckerMeasurementProcedure, CompensatingWithoutEverMeasuringIsReported) {
  auto s = make_scenario(100, MHz(8), true, 3);
  s.script.erase(s.script.begin());
  s.master.fixed_t_d = us(1) + ns(200);  // right, but never measured (2.1.2)
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementProcedure), 1U);
  EXPECT_EQ(test_support::count_ok(r), 3U);
}

// Without t_ST on 100 m the master drives DATA before the encoder's release has come back.
TEST(CheckerContention, MissingTstOnALongCableCollidesInsideTheReadFrames) {
  auto s = make_scenario(100, MHz(8), true, 2);
  s.master.t_st = Time::zero();
  const auto r = scenarios::run_scenario(s);
  EXPECT_GE(count_violations(r, checker::check::kContention), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kContention) {
      ASSERT_TRUE(v.frame.has_value());
      EXPECT_GE(*v.frame, 3U);  // frames 0..2 measure t_D at 200 kHz, where the first LOW is long enough
    }
}

// ---- Findings as they are made: the listener, the watermark of settled frames, contentions
// reported as they end, and the checker's memory in a long run.

namespace {

namespace fs = std::filesystem;

// A scenario run as scenarios::run_scenario runs it, with the checker's finding listener attached:
// each finding heard with the simulated time and the checker's settled_frames() at that moment.
// `declared`: the master declares its frames; without, the checker finds them on the wires, in
// a live run or (`capture`) as a capture that starts at rest.
struct ListenedRun final : master::MasterObserver {
  struct Heard {
    Time at;
    std::uint64_t mark;
    checker::Violation v;
  };

  explicit ListenedRun(const scenarios::Scenario& s, bool declared = true, bool capture = false)
      : scenario(s),
        params(with_seed(s)),
        line(kernel, s.line),
        encoder(kernel, line, s.encoder),
        master(kernel, line, params),
        checker(kernel, line, scenarios::declared_encoder(s.encoder), scenarios::declared_master(params), s.checker),
        declarations(checker) {
    for (const auto& p : s.bus) bus.push_back(std::make_unique<slave::Encoder>(kernel, line.add_encoder(), p));
    if (declared) master.add_observer(&declarations);
    master.add_observer(this);
    if (capture) checker.begin_capture(kernel.now(), true);
    checker.set_finding_listener([this](const checker::Violation& v) {
      heard.push_back({kernel.now(), watch_mark(), v});
    });
  }

  void run() {
    for (const auto& op : scenario.script) master.enqueue(op);
    scenarios::EventDriver events(kernel, line, encoder, &master, checker, scenario.events, params.seed,
                                  sim::period_of(params.f_c));
    master.start();
    kernel.run(scenario.max_time);
    checker.finish();
  }

  // The mark as it stands, noting whether it ever went down.
  std::uint64_t watch_mark() {
    const std::uint64_t mark = checker.settled_frames();
    mark_decreased = mark_decreased || mark < last_mark;
    last_mark = mark;
    return mark;
  }
  void on_frame_start(const master::FrameResult& f) override {
    starts.emplace_back(f.start, f.index);
    watch_mark();
  }
  void on_sample(const master::FrameResult&, unsigned, bool, bool) override {}
  void on_frame_end(const master::FrameResult&) override {
    watch_mark();
    backlogs.push_back(checker.backlog());
    logged.push_back(line.contentions().size());
  }

  static master::MasterParams with_seed(const scenarios::Scenario& s) {
    master::MasterParams p = s.master;
    p.seed = s.seed;
    return p;
  }

  scenarios::Scenario scenario;
  master::MasterParams params;
  Kernel kernel;
  line::Line line;
  slave::Encoder encoder;
  std::vector<std::unique_ptr<slave::Encoder>> bus;
  master::Master master;
  master::MasterFunctions functions{master};
  checker::TimingChecker checker;
  scenarios::MasterDeclarations declarations;
  std::vector<Heard> heard;
  std::vector<std::pair<Time, std::uint64_t>> starts;  // FE1 at the master logic, frame index
  std::vector<checker::TimingChecker::Backlog> backlogs;  // at each frame's end
  std::vector<std::size_t> logged;                        // the line's contention log, at each frame's end
  bool mark_decreased = false;
  std::uint64_t last_mark = 0;
};

std::string describe(const checker::Violation& v) {
  return v.check + " at " + format_time(v.time) + " frame " + (v.frame ? std::to_string(*v.frame) : "-") + ": " +
         v.message;
}

// Without t_ST on 100 m at 8 MHz the master drives DATA into the encoder's release in every read
// frame (CheckerContention above).
scenarios::Scenario colliding_reads(unsigned reads) {
  auto s = make_scenario(100, MHz(8), true, reads);
  s.master.t_st = Time::zero();
  return s;
}

}  // namespace

TEST(CheckerFindingListener, HearsEveryFindingAlsoThoseBeyondTheCap) {
  auto s = make_scenario(1, MHz(4), false, 5);  // f_c and t_HI in every frame
  s.master.t_st = Time::zero();
  const auto all = scenarios::run_scenario(s);
  ASSERT_GE(all.violations.size(), 10U);
  s.checker.max_findings_per_check = 1;
  ListenedRun capped(s);
  capped.run();
  // Every finding of the uncapped run is heard, once, though only one per check is kept.
  ASSERT_EQ(capped.heard.size(), all.violations.size());
  EXPECT_EQ(capped.heard.size(), capped.checker.violations().size() + capped.checker.findings_not_kept());
  std::vector<std::string> heard, expected;
  for (const auto& h : capped.heard) heard.push_back(describe(h.v));
  for (const auto& v : all.violations) expected.push_back(describe(v));
  std::sort(heard.begin(), heard.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(heard, expected);
  for (const auto& v : capped.checker.violations())
    EXPECT_NE(std::find(expected.begin(), expected.end(), describe(v)), expected.end()) << describe(v);
  EXPECT_LT(capped.checker.violations().size(), all.violations.size());
}

// Each bundled, field and safety scenario, with the master's declarations and judged from the
// wires alone (live, and as a capture): no finding names a frame below the mark as it stood when
// the finding came, and the mark never goes down.
class CheckerSettledFrames : public ::testing::TestWithParam<fs::path> {};

TEST_P(CheckerSettledFrames, NoFindingArrivesForASettledFrame) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  for (const auto& [declared, capture] : {std::pair{true, false}, std::pair{false, false}, std::pair{false, true}}) {
    SCOPED_TRACE(declared ? "declared" : capture ? "from the wires, a capture" : "from the wires, live");
    ListenedRun run(scenario, declared, capture);
    run.run();
    for (const auto& h : run.heard) {
      if (h.v.frame) {
        EXPECT_GE(*h.v.frame, h.mark) << describe(h.v) << " heard at " << format_time(h.at);
      }
    }
    EXPECT_FALSE(run.mark_decreased);
    EXPECT_EQ(run.checker.settled_frames(), UINT64_MAX);
    EXPECT_EQ(run.heard.size(), run.checker.violations().size() + run.checker.findings_not_kept());
    if (!declared) continue;
    // The run is run_scenario's: the same findings in the same order.
    const auto r = scenarios::run_scenario(scenario);
    ASSERT_EQ(run.checker.violations().size(), r.violations.size());
    for (std::size_t i = 0; i < r.violations.size(); ++i)
      EXPECT_EQ(describe(run.checker.violations()[i]), describe(r.violations[i]));
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CheckerSettledFrames, ::testing::ValuesIn(test_support::scenario_files()),
                         [](const auto& param_info) {
                           std::string name = param_info.param.parent_path().filename().string() + "_" +
                                              param_info.param.stem().string();
                           std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
                           return name;
                         });

// A contention is reported as it ends, against the frame that had begun (FE1 at the master
// logic) when it began; with a cap of one, the one kept is the first to begin.
TEST(CheckerContention, IsReportedAsItEndsAgainstTheFrameItBeganIn) {
  auto s = colliding_reads(4);
  ListenedRun run(s);
  run.run();
  const auto& log = run.line.contentions();
  std::size_t heard = 0;
  for (const auto& h : run.heard) {
    if (h.v.check != checker::check::kContention) continue;
    ++heard;
    const auto c = std::find_if(log.begin(), log.end(), [&](const line::Contention& l) {
      return l.start == h.v.time && l.where == h.v.where;
    });
    ASSERT_NE(c, log.end()) << describe(h.v);
    EXPECT_EQ(h.at, c->end) << describe(h.v);
    std::optional<std::uint64_t> began;
    for (const auto& [start, index] : run.starts)
      if (start <= c->start) began = index;
    EXPECT_EQ(h.v.frame, began) << describe(h.v);
    EXPECT_GE(h.v.frame.value_or(0), 3U);  // frames 0..2 measure t_D at 200 kHz, where the first LOW is long enough
  }
  EXPECT_EQ(heard, log.size());
  EXPECT_GE(heard, 4U);  // one in each of the four reads
  // Among findings of the same time contentions still come last, in the order they began.
  const auto& v = run.checker.violations();
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i].time == v[i - 1].time && v[i - 1].check == checker::check::kContention) {
      EXPECT_EQ(v[i].check, checker::check::kContention);
    }
  }

  s.checker.max_findings_per_check = 1;
  ListenedRun capped(s);
  capped.run();
  std::vector<checker::Violation> kept;
  for (const auto& k : capped.checker.violations())
    if (k.check == checker::check::kContention) kept.push_back(k);
  ASSERT_EQ(kept.size(), 1U);
  EXPECT_EQ(kept[0].time, log.front().start);
  EXPECT_EQ(kept[0].where, log.front().where);
}

// A contention in every frame of a long run: what the line logs and what the checker holds stay
// as they were after the first frames.
TEST(CheckerContention, ALongRunThatCollidesInEveryFrameKeepsItsMemoryBounded) {
  constexpr unsigned kReads = 20000;
  auto s = colliding_reads(kReads);
  s.max_time = ms(kReads / 5);  // 100 us a read
  s.checker.max_findings_per_check = 3;
  ListenedRun run(s);
  run.run();
  ASSERT_GT(run.backlogs.size(), kReads);
  std::size_t contentions = 0;
  for (const auto& h : run.heard) contentions += h.v.check == checker::check::kContention;
  EXPECT_GE(contentions, kReads);
  EXPECT_GE(run.line.contentions_seen(), contentions);
  EXPECT_EQ(run.line.contentions().size(), line::Line::kContentionLogLimit);
  EXPECT_EQ(run.logged.back(), line::Line::kContentionLogLimit);
  using Backlog = checker::TimingChecker::Backlog;
  const auto most = [&](std::size_t frames, std::size_t Backlog::*field) {
    std::size_t m = 0;
    for (std::size_t i = 0; i < frames; ++i) m = std::max(m, run.backlogs[i].*field);
    return m;
  };
  constexpr std::size_t kEarly = 20;
  for (std::size_t Backlog::*field :
       {&Backlog::frames_not_at_encoder, &Backlog::frame_starts, &Backlog::contentions, &Backlog::start_bits_in_flight,
        &Backlog::master_rising_edges, &Backlog::master_driven_changes, &Backlog::encoder_edges,
        &Backlog::delay_measurements})
    EXPECT_EQ(most(run.backlogs.size(), field), most(kEarly, field));
  const Backlog& last = run.backlogs.back();
  EXPECT_LE(last.frames_not_at_encoder, 1U);
  EXPECT_LE(last.frame_starts, 1U);
  EXPECT_LE(last.contentions, 2U);
  EXPECT_LE(last.start_bits_in_flight, 1U);
  EXPECT_LE(last.master_driven_changes, 2U);
  EXPECT_LE(last.findings_kept, 3U * checker::check::all().size());  // each row's first three
}
