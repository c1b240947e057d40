// The checker with a continuous clock (2.3.1): t_D and its tolerance judged for every word at
// their limits, a later word's start bit against 2.3.1.1's "maximum of 7 Low Bits" (in place of
// t_cal, whose minimum belongs to the mode command), and t_z / t_OE only at the mode command,
// where DATA changes direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/checker/checker.hpp"
#include "endatsim/protocol/frame.hpp"
#include "scenario_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using MC = protocol::ModeCommand;
using test_support::count_violations;
using test_support::make_scenario;

namespace {

// An EnDat 2.1 encoder read with "Encoder send position values" and `words` words in all.
scenarios::Scenario continuous_reads(double cable_m, Hertz f_c, bool compensated, unsigned words) {
  auto s = make_scenario(cable_m, f_c, compensated, 1);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.script.back().command = MC::EncoderSendPositionValues;
  s.script.back().continuous_words = words - 1;
  return s;
}

std::vector<checker::Violation> of(const scenarios::ScenarioResult& r, std::string_view check) {
  std::vector<checker::Violation> v;
  std::copy_if(r.violations.begin(), r.violations.end(), std::back_inserter(v),
               [&](const auto& x) { return x.check == check; });
  return v;
}

// An encoder written out by hand from 2.3.1.1 (Figure 15) and docs/model.md §6 for "Encoder send
// position values" with a continuous clock: DATA released at FE1, driven LOW from FE9, the first
// start bit on RE11, and after each word's CRC one HIGH bit, `low_bits` LOW bits and the next
// word, each level `output_delay` after the rising edge reached its logic, as the encoder model
// does. Unlike the model (which refuses more than 7, 2.3.1.1) it inserts as many LOW bits as
// asked, and with `release_in_gap` its driver is off during them.
class HandWrittenEncoder {
 public:
  HandWrittenEncoder(Kernel& k, line::Line& line, const slave::EncoderParams& p, unsigned words, unsigned low_bits,
                     bool release_in_gap)
      : k_(k), pins_(line.encoder()), delay_(p.output_delay) {
    const auto word = protocol::encode_position_frame(protocol::EndatVersion::V2_1, p.position_bits,
                                                      {false, true, p.motion.start});
    for (unsigned w = 0; w < words; ++w) {
      if (w != 0) {
        plan_.push_back(kHigh);
        plan_.insert(plan_.end(), low_bits, release_in_gap ? kReleased : kLow);
      }
      for (auto bit : word) plan_.push_back(bit != 0 ? kHigh : kLow);
    }
    plan_.push_back(kHigh);  // end of data (docs/model.md §2)
    drive(kLow);             // idle: DATA driven LOW (docs/model.md §2)
    pins_.clock_in.on_change(bind<&HandWrittenEncoder::on_clock>(this));
  }

 private:
  static constexpr std::uint64_t kLow = 0, kHigh = 1, kReleased = 2;
  static constexpr unsigned kFirstAnswerClock = 11;  // docs/model.md §1

  void on_clock(std::uint64_t level) {
    if (level == 0) {
      ++falling_;
      if (falling_ == 1) k_.schedule(delay_, bind<&HandWrittenEncoder::drive>(this, kReleased));
      if (falling_ == 9) k_.schedule(delay_, bind<&HandWrittenEncoder::drive>(this, kLow));
      return;
    }
    ++rising_;
    if (rising_ < kFirstAnswerClock) return;
    const std::size_t slot = rising_ - kFirstAnswerClock;
    k_.schedule(delay_, bind<&HandWrittenEncoder::drive>(this, slot < plan_.size() ? plan_[slot] : kHigh));
  }
  void drive(std::uint64_t what) {
    pins_.data_enable.write(what != kReleased);
    if (what != kReleased) pins_.data_out.write(what == kHigh);
  }

  Kernel& k_;
  line::Line::EncoderSide pins_;
  Time delay_;
  std::vector<std::uint64_t> plan_;
  unsigned falling_ = 0;
  unsigned rising_ = 0;
};

struct HandRun {
  std::vector<master::FrameResult> frames;
  std::vector<checker::Violation> violations;
  std::size_t count(std::string_view check) const {
    return static_cast<std::size_t>(
        std::count_if(violations.begin(), violations.end(), [&](const auto& v) { return v.check == check; }));
  }
};

// One read of `words` words at 1 MHz over 10 m from the hand-written encoder, checked.
HandRun run_hand_written(unsigned words, unsigned low_bits, bool release_in_gap = false) {
  const auto s = continuous_reads(10, MHz(1), false, words);
  Kernel kernel;
  line::Line line(kernel, s.line);
  HandWrittenEncoder encoder(kernel, line, s.encoder, words, low_bits, release_in_gap);
  master::Master master(kernel, line, s.master);
  checker::TimingChecker checker(kernel, line, scenarios::declared_encoder(s.encoder), scenarios::declared_master(s.master),
                                 s.checker);
  scenarios::MasterDeclarations declarations(checker);
  master.add_observer(&declarations);
  for (const auto& op : s.script) master.enqueue(op);
  master.start();
  kernel.run(ms(1));
  checker.finish();
  return {master.frames(), checker.violations()};
}

}  // namespace

TEST(CheckerContinuousClock, DataDelayOfEveryWordAtTheBoundByOnePicosecond) {
  // 2.3.2 t_D <= 0.2 + 0.01 x 10 = 0.3 us: the default line and encoder sit exactly on the bound.
  auto s = continuous_reads(10, MHz(1), false, 5);
  auto r = scenarios::run_scenario(s);
  ASSERT_EQ(test_support::count_ok(r), 5U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelay), 0U);
  s.encoder.output_delay += ps(1);
  r = scenarios::run_scenario(s);
  EXPECT_EQ(test_support::count_ok(r), 5U);
  const auto t_d = of(r, checker::check::kDataDelay);
  ASSERT_EQ(t_d.size(), 5U) << "one per word, not one per mode command";
  // 32 bits a word (S F1 25 CRC), a HIGH and a LOW bit: start bits on RE11, RE45, RE79 ...
  for (std::size_t w = 0; w < t_d.size(); ++w) {
    EXPECT_EQ(t_d[w].frame, w) << "each word is reported as the master numbers it";
    EXPECT_EQ(t_d[w].clock, 11U + 34U * w);
    EXPECT_EQ(t_d[w].measured, "300.001 ns");
    EXPECT_EQ(t_d[w].limit, "<= 300 ns");
  }
}

TEST(CheckerContinuousClock, DataDelayOfALaterWordIsNotTakenFromTheHighBitStillOnTheCable) {
  // 8 MHz over 100 m with compensation: the round trip (1.2 us) is almost ten bit slots, so the
  // HIGH bit after a word's CRC is still on the cable when the next start bit leaves the encoder.
  auto s = continuous_reads(100, MHz(8), true, 4);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(test_support::count_ok(r), 4U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelay), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelayTolerance), 0U);
  s.encoder.output_delay += ps(1);
  EXPECT_EQ(count_violations(scenarios::run_scenario(s), checker::check::kDataDelay), 4U + 3U)
      << "four words and the three measurement frames";
}

TEST(CheckerContinuousClock, DelayToleranceOfEveryWordByOnePicosecond) {
  // 2.3: a compensating master's t_D within a tenth of the period: 50 ns at 2 MHz around the
  // line's 300 ns.
  auto s = continuous_reads(10, MHz(2), true, 3);
  s.script.erase(s.script.begin());  // compensates with a value set by hand
  s.master.fixed_t_d = ns(350);
  auto r = scenarios::run_scenario(s);
  ASSERT_EQ(test_support::count_ok(r), 3U);
  EXPECT_EQ(count_violations(r, checker::check::kDataDelayTolerance), 0U);
  s.master.fixed_t_d = ns(350) + ps(1);
  r = scenarios::run_scenario(s);
  EXPECT_EQ(test_support::count_ok(r), 3U);
  const auto tolerance = of(r, checker::check::kDataDelayTolerance);
  ASSERT_EQ(tolerance.size(), 3U);
  for (const auto& v : tolerance) EXPECT_EQ(v.measured, "50.001 ns");
}

TEST(CheckerContinuousClock, LaterWordsNeedNoCalculationTimeButAtMostSevenLowBits) {
  // 2.3.1.1: "Independently of the t_CAL, a maximum of 7 Low Bits are inserted." The encoder
  // model's later words come after one LOW bit (34 slots apart, far less than t_cal's minimum
  // 10.5 periods after a mode command) and after seven.
  for (unsigned low_bits : {1U, 7U}) {
    auto s = continuous_reads(10, MHz(1), false, 4);
    s.encoder.continuous_low_bits = low_bits;
    const auto r = scenarios::run_scenario(s);
    EXPECT_EQ(test_support::count_ok(r), 4U) << low_bits;
    EXPECT_EQ(count_violations(r, checker::check::kCalculationTime), 0U) << low_bits;
  }
}

TEST(CheckerContinuousClock, EightLowBitsBeforeALaterWordAreOneTooMany) {
  const auto inside = run_hand_written(3, 7);
  ASSERT_EQ(inside.frames.size(), 3U);
  for (const auto& f : inside.frames) EXPECT_EQ(f.outcome, master::FrameOutcome::Ok);
  EXPECT_TRUE(inside.violations.empty()) << inside.violations.front().check << ": " << inside.violations.front().message;

  const auto outside = run_hand_written(3, 8);
  ASSERT_EQ(outside.frames.size(), 3U);
  for (const auto& f : outside.frames) EXPECT_EQ(f.outcome, master::FrameOutcome::Ok) << "the master still finds them";
  ASSERT_EQ(outside.count(checker::check::kCalculationTime), 2U);
  unsigned clock = 11;
  for (const auto& v : outside.violations) {
    ASSERT_EQ(v.check, checker::check::kCalculationTime) << v.message;
    clock += 32 + 1 + 8;  // the previous word, its HIGH bit, eight LOW bits
    EXPECT_EQ(v.clock, clock);
    EXPECT_EQ(v.frame, (clock - 11) / 41);
    EXPECT_EQ(v.measured, "8 LOW bits");
    EXPECT_EQ(v.limit, "<= 7 LOW bits");
    EXPECT_NE(v.spec.find("2.3.1.1"), std::string::npos);
  }
}

TEST(CheckerContinuousClock, DriverRowsBelongToTheModeCommandOnly) {
  // t_z and t_OE at one period of an 8 MHz clock, just outside (as CheckerDriverTimes): reported
  // once for the frame's turnarounds, not for each of its five words, which have none.
  auto s = continuous_reads(1, MHz(8), true, 5);
  s.checker.t_z_per_frame_period = true;
  s.encoder.output_delay = ns(85) + ps(1);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(test_support::count_ok(r), 5U);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOff), 1U);
  EXPECT_EQ(count_violations(r, checker::check::kDriverOn), 1U);
}

TEST(CheckerContinuousClock, ADriverThatGoesOffBetweenWordsLeavesDataFloating) {
  // No turnaround between words: an encoder that releases DATA for the LOW bits is no t_z or
  // t_OE matter but leaves the master sampling the fail-safe level.
  const auto r = run_hand_written(3, 2, true);
  EXPECT_GE(r.count(checker::check::kFloatingData), 1U);
  EXPECT_EQ(r.count(checker::check::kDriverOff), 0U);
  EXPECT_EQ(r.count(checker::check::kDriverOn), 0U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kFloatingData) {
      EXPECT_EQ(v.where, line::ObservationPoint::MasterPins);
      EXPECT_GT(v.clock.value_or(0), 43U) << "after the first word";
    }
}

TEST(CheckerContinuousClock, EveryWordIsJudgedOnItsOwn) {
  // 2 MHz over 40 m without compensation: t_D 0.6 us > T/2, every word is sampled off-window.
  auto s = make_scenario(40, MHz(2), false, 1);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.script.back().command = protocol::ModeCommand::EncoderSendPositionValues;
  s.script.back().continuous_words = 4;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 5U);
}
