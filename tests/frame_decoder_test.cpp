// The passive frame decoder (checker/frame_decoder.hpp) against the master's own view: every
// bundled, field and safety scenario is run with a VCD; the encoder pins' CLOCK and DATA are
// read back from the file and decoded with nothing but the declared encoder; every frame the
// master read cleanly must come out the same (mode command, position or parameter echo, CRC,
// additional data, command supplement).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>
#include <unistd.h>

#include "endatsim/checker/frame_decoder.hpp"
#include "endatsim/scenarios/scenarios.hpp"
#include "endatsim/scenarios/vcd_reader.hpp"

#include "scenario_support.hpp"

namespace {

using namespace endatsim;
namespace fs = std::filesystem;

checker::DecoderParams declared(const scenarios::Scenario& s) {
  checker::DecoderParams p;
  p.position_bits = s.encoder.position_bits;
  p.clock_to_data = s.line.encoder.receiver_delay + s.encoder.output_delay + s.line.encoder.driver_delay;
  p.t_m = s.encoder.t_m;
  return p;
}

// Decodes the encoder pins of a VCD written by `endatsim run`.
std::vector<checker::WireFrame> decode_vcd(const std::string& path, const checker::DecoderParams& params) {
  const auto vcd = scenarios::read_vcd_file(path);
  const auto* clock = vcd.find("endat.encoder_clock");
  const auto* data = vcd.find("endat.encoder_data");
  EXPECT_NE(clock, nullptr);
  EXPECT_NE(data, nullptr);
  if (clock == nullptr || data == nullptr) return {};
  // Merge both change lists in time order; CLOCK before DATA at equal times, as the simulator
  // commits them (a DATA change caused by a clock edge is later by the encoder's delay anyway).
  std::vector<std::tuple<std::int64_t, int, char>> edges;
  for (const auto& c : clock->changes) edges.emplace_back(c.time, 0, c.value);
  for (const auto& c : data->changes) edges.emplace_back(c.time, 1, c.value);
  std::stable_sort(edges.begin(), edges.end());
  checker::FrameDecoder decoder(params);
  for (const auto& [time, wire, value] : edges) {
    const sim::Time t{time * vcd.timescale_ps};
    if (wire == 0) decoder.on_clock(t, value == '1');
    else decoder.on_data(t, value == '1');
  }
  decoder.finish();
  return decoder.take_finished();
}

class DecoderRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(DecoderRoundTrip, EveryCleanFrameOfTheMasterIsDecodedFromTheWires) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = fs::temp_directory_path() /
                       ("endatsim_decoder_" + std::to_string(getpid()) + "_" + GetParam().stem().string() + ".vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  const auto r = scenarios::run_scenario(scenario, options);
  // Faults on the wires at the encoder's end change what the encoder pins show from what the
  // master received: such frames are compared where the master cannot see them.
  const bool encoder_end_faults = std::any_of(scenario.events.begin(), scenario.events.end(), [](const auto& e) {
    using K = scenarios::Event::Kind;
    const bool line_fault = e.kind == K::BitFlip || e.kind == K::Glitch || e.kind == K::Stuck || e.kind == K::RandomBitErrors;
    return line_fault && e.end == line::ObservationPoint::EncoderPins;
  });
  const auto decoded = decode_vcd(vcd.string(), declared(scenario));
  fs::remove(vcd);
  // FE1 reaches the encoder pins one master driver delay and one cable delay after the master;
  // 2 us covers the longest cable a set_cable event may switch to.
  const sim::Time path = scenario.line.master.driver_delay + sim::us(2);
  std::size_t compared = 0;
  for (const auto& f : r.frames) {
    if (encoder_end_faults) break;
    // Clean: read as good by a master whose own CRC agrees (a master that accepts any CRC may
    // call a disturbed frame good).
    if (f.word != 0 || f.outcome != master::FrameOutcome::Ok || f.crc_received != f.crc_expected) continue;
    if (f.position_bits != 0 && f.position_bits != scenario.encoder.position_bits) continue;  // clocked another width
    const auto it = std::find_if(decoded.begin(), decoded.end(), [&](const checker::WireFrame& w) {
      return w.fe1 >= f.start && w.fe1 <= f.start + path;
    });
    ASSERT_NE(it, decoded.end()) << "no decoded frame for master frame " << f.index << " at " << sim::format_time(f.start);
    const auto& w = *it;
    const std::string where = "frame " + std::to_string(f.index) + " at " + sim::format_time(f.start);
    ASSERT_TRUE(w.command.has_value()) << where;
    EXPECT_EQ(*w.command, f.command) << where;
    ASSERT_TRUE(w.answer_complete) << where;
    EXPECT_TRUE(w.crc_ok) << where;
    using protocol::Field;
    const auto field = [&](Field x) { return w.fields[static_cast<std::size_t>(x)]; };
    switch (protocol::info(f.command).answer) {
      case protocol::AnswerFormat::Position:
        EXPECT_EQ(field(Field::Position), f.position) << where;
        EXPECT_EQ(field(Field::Error1) != 0, f.error1) << where;
        break;
      case protocol::AnswerFormat::TestValues:
        EXPECT_EQ(field(Field::TestValue), f.test_value) << where;
        break;
      case protocol::AnswerFormat::Parameter:
        EXPECT_EQ(field(Field::Address), f.echo_address) << where;
        EXPECT_EQ(field(Field::Parameter), f.echo_parameter) << where;
        break;
    }
    ASSERT_EQ(w.additional_data.size(), f.additional_data.size()) << where;
    for (std::size_t i = 0; i < w.additional_data.size(); ++i) {
      EXPECT_EQ(w.additional_data[i].status, f.additional_data[i].status) << where;
      EXPECT_EQ(w.additional_data[i].data, f.additional_data[i].data) << where;
      EXPECT_TRUE(w.additional_data[i].crc_ok) << where;
    }
    EXPECT_EQ(w.supplement, f.supplement) << where;
    ++compared;
  }
  const bool any_ok = std::any_of(r.frames.begin(), r.frames.end(),
                                  [](const auto& f) { return f.outcome == master::FrameOutcome::Ok; });
  if (!encoder_end_faults && any_ok) {
    EXPECT_GT(compared, 0U) << "no clean frame to compare";
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, DecoderRoundTrip, ::testing::ValuesIn(test_support::scenario_files()), [](const auto& param_info) {
  std::string name = param_info.param.parent_path().filename().string() + "_" + param_info.param.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
});

}  // namespace

namespace {

// A capture's window may open inside a frame: the first falling edge begins a frame only after
// CLOCK has been HIGH for t_m from the window's opening on (D297403 2.3.2 recovery time I).
std::size_t frames_after_high(sim::Time high) {
  checker::DecoderParams p;
  p.t_m = sim::us(10);
  checker::FrameDecoder decoder(p);
  const sim::Time start = sim::ms(1);
  decoder.begin_capture(start);
  decoder.on_clock(start, true);
  decoder.on_clock(start + high, false);  // FE1, if CLOCK was HIGH long enough
  decoder.on_clock(start + high + sim::ns(500), true);
  decoder.finish();
  return decoder.take_finished().size();
}

}  // namespace

TEST(FrameDecoderCapture, TheFirstFrameBeginsOnlyAfterClockWasHighForTm) {
  EXPECT_EQ(frames_after_high(sim::us(10) - sim::ps(1)), 0U);
  EXPECT_EQ(frames_after_high(sim::us(10)), 1U);
}

TEST(FrameDecoderCapture, EdgesBeforeTheFirstFrameAreCountedAndACutFrameIsTold) {
  checker::DecoderParams p;
  p.t_m = sim::us(10);
  checker::FrameDecoder decoder(p);
  decoder.begin_capture(sim::Time::zero());
  decoder.on_clock(sim::Time::zero(), false);  // LOW from the start: no edge seen
  decoder.on_clock(sim::ns(500), true);
  decoder.on_clock(sim::ns(1000), false);
  decoder.on_clock(sim::ns(1500), true);
  EXPECT_EQ(decoder.edges_before_first_frame(), 3U);
  EXPECT_TRUE(decoder.on_clock(sim::ns(1500) + sim::us(10), false));  // FE1
  decoder.on_clock(sim::ns(2000) + sim::us(10), true);
  const sim::Time last_rise = sim::ns(2000) + sim::us(10);
  EXPECT_TRUE(decoder.cuts_frame(last_rise + sim::us(10) - sim::ps(1)));
  EXPECT_FALSE(decoder.cuts_frame(last_rise + sim::us(10)));
  decoder.on_clock(last_rise + sim::us(1), false);  // LOW at the end: cut however long
  EXPECT_TRUE(decoder.cuts_frame(last_rise + sim::ms(1)));
  // A live run never opens a window: its first falling edge is FE1.
  checker::FrameDecoder live(p);
  EXPECT_TRUE(live.on_clock(sim::ns(40), false));
  EXPECT_EQ(live.edges_before_first_frame(), 0U);
}

// A master that gives no pulse after the last bit: the slot after the last rising edge is read
// once CLOCK has stayed HIGH for t_m, which ends the frame. A capture that ends before that cuts
// the frame: the slot is not read, and the answer stays incomplete, as the rows that need the
// frame's end say (before, finish() read it whatever the capture's end).
TEST(FrameDecoderCapture, TheSlotAfterTheLastEdgeIsReadOnlyOnceTheFrameIsOver) {
  auto s = test_support::make_scenario(3, sim::MHz(2), false, 1);
  s.master.extra_clock_after_last_bit = false;
  const fs::path vcd = fs::temp_directory_path() / ("endatsim_decoder_" + std::to_string(getpid()) + "_tail.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(s, options);
  const auto file = scenarios::read_vcd_file(vcd.string());
  fs::remove(vcd);
  const auto* clock = file.find("endat.encoder_clock");
  const auto* data = file.find("endat.encoder_data");
  ASSERT_NE(clock, nullptr);
  ASSERT_NE(data, nullptr);
  std::vector<std::tuple<std::int64_t, int, char>> edges;
  for (const auto& c : clock->changes) edges.emplace_back(c.time * file.timescale_ps, 0, c.value);
  for (const auto& c : data->changes) edges.emplace_back(c.time * file.timescale_ps, 1, c.value);
  std::stable_sort(edges.begin(), edges.end());
  std::int64_t last_rise = 0;
  for (const auto& [t, wire, value] : edges)
    if (wire == 0 && value == '1') last_rise = t;
  const auto p = declared(s);
  for (const auto& [after, complete] : {std::pair{sim::us(1) + sim::ns(500), false}, std::pair{p.t_m, true}}) {
    const sim::Time end = sim::Time{last_rise} + after;
    checker::FrameDecoder decoder(p);
    for (const auto& [t, wire, value] : edges) {
      if (sim::Time{t} > end) break;
      if (wire == 0) decoder.on_clock(sim::Time{t}, value == '1');
      else decoder.on_data(sim::Time{t}, value == '1');
    }
    decoder.finish(end);
    const auto frames = decoder.take_finished();
    ASSERT_EQ(frames.size(), 1U);
    EXPECT_EQ(frames.back().clocks, 43U);
    EXPECT_EQ(frames.back().answer_complete, complete) << after.count();
    EXPECT_EQ(frames.back().crc_ok, complete) << after.count();
  }
}
