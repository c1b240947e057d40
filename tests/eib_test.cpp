// The External Interface Box (3.5.7, appendix A2 cause 5, appendix A10): the factory image, the
// accesses refused before initial commissioning, the commissioning by 2.1 parameter writes and
// the EIB behaving as the connected encoder afterwards. The master reads and writes through its
// own frames; only the final memory and the encoder's frames are looked at directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "endatsim/protocol/parameters.hpp"
#include "scenario_support.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/encoder.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using MC = protocol::ModeCommand;
using Outcome = master::FrameOutcome;
namespace pm = protocol::parameters;

namespace {

constexpr std::uint64_t kStart = 5'000'000;  // where the connected scale stands at switch-on
constexpr std::int64_t kSpeed = 1'000'000;   // measuring steps per second

// The connected encoder: an incremental linear encoder with one reference mark (word 14 type 0),
// 20 um signal period (3.5.8 example), 32-bit position; the EIB subdivides a signal period into
// 4096 steps (A10, the 12-bit example of 3.9.22), so words 20/21 stay 0 (3.5.12).
std::map<unsigned, std::uint16_t> connected_encoder_words() {
  const auto period = pm::encode_signal_period(20'000);
  return {{8, pm::encode_version(2)},
          {13, pm::encode_position_bits(32)},
          {14, pm::encode_encoder_type(pm::EncoderType::IncrementalLinear)},
          {15, period[0]},
          {16, period[1]},
          {30, pm::encode_direction(false)},
          {31, pm::kNvmBit15},
          {37, pm::encode_command_set({true, false, false})},
          {39, pm::encode_calculation_time(pm::calculation_time_from(std::chrono::microseconds(5)))},
          {40, pm::encode_ordering_designation("EnDat22")}};
}

std::uint16_t checksum_after(const std::map<unsigned, std::uint16_t>& writes) {
  const auto image = slave::eib_factory_image();
  std::vector<std::uint16_t> m(48, 0);
  for (unsigned n = 4; n < 48; ++n) m[n] = slave::Memory(image).manufacturer_word(n);
  for (const auto& [n, v] : writes) m[n] = v;
  return pm::manufacturer_checksum(m);
}

master::Operation select(std::uint8_t mrs) { return op(MC::SelectionOfMemoryArea, mrs); }
master::Operation write(std::uint8_t address, std::uint16_t value) {
  return op(MC::EncoderReceiveParameters, address, value);
}
master::Operation read(std::uint8_t address) { return op(MC::EncoderSendParameters, address); }
master::Operation read_position() { return op(MC::EncoderSendPositionValues); }
master::Operation await_not_busy() {
  master::Operation o;
  o.kind = master::Operation::Kind::AwaitNotBusy;
  o.count = 100;
  o.cycle = us(50);
  return o;
}
// Area BD answers 2.2 mode commands only (2.4.2.1): the access in the command supplement.
std::vector<master::Operation> write_endat22(std::uint8_t address, std::uint16_t value) {
  return {op(MC::EncoderSendPositionValuesAndReceiveParameter, address, value), await_not_busy()};
}

// 2.1 parameter writes, area by area (A5 first, so that word 47 is saved before word 14: the
// order that works for either activation), the 2.2 area's A10 scaling, then a reset.
std::vector<master::Operation> commissioning(std::uint16_t checksum_offset = 0) {
  auto words = connected_encoder_words();
  words[47] = static_cast<std::uint16_t>(checksum_after(words) + checksum_offset);
  std::vector<master::Operation> ops;
  for (auto [mrs, first] : {std::pair{0xA5, 32U}, {0xA3, 16U}}) {
    ops.push_back(select(static_cast<std::uint8_t>(mrs)));
    for (const auto& [n, v] : words)
      if (n >= first && n < first + 16) ops.push_back(write(static_cast<std::uint8_t>(n - first), v));
  }
  // A10: LSB weighting = signal period / subdivision values (EnDat 2.2 words 27..29, 3.9.37).
  const std::uint16_t scaling = pm::encode_resolution_scaling(pm::ResolutionScaling::GratingSubdivision,
                                                              pm::ResolutionScaling::SeeWords20And21);
  ops.push_back(op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45, 0));  // busy in additional data 1
  for (const auto& part : {std::vector{op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xBD, 0),
                                       await_not_busy()},
                           write_endat22(27, scaling), write_endat22(28, 4096),
                           write_endat22(63, static_cast<std::uint16_t>(scaling + 4096))})
    ops.insert(ops.end(), part.begin(), part.end());
  ops.push_back(select(0xA1));
  for (const auto& [n, v] : words)
    if (n < 16 && n != 14) ops.push_back(write(static_cast<std::uint8_t>(n), v));
  ops.push_back(write(14, words[14]));
  return ops;
}

scenarios::Scenario scenario(std::vector<std::vector<master::Operation>> parts) {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.script.clear();
  for (const auto& part : parts) s.script.insert(s.script.end(), part.begin(), part.end());
  s.encoder.kind = slave::EncoderKind::Eib;
  s.encoder.position_bits = 32;  // the width of the "no valid position" answer before commissioning
  s.encoder.motion = {kStart, kSpeed};
  s.encoder.t_ac_read = us(100);
  s.encoder.t_ac_write = us(300);
  s.master.position_bits = 32;
  return s;
}

const master::FrameResult& frame_of(const scenarios::ScenarioResult& r, std::size_t operation) {
  const master::FrameResult* f = nullptr;
  for (const auto& x : r.frames)
    if (x.operation == operation) f = &x;
  if (f == nullptr) throw std::runtime_error("no frame for operation " + std::to_string(operation));
  return *f;
}

std::uint16_t manufacturer_word(const slave::MemoryImage& image, unsigned n) {
  return slave::Memory(image).manufacturer_word(n);
}

}  // namespace

TEST(EibTest, FactoryImageHoldsOnlyTypeMemorySizeIdAndSerial) {
  // 3.5.7: "the encoder type F_hex and the memory size, serial number and ID number are saved
  // in factory delivery state".
  const slave::Memory m(slave::eib_factory_image());
  EXPECT_EQ(m.manufacturer_word(14), 0xF001) << "type F, NVM bit 0";
  EXPECT_EQ(m.manufacturer_word(9), 0x2020) << "OEM areas 1 and 2: addresses 0 .. 63 (3.5.5)";
  EXPECT_EQ(pm::id_number_string(pm::decode_id_number(m.manufacturer_word(24), m.manufacturer_word(25),
                                                      m.manufacturer_word(26))),
            "1000000 01");
  EXPECT_EQ(pm::decode_serial_number(m.manufacturer_word(27), m.manufacturer_word(28), m.manufacturer_word(29)).number,
            10'000'001U);
  std::vector<std::uint16_t> words(48, 0);
  for (unsigned n = 4; n < 48; ++n) {
    words[n] = m.manufacturer_word(n);
    if (n != 14 && n != 47 && !slave::eib_factory_word(n)) {
      EXPECT_EQ(words[n], 0) << "word " << n;
    }
  }
  EXPECT_EQ(words[47], pm::manufacturer_checksum(words));
  EXPECT_EQ(m.endat22_word(63), 0);
  EXPECT_EQ(m.operating_status(2), 0) << "no write protection set yet";
}

TEST(EibTest, TypeTwoUntilCommissioned) {
  // A2 cause 5 for every memory access outside the commissioning areas; reading the memory
  // size, ID and serial number works; the box's own words stay write-protected.
  const auto r = scenarios::run_scenario(scenario({{select(0xB9), select(0xA9), select(0xA7), select(0xA1), read(9),
                                                    select(0xA3), read(24 - 16), read(27 - 16), write(24 - 16, 1),
                                                    read_position()}}));
  for (std::size_t i : {0U, 1U, 2U}) EXPECT_EQ(frame_of(r, i).outcome, Outcome::Type2Error) << "operation " << i;
  EXPECT_EQ(r.encoder_frames[0].error, protocol::ErrorCause::EibNotInitialised);
  EXPECT_EQ(r.encoder_frames[1].error, protocol::ErrorCause::EibNotInitialised);
  EXPECT_EQ(frame_of(r, 3).outcome, Outcome::Ok);
  EXPECT_EQ(frame_of(r, 4).echo_parameter, 0x2020);
  EXPECT_EQ(frame_of(r, 6).echo_parameter, manufacturer_word(slave::eib_factory_image(), 24));
  EXPECT_EQ(frame_of(r, 7).echo_parameter, manufacturer_word(slave::eib_factory_image(), 27));
  EXPECT_EQ(frame_of(r, 8).outcome, Outcome::Type2Error);
  EXPECT_EQ(r.encoder_frames[8].error, protocol::ErrorCause::WriteProtected) << "the ID number belongs to the box";
  // EibPositionBeforeCommissioning::ErrorBit: F1 set, no position.
  EXPECT_EQ(frame_of(r, 9).outcome, Outcome::Ok);
  EXPECT_TRUE(frame_of(r, 9).error1);
  EXPECT_EQ(frame_of(r, 9).position, 0U);
}

TEST(EibTest, CommissioningByParameterWritesThenResetMakesItTheConnectedEncoder) {
  auto ops = commissioning();
  const std::size_t reset_at = ops.size();
  ops.push_back(read_position());  // before the reset: still not initiated
  ops.push_back(op(MC::EncoderReceiveReset));
  ops.push_back(read_position());
  ops.push_back(select(0xB9));
  ops.push_back(select(0xA1));
  ops.push_back(write(13, 0x8019));
  const auto r = scenarios::run_scenario(scenario({ops}));
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(r.busy_timeouts, 0U);
  EXPECT_EQ(r.encoder_memory.areas.at(protocol::MemoryArea::ManufacturerEndat22).at(28), 4096) << "A10 scaling saved";
  for (std::size_t i = 0; i < reset_at; ++i) EXPECT_EQ(frame_of(r, i).outcome, Outcome::Ok) << "operation " << i;
  EXPECT_TRUE(frame_of(r, reset_at).error1) << "word 14 written, but not activated before the reset";
  const auto& f = frame_of(r, reset_at + 2);
  EXPECT_EQ(f.outcome, Outcome::Ok);
  EXPECT_FALSE(f.error1);
  // Incremental: relative to the activating reset, well below the scale's 5 000 000.
  EXPECT_GT(f.position, 0U);
  EXPECT_LT(f.position, 100'000U);
  const auto latched = std::find_if(r.encoder_frames.begin(), r.encoder_frames.end(),
                                    [&](const slave::EncoderFrame& e) { return e.start >= f.start; });
  ASSERT_NE(latched, r.encoder_frames.end());
  EXPECT_EQ(f.position, latched->position);
  EXPECT_EQ(frame_of(r, reset_at + 3).outcome, Outcome::Ok) << "the operating status is open now";
  EXPECT_EQ(frame_of(r, reset_at + 5).outcome, Outcome::Type2Error) << "the manufacturer's words are protected again";
  EXPECT_EQ(manufacturer_word(r.encoder_memory, 14), 0x0001);
  EXPECT_EQ(manufacturer_word(r.encoder_memory, 13), 0x8020);
}

TEST(EibTest, WrongChecksumKeepsItNotInitiated) {
  auto ops = commissioning(1);
  const std::size_t n = ops.size();
  ops.push_back(op(MC::EncoderReceiveReset));
  ops.push_back(read_position());
  ops.push_back(select(0xB9));
  const auto r = scenarios::run_scenario(scenario({ops}));
  EXPECT_TRUE(frame_of(r, n + 1).error1);
  EXPECT_EQ(frame_of(r, n + 2).outcome, Outcome::Type2Error);
  // Without the check the same image activates.
  auto s = scenario({ops});
  s.encoder.eib_activation_checks_checksum = false;
  const auto unchecked = scenarios::run_scenario(s);
  EXPECT_FALSE(frame_of(unchecked, n + 1).error1);
  EXPECT_EQ(frame_of(unchecked, n + 2).outcome, Outcome::Ok);
}

TEST(EibTest, Word14WriteActivatesWithoutReset) {
  auto ops = commissioning();
  const std::size_t n = ops.size();
  ops.push_back(read_position());
  auto s = scenario({ops});
  s.encoder.eib_activation = slave::EibActivation::Word14Write;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(frame_of(r, n - 1).outcome, Outcome::Ok);
  EXPECT_FALSE(frame_of(r, n).error1);
  EXPECT_LT(frame_of(r, n).position, 100'000U);
}

TEST(EibTest, NotSupportedAnswersPositionRequestsWithTypeOne) {
  auto s = scenario({{read_position()}});
  s.encoder.eib_position_before_commissioning = slave::EibPositionBeforeCommissioning::NotSupported;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(frame_of(r, 0).outcome, Outcome::Type1Error);
  EXPECT_EQ(r.encoder_frames[0].error, protocol::ErrorCause::ModeCommandDisrupted);
}

TEST(EibTest, SignalPeriodAndSubdivisionWeightTheLsb) {
  // A10: with words 20/21 = 0 the measuring step is the signal period over the subdivision
  // values of EnDat 2.2 words 27..29: 20 um / 4096 steps, 204 800 steps per mm.
  std::vector<std::uint16_t> m(48, 0), e(64, 0);
  for (const auto& [n, v] : connected_encoder_words()) m[n] = v;
  e[27] = 0x0001;
  e[28] = 4096;
  const auto scale = pm::steps_per_reference_unit(m, e);
  ASSERT_TRUE(scale.has_value());
  EXPECT_EQ(scale->steps % scale->per, 0U);
  EXPECT_EQ(scale->steps / scale->per, 204'800U) << "steps per mm";
  e[27] = 0;
  EXPECT_FALSE(pm::steps_per_reference_unit(m, e).has_value()) << "no scaling: words 20/21 are 0";
  // Rotary (type 8): 2048 periods per revolution x 4096 = 2^23 steps per revolution.
  m[14] = pm::encode_encoder_type(pm::EncoderType::IncrementalRotary);
  m[15] = 2048;
  e[27] = 0x0001;
  EXPECT_EQ(pm::steps_per_revolution(m, e), std::optional<std::uint64_t>{std::uint64_t{1} << 23});
}
