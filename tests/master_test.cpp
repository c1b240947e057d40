#include <gtest/gtest.h>

#include "scenario_support.hpp"
#include "endatsim/master/functions.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/slave/encoder.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::count_ok;
using endatsim::test_support::count_violations;
using endatsim::test_support::make_scenario;

struct DelayCase {
  double cable_m;
  Hertz f_c;
  friend void PrintTo(const DelayCase& c, std::ostream* os) { *os << c.cable_m << " m, " << format_frequency(c.f_c); }
};

class DelayMeasurement : public ::testing::TestWithParam<DelayCase> {};

// 2.1.2: measured at 200 kHz, mean of three, within T/8 of the true round trip; reads then succeed.
TEST_P(DelayMeasurement, MeasuresTheRoundTripWithinAnEighthPeriodAndReadsCorrectly) {
  const auto [cable, f_c] = GetParam();
  const auto r = scenarios::run_scenario(make_scenario(cable, f_c, true));
  ASSERT_EQ(r.measurements.size(), 1U);
  const auto& m = r.measurements[0];
  ASSERT_TRUE(m.accepted) << m.reason;
  EXPECT_EQ(m.counts.size(), 3U);
  const Time error = m.t_d > r.true_round_trip ? m.t_d - r.true_round_trip : r.true_round_trip - m.t_d;
  EXPECT_LE(error, period_of(f_c) / 8) << "measured " << format_time(m.t_d) << ", true " << format_time(r.true_round_trip);
  EXPECT_EQ(count_ok(r), 3U);
  for (const auto& f : r.frames) {
    if (f.measurement) EXPECT_EQ(f.f_c, kHz(200));
    else EXPECT_EQ(f.position, 104462U);
  }
  EXPECT_EQ(count_violations(r, checker::check::kSamplingWindow), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kContention), 0U);
}

INSTANTIATE_TEST_SUITE_P(CableAndClock, DelayMeasurement,
                         ::testing::Values(DelayCase{0, MHz(1)}, DelayCase{0, MHz(16)}, DelayCase{10, MHz(2)},
                                           DelayCase{20, MHz(16)}, DelayCase{25, MHz(4)}, DelayCase{50, MHz(8)},
                                           DelayCase{75, MHz(1)}, DelayCase{100, MHz(8)}, DelayCase{100, MHz(2)},
                                           DelayCase{100, MHz(16)}),
                         [](const auto& param_info) {
                           return std::to_string(static_cast<int>(param_info.param.cable_m)) + "m_" +
                                  std::to_string(param_info.param.f_c / 1'000'000) + "MHz";
                         });

TEST(MasterFrame, ClockCountIsOneMoreThanTheLastBitByDefault) {
  // docs/model.md §5: 2.2, n = 25, s = 11 -> last bit at RE43, 44 pulses; 43 without the extra one.
  auto s = make_scenario(1, MHz(1), false, 1);
  auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_ok(r), 1U);
  EXPECT_EQ(r.frames[0].clocks, 44U);
  EXPECT_EQ(r.frames[0].start_bit_clock, 11U);
  s.master.extra_clock_after_last_bit = false;
  r = scenarios::run_scenario(s);
  ASSERT_EQ(count_ok(r), 1U);
  EXPECT_EQ(r.frames[0].clocks, 43U);
  EXPECT_EQ(r.frames[0].position, 104462U);
}

// 2.3: the master drives DATA from FE2 with a dummy 0, then M2 M1 M0 (M2) (M1) (M0) on FE3..FE8;
// the encoder takes each bit at the following rising edge, at its own pins.
TEST(MasterFrame, SendsDummyZeroAndModeBitsBeforeTheRisingEdges) {
  for (auto command : {protocol::ModeCommand::EncoderSendPositionValues,
                       protocol::ModeCommand::EncoderSendPositionValuesWithAdditionalData}) {
    Kernel k;
    line::LineParams lp;
    lp.cable_length_m = 50;
    line::Line l(k, lp);
    slave::Encoder e(k, l, {});
    master::MasterParams mp;
    mp.f_c = MHz(1);
    master::Master m(k, l, mp);
    struct Rec {
      line::Line::Pins pins;
      std::string bits;
      void on(std::uint64_t v) {
        if (v != 0 && bits.size() < 8) bits += pins.data.read() ? '1' : '0';
      }
    } rec{l.pins(line::ObservationPoint::EncoderPins), {}};
    rec.pins.clock.on_change(bind<&Rec::on>(&rec));
    master::Operation op;
    op.command = command;
    m.enqueue(op);
    m.start();
    k.run();
    std::string mode;
    for (int i = 5; i >= 0; --i) mode += ((protocol::info(command).bits >> i) & 1U) ? '1' : '0';
    // RE1 sees the undriven line (fail-safe HIGH) after the encoder released it at FE1.
    EXPECT_EQ(rec.bits, "10" + mode) << protocol::info(command).name;
    ASSERT_EQ(m.frames().size(), 1U);
    EXPECT_EQ(m.frames()[0].outcome, master::FrameOutcome::Ok);
  }
}

namespace {

// A master of its own on a short line, for the functions on top of the scheduler.
master::MasterParams at_1mhz() {
  master::MasterParams p;
  p.f_c = MHz(1);
  return p;
}

struct Bench {
  explicit Bench(const master::MasterParams& p = at_1mhz()) : m(k, l, p) {}
  // Runs one operation of this kind to its end.
  void run(master::Operation::Kind kind) {
    master::Operation op;
    op.kind = kind;
    m.enqueue(op);
    m.start();
    k.run();
  }
  Kernel k;
  line::Line l{k, {}};
  slave::Encoder e{k, l, {}};
  master::Master m;
};

// A function that owns one operation kind: it expands it into two position reads and counts what
// it sees, and asks once for word 1 of the operating status.
class Recorder final : public master::MasterFunction {
 public:
  master::Planned plan(const master::FunctionContext& ctx, master::Sequence& plan) override {
    if (ctx.operation.kind != master::Operation::Kind::DiagnosisSetup) return {};
    plan.frame(protocol::ModeCommand::EncoderSendPositionValues);
    plan.frame(protocol::ModeCommand::EncoderSendPositionValues);
    return {master::Planned::What::Expanded};
  }
  void on_frame(master::FrameResult& f, const master::FunctionContext& ctx) override {
    frames.push_back({f.command, ctx.operation.purpose});
  }
  std::optional<master::StatusRead> status_read_due() const override {
    if (asked) return std::nullopt;
    return master::StatusRead{protocol::word::kWarnings, master::Operation::Purpose::DiagnosisWarnings};
  }
  void status_read_planned() override { asked = true; }
  std::vector<std::pair<protocol::ModeCommand, master::Operation::Purpose>> frames;
  bool asked = false;
};

}  // namespace

// The scheduler knows its functions only through their interface: an operation it does not plan
// goes to them, every frame comes back to them, and the status word they ask for is read (after
// the expanded sequence, whose memory area selection it must not split: 2.4.1).
TEST(MasterFunctions, AFunctionPlansItsOperationSeesEveryFrameAndHasItsStatusWordRead) {
  Bench b;
  Recorder r;
  b.m.add_function(r);
  b.run(master::Operation::Kind::DiagnosisSetup);
  ASSERT_TRUE(b.m.finished());
  using MC = protocol::ModeCommand;
  using P = master::Operation::Purpose;
  const std::vector<std::pair<MC, P>> expected{{MC::EncoderSendPositionValues, P::None},
                                               {MC::EncoderSendPositionValues, P::None},
                                               {MC::SelectionOfMemoryArea, P::None},
                                               {MC::EncoderSendParameters, P::DiagnosisWarnings}};
  EXPECT_EQ(r.frames, expected);
  EXPECT_TRUE(r.asked);
}

TEST(MasterFunctions, AnOperationNoFunctionPlansIsRefusedNamingWhatAttachesThem) {
  Bench b;
  try {
    b.run(master::Operation::Kind::SafetyStartup);
    FAIL() << "a safety start-up without the safety functions ran";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "operation safety_startup: no function on this master plans it (master/functions.hpp attaches them)");
  }
}

// With MasterFunctions attached, the same operation runs: the safety start-up's position reads
// release the axis (and nothing but the functions' report says so).
TEST(MasterFunctions, TheStandardSetRunsTheSafetyStartUpAndReportsTheRelease) {
  master::MasterParams p = at_1mhz();
  p.safety.startup_positions = true;  // three agreeing values release the axis
  Bench with_safety(p);
  master::MasterFunctions functions(with_safety.m);
  with_safety.run(master::Operation::Kind::SafetyStartup);
  ASSERT_TRUE(with_safety.m.finished());
  EXPECT_TRUE(functions.safety().axis_released);
  EXPECT_EQ(functions.safety().startup_reads, 3U);
  EXPECT_EQ(with_safety.m.frame_count(), 3U);
}

TEST(MasterFrame, EnDat21FrameHas43Pulses) {
  auto s = make_scenario(1, MHz(1), false, 1);
  s.script.back().command = protocol::ModeCommand::EncoderSendPositionValues;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(count_ok(r), 1U);
  EXPECT_EQ(r.frames[0].clocks, 43U);
}

TEST(MasterFrame, WithoutCompensationShortCablesReadCleanly) {
  const auto r = scenarios::run_scenario(make_scenario(10, MHz(1), false, 5));
  EXPECT_EQ(count_ok(r), 5U);
  EXPECT_TRUE(r.violations.empty());
}

TEST(MasterFrame, NoStartBitTimesOutAndTheNextReadWorks) {
  auto s = make_scenario(1, MHz(1), false, 1);
  s.encoder.type1 = slave::Type1Handling::NoStartBit;
  s.master.start_bit_timeout = us(200);
  test_support::prepend_disturbed_read(s, 0b000101);
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 2U);
  EXPECT_EQ(r.frames[0].outcome, master::FrameOutcome::NoStartBit);
  EXPECT_GE(r.frames[0].end - r.frames[0].start, us(200));
  EXPECT_EQ(r.frames[1].outcome, master::FrameOutcome::Ok);
  // A2: after an error handling the master waits the maximum t_m (30 us) before the next command.
  EXPECT_GE(r.frames[1].start - r.frames[0].end, us(30));
}

TEST(MasterFrame, MovingAxisPositionsAreTheOnesLatchedAtFE1) {
  auto s = make_scenario(30, MHz(4), true, 20);
  s.encoder.motion.counts_per_s = 1'234'567;
  s.expect.positions_match_encoder = true;
  const auto r = scenarios::run_scenario(s);
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(count_ok(r), 20U);
  EXPECT_NE(r.frames.back().position, r.frames[3].position);
}

TEST(MasterJitter, SeededJitterMovesEdgesButReadsStayCorrect) {
  auto s = make_scenario(10, MHz(1), false, 10);
  s.master.jitter = ns(20);
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count_ok(r), 10U);
  EXPECT_NE((r.frames[1].end - r.frames[1].start), (r.frames[2].end - r.frames[2].start));
}

TEST(MasterParams, RejectsClockOutsideTheModelNamingTheLimit) {
  master::MasterParams p;
  p.f_c = MHz(20);
  try {
    p.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("16 MHz"), std::string::npos) << e.what();
  }
  p.f_c = kHz(50);
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p.f_c = MHz(1);
  p.jitter = us(1);
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

namespace {

struct CableSwap {
  line::Line* line;
  void go() { line->set_cable(60, ns(5)); }
};

struct MeasurementBench {
  explicit MeasurementBench(unsigned max_rounds) : line(k, line_params()), encoder(k, line, {}), master(k, line, params(max_rounds)) {}
  static line::LineParams line_params() {
    line::LineParams p;
    p.cable_length_m = 10;
    return p;
  }
  static master::MasterParams params(unsigned max_rounds) {
    master::MasterParams p;
    p.f_c = MHz(8);
    p.delay_compensation = true;
    p.t_st = us(2);
    p.measurement.f_e = MHz(64);
    p.measurement.max_rounds = max_rounds;
    return p;
  }
  void run_with_swap_after_first_frame() {
    master.enqueue({master::Operation::Kind::MeasureDelay, {}, {}, {}, 1, {}, {}, 0});
    master.start();
    // The first 200 kHz frame ends after ~215 us; the next begins ~30.5 us later.
    CableSwap swap{&line};
    k.schedule(us(235), sim::bind<&CableSwap::go>(&swap));
    k.run();
  }
  Kernel k;
  line::Line line;
  slave::Encoder encoder;
  master::Master master;
};

}  // namespace

// The part on its own (master/delay_measurement.hpp): where a measurement round began.
TEST(MasterDelayMeasurement, ARoundBeginsAtTheStartOfItsFirstFrame) {
  master::DelayMeasurementParams p;
  p.count = 3;
  master::DelayMeasurement m(p, sim::MHz(8));
  m.frame_recorded(sim::us(10));
  m.frame_recorded(sim::us(20));
  EXPECT_EQ(m.round_start(sim::us(99)), sim::us(99));  // fewer frames than a round
  m.frame_recorded(sim::us(30));
  EXPECT_EQ(m.round_start(sim::us(99)), sim::us(10));
  m.frame_recorded(sim::us(40));
  EXPECT_EQ(m.round_start(sim::us(99)), sim::us(20));
}

TEST(MasterDelayMeasurement, AValueFartherThanAnEighthPeriodFromTheMeanIsRejectedAndRemeasured) {
  MeasurementBench b(3);
  b.run_with_swap_after_first_frame();
  const auto& m = b.master.measurements();
  ASSERT_EQ(m.size(), 2U);
  EXPECT_FALSE(m[0].accepted);
  EXPECT_NE(m[0].reason.find("deviates"), std::string::npos) << m[0].reason;
  EXPECT_NE(m[0].reason.find("T/8 = 15.625 ns"), std::string::npos) << m[0].reason;
  EXPECT_TRUE(m[1].accepted);
  ASSERT_TRUE(b.master.t_d().has_value());
  const Time truth = b.line.round_trip(b.encoder.params().output_delay);
  EXPECT_EQ(truth, ns(800));
  EXPECT_LE(*b.master.t_d() > truth ? *b.master.t_d() - truth : truth - *b.master.t_d(), period_of(MHz(8)) / 8);
}

TEST(MasterDelayMeasurement, WithoutFurtherRoundsTheMasterStaysUncompensated) {
  MeasurementBench b(1);
  b.run_with_swap_after_first_frame();
  ASSERT_EQ(b.master.measurements().size(), 1U);
  EXPECT_FALSE(b.master.measurements()[0].accepted);
  EXPECT_FALSE(b.master.t_d().has_value());
}

TEST(MasterContinuousClock, ReadsEveryWordOfAContinuousClock) {
  auto s = make_scenario(10, MHz(1), false, 1);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.encoder.motion.counts_per_s = 1'000'000;
  s.script.back().command = protocol::ModeCommand::EncoderSendPositionValues;
  s.script.back().continuous_words = 3;
  s.expect.positions_match_encoder = true;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 4U);
  EXPECT_TRUE(r.passed());
  for (unsigned w = 0; w < 4; ++w) {
    EXPECT_EQ(r.frames[w].word, w);
    EXPECT_EQ(r.frames[w].outcome, master::FrameOutcome::Ok);
  }
  // 1 HIGH + 1 LOW + S + F1 + 25 + 5 = 34 clocks per word at 1 MHz: 34 counts apart.
  EXPECT_EQ(r.frames[2].position - r.frames[1].position, 34U);
  EXPECT_EQ(r.encoder_frames.at(0).continuous_words, 3U);
}

class ContinuousClockVariants : public ::testing::TestWithParam<std::pair<bool, bool>> {};

// Regression: with compensation (t_D > T/2) or without the extra pulse, the last bit of a word
// is taken after the word's last rising edge; the clock must still run on to the next word.
TEST_P(ContinuousClockVariants, EveryWordArrivesWithCompensationAndWithoutTheExtraPulse) {
  const auto [compensated, extra_clock] = GetParam();
  auto s = make_scenario(100, MHz(2), compensated, 2);
  if (!compensated) s.line.cable_length_m = 10, s.master.f_c = MHz(1);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.encoder.motion.counts_per_s = 100'000;
  s.master.extra_clock_after_last_bit = extra_clock;
  s.script.back().command = protocol::ModeCommand::EncoderSendPositionValues;
  s.script.back().continuous_words = 3;
  s.script.back().cycle = ms(1);
  s.expect.positions_match_encoder = true;
  const auto r = scenarios::run_scenario(s);
  EXPECT_TRUE(r.finished);
  EXPECT_EQ(count_ok(r), 8U);
  EXPECT_TRUE(r.passed());
}

INSTANTIATE_TEST_SUITE_P(CompensationAndExtraClock, ContinuousClockVariants,
                         ::testing::Values(std::pair{true, true}, std::pair{true, false}, std::pair{false, false}));
