#include <gtest/gtest.h>

#include "scenario_support.hpp"

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
      EXPECT_EQ(v.limit, ">= 20.5 us");
    }
}

TEST(CheckerSamplingWindow, CatchesAMissingDelayCompensation) {
  auto s = make_scenario(100, MHz(2), false, 2);
  s.master.start_bit_detection = master::StartBitDetection::FirstHigh;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 2U);
  EXPECT_EQ(r.violations.front().where, line::ObservationPoint::MasterPins);
}

TEST(CheckerSamplingWindow, ACarefulMasterWithoutCompensationStillSamplesOutsideTheWindow) {
  // It finds the start bit two slots late and reads consistently shifted bits: the data are
  // right by luck of the phase, but every sample is taken outside the bit the master means.
  const auto r = scenarios::run_scenario(make_scenario(100, MHz(2), false, 2));
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 2U);
}

TEST(CheckerContention, MissingTstOnALongCableMakesBothDriversCollide) {
  auto s = make_scenario(100, MHz(8), true, 1);
  s.master.t_st = Time::zero();
  const auto r = scenarios::run_scenario(s);
  EXPECT_GE(count_violations(r, checker::check::kContention), 1U);
}

TEST(CheckerMeasurementClock, DelayMeasuredAt1MHzIsReported) {
  auto s = make_scenario(10, MHz(2), true, 1);
  s.master.measurement.f_c = MHz(1);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementClock), 3U);
}

TEST(CheckerClockFrequency, EdgeJitterAtTheLimitIsNotAViolation) {
  auto s = make_scenario(1, MHz(2), false, 20);
  s.master.jitter = ns(5);
  const auto r = scenarios::run_scenario(s);
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
