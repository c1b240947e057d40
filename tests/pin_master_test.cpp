// Masters that only drive pins, written here edge by edge from the spec (no master model, no
// declarations to the checker): the checker must find their frames on the wires and judge every
// row that needs nothing but wires. Each defective master breaks one rule and is caught by that
// rule's row; the same master without the defect draws no violation. Every run is recorded to a
// VCD too, and `check` of that capture must break the same rows as often as the live run did:
// at the encoder's connector every row observable there, at the master's the round trip's.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include "capture_support.hpp"
#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/scenarios/waveform_names.hpp"
#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/sim/vcd.hpp"
#include "endatsim/slave/encoder.hpp"
#include "test_support.hpp"

namespace {

using namespace endatsim;
using namespace endatsim::sim;
using test_support::bits_msb;
namespace position = protocol::frame_position;

// One frame of a pin-driving master: FE1 at `start` (master logic), the first LOW phase `t_st`
// (0: half a period), then `clocks` pulses of period 1/f_c; on FE_k the DATA driver does what
// drive[k-1] says ('0'/'1' drive, anything else release); the last rising edge releases DATA.
struct PinFrame {
  Time start;
  Hertz f_c;
  unsigned clocks;
  std::string drive;
  Time t_st{0};
};

// "-0" then six mode bits (M2 first), then a 2.1 payload: the master's part of a frame (2.3).
std::string header(std::uint8_t mode_bits, const std::string& payload = "") {
  return "-0" + bits_msb(mode_bits, 6) + payload;
}

class PinMaster {
 public:
  PinMaster(Kernel& k, line::Line& line, const std::vector<PinFrame>& frames)
      : k_(k), m_(line.master()), timer_(k, sim::bind<&PinMaster::step>(this)) {
    for (const auto& f : frames) {
      const Time half = period_of(f.f_c) / 2;
      Time t = f.start;
      for (unsigned n = 1; n <= f.clocks; ++n) {
        const char c = n <= f.drive.size() ? f.drive[n - 1] : '-';
        edges_.push_back({t, false, c});
        t += n == 1 && f.t_st > Time::zero() ? f.t_st : half;
        edges_.push_back({t, true, n == f.clocks ? 'r' : ' '});  // 'r': DATA released with the last edge
        t += half;
      }
    }
    std::stable_sort(edges_.begin(), edges_.end(), [](const Edge& a, const Edge& b) { return a.at < b.at; });
    if (!edges_.empty()) timer_.start(edges_.front().at - k.now());
  }

 private:
  struct Edge {
    Time at;
    bool clock;
    char drive;
  };
  void step() {
    const Edge e = edges_[next_++];
    if (!e.clock) sampled_ += m_.data_in.read() ? '1' : '0';  // this master samples on its falling edges
    m_.clock_out.write(e.clock);
    if (e.drive == 'r') m_.data_enable.write(false);
    if (!e.clock) {
      m_.data_enable.write(e.drive == '0' || e.drive == '1');
      if (e.drive == '0' || e.drive == '1') m_.data_out.write(e.drive == '1');
    }
    if (next_ < edges_.size()) timer_.start(edges_[next_].at - k_.now());
  }

 public:
  // DATA at the master's logic at each of its falling edges, every frame's in a row.
  const std::string& sampled() const { return sampled_; }

 private:
  std::string sampled_;
  Kernel& k_;
  line::Line::MasterSide m_;
  Timer timer_;
  std::vector<Edge> edges_;
  std::size_t next_ = 0;
};

constexpr std::uint8_t k21Position = 0b000111;  // "Encoder send position values" (2.3.1)
constexpr std::uint8_t k22Position = 0b111000;  // "... with additional data" (2.3.1)
constexpr std::uint8_t k21SendParameter = 0b100011;     // "Encoder send parameters" (2.5)
constexpr std::uint8_t k21SelectMemoryArea = 0b001110;  // "Selection of memory area" (2.4.1)

struct Run {
  std::vector<checker::Violation> violations;
  std::vector<checker::RowConformance> conformance;
  bool from_wires = false;
  // DATA at each falling edge: at the master's logic, what the master sampled; at the encoder's
  // pins, what the encoder had put out by then (the bit of the slot).
  std::string sampled;
  std::string sent;
  const checker::RowConformance& row(std::string_view check) const {
    return *std::find_if(conformance.begin(), conformance.end(), [&](const auto& c) { return c.check == check; });
  }
  std::size_t count(std::string_view check) const {
    return static_cast<std::size_t>(std::count_if(violations.begin(), violations.end(),
                                                  [&](const auto& v) { return v.check == check; }));
  }
  std::string list() const {
    std::string s;
    for (const auto& v : violations) s += v.check + " " + v.measured + " (" + v.limit + "): " + v.message + "\n";
    return s;
  }
};

// The cable's delay changes between frames: at each `at`, to this delay (in metres of 1 ns).
struct CableChange {
  Time at;
  Time delay;
};

// The capture of a live run, checked at the encoder's connector (with its driver enable) and at
// the master's (the round trip's rows); both must find what the live checker found.
void expect_capture_agrees(const std::filesystem::path& vcd, const Run& live, const slave::EncoderParams& encoder,
                           const line::LineParams& lp, const checker::CheckerParams& params) {
  scenarios::CaptureCheckOptions at_encoder;
  at_encoder.file = vcd.string();
  at_encoder.clock = "encoder_clock";
  at_encoder.data = "encoder_data";
  at_encoder.data_enable = "encoder_data_driver_enable";
  at_encoder.encoder = scenarios::declared_encoder(encoder);
  at_encoder.encoder.output_delay = lp.encoder.receiver_delay + encoder.output_delay + lp.encoder.driver_delay;
  at_encoder.checker = params;
  at_encoder.cable_m = lp.cable_length_m;
  const auto e = scenarios::check_capture(at_encoder);
  EXPECT_EQ(test_support::wire_rows(e.violations, e.conformance), test_support::wire_rows(live.violations, e.conformance))
      << "the capture at the encoder's connector";

  auto at_master = at_encoder;
  at_master.at = scenarios::CaptureCheckOptions::At::Master;
  at_master.clock = "master_clock";
  at_master.data = "master_data";
  at_master.data_enable.reset();
  // The round trip between the master's pins, as a user who knows the line gives it (--t-d):
  // without it or a measurement in the capture, compensated frames' start-bit rows are undecided.
  at_master.t_d = at_encoder.encoder.output_delay + 2 * lp.cable_delay();
  const auto m = scenarios::check_capture(at_master);
  const auto round_trip_rows = [&](const std::vector<checker::Violation>& v) {
    auto rows = test_support::wire_rows(v, m.conformance);
    std::erase_if(rows, [](const auto& r) {
      return r.first != checker::check::kDataDelay && r.first != checker::check::kMeasurementSpread;
    });
    return rows;
  };
  EXPECT_EQ(round_trip_rows(m.violations), round_trip_rows(live.violations)) << "the capture at the master's connector";
}

Run run(const std::vector<PinFrame>& frames, slave::EncoderParams encoder = {}, double cable_m = 1, Time until = ms(2),
        const checker::CheckerParams& params = {}, const std::vector<CableChange>& cable_changes = {}) {
  static unsigned runs = 0;
  const auto vcd = std::filesystem::temp_directory_path() /
                   ("endatsim_pin_master_" + std::to_string(::getpid()) + "_" + std::to_string(++runs) + ".vcd");
  Kernel k;
  line::LineParams lp;
  lp.cable_length_m = cable_m;
  line::Line line(k, lp);
  slave::Encoder e(k, line, encoder);
  checker::TimingChecker checker(k, line, scenarios::declared_encoder(encoder), {}, params);
  PinMaster m(k, line, frames);
  test_support::PinSampler at_encoder(k, line);
  sim::VcdWriter recording(k, vcd.string());
  scenarios::add_pin_waves(recording, line);
  recording.start();
  for (const auto& change : cable_changes) {
    k.run(change.at);
    line.set_cable(static_cast<double>(change.delay.count()) / 1000, ns(1));
  }
  k.run(until);
  checker.finish();
  recording.finish();
  Run live{checker.violations(), checker.conformance(), checker.judged_from_wires(), m.sampled(),
           at_encoder.slots(0, UINT32_MAX - 1)};
  // The capture knows the line as it was at the end; a capture with the cable changing under it
  // is judged at the master's connector only through the round trip it shows.
  lp.cable_length_m = line.params().cable_length_m;
  expect_capture_agrees(vcd, live, encoder, lp, params);
  std::filesystem::remove(vcd);
  return live;
}

slave::EncoderParams quick_encoder() {
  slave::EncoderParams p;
  p.t_cal = us(1);  // the start bit on RE11 at 1 MHz and above
  return p;
}

// 2.1 position reads at 1 MHz: start bit on RE11, 32 answer bits (S F1 25 position bits CRC),
// one more pulse for the HIGH end.
std::vector<PinFrame> position_reads_21(unsigned n, Time cycle, unsigned clocks = 11 + 32) {
  std::vector<PinFrame> out;
  for (unsigned i = 0; i < n; ++i) out.push_back({us(10) + cycle * i, MHz(1), clocks, header(k21Position)});
  return out;
}

// 2.2 position reads: 33 answer bits (S F1 F2 25 bits CRC), no additional data selected.
std::vector<PinFrame> position_reads_22(unsigned n, Time cycle, Hertz f_c, Time t_st, unsigned clocks = 11 + 33) {
  std::vector<PinFrame> out;
  for (unsigned i = 0; i < n; ++i) out.push_back({us(10) + cycle * i, f_c, clocks, header(k22Position), t_st});
  return out;
}

TEST(PinMaster, ACleanMasterDrawsNoViolationAndIsJudgedFromTheWires) {
  const auto r = run(position_reads_21(5, us(100)), quick_encoder());
  EXPECT_TRUE(r.from_wires);
  EXPECT_TRUE(r.violations.empty()) << r.list();
}

// The conformance table: every row of the timing table, judged (how often) or why not.
TEST(PinMaster, TheConformanceTableSaysWhatWasJudgedAndWhatCouldNotBe) {
  using S = checker::RowConformance::Status;
  const auto r = run(position_reads_21(5, us(100)), quick_encoder());
  EXPECT_EQ(r.conformance.size(), protocol::timing_rows().size());
  EXPECT_EQ(r.row(checker::check::kClockFrequency).status, S::Judged);
  EXPECT_EQ(r.row(checker::check::kClockFrequency).judged, 5U);
  EXPECT_EQ(r.row(checker::check::kClockFrequency).violations, 0U);
  EXPECT_EQ(r.row(checker::check::kRecovery).judged, 4U);  // between five frames
  EXPECT_EQ(r.row(checker::check::kSamplingWindow).status, S::NotObservable);
  EXPECT_EQ(r.row(checker::check::kTimeBetweenCycles).status, S::NotApplicable);  // no 2.1 parameter frame
  const auto broken = run(position_reads_22(3, us(100), MHz(16), ns(400)), quick_encoder(), 10);
  EXPECT_EQ(broken.row(checker::check::kStartDelay).judged, 3U);
  EXPECT_EQ(broken.row(checker::check::kStartDelay).violations, 3U);
  EXPECT_EQ(broken.row(checker::check::kClockFrequency).warnings, 3U);
}

// Each judged row shows its worst case and the margin to its limit, also when it passes: t_ST
// exactly at note 8's 1 us is inside by 0 ps, one picosecond less is outside by 1 ps.
TEST(PinMaster, TheConformanceTableShowsEachRowsWorstValueAndItsMargin) {
  const auto exact = run(position_reads_22(3, us(100), MHz(16), us(1)), quick_encoder(), 10);
  const auto& t_st = exact.row(checker::check::kStartDelay);
  ASSERT_EQ(t_st.worst.size(), 1U);
  EXPECT_EQ(t_st.worst[0].of, checker::LimitOf::Spec);
  EXPECT_EQ(t_st.worst[0].measured, "1 us");
  EXPECT_EQ(t_st.worst[0].limit, ">= 1 us");
  EXPECT_EQ(t_st.worst[0].margin, "0 ps");
  EXPECT_TRUE(t_st.worst[0].inside);
  const auto short_by_1ps = run(position_reads_22(3, us(100), MHz(16), us(1) - ps(1)), quick_encoder(), 10);
  const auto& broken = short_by_1ps.row(checker::check::kStartDelay);
  ASSERT_EQ(broken.worst.size(), 1U);
  EXPECT_EQ(broken.worst[0].margin, "-1 ps");
  EXPECT_FALSE(broken.worst[0].inside);
  // The waits between frames count against both limits: the envelope's t_m 30 us + t_R 500 ns and
  // this encoder's; 100 us between frames leaves a margin to each.
  const auto& recovery = exact.row(checker::check::kRecovery);
  ASSERT_EQ(recovery.worst.size(), 2U);
  EXPECT_EQ(recovery.worst[0].limit, ">= 30.5 us");
  EXPECT_EQ(recovery.worst[1].of, checker::LimitOf::ThisEncoder);
  EXPECT_TRUE(recovery.worst[0].inside);
  // Rows judged on frequency and counts show hertz and clocks; rows that were not judged, nothing.
  EXPECT_NE(exact.row(checker::check::kClockFrequency).worst.at(0).measured.find("MHz"), std::string::npos);
  EXPECT_NE(exact.row(checker::check::kClockCount).worst.at(0).limit.find("clocks"), std::string::npos);
  EXPECT_TRUE(exact.row(checker::check::kTimeBetweenCycles).worst.empty());
}

TEST(PinMaster, ACleanSixteenMegahertzMasterWithOneMicrosecondTstIsClean) {
  const auto r = run(position_reads_22(5, us(100), MHz(16), us(1)), quick_encoder(), 10);
  EXPECT_EQ(r.count(checker::check::kClockFrequency), 5U) << "16 MHz is only a warning (special applications)";
  for (const auto& v : r.violations) EXPECT_EQ(v.severity, checker::Severity::Warning) << r.list();
}

TEST(PinMaster, AStartDelayTooShortAtSixteenMegahertzIsCaught) {
  const auto r = run(position_reads_22(3, us(100), MHz(16), ns(400)), quick_encoder(), 10);
  EXPECT_EQ(r.count(checker::check::kStartDelay), 3U) << r.list();
}

// 2.3.2 note 8 at 16 MHz: 1 us, to the picosecond, whatever the cable.
TEST(PinMaster, StartDelayAtSixteenMegahertzIsOneMicrosecondToThePicosecond) {
  EXPECT_EQ(run(position_reads_22(1, us(100), MHz(16), us(1)), quick_encoder(), 10).count(checker::check::kStartDelay), 0U);
  const auto r = run(position_reads_22(1, us(100), MHz(16), us(1) - ps(1)), quick_encoder(), 10);
  ASSERT_EQ(r.count(checker::check::kStartDelay), 1U) << r.list();
  for (const auto& v : r.violations)
    if (v.check == checker::check::kStartDelay) {
      EXPECT_EQ(v.limit, ">= 1 us");
      EXPECT_EQ(v.spec, "2.3.2 t_ST and note 8");
    }
}

// "Can be reduced with a shorter cable" only through the named option, which the finding names.
TEST(PinMaster, AShorterStartDelayForAShortCableOnlyWithTheNamedOption) {
  checker::CheckerParams reduced;
  reduced.t_st_reduced_for_cable = true;
  const auto frames = position_reads_22(1, us(100), MHz(16), ns(250));  // 1 us x (0.2 + 0.1) / 1.2 on 10 m
  EXPECT_EQ(run(frames, quick_encoder(), 10).count(checker::check::kStartDelay), 1U);
  EXPECT_EQ(run(frames, quick_encoder(), 10, ms(2), reduced).count(checker::check::kStartDelay), 0U);
  const auto r = run(position_reads_22(1, us(100), MHz(16), ns(250) - ps(1)), quick_encoder(), 10, ms(2), reduced);
  ASSERT_EQ(r.count(checker::check::kStartDelay), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kStartDelay) {
      EXPECT_NE(v.spec.find("t_st_reduced_for_cable"), std::string::npos) << v.spec;
    }
  // The conformance table names the option on t_ST's row, and only there, so every report says so.
  EXPECT_NE(r.row(checker::check::kStartDelay).relaxed_by.find("t_st_reduced_for_cable"), std::string::npos);
  for (const auto& c : r.conformance)
    if (c.check != checker::check::kStartDelay) {
      EXPECT_EQ(c.relaxed_by, "") << c.check;
    }
  for (const auto& c : run(frames, quick_encoder(), 10).conformance) EXPECT_EQ(c.relaxed_by, "") << c.check;
}

TEST(PinMaster, NoRecoveryWaitIsCaught) {
  // The next frame 3 us after the last rising edge: t_m (20 us) + t_R have not passed.
  auto frames = position_reads_22(1, us(100), MHz(8), us(2));
  const Time end = frames[0].start + us(2) + period_of(MHz(8)) * (frames[0].clocks - 1);
  frames.push_back({end + us(3), MHz(8), 44, header(k22Position), us(2)});
  const auto r = run(frames, quick_encoder());
  EXPECT_EQ(r.count(checker::check::kRecovery), 1U) << r.list();
  // With the wait any compliant encoder may need (t_m 30 us + t_R) it is clean.
  frames.back().start = end + us(31);
  const auto fixed = run(frames, quick_encoder());
  EXPECT_EQ(fixed.count(checker::check::kRecovery), 0U) << fixed.list();
}

TEST(PinMaster, AWaitThatSuitsATenMicrosecondEncoderOnlyIsOutsideTheEnvelope) {
  // The encoder on the bench declares t_m = 10 us; the master waits 11 us between frames.
  auto encoder = quick_encoder();
  encoder.t_m = us(10);
  auto frames = position_reads_22(1, us(100), MHz(8), us(2));
  const Time end = frames[0].start + us(2) + period_of(MHz(8)) * (frames[0].clocks - 1);
  frames.push_back({end + us(11), MHz(8), 44, header(k22Position), us(2)});
  const auto r = run(frames, encoder);
  ASSERT_EQ(r.count(checker::check::kRecovery), 1U) << r.list();
  const auto& v = *std::find_if(r.violations.begin(), r.violations.end(),
                                [](const auto& x) { return x.check == checker::check::kRecovery; });
  EXPECT_EQ(v.verdict, checker::Verdict::SpecEnvelope);
  EXPECT_EQ(v.measured, "11 us");
  EXPECT_NE(v.message.find("t_m 30 us"), std::string::npos) << v.message;
  const auto verdicts = checker::conclude(r.violations);
  EXPECT_TRUE(verdicts.this_encoder);
  EXPECT_FALSE(verdicts.spec_envelope);
  // Declared t_m 20 us: the same wait fails this encoder as well.
  encoder.t_m = us(20);
  const auto longer = run(frames, encoder);
  EXPECT_FALSE(checker::conclude(longer.violations).this_encoder) << longer.list();
}

// "A continuous clock is only possible with the mode command 'Encoder send position value'"
// (2.3.1): after "Encoder send test values" (010101: S, F1, 40 bits, CRC; the start bit on RE11,
// the last CRC bit on RE57) one more pulse for the HIGH end is all, and further pulses are beyond
// the frame's end, as after a 2.2 frame.
TEST(PinMaster, PulsesBeyondATestValuesFrameAreCaughtAsNoContinuousClockFollowsIt) {
  constexpr std::uint8_t k21TestValues = 0b010101;
  const auto reads = [](unsigned clocks) {
    return std::vector<PinFrame>{{us(10), MHz(1), clocks, header(k21TestValues)}, {us(200), MHz(1), clocks, header(k21TestValues)}};
  };
  const auto exact = run(reads(11 + 47), quick_encoder());
  EXPECT_EQ(exact.count(checker::check::kClockCount), 0U) << exact.list();
  EXPECT_EQ(exact.row(checker::check::kClockCount).judged, 2U);
  const auto longer = run(reads(11 + 47 + 5), quick_encoder());
  ASSERT_EQ(longer.count(checker::check::kClockCount), 2U) << longer.list();
  EXPECT_EQ(longer.violations.front().limit, "<= 58");
  EXPECT_EQ(longer.violations.front().measured, "63 pulses");
}

TEST(PinMaster, TooFewClocksAreCaught) {
  const auto r = run(position_reads_21(2, us(100), 11 + 20), quick_encoder());  // stops inside the position
  EXPECT_EQ(r.count(checker::check::kClockCount), 2U) << r.list();
  EXPECT_EQ(run(position_reads_21(2, us(100), 11 + 31), quick_encoder()).count(checker::check::kClockCount), 0U)
      << "the last CRC bit on RE42 is enough";
}

TEST(PinMaster, AClockAboveTheTableIsCaught) {
  const auto r = run(position_reads_22(2, us(100), MHz(20), us(1)), quick_encoder());
  // Each frame: above the table (both verdicts) and above the model's word 25, 16 MHz (this encoder).
  EXPECT_EQ(r.count(checker::check::kClockFrequency), 4U) << r.list();
  std::size_t both = 0;
  for (const auto& v : r.violations)
    if (v.check == checker::check::kClockFrequency) {
      EXPECT_EQ(v.severity, checker::Severity::Error);
      both += v.verdict == checker::Verdict::Both;
    }
  EXPECT_EQ(both, 2U);
}

TEST(PinMaster, ModeBitsOnAnUndrivenLineAreCaught) {
  std::vector<PinFrame> frames{{us(10), MHz(1), 43, std::string(43, '-')}};
  const auto r = run(frames, quick_encoder());
  EXPECT_EQ(r.count(checker::check::kFloatingData), 1U) << r.list();
}

TEST(PinMaster, A21ParameterFrameTooSoonAfterTheLastIsCaught) {
  // "Encoder send parameters" for word 13 (8 + 16 payload bits; answer on RE35 or later after
  // t_ac) 200 us after a position read: t_b > 1 ms is not kept (2.3.2).
  auto p = quick_encoder();
  p.t_ac_read = Time::zero();
  std::vector<PinFrame> frames = position_reads_21(1, us(100));
  const std::string payload = bits_msb(0x0D, 8) + bits_msb(0, 16);
  frames.push_back({us(210), MHz(1), 35 + 30, header(k21SendParameter, payload)});
  const auto r = run(frames, p);
  EXPECT_EQ(r.count(checker::check::kTimeBetweenCycles), 1U) << r.list();
  frames.back().start = us(10) + us(43) + ms(1) + us(1);
  EXPECT_EQ(run(frames, p, 1, ms(3)).count(checker::check::kTimeBetweenCycles), 0U);
}

TEST(PinMaster, PowerOnWithoutT3IsCaught) {
  // 2.3.3: CLOCK HIGH for t1 + t2, one LOW pulse > 125 ns, then t3 = 380 .. 420 ms before the
  // first request. This master requests 50 ms after its pulse.
  auto p = quick_encoder();
  p.startup_time = ms(500);
  std::vector<PinFrame> frames{{ms(900), MHz(1), 1, ""}};
  auto reads = position_reads_21(2, us(100));
  for (auto& f : reads) f.start += ms(950);
  frames.insert(frames.end(), reads.begin(), reads.end());
  const auto r = run(frames, p, 1, ms(951));
  EXPECT_EQ(r.count(checker::check::kPowerOn), 1U) << r.list();
  for (auto& f : frames)
    if (f.clocks > 1) f.start += ms(350);  // t3 = 400 ms
  const auto fixed = run(frames, p, 1, ms(1301));
  EXPECT_EQ(fixed.count(checker::check::kPowerOn), 0U) << fixed.list();
}

// The start-bit polling findings of `check` for pin-driven `frames` against the model encoder,
// judged with the model's declaration as `declare` changes it.
std::vector<checker::Violation> polling_findings(const slave::EncoderParams& model, const std::vector<PinFrame>& frames,
                                                 std::string_view check,
                                                 const std::function<void(checker::EncoderDeclaration&)>& declare) {
  Kernel k;
  line::Line line(k, line::LineParams{});
  slave::Encoder e(k, line, model);
  auto declaration = scenarios::declared_encoder(model);
  declare(declaration);
  checker::TimingChecker checker(k, line, declaration);
  PinMaster m(k, line, frames);
  k.run(ms(1));
  checker.finish();
  std::vector<checker::Violation> polling;
  for (const auto& v : checker.violations())
    if (v.check == check && v.field == "start-bit polling") polling.push_back(v);
  return polling;
}

// The t_cal verdict on one frame of `mode` clocked 40 times at 1 MHz (FE1 to RE40: 39.5 us of
// polling, no start bit from the model's slow encoder); none when the polling passes.
std::optional<checker::Verdict> t_cal_polling_verdict(const slave::EncoderParams& model, std::uint8_t mode,
                                                      const std::function<void(checker::EncoderDeclaration&)>& declare) {
  const std::vector<PinFrame> frames{{us(10), MHz(1), 40, header(mode)}};
  const auto v = polling_findings(model, frames, checker::check::kCalculationTime, declare);
  return v.size() == 1 ? std::optional{v[0].verdict} : std::nullopt;
}

}  // namespace

// 2.3.2: polling for the start bit must not depend on t_cal. An encoder still calculating (the
// model takes 500 us) while the master gives up after RE40, 39.5 us after FE1.
TEST(PinMaster, GivingUpTheStartBitBeforeTCalIsCaughtToThePicosecond) {
  slave::EncoderParams model;
  model.t_cal = us(500);
  const auto frames = position_reads_21(1, us(100), 40);
  const auto polled_with = [&](Time declared_t_cal) {
    return polling_findings(model, frames, checker::check::kCalculationTime,
                            [&](checker::EncoderDeclaration& d) { d.t_cal = declared_t_cal; });
  };
  // The datasheet says 39.5 us: the master waited exactly that; only the envelope's 1 ms is missed.
  auto v = polled_with(ns(39'500));
  ASSERT_EQ(v.size(), 1U);
  EXPECT_EQ(v[0].verdict, checker::Verdict::SpecEnvelope);
  EXPECT_EQ(v[0].measured, "39.5 us");
  // One picosecond more: the master gave up before this encoder could answer.
  v = polled_with(ns(39'500) + ps(1));
  ASSERT_EQ(v.size(), 1U);
  EXPECT_EQ(v[0].verdict, checker::Verdict::Both);
}

// The German brochure (both editions): t_cal may differ for 2.1 and 2.2 mode commands. The declared 2.2 value
// (t_cal_22) judges 111000 frames, t_cal the 000111 ones; each to the picosecond.
TEST(PinMaster, EachModeCommandTypesPollingIsJudgedAgainstItsOwnTCal) {
  slave::EncoderParams model;
  model.version = protocol::EndatVersion::V2_2;
  model.t_cal = us(500);
  model.t_cal_22 = us(500);
  const auto verdict = [&](std::uint8_t mode, Time t_cal, Time t_cal_22) {
    return t_cal_polling_verdict(model, mode, [&](checker::EncoderDeclaration& d) {
      d.t_cal = t_cal;
      d.t_cal_22 = t_cal_22;
    });
  };
  const Time polled = ns(39'500);  // FE1 to RE40 at 1 MHz
  EXPECT_EQ(verdict(k22Position, ms(1), polled), checker::Verdict::SpecEnvelope);
  EXPECT_EQ(verdict(k22Position, us(1), polled + ps(1)), checker::Verdict::Both);
  EXPECT_EQ(verdict(k21Position, polled, ms(1)), checker::Verdict::SpecEnvelope);
  EXPECT_EQ(verdict(k21Position, polled + ps(1), us(1)), checker::Verdict::Both);
}

// 3.6.5: an encoder that declares a longer calculation time in energy-saving mode may take it
// whenever the master switches the mode on; polling is judged against the longer of the two.
TEST(PinMaster, PollingIsJudgedAgainstTheEnergySavingTCalWhereItIsLonger) {
  slave::EncoderParams model;
  model.t_cal = us(500);
  const auto verdict = [&](Time t_cal, std::optional<Time> t_cal_energy_saving) {
    return t_cal_polling_verdict(model, k21Position, [&](checker::EncoderDeclaration& d) {
      d.t_cal = t_cal;
      d.t_cal_energy_saving = t_cal_energy_saving;
    });
  };
  const Time polled = ns(39'500);  // FE1 to RE40 at 1 MHz
  EXPECT_EQ(verdict(us(1), polled), checker::Verdict::SpecEnvelope);
  EXPECT_EQ(verdict(us(1), polled + ps(1)), checker::Verdict::Both);
  EXPECT_EQ(verdict(polled + ps(1), us(1)), checker::Verdict::Both) << "a shorter one does not lower the limit";
  EXPECT_EQ(verdict(us(1), std::nullopt), checker::Verdict::SpecEnvelope);
  model.t_cal_energy_saving = us(20);
  EXPECT_EQ(scenarios::declared_encoder(model).t_cal_energy_saving, us(20));
}

// 2.3.2 t_ac: a 2.1 parameter frame polls for the acknowledgment through the memory access. The
// model takes 2 ms to select memory area A1h; the master gives up 40 us after its last payload bit.
TEST(PinMaster, GivingUpTheStartBitBeforeTAcIsCaughtToThePicosecond) {
  slave::EncoderParams model;
  model.t_ac_read = ms(2);
  model.t_ac_write = ms(2);
  const std::string payload = bits_msb(0xA1, 8) + bits_msb(0, 16);
  const unsigned last_payload = position::kTurnaround - 1 + 24;
  const std::vector<PinFrame> frames{{us(100), MHz(1), last_payload + 40, header(k21SelectMemoryArea, payload)}};
  const auto polled_with = [&](std::optional<Time> declared_t_ac) {
    return polling_findings(model, frames, checker::check::kMemoryAccess,
                            [&](checker::EncoderDeclaration& d) { d.t_ac = declared_t_ac; });
  };
  EXPECT_EQ(scenarios::declared_encoder(model).t_ac, ms(2));  // the model's longest access is declared
  // The datasheet says 40 us: the master waited exactly that; only the envelope's 12 ms is missed.
  auto v = polled_with(us(40));
  ASSERT_EQ(v.size(), 1U);
  EXPECT_EQ(v[0].verdict, checker::Verdict::SpecEnvelope);
  EXPECT_EQ(v[0].measured, "40 us");
  EXPECT_EQ(v[0].limit, ">= 12 ms (spec envelope)");
  // One picosecond more: the master gave up before this encoder could answer.
  v = polled_with(us(40) + ps(1));
  ASSERT_EQ(v.size(), 1U);
  EXPECT_EQ(v[0].verdict, checker::Verdict::Both);
  EXPECT_EQ(v[0].limit, ">= 40.000001 us (this encoder's t_ac)");
  // No declaration: the envelope's 12 ms is the only limit, and it counts against both.
  v = polled_with(std::nullopt);
  ASSERT_EQ(v.size(), 1U);
  EXPECT_EQ(v[0].verdict, checker::Verdict::Both);
  EXPECT_EQ(v[0].limit, ">= 12 ms");
}

TEST(PinMaster, FindingsBeyondTheCapAreCountedNotKept) {
  checker::CheckerParams params;
  params.max_findings_per_check = 2;
  Kernel k;
  line::Line line(k, line::LineParams{});
  slave::Encoder e(k, line, quick_encoder());
  checker::TimingChecker checker(k, line, scenarios::declared_encoder(quick_encoder()), {}, params);
  PinMaster m(k, line, position_reads_22(5, us(100), MHz(20), us(1)));  // every frame above the table
  k.run(ms(1));
  checker.finish();
  std::size_t kept = 0;
  for (const auto& v : checker.violations()) kept += v.check == checker::check::kClockFrequency;
  EXPECT_EQ(kept, 2U);
  const auto rows = checker.conformance();
  const auto f_c = std::find_if(rows.begin(), rows.end(), [](const auto& c) { return c.check == checker::check::kClockFrequency; });
  EXPECT_EQ(f_c->violations, 10U);  // five frames, each above the table and above word 25
  // t_OE read as one period of the frame's clock (the default): the encoder's 60 ns turnaround
  // exceeds T = 50 ns at 20 MHz in each of the five frames.
  const auto t_oe = std::find_if(rows.begin(), rows.end(), [](const auto& c) { return c.check == checker::check::kDriverOn; });
  EXPECT_EQ(t_oe->violations, 5U);
  // t_z as well, judged once the wires show the frame's f_c (the release comes before RE2).
  const auto t_z = std::find_if(rows.begin(), rows.end(), [](const auto& c) { return c.check == checker::check::kDriverOff; });
  EXPECT_EQ(t_z->violations, 5U);
  EXPECT_EQ(checker.findings_not_kept(), 8U + 3U + 3U);  // beyond the cap of two per check
  EXPECT_FALSE(checker.conclusion().spec_envelope);
  EXPECT_FALSE(checker.conclusion().this_encoder);
}

// 2.3.3: after CLOCK was LOW, the HIGH phase before the power-on pulse is t2, 80 .. 120 ms.
TEST(PinMaster, PowerOnT2IsJudgedToThePicosecondAfterALowClock) {
  auto p = quick_encoder();
  p.startup_time = ms(500);
  const auto power_on_with_t2 = [&](Time t2) {
    // CLOCK LOW until 850 ms (a first LOW phase of that length), HIGH for t2, the pulse, t3 = 400 ms.
    std::vector<PinFrame> frames{{Time::zero(), MHz(1), 1, "", ms(850)}, {ms(850) + t2, MHz(1), 1, ""}};
    auto reads = position_reads_21(1, us(100));
    reads[0].start = ms(850) + t2 + ns(500) + ms(400);
    frames.insert(frames.end(), reads.begin(), reads.end());
    const auto r = run(frames, p, 1, reads[0].start + ms(1));
    std::size_t t2_findings = 0;
    for (const auto& v : r.violations) t2_findings += v.check == checker::check::kPowerOn && v.limit == "t2 = 80 .. 120 ms";
    return t2_findings;
  };
  EXPECT_EQ(power_on_with_t2(ms(100)), 0U);
  EXPECT_EQ(power_on_with_t2(ms(120)), 0U);
  EXPECT_EQ(power_on_with_t2(ms(120) + ps(1)), 1U);
  EXPECT_EQ(power_on_with_t2(ms(80)), 0U);
  EXPECT_EQ(power_on_with_t2(ms(80) - ps(1)), 1U);
}

// 2.1.2: three measurements at 200 kHz, then frames at 4 MHz (T/8 = 31.25 ns) with compensation.
// Between measurements the cable's delay changes, so the round trips the master counts differ:
// t_D, t_D, t_D + 2c (c the added cable delay, crossed twice). The third deviates 4c/3 from the
// mean.
namespace measurements {

// A position read at 750 kHz first (without compensation, within 2 t_D up to 46 m of cable): the
// measurements that follow are all on the wires.
std::vector<PinFrame> frames(unsigned measured) {
  std::vector<PinFrame> out{{us(10), kHz(750), 43, header(k21Position)}};
  for (unsigned i = 0; i < measured; ++i) out.push_back({us(100) + us(300) * i, kHz(200), 43, header(k21Position)});
  for (unsigned i = 0; i < 2; ++i) out.push_back({us(1300) + us(100) * i, MHz(4), 43, header(k21Position), us(2)});
  return out;
}

Run with_third_later_by(Time c, unsigned measured = 3) {
  const Time base = ns(5);
  const std::vector<CableChange> changes{{us(5), base}, {us(650), base + c}};
  return run(frames(measured), quick_encoder(), 1, ms(2), {}, changes);
}

}  // namespace measurements

TEST(PinMaster, DelayMeasurementsMustAgreeWithinAnEighthOfThePeriod) {
  // 4c/3 against 31250 ps: c = 23437 ps deviates 31249.3 ps, c = 23438 ps 31250.7 ps.
  const auto inside = measurements::with_third_later_by(ps(23437));
  EXPECT_TRUE(inside.violations.empty()) << inside.list();
  EXPECT_EQ(inside.row(checker::check::kMeasurementSpread).judged, 1U);
  const auto outside = measurements::with_third_later_by(ps(23438));
  ASSERT_EQ(outside.count(checker::check::kMeasurementSpread), 1U) << outside.list();
  const auto& v = outside.violations.front();
  EXPECT_EQ(v.where, line::ObservationPoint::MasterPins);
  EXPECT_EQ(v.limit, "<= T/8 = 31.25 ns (f_c 4 MHz)");
  EXPECT_EQ(v.measured, "31.251 ns from the mean");
  EXPECT_NE(v.message.find("measurement 3 of 3"), std::string::npos) << v.message;
  EXPECT_EQ(v.verdict, checker::Verdict::Both);
}

TEST(PinMaster, AMasterThatMeasuresAgainAfterAnOutlierPasses) {
  // Four measurements: the first before the cable settled, the latest three agree.
  const std::vector<CableChange> changes{{us(5), ns(45)}, {us(350), ns(5)}};
  const auto r = run(measurements::frames(4), quick_encoder(), 1, ms(2), {}, changes);
  EXPECT_TRUE(r.violations.empty()) << r.list();
  // The same four, the outlier last: the latest three disagree.
  const std::vector<CableChange> late{{us(5), ns(5)}, {us(950), ns(45)}};
  const auto bad = run(measurements::frames(4), quick_encoder(), 1, ms(2), {}, late);
  EXPECT_EQ(bad.count(checker::check::kMeasurementSpread), 1U) << bad.list();
}

TEST(PinMaster, CompensatingAfterTwoMeasurementsIsCaught) {
  const auto two = measurements::with_third_later_by(ps(0), 2);
  ASSERT_EQ(two.count(checker::check::kMeasurementSpread), 1U) << two.list();
  EXPECT_EQ(two.violations.front().measured, "2 measurement(s)");
  EXPECT_TRUE(measurements::with_third_later_by(ps(0), 3).violations.empty());
}

// A 2.2 frame with a command supplement at 1 MHz: the answer from RE11 (`answer_bits` long), then
// five undriven and two LOW lead bits, the supplement's start bit and 8 + 16 bits, the last on
// the frame's last rising edge.
PinFrame with_supplement(Time start, std::uint8_t mode_bits, std::uint8_t mrs, std::uint16_t value,
                         unsigned answer_bits = 33) {
  const unsigned last_answer_bit = position::kEarliestStartBit - 1 + answer_bits;
  const std::string drive = header(mode_bits) + std::string(last_answer_bit - position::kLastModeBit, '-') +
                            std::string(5, '-') + "001" + bits_msb(mrs, 8) + bits_msb(value, 16);
  return {start, MHz(1), static_cast<unsigned>(drive.size()), drive};
}

constexpr std::uint8_t k22Selection = 0b001001;        // "... and selection of the memory area"
constexpr std::uint8_t k22ReceiveParameter = 0b011011;  // "... and receive parameter"
constexpr std::uint8_t kOperatingStatus = 0xB9;         // MRS code (2.4.2.1)
constexpr unsigned kWithAdditionalData1 = 33 + 30;     // 2.2 position answer and one datum

TEST(PinMaster, ClocksAfterTheCommandSupplementAreCaughtToTheCount) {
  // Operating status selected (MRS B9): the supplement's start bit on RE51, its last bit on RE75.
  const PinFrame frame = with_supplement(us(10), k22Selection, kOperatingStatus, 0);
  ASSERT_EQ(frame.clocks, 75U);
  const auto exact = run({frame}, quick_encoder());
  EXPECT_TRUE(exact.violations.empty()) << exact.list();
  EXPECT_EQ(exact.row(checker::check::kClockCount).judged, 1U);
  PinFrame longer = frame;
  ++longer.clocks;
  const auto one_more = run({longer}, quick_encoder());
  ASSERT_EQ(one_more.count(checker::check::kClockCount), 1U) << one_more.list();
  EXPECT_EQ(one_more.violations.front().limit, "<= 75 (the supplement's last bit)");
  EXPECT_EQ(one_more.violations.front().severity, checker::Severity::Error);
}

TEST(PinMaster, AWriteWhileBusyIsCaught) {
  // Additional data 1 selected (MRS 40h, 2.4.2.2), then a memory area selected: a 2.2 memory
  // access, after which the encoder shows Busy in additional data 1 (2.6.1).
  std::vector<PinFrame> frames{with_supplement(us(10), k22Selection, 0x40, 0),
                               with_supplement(us(200), k22Selection, kOperatingStatus, 0, kWithAdditionalData1)};
  // A write 100 us after the access: nothing has shown Busy = 0.
  auto hasty = frames;
  hasty.push_back(with_supplement(us(400), k22ReceiveParameter, 0x00, 0x0000, kWithAdditionalData1));
  const auto r = run(hasty, quick_encoder());
  ASSERT_EQ(r.count(checker::check::kAccessWhileBusy), 1U) << r.list();
  EXPECT_EQ(r.violations.front().frame, 2U);
  // The careful master reads the position with additional data 1 until Busy = 0, then writes.
  auto careful = frames;
  careful.push_back({us(1000), MHz(1), 10 + kWithAdditionalData1 + 1, header(0b111000)});
  careful.push_back(with_supplement(us(1200), k22ReceiveParameter, 0x00, 0x0000, kWithAdditionalData1));
  const auto fine = run(careful, quick_encoder());
  EXPECT_EQ(fine.count(checker::check::kAccessWhileBusy), 0U) << fine.list();
  EXPECT_EQ(fine.row(checker::check::kAccessWhileBusy).judged, 2U);
}

TEST(PinMaster, TstAndTloMaximaAreThoseOfTheDeclaredEncoder) {
  // 2.3.2 "t_ST maximum, t_LO maximum: see encoder specifications". A datasheet's 3 us t_ST and
  // 500 ns t_LO, against frames at 8 MHz with a first LOW phase of 3 us (+ 1 ps) and 2.1 reads at
  // 1 MHz, whose LOW phases are 500 ns.
  auto encoder = quick_encoder();
  encoder.t_st_max = us(3);
  encoder.t_lo_max = ns(500);
  const auto inside = run(position_reads_22(2, us(100), MHz(8), us(3)), encoder);
  EXPECT_TRUE(inside.violations.empty()) << inside.list();
  const auto outside = run(position_reads_22(2, us(100), MHz(8), us(3) + ps(1)), encoder);
  ASSERT_EQ(outside.count(checker::check::kStartDelay), 2U) << outside.list();
  EXPECT_EQ(outside.violations.front().verdict, checker::Verdict::ThisEncoder);
  EXPECT_EQ(outside.violations.front().limit, "<= 3 us (this encoder's t_ST maximum)");
  EXPECT_TRUE(checker::conclude(outside.violations).spec_envelope);

  EXPECT_TRUE(run(position_reads_21(2, us(100)), encoder).violations.empty());
  encoder.t_lo_max = ns(500) - ps(1);
  const auto low = run(position_reads_21(2, us(100)), encoder);
  ASSERT_EQ(low.count(checker::check::kPulseLow), 2U) << low.list();
  EXPECT_EQ(low.violations.front().verdict, checker::Verdict::ThisEncoder);
  // Without a declared maximum the envelope has none: the same frames are clean.
  encoder.t_lo_max.reset();
  EXPECT_TRUE(run(position_reads_21(2, us(100)), encoder).violations.empty());
}

// Without delay compensation a master samples DATA on its falling edge: on 100 m the encoder's
// bit comes back t_D = 1.2 us after the rising edge that sent it, later than that edge at 2 MHz
// (T/2 = 250 ns), so the master samples before t_D and reads the bits of earlier slots. The
// wires show it as a clock above what the cable allows without compensation (2.1.1, Figure 2:
// 1/(2 t_D), docs/model.md §9); 400 kHz (T/2 = 1.25 us) samples every bit after it arrives.
TEST(PinMaster, SamplingBeforeTheDataDelayIsCaughtAsAClockTooFastForTheCable) {
  const auto reads = [](Hertz f_c) {
    std::vector<PinFrame> out;
    // A first LOW of 2 us lets the encoder's release come back over 100 m before FE2 (note 8).
    for (unsigned i = 0; i < 2; ++i) out.push_back({us(10) + us(300) * i, f_c, 11 + 32, header(k21Position), us(2)});
    return out;
  };
  const auto answer = [](const std::string& s, unsigned frame) { return s.substr(frame * 43 + 10, 33); };
  const auto fast = run(reads(MHz(2)), quick_encoder(), 100);
  EXPECT_EQ(fast.count(checker::check::kClockFrequency), 2U) << fast.list();
  ASSERT_EQ(fast.sampled.size(), 2U * 43);
  for (unsigned i = 0; i < 2; ++i) EXPECT_NE(answer(fast.sampled, i), answer(fast.sent, i)) << "frame " << i;
  const auto slow = run(reads(kHz(400)), quick_encoder(), 100);
  EXPECT_EQ(slow.count(checker::check::kClockFrequency), 0U) << slow.list();
  EXPECT_TRUE(slow.violations.empty()) << slow.list();
  for (unsigned i = 0; i < 2; ++i) EXPECT_EQ(answer(slow.sampled, i), answer(slow.sent, i)) << "frame " << i;
}
