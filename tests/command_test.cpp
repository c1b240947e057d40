// Every mode command, bit by bit in both directions, against sequences written out from the
// spec (2.3–2.10, docs/model.md §3, §4) with a hand-written master (ScriptedFrame). The CRC
// values come from protocol::make_crc_*, which crc_test checks against the examples of A4.
#include <gtest/gtest.h>

#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/encoder.hpp"
#include "test_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::bits_lsb;
using endatsim::test_support::bits_msb;
using endatsim::test_support::PinSampler;
using endatsim::test_support::ScriptedFrame;
using protocol::ErrorCause;
using MC = protocol::ModeCommand;

namespace {

slave::EncoderParams params(protocol::EndatVersion v = protocol::EndatVersion::V2_2) {
  slave::EncoderParams p;
  p.version = v;
  p.position_bits = 8;
  p.t_cal = Time::zero();
  p.t_ac_read = Time::zero();
  p.t_ac_write = Time::zero();
  p.reset_time = Time::zero();  // frames every 200 us, also right after a reset
  p.motion.start = 0xA5;
  return p;
}

struct Bench {
  explicit Bench(const slave::EncoderParams& ep) : line(k, {}), encoder(k, line, ep), sampler(k, line) {}
  // One scripted frame every 200 us (well after t_m + t_R); the kernel runs to the end of the
  // frame's slot, so that a longer memory access is still under way at the next frame.
  void frame(unsigned clocks, const std::string& drive) {
    const Time slot = us(200) * static_cast<std::int64_t>(frames.size());
    starts.push_back(std::max(slot, k.now()));
    frames.push_back(std::make_unique<ScriptedFrame>(k, line, us(1), clocks, drive, starts.back()));
    k.run(starts.back() + us(199));
  }
  const slave::EncoderFrame& last() const { return encoder.frames().back(); }
  std::string slots(std::size_t frame, unsigned first, unsigned last) const {
    return sampler.slots_at(starts.at(frame), first, last);
  }
  Kernel k;
  line::Line line;
  slave::Encoder encoder;
  PinSampler sampler;
  std::vector<std::unique_ptr<ScriptedFrame>> frames;
  std::vector<Time> starts;
};

std::string payload(std::uint8_t address, std::uint16_t parameter) {
  return bits_msb(address, 8) + bits_msb(parameter, 16);
}

// 2.1 parameter frame (docs/model.md §3): master FE2..FE32, turnaround 33/34, start bit RE35,
// 8 + 16 bits, CRC on slots 60..64. 65 clocks: the last falling edge samples the CRC's last bit
// (one more pulse would be "more clock pulses than required", 2.4.1).
std::string parameter_frame_slots(std::uint8_t mode, std::uint32_t sent, std::uint8_t address, std::uint16_t param) {
  return ScriptedFrame::header(mode, payload(static_cast<std::uint8_t>(sent >> 16), static_cast<std::uint16_t>(sent)))
             .substr(1) +
         "00" "1" + payload(address, param) + bits_msb(protocol::make_crc_norm(address, param), 5);
}


}  // namespace

// ---- 2.1 parameter frames ------------------------------------------------------------------

TEST(ModeCommandSelectionOfMemoryArea, EchoesTheMrsCodeBitExact) {
  // 2.4.1: select the OEM area A9; the encoder repeats the MRS code and the 16 bits.
  Bench b(params());
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0x0000)));
  EXPECT_EQ(b.sampler.slots(2, 64), parameter_frame_slots(0b001110, 0xA90000, 0xA9, 0x0000));
  EXPECT_EQ(b.last().start_bit_clock, 35U);
  EXPECT_FALSE(b.last().error.has_value());
}

TEST(ModeCommandEncoderReceiveParameters, WritesA5B4AtAddress0BOfOemArea2) {
  // The example of 2.6.1: address 0B, parameter A5B4 in the OEM2 area (MRS AB); read back (2.5).
  Bench b(params());
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xAB, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x0B, 0xA5B4)));
  EXPECT_EQ(b.slots(1, 2, 64), parameter_frame_slots(0b011100, 0x0BA5B4, 0x0B, 0xA5B4));
  EXPECT_EQ(b.encoder.memory().image().areas.at(protocol::MemoryArea::Oem2).at(0x0B), 0xA5B4);
  b.frame(65, ScriptedFrame::header(0b100011, payload(0x0B, 0)));
  EXPECT_EQ(b.slots(2, 2, 64), parameter_frame_slots(0b100011, 0x0B0000, 0x0B, 0xA5B4));
}

TEST(ModeCommandEncoderReceiveReset, EchoesItsBitsAndClearsTheAdditionalDataSelection) {
  Bench b(params());
  // 2.4.2.2 selection through the 2.2 supplement, then 2.7 reset.
  b.frame(59, ScriptedFrame::header(0b001001) + std::string(18, '-') + "0000000" "1" + payload(0x4C, 0));
  ASSERT_EQ(b.encoder.additional_data_1(), protocol::Information::Temperature1);
  b.frame(65, ScriptedFrame::header(0b101010, payload(0x00, 0x0000)));
  EXPECT_EQ(b.slots(1, 2, 64), parameter_frame_slots(0b101010, 0, 0x00, 0x0000));
  EXPECT_FALSE(b.encoder.additional_data_1().has_value());  // 2.4.2.2: "after a reset ... no additional data"
}

TEST(ModeCommandEncoderReceiveTestCommand, SetsThePortForSendTestValues) {
  // 2.8 then 2.9: S F1 40 bits LSB first, CRC over 40 bits (A4.4.2).
  auto p = params(protocol::EndatVersion::V2_1);
  p.sensors.test_values[0x05] = 0x12'3456'789AULL;
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b110001, payload(0x05, 0)));
  EXPECT_EQ(b.sampler.slots(2, 64), parameter_frame_slots(0b110001, 0x050000, 0x05, 0));
  b.frame(59, ScriptedFrame::header(0b010101));
  const std::uint64_t v = 0x12'3456'789AULL;
  EXPECT_EQ(b.slots(1, 9, 58),
            "00" "1" "0" + bits_lsb(v, 40) + bits_msb(protocol::make_crc_pos(40, false, true, false, v), 5) + "1");
}

TEST(ModeCommandEncoderReceiveCommunicationCommand, EchoesAddressAndInstruction) {
  // 2.10: address 17 = 11h assigned in operating parameter word 4, then addressed with 010010.
  auto p = params();
  p.memory = slave::default_memory_image(p);
  p.memory->areas[protocol::MemoryArea::OperatingParameters][slave::word::kEncoderAddress] = 0x0011;
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b010010, payload(0x11, 0x0000)));
  EXPECT_EQ(b.sampler.slots(2, 64), parameter_frame_slots(0b010010, 0x110000, 0x11, 0x0000));
}

// ---- type II: the echo comes back inverted (A2 4.2.2) -----------------------------------

struct TypeTwoCase {
  const char* name;
  std::uint8_t select;  // MRS code selected first with 001110 (0 = none)
  std::uint8_t mode;
  std::uint8_t address;
  std::uint16_t parameter;
  ErrorCause cause;
};

class TypeTwo : public ::testing::TestWithParam<TypeTwoCase> {};

TEST_P(TypeTwo, AnswersWithTheInvertedEcho) {
  const auto& c = GetParam();
  Bench b(params());
  if (c.select != 0) b.frame(65, ScriptedFrame::header(0b001110, payload(c.select, 0)));
  const std::size_t at = c.select != 0 ? 1 : 0;
  b.frame(65, ScriptedFrame::header(c.mode, payload(c.address, c.parameter)));
  const auto inv8 = static_cast<std::uint8_t>(~c.address);
  const auto inv16 = static_cast<std::uint16_t>(~c.parameter);
  if (c.mode != 0b100011)  // a read echoes the (inverted) bits sent in place of the data
    EXPECT_EQ(b.slots(at, 2, 64),
              parameter_frame_slots(c.mode, std::uint32_t{c.address} << 16 | c.parameter, inv8, inv16));
  else
    EXPECT_EQ(b.slots(at, 35, 43), "1" + bits_msb(inv8, 8));
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, c.cause);
  EXPECT_EQ(protocol::error_type(c.cause), protocol::ErrorType::II);
}

INSTANTIATE_TEST_SUITE_P(
    AppendixA2, TypeTwo,
    ::testing::Values(
        TypeTwoCase{"Cause2AdditionalDataWithA21Command", 0, 0b001110, 0x4C, 0, ErrorCause::MrsFrameDisrupted},
        TypeTwoCase{"Cause2NotAnAreaCode", 0, 0b001110, 0xA8, 0, ErrorCause::MrsFrameDisrupted},
        TypeTwoCase{"Cause7Endat22AreaWithA21Command", 0, 0b001110, 0xBD, 0, ErrorCause::ImpermissibleMemoryArea},
        TypeTwoCase{"Cause7AreaNotAvailable", 0, 0b001110, 0xAD, 0, ErrorCause::ImpermissibleMemoryArea},
        TypeTwoCase{"Cause8AddressBeyondTheOemArea", 0xA9, 0b100011, 0x40, 0, ErrorCause::ImpermissibleAddress},
        TypeTwoCase{"Cause8ManufacturerAddressBelow4", 0xA1, 0b100011, 0x03, 0, ErrorCause::ImpermissibleAddress},
        TypeTwoCase{"Cause9WriteIntoManufacturerArea", 0xA1, 0b011100, 0x0D, 0x8019, ErrorCause::WriteProtected},
        TypeTwoCase{"Cause10ClearingAWriteProtectionBit", 0xB9, 0b011100, 0x02, 0x0000,
                    ErrorCause::WriteProtectionCleared},
        TypeTwoCase{"Cause8SettingSingleErrorBits", 0xB9, 0b011100, 0x00, 0x0001, ErrorCause::ImpermissibleAddress}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(TypeTwo, Cause9OemAreaAfterItsWriteProtectionIsActivatedByReset) {
  // 3.4.3: OR bit 2 into word 2, then "Encoder receive reset" activates it.
  Bench b(params());
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xB9, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x02, 0x0039 | 0x0004)));
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x00, 0x1234)));
  EXPECT_FALSE(b.last().error.has_value()) << "not active before the reset";
  b.frame(65, ScriptedFrame::header(0b101010, payload(0, 0)));
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x00, 0x5678)));
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, ErrorCause::WriteProtected);
  EXPECT_EQ(b.encoder.memory().image().areas.at(protocol::MemoryArea::Oem1).at(0), 0x1234);
}

TEST(TypeTwo, Cause3ATransmissionNotCompletedIsHandedOnWithTheNextAcknowledgment) {
  // A2 cause 3: "A transmission was not completed ... The error handling will be transferred
  // with the next query." A selection cut after 12 of its 24 payload bits, then two complete ones.
  Bench b(params());
  b.frame(20, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  EXPECT_FALSE(b.last().error.has_value());
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, ErrorCause::TransmissionNotCompleted);
  EXPECT_EQ(protocol::error_type(*b.last().error), protocol::ErrorType::II);
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  EXPECT_FALSE(b.last().error.has_value()) << "handed on once";
}

TEST(TypeTwo, Cause8AccessWhileBusyAfterTheFrame) {
  auto p = params();
  p.t_ac_placement = slave::MemoryAccessPlacement::AfterFrame;
  p.t_ac_write = ms(1);
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x01, 0x1111)));
  EXPECT_FALSE(b.last().error.has_value());
  b.frame(65, ScriptedFrame::header(0b100011, payload(0x01, 0)));  // 200 us later: still busy
  ASSERT_TRUE(b.last().error.has_value());
  // 2.3.1 note 1 and A2 cause 8: "with still set active busy bit".
  EXPECT_EQ(*b.last().error, ErrorCause::ImpermissibleAddress);
}

// 2.3.1 note 1: a reset with Busy = 1 gets type II as well (A2 cause 8), and does not take place:
// the additional data selected before it stay selected (2.4.2.2).
TEST(TypeTwo, Cause8ResetWhileBusyIsRefusedAndResetsNothing) {
  auto p = params();
  p.t_ac_placement = slave::MemoryAccessPlacement::AfterFrame;
  p.t_ac_write = ms(1);
  Bench b(p);
  b.frame(59, ScriptedFrame::header(0b001001) + std::string(18, '-') + "0000000" "1" + payload(0x4C, 0));
  ASSERT_EQ(b.encoder.additional_data_1(), protocol::Information::Temperature1);
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x01, 0x1111)));
  ASSERT_FALSE(b.last().error.has_value());
  b.frame(65, ScriptedFrame::header(0b101010, payload(0, 0)));  // 200 us later: still busy
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, ErrorCause::ImpermissibleAddress);
  EXPECT_EQ(b.encoder.additional_data_1(), protocol::Information::Temperature1) << "the reset did not take place";
}

TEST(TypeTwo, TooManyClocksDiscardTheWrite) {
  // 2.4.1: "If more clock pulses than required are sent ... an error message is output".
  Bench b(params());
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  b.frame(69, ScriptedFrame::header(0b011100, payload(0x01, 0x2222)));
  EXPECT_TRUE(b.last().too_many_clocks);
  EXPECT_EQ(b.encoder.memory().image().areas.at(protocol::MemoryArea::Oem1).at(1), 0);
}

TEST(ModeCommandInFrameMemoryAccess, StartBitWaitsForTac) {
  // docs/model.md §7 (InFrame, the default): the acknowledgment's start bit waits t_ac after the
  // last payload bit (RE32 at 31.5 us at 1 MHz).
  auto p = params();
  p.t_ac_read = us(10);
  Bench b(p);
  b.frame(80, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  EXPECT_EQ(b.last().start_bit_clock, 42U);  // first RE_k >= 41.5 us
}

// ---- 2.2: the command supplement and additional data ------------------------------------

namespace {

// docs/model.md §4 for an 8-bit position and no additional data: the encoder's S F1 F2 pos CRC
// on slots 11..26, its driver off from RE27; the master's 7 lead LOW bits on FE28..34, start bit
// FE35, 24 bits FE36..59. Each selected additional datum shifts this by 30 clocks.
std::string supplement_frame(std::uint8_t mode, std::uint8_t address, std::uint16_t parameter, unsigned k = 0) {
  return ScriptedFrame::header(mode) + std::string(19 + 30 * k, '-') + "0000000" "1" + payload(address, parameter);
}

std::string position22(std::uint64_t pos) {
  return "1" "0" "1" + bits_lsb(pos, 8) + bits_msb(protocol::make_crc_pos(8, false, true, true, pos), 5);
}

// 2.3.1 status table: an absolute encoder's additional data carry RM from switch-on.
constexpr std::uint8_t kRm = protocol::AdditionalDataStatus::kReferenceMark;

std::string additional_datum(std::uint8_t status, std::uint16_t data) {
  return "0" + bits_msb(status, 8) + bits_msb(data, 16) + bits_msb(protocol::make_crc_norm(status, data), 5);
}

}  // namespace

struct SupplementCase {
  const char* name;
  std::uint8_t mode;
};

class Supplement : public ::testing::TestWithParam<SupplementCase> {};

TEST_P(Supplement, EncoderAnswersThenTakesTheSupplementAfterItsStartBit) {
  Bench b(params());
  b.frame(59, supplement_frame(GetParam().mode, 0x4C, 0x0102));
  // Slot 27: nobody drives (fail-safe HIGH); then the master's lead bits, start bit, 24 bits.
  EXPECT_EQ(b.sampler.slots(9, 58), "00" + position22(0xA5) + "1" "0000000" "1" + payload(0x4C, 0x0102).substr(0, 23));
  ASSERT_TRUE(b.last().supplement.has_value());
  EXPECT_EQ(*b.last().supplement, 0x4C0102U);
}

INSTANTIATE_TEST_SUITE_P(EnDat22, Supplement,
                         ::testing::Values(SupplementCase{"SelectionOfMemoryArea", 0b001001},
                                           SupplementCase{"ReceiveParameter", 0b011011},
                                           SupplementCase{"SendParameter", 0b100100},
                                           SupplementCase{"ReceiveErrorReset", 0b101101},
                                           SupplementCase{"ReceiveTestCommand", 0b110110}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(AdditionalData, AnAddressedDatumCarriesTheAddressInByte1AndTheDataInByte2) {
  // 2.3.5: "Address or data" in byte 1, "Data" in byte 2; a parameter travels as LSB (I = 5) and MSB (I = 6).
  EXPECT_EQ(protocol::make_addressed_datum(0x0B, 0xB4), 0x0BB4);
  EXPECT_EQ(protocol::datum_address(0x0BB4), 0x0B);
  EXPECT_EQ(protocol::datum_byte(0x0BB4), 0xB4);
  EXPECT_EQ(protocol::lsb_of(0xA5B4), 0xB4);
  EXPECT_EQ(protocol::msb_of(0xA5B4), 0xA5);
  EXPECT_EQ(protocol::parameter_of(0xA5, 0xB4), 0xA5B4);
}

TEST(AdditionalData, PositionValue2TakesAsManyOfItsThreeWordsAsItsWidthNeeds) {
  // 2.3.5.1: I = 2, 3, 4 carry words 1, 2, 3 of position value 2, 16 bits each.
  EXPECT_EQ(protocol::position_value2_words(16), 1U);
  EXPECT_EQ(protocol::position_value2_words(17), 2U);
  EXPECT_EQ(protocol::position_value2_words(25), 2U);
  EXPECT_EQ(protocol::position_value2_words(48), 3U);
  EXPECT_EQ(protocol::position_value2_words(63), 3U);
}

TEST(AdditionalData, SelectedTemperatureFollowsFromTheNextFrame) {
  // 2.3.5.1 / 2.4.2.2: MRS 4Ch selects temperature 1; it comes with the next 2.2 position frame.
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 9, 57), "00" + position22(0xA5) + additional_datum(kRm | 0x0C, 2982) + "1");
}

// 2.3.1 status table, RM: "already set with switch-on with absolute encoders" (an incremental
// one sets it after its reference run: IncrementalEncoder below).
TEST(AdditionalData, AnAbsoluteEncoderSendsRmFromSwitchOn) {
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 28, 35), bits_msb(0x40 | 0x0C, 8)) << "the first datum after switch-on: RM, temperature 1";
}

TEST(AdditionalData, AdditionalData2ComesBeforeAdditionalData1) {
  auto p = params();
  p.sensors.acceleration = 0x0123;
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(89, supplement_frame(0b001001, 0x52, 0, 1));  // 52h: acceleration (additional data 2)
  b.frame(88, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 9, 87),
            "00" + position22(0xA5) + additional_datum(kRm | 0x12, 0x0123) + additional_datum(kRm | 0x0C, 2982) + "1");
}

TEST(AdditionalData, StopSendingEndsTheSelection) {
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(89, supplement_frame(0b001001, 0x4F, 0, 1));
  b.frame(28, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 9, 27), "00" + position22(0xA5) + "1");
}

TEST(AdditionalData, TypeThreeForAnImpermissibleCodeUntilReselected) {
  // A2 cause 13: I = 11010 (26) may not be selected; additional data 2 answers I = 31.
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x5A, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 27, 35), "0" + bits_msb(kRm | 31, 8));
  b.frame(89, supplement_frame(0b001001, 0x52, 0, 1));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(3, 27, 35), "0" + bits_msb(kRm | 0x12, 8));
}

TEST(AdditionalData, TypeThreeForACodeTheEncoderDoesNotSupport) {
  // A2 cause 14: word 0 of the EnDat 2.2 manufacturer area without bit 2 (temperature 1).
  auto p = params();
  p.memory = slave::default_memory_image(p);
  auto& e = p.memory->areas[protocol::MemoryArea::ManufacturerEndat22];
  e[0] = 0x001B;
  e[63] = protocol::parameters::endat22_checksum(e);
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 27, 35), "0" + bits_msb(kRm | 15, 8));
}

TEST(AdditionalData, TypeFourNopWhileTheDatumCannotBeUpdated) {
  auto p = params();
  p.sensors.not_updatable = {protocol::Information::Temperature1};
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x4C, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 27, 56), additional_datum(kRm | 0x00, 0));
}

TEST(AdditionalData, AdditionalSensorsRollTheirAddressAndCarryThe115KOffset) {
  // 2.3.5.1: the address rises with every interrogation; 12 bits of (T - 115 K) in 0.1 K.
  auto p = params();
  p.sensors.additional_sensors = {2982, 3032};
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x4E, 0));
  for (int i = 0; i < 3; ++i) b.frame(58, ScriptedFrame::header(0b111000));
  const auto data_of = [&](unsigned frame) { return b.slots(frame, 36, 51); };
  EXPECT_EQ(data_of(1), bits_msb(0x0000 | (2982 - 1150), 16));
  EXPECT_EQ(data_of(2), bits_msb(0x1000 | (3032 - 1150), 16));
  EXPECT_EQ(data_of(3), bits_msb(0x0000 | (2982 - 1150), 16));
}

TEST(AdditionalData, MemoryReadThroughTheSupplementShowsBusyThenTheValue) {
  // 2.5.1: read address 0Dh (word 13) of A1 with 100100; I = 5 (memory parameter LSB) shows the
  // address and the LSB once Busy = 0.
  auto p = params();
  p.t_ac_read = us(300);
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x45, 0));
  b.frame(89, supplement_frame(0b001001, 0xA1, 0, 1));  // busy 300 us
  b.frame(58, ScriptedFrame::header(0b111000));       // 200 us later
  EXPECT_EQ(b.slots(2, 28, 35), bits_msb(kRm | 0x20 | 5, 8)) << "Busy set";
  b.frame(89, supplement_frame(0b100100, 0x0D, 0, 1));  // 400 us after the selection: done
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(4, 28, 35), bits_msb(kRm | 0x20 | 5, 8)) << "busy with the read";
  b.frame(58, ScriptedFrame::header(0b111000));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(6, 28, 51), bits_msb(kRm | 5, 8) + bits_msb(0x0D, 8) + bits_msb(0x08, 8));
}

TEST(AdditionalData, AccessWhileBusyWithA22CommandIsIgnored) {
  // 2.3.1 note 1: "Parameter access attempts with EnDat 2.2 commands will be ignored."
  auto p = params();
  p.t_ac_write = us(500);
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0xA9, 0));
  b.frame(59, supplement_frame(0b011011, 0x01, 0x1111));
  b.frame(59, supplement_frame(0b011011, 0x02, 0x2222));  // 200 us later: busy
  EXPECT_TRUE(b.last().supplement_ignored);
  b.k.run();
  const auto& oem = b.encoder.memory().image().areas.at(protocol::MemoryArea::Oem1);
  EXPECT_EQ(oem.at(1), 0x1111);
  EXPECT_EQ(oem.at(2), 0);
}

TEST(ModeCommandErrorReset, ClearsWordsZeroAndOne) {
  // 2.7.1: errors and warnings are reset; F1 = 1 / F2 = 0 before, 0 / 1 once the source is gone.
  auto p = params();
  p.error_sources = 0x0004;
  Bench b(p);
  b.frame(28, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.sampler.slots(11, 13), "110");
  EXPECT_EQ(b.encoder.memory().operating_status(0), 0x0004);
  b.frame(59, supplement_frame(0b101101, 0, 0));
  EXPECT_EQ(b.encoder.memory().operating_status(0), 0x0000);
}

TEST(ModeCommandTestCommand22, ForcedDynamicSamplingSetsF1AndIsAcknowledged) {
  // 3.5.3: port 01h forces error message 1; I = 8 acknowledges the port; port 00h ends it.
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x48, 0));
  b.frame(89, supplement_frame(0b110110, 0x01, 0, 1));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 11, 13), "111");
  EXPECT_EQ(b.slots(2, 28, 43), bits_msb(kRm | 8, 8) + bits_msb(0x01, 8));
  b.frame(89, supplement_frame(0b110110, 0x00, 0, 1));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(4, 11, 13), "101");
}

TEST(ModeCommandType1, A21EncoderAnswers22CommandsAsNotSupported) {
  Bench b(params(protocol::EndatVersion::V2_1));
  b.frame(30, ScriptedFrame::header(0b111000));
  EXPECT_TRUE(b.last().type1_error);
  EXPECT_EQ(*b.last().error, ErrorCause::ModeCommandDisrupted);
  EXPECT_EQ(b.sampler.slots(10, 20), "11111111111");  // docs/model.md §10, hypothesis A: DATA HIGH
}

TEST(ModeCommandEncoderReceiveCommunicationCommand, HighImpedanceBroadcastSilencesTheEncoder) {
  // 2.10 / A2 cause 6: address 0000h with "data driver at high-impedance": the acknowledgment
  // is inverted, then the encoder keeps off the bus.
  Bench b(params());
  b.frame(65, ScriptedFrame::header(0b010010, payload(0x00, 0x0002)));
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, ErrorCause::DataDriverHighImpedanceBroadcast);
  b.frame(30, ScriptedFrame::header(0b000111));
  EXPECT_EQ(b.last().start_bit_clock, 11U) << int(b.last().mode_bits) << " t1 " << b.last().type1_error << " clocks " << b.last().clocks << " n " << b.encoder.frames().size();
  EXPECT_EQ(b.slots(1, 10, 20), "11111111111") << "fail-safe HIGH: nobody drives";
}

// ---- the remaining causes of appendix A2 -------------------------------------------------

TEST(AppendixA2, Cause4CommunicationCommandNotPermitted) {
  auto p = params();
  p.communication_command_permitted = false;
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b010010, payload(0x00, 0x0000)));
  EXPECT_EQ(b.sampler.slots(35, 59), "1" + payload(0xFF, 0xFFFF));
  EXPECT_EQ(*b.last().error, ErrorCause::CommunicationCommandNotPermitted);
}

TEST(AppendixA2, Cause12TheActiveEncoderGetsAnotherAddress) {
  // 2.10: the selected encoder (address 11h) receives a communication command for 22h.
  auto p = params();
  p.memory = slave::default_memory_image(p);
  p.memory->areas[protocol::MemoryArea::OperatingParameters][slave::word::kEncoderAddress] = 0x0011;
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b010010, payload(0x22, 0x0000)));
  EXPECT_EQ(b.sampler.slots(35, 43), "1" + bits_msb(0xDD, 8));
  EXPECT_EQ(*b.last().error, ErrorCause::UnknownCommunicationAddress);
  b.frame(30, ScriptedFrame::header(0b000111));  // no longer addressed: silent
  EXPECT_EQ(b.last().start_bit_clock, 0U);
}

TEST(AppendixA2, Cause11BlockAddressBeyondWord24IsAcknowledgedInverted) {
  // 2.4.2 / 3.2: two section-2 blocks (word 24); block 5 does not exist. The MRS acknowledgment
  // (additional data 1, I = 7) carries the MRS code and the block address inverted.
  auto p = params();
  p.memory = slave::default_memory_image(p);
  auto& e = p.memory->areas[protocol::MemoryArea::ManufacturerEndat22];
  e[slave::word::kSection2Blocks] = 2;
  e[63] = protocol::parameters::endat22_checksum(e);
  p.memory->section2_blocks.assign(2, std::vector<std::uint16_t>(256, 0));
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x47, 0));
  b.frame(89, supplement_frame(0b001001, 0xBF, 0x0005, 1));
  EXPECT_EQ(*b.last().error, ErrorCause::ImpermissibleBlockAddress);
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 28, 51), bits_msb(kRm | 7, 8) + bits_msb(0x40, 8) + bits_msb(0xFA, 8));
  b.frame(89, supplement_frame(0b001001, 0xBF, 0x0001, 1));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(4, 28, 51), bits_msb(kRm | 7, 8) + bits_msb(0xBF, 8) + bits_msb(0x01, 8));
}

// 2.4.2.1: "If ... more clock pulses than necessary are sent, an error message is output
// compliant to Appendix A2": cause 2, the MRS code and block address acknowledged inverted, and the
// memory area is not selected; the same selection with the right number of clocks is taken.
TEST(AppendixA2, Cause2MoreClocksThanASelectionNeeds) {
  auto p = params();
  p.t_ac_read = us(300);  // a selection that went ahead would still be busy 200 us later
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x47, 0));             // additional data 1: MRS acknowledgment
  b.frame(90, supplement_frame(0b001001, 0xA1, 0x0000, 1));     // one clock pulse more than it needs
  EXPECT_EQ(b.last().error, std::optional{ErrorCause::MrsFrameDisrupted});
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 28, 51), bits_msb(kRm | 7, 8) + bits_msb(0x5E, 8) + bits_msb(0xFF, 8)) << "A1h 00h inverted";
  EXPECT_FALSE(b.encoder.busy()) << "no memory access was started";
  b.frame(89, supplement_frame(0b001001, 0xA1, 0x0000, 1));
  EXPECT_FALSE(b.last().error.has_value());
  EXPECT_TRUE(b.encoder.busy()) << "the selection with the right clocks goes ahead";
  b.frame(58, ScriptedFrame::header(0b111000));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(5, 28, 51), bits_msb(kRm | 7, 8) + bits_msb(0xA1, 8) + bits_msb(0x00, 8));
}

TEST(AppendixA2, Cause15PositionValue2InBothAdditionalData) {
  // Interpretation of cause 15: with "position value 2" offered by additional data 2 (3.9.3 bit 6)
  // and selected in additional data 1 as well, additional data 2 answers I = 31.
  auto p = params();
  p.memory = slave::default_memory_image(p);
  auto& e = p.memory->areas[protocol::MemoryArea::ManufacturerEndat22];
  e[slave::word::kAdditionalData2Support] |= 0x0040;
  e[63] = protocol::parameters::endat22_checksum(e);
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x42, 0));
  b.frame(89, supplement_frame(0b001001, 0x56, 0, 1));
  b.frame(88, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(2, 27, 35), "0" + bits_msb(kRm | 31, 8));
  EXPECT_EQ(b.slots(2, 57, 65), "0" + bits_msb(kRm | 2, 8));
}

TEST(AppendixA2, EveryCauseHasItsType) {
  using T = protocol::ErrorType;
  EXPECT_EQ(protocol::error_type(ErrorCause::ModeCommandDisrupted), T::I);
  for (auto c : {ErrorCause::MrsFrameDisrupted, ErrorCause::TransmissionNotCompleted, ErrorCause::CommunicationCommandNotPermitted,
                 ErrorCause::EibNotInitialised, ErrorCause::DataDriverHighImpedanceBroadcast,
                 ErrorCause::ImpermissibleMemoryArea, ErrorCause::ImpermissibleAddress, ErrorCause::WriteProtected,
                 ErrorCause::WriteProtectionCleared, ErrorCause::ImpermissibleBlockAddress,
                 ErrorCause::UnknownCommunicationAddress})
    EXPECT_EQ(protocol::error_type(c), T::II) << protocol::describe(c);
  for (auto c : {ErrorCause::ImpermissibleAdditionalData, ErrorCause::UnsupportedAdditionalData,
                 ErrorCause::DuplicateAdditionalData})
    EXPECT_EQ(protocol::error_type(c), T::III) << protocol::describe(c);
  EXPECT_EQ(protocol::error_type(ErrorCause::AdditionalDataNotUpdated), T::IV);
}

// ---- what the encoder outputs: datum shift (3.6.2) and direction (3.5.16) ----------------

namespace {

slave::EncoderParams rotary_13bit(std::uint64_t measured) {
  auto p = params();
  p.position_bits = 13;  // 8192 measuring steps per revolution
  p.motion.start = measured;
  p.memory = slave::default_memory_image(p);
  return p;
}

std::uint64_t position_sent(Bench& b) { return b.last().position; }

}  // namespace

TEST(DatumShift, RotaryExampleOf362ShiftsBy568StepsAfterTheReset) {
  // 3.6.2: +20 deg (+5 deg from the manufacturer) at 8192 steps/rev -> 569 steps, EnDat-compliant
  // 568 = 238h; stored as the two's complement FFFFFDC8h and added to the position.
  auto p = rotary_13bit(1000);
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA7, 0)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x00, 0xFDC8)));
  b.frame(65, ScriptedFrame::header(0b011100, payload(0x01, 0xFFFF)));
  b.frame(27, ScriptedFrame::header(0b000111));
  EXPECT_EQ(position_sent(b), 1000U) << "operating parameters become valid with the reset (3.6)";
  b.frame(65, ScriptedFrame::header(0b101010, payload(0, 0)));
  b.frame(31, ScriptedFrame::header(0b000111));
  EXPECT_EQ(position_sent(b), 1000U - 568U);
  EXPECT_EQ(b.slots(5, 9, 30),
            "00" "1" "0" + bits_lsb(432, 13) + bits_msb(protocol::make_crc_pos(13, false, true, false, 432), 5));
}

TEST(DatumShift, BelowZeroWrapsToTheTopOfTheRange) {
  // 3.5.13 note: "directly after the zero position follows the position value 2^x - 1".
  auto p = rotary_13bit(100);
  p.memory->areas[protocol::MemoryArea::OperatingParameters][0] = 0xFF38;  // -200
  p.memory->areas[protocol::MemoryArea::OperatingParameters][1] = 0xFFFF;
  Bench b(p);
  b.frame(27, ScriptedFrame::header(0b000111));
  EXPECT_EQ(position_sent(b), 8192U - 100U);
}

TEST(DirectionOfRotation, Word30Bit0TurnsTheCountingDirection) {
  auto p = rotary_13bit(100);
  auto& m2 = p.memory->areas[protocol::MemoryArea::Manufacturer2];
  m2[30 - 16] |= 0x0001;
  auto& m3 = p.memory->areas[protocol::MemoryArea::Manufacturer3];
  std::vector<std::uint16_t> all(48, 0);
  for (unsigned i = 4; i < 48; ++i) all[i] = i < 16 ? p.memory->areas[protocol::MemoryArea::Manufacturer1][i] : i < 32 ? m2[i - 16] : m3[i - 32];
  m3[15] = protocol::parameters::manufacturer_checksum(all);
  Bench b(p);
  b.frame(27, ScriptedFrame::header(0b000111));
  EXPECT_EQ(position_sent(b), 8192U - 100U);
}

// ---- incremental encoders: relative position, RM and position value 2 (2.3.4.3) -----------

namespace {

slave::EncoderParams incremental(protocol::parameters::EncoderType type, std::int64_t counts_per_s) {
  auto p = params();
  p.position_bits = 16;
  p.motion.start = 30000;
  p.motion.counts_per_s = counts_per_s;
  p.reference_marks = {31000, 33000};
  p.memory = slave::default_memory_image(p);
  auto& m1 = p.memory->areas[protocol::MemoryArea::Manufacturer1];
  m1[slave::word::kEncoderType] = protocol::parameters::encode_encoder_type(type);
  return p;
}

}  // namespace

// 16-bit position: the answer ends with the CRC on slots 30..34, the additional datum on 35..64.
std::string select_position_value_2_16bit() {
  return ScriptedFrame::header(0b001001) + std::string(27, '-') + "0000000" "1" + payload(0x42, 0);
}

void frame_at(Bench& b, Time at) {
  b.starts.push_back(at);
  b.frames.push_back(std::make_unique<ScriptedFrame>(b.k, b.line, us(1), 65, ScriptedFrame::header(0b111000), at));
  b.k.run(at + ms(1));
}

TEST(IncrementalEncoder, RelativePositionThenRmAfterTheReferenceMark) {
  // 10 000 steps/s from 30 000: the mark at 31 000 is crossed after 100 ms.
  using T = protocol::parameters::EncoderType;
  Bench b(incremental(T::IncrementalRotary, 10'000));
  b.frame(67, select_position_value_2_16bit());
  b.frame(65, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.last().position, 2U) << "relative: 200 us x 10 000/s";
  // WRN: word 1 bit 4 "reference point not reached" (3.4.2), latched until cleared.
  EXPECT_EQ(b.slots(1, 36, 43), bits_msb(0x80, 8)) << "RM = 0, position value 2 not yet available (NOP)";
  frame_at(b, ms(150));
  EXPECT_EQ(b.last().position, 1500U);
  EXPECT_EQ(b.slots(2, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(31500, 16)) << "RM = 1, absolute position value 2";
}

TEST(IncrementalEncoder, DistanceCodedMarksNeedTwoCrossings) {
  using T = protocol::parameters::EncoderType;
  Bench b(incremental(T::IncrementalRotaryDistanceCoded, 10'000));
  b.frame(67, select_position_value_2_16bit());
  frame_at(b, ms(150));
  EXPECT_EQ(b.slots(1, 36, 43), bits_msb(0x80, 8)) << "one mark crossed: not yet referenced";
  EXPECT_NE(b.encoder.memory().operating_status(slave::word::kWarnings) & 0x0010, 0) << "reference point not reached";
  frame_at(b, ms(350));
  EXPECT_EQ(b.slots(2, 36, 43), bits_msb(0xC0 | 2, 8)) << "second mark at 33 000 crossed at 300 ms";
}

namespace {

// 16 signal periods per revolution, 2^16 steps per revolution (4096 per period), word 18 = 2
// signal periods: equidistant marks every 8192 steps, eight per revolution (3.5.10.2).
slave::EncoderParams equidistant(std::optional<std::uint64_t> selected = std::nullopt) {
  auto p = incremental(protocol::parameters::EncoderType::IncrementalRotary, 10'000);
  p.selected_reference_mark = selected;
  auto& m1 = p.memory->areas[protocol::MemoryArea::Manufacturer1];
  auto& m2 = p.memory->areas[protocol::MemoryArea::Manufacturer2];
  m1[15] = 16;     // word 15: signal periods per revolution
  m2[2] = 2;       // word 18: distance of the marks in signal periods
  m2[5] = 0x0001;  // words 20/21: 65536 steps per revolution
  m2[4] = 0x0000;
  return p;
}

void scripted_at(Bench& b, Time at, unsigned clocks, const std::string& drive) {
  b.starts.push_back(at);
  b.frames.push_back(std::make_unique<ScriptedFrame>(b.k, b.line, us(1), clocks, drive, at));
  b.k.run(at + ms(1));
}

// 1 ms after the last frame: 2.7 (RM = 0, additional data deselected), then position value 2 again.
void reset_and_reselect(Bench& b) {
  const Time at = b.starts.back() + ms(1);
  scripted_at(b, at, 65, ScriptedFrame::header(0b101010, payload(0, 0)));
  scripted_at(b, at + ms(1), 67, select_position_value_2_16bit());
}

}  // namespace

// 3.10.5: writing operating parameters 2 word 11 with bit 0 = 1, bit 1 = 0 resets RM and sets the
// warning "reference point not reached"; position value and position value 2 stay as they are.
// The mark at 33 000, crossed at 300 ms, sets RM again.
TEST(IncrementalEncoder, OperatingParameters2Word11ResetsRmButNotThePositionValues) {
  using T = protocol::parameters::EncoderType;
  Bench b(incremental(T::IncrementalRotary, 10'000));
  b.frame(67, select_position_value_2_16bit());
  frame_at(b, ms(150));
  ASSERT_EQ(b.slots(1, 36, 43), bits_msb(0xC0 | 2, 8)) << "referenced at the mark at 31 000";
  // The answer now carries additional data 1 (30 bits) before the supplement.
  const auto supplement = [](std::uint8_t mode, std::uint8_t address, std::uint16_t value) {
    return ScriptedFrame::header(mode) + std::string(27 + 30, '-') + "0000000" "1" + payload(address, value);
  };
  scripted_at(b, ms(151), 97, supplement(0b001001, 0xBB, 0));  // select operating parameters 2 (MRS BB)
  scripted_at(b, ms(155), 97, supplement(0b011011, protocol::word::kReferencing, 0x0001));
  frame_at(b, ms(160));  // the write done (t_ac 3 ms): additional data 1 is memory parameters LSB now
  frame_at(b, ms(161));
  for (const auto& f : b.encoder.frames())
    if (f.error) ADD_FAILURE() << "frame at " << sim::format_time(f.start) << ": " << protocol::describe(*f.error);
  EXPECT_EQ(b.last().position, 1610U) << "position value 1 goes on";
  EXPECT_FALSE(b.encoder.referenced());
  EXPECT_NE(b.encoder.memory().operating_status(slave::word::kWarnings) & 0x0010, 0) << "reference point not reached";
  scripted_at(b, ms(162), 67, select_position_value_2_16bit());
  frame_at(b, ms(170));
  EXPECT_EQ(b.slots(b.frames.size() - 1, 36, 59), bits_msb(0x80 | 2, 8) + bits_msb(31700, 16))
      << "RM = 0, position value 2 still absolute";
  frame_at(b, ms(350));
  EXPECT_TRUE(b.encoder.referenced()) << "the mark at 33 000 crossed at 300 ms";
  EXPECT_EQ(b.slots(b.frames.size() - 1, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(33500, 16));
}

TEST(IncrementalEncoder, ReferenceModeFollowsWord14AndWord18) {
  namespace pm = protocol::parameters;
  using T = pm::EncoderType;
  const auto mode = [](const slave::EncoderParams& p) {
    return slave::reference_scheme(slave::Memory(*p.memory), p.reference_marks, p.selected_reference_mark, 16);
  };
  EXPECT_EQ(mode(incremental(T::IncrementalRotary, 0)).marks, pm::ReferenceMarks::One) << "word 18 = 0";
  const auto coded = mode(incremental(T::IncrementalRotaryBatteryDistanceCoded, 0));
  EXPECT_EQ(coded.marks, pm::ReferenceMarks::DistanceCoded);
  EXPECT_EQ(coded.crossings, 2U);
  const auto equal = mode(equidistant());
  EXPECT_EQ(equal.marks, pm::ReferenceMarks::Equidistant);
  EXPECT_EQ(equal.distance, 8192U) << "2 periods x 65536 / 16 steps";
  EXPECT_EQ(equal.first, 0U) << "3.5.11: word 19 only for linear encoders";
  EXPECT_EQ(mode(incremental(T::Singleturn, 0)).marks, pm::ReferenceMarks::None);
  auto unscaled = equidistant();
  unscaled.memory->areas[protocol::MemoryArea::Manufacturer1][15] = 0;  // no signal period: marks in P unplaceable
  EXPECT_THROW(mode(unscaled), std::invalid_argument);
  EXPECT_THROW(unscaled.validate(), std::invalid_argument);
}

TEST(IncrementalEncoder, EquidistantMarksReferenceAtTheFirstCrossing) {
  // From 30 000 at 10 000 steps/s the first mark crossed is the fifth, at 32 768 (276.8 ms).
  Bench b(equidistant());
  b.frame(67, select_position_value_2_16bit());
  frame_at(b, ms(250));
  EXPECT_EQ(b.slots(1, 36, 43), bits_msb(0x80, 8)) << "no mark crossed yet: RM = 0, NOP";
  frame_at(b, ms(300));
  EXPECT_EQ(b.last().position, 3000U) << "position value 1 stays relative";
  // The crossed mark is taken as the first: position value 2 = 33 000 - 4 x 8192 = 232.
  EXPECT_EQ(b.slots(2, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(232, 16)) << "RM = 1 at the first crossing";
  reset_and_reselect(b);
  frame_at(b, ms(304));
  EXPECT_EQ(b.slots(5, 36, 43), bits_msb(0x80, 8)) << "after the reset RM is 0 again";
  frame_at(b, ms(1200));  // 42 000: the mark at 40 960 crossed since the reset
  EXPECT_EQ(b.slots(6, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(42'000 - 40'960, 16));
}

TEST(IncrementalEncoder, SelectedEquidistantMarkIsTheOnlyReference) {
  // 2.3.4.3: "reference marks can be selected using the hardware": mark 5 at 40 960.
  Bench b(equidistant(5));
  b.frame(67, select_position_value_2_16bit());
  frame_at(b, ms(300));
  EXPECT_EQ(b.slots(1, 36, 43), bits_msb(0x80, 8)) << "the mark at 32 768 is not the selected one";
  frame_at(b, ms(1200));
  EXPECT_EQ(b.slots(2, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(42'000, 16)) << "absolute: the mark sits where it is";
  EXPECT_THROW(slave::EncoderParams(equidistant(8)).validate(), std::invalid_argument) << "only marks 0 .. 7 exist";
}

TEST(IncrementalEncoder, OneMarkAndDistanceCodedMarksAfterReset) {
  // The other two modes: RM back to 0 after a reset, set again at the next crossing(s).
  using T = protocol::parameters::EncoderType;
  Bench one(incremental(T::IncrementalLinear, 10'000));
  one.frame(67, select_position_value_2_16bit());
  frame_at(one, ms(150));
  EXPECT_EQ(one.slots(1, 36, 43), bits_msb(0xC0 | 2, 8)) << "31 000 crossed";
  reset_and_reselect(one);
  frame_at(one, ms(200));
  EXPECT_EQ(one.slots(4, 36, 43), bits_msb(0x80, 8)) << "no mark between 31 510 and 32 000";
  frame_at(one, ms(350));
  EXPECT_EQ(one.slots(5, 36, 59), bits_msb(0xC0 | 2, 8) + bits_msb(33'500, 16)) << "33 000 crossed";
  Bench coded(incremental(T::IncrementalLinearDistanceCoded, 10'000));
  coded.frame(67, select_position_value_2_16bit());
  frame_at(coded, ms(350));
  reset_and_reselect(coded);
  frame_at(coded, ms(400));
  EXPECT_EQ(coded.slots(4, 36, 43), bits_msb(0x80, 8)) << "two marks needed again after the reset";
}

TEST(AdditionalData, DiagnosisSendsTheActivatedValuationNumbersInTurn) {
  // 3.6.3 / A3: word 3 of the operating parameters activates valuation numbers 1 and 3.
  auto p = params();
  p.sensors.valuation_numbers = {91, 92, 93, 94, 95, 96};
  p.memory = slave::default_memory_image(p);
  p.memory->areas[protocol::MemoryArea::OperatingParameters][slave::word::kDiagnosticsConfiguration] = 0x0005;
  Bench b(p);
  b.frame(59, supplement_frame(0b001001, 0x41, 0));
  for (int i = 0; i < 3; ++i) b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 28, 51), bits_msb(kRm | 0x01, 8) + bits_msb(0x01, 8) + bits_msb(91, 8));
  EXPECT_EQ(b.slots(2, 28, 51), bits_msb(kRm | 0x01, 8) + bits_msb(0x03, 8) + bits_msb(93, 8));
  EXPECT_EQ(b.slots(3, 28, 51), bits_msb(kRm | 0x01, 8) + bits_msb(0x01, 8) + bits_msb(91, 8));
}

TEST(AdditionalData, DiagnosisWithoutActivatedValuationNumbersIsNop) {
  Bench b(params());
  b.frame(59, supplement_frame(0b001001, 0x41, 0));
  b.frame(58, ScriptedFrame::header(0b111000));
  EXPECT_EQ(b.slots(1, 28, 35), bits_msb(kRm | 0x00, 8));
}

TEST(AppendixA2, Cause5EncoderBehindAnEibNotYetInitiated) {
  // 3.5.7: an EIB in factory delivery state (word 14 type Fh) is "not yet initiated": selecting
  // the OEM area is answered with the inverted echo; the encoder manufacturer's area stays open
  // for initial commissioning.
  auto p = params();
  p.kind = slave::EncoderKind::Eib;
  Bench b(p);
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA9, 0)));
  ASSERT_TRUE(b.last().error.has_value());
  EXPECT_EQ(*b.last().error, ErrorCause::EibNotInitialised);
  EXPECT_EQ(b.slots(0, 35, 43), "1" + bits_msb(0x56, 8));
  b.frame(65, ScriptedFrame::header(0b001110, payload(0xA1, 0)));
  EXPECT_FALSE(b.last().error.has_value()) << "A1 is open for commissioning";
}

// 2.10 as a part of its own: who is addressed, who may drive DATA, and when a new address counts.
TEST(BusAddressing, ANewAddressTakesEffectOnlyAfterTheFrameThatGaveIt) {
  using Instructions = slave::BusAddressing::Reaction::Instructions;
  slave::BusAddressing bus;
  EXPECT_TRUE(bus.selected());
  EXPECT_TRUE(bus.drives(0x0000));
  EXPECT_FALSE(bus.drives(protocol::parameters::kInstructionHighImpedance));
  // Another encoder's address: the active one answers with cause 12 and is deselected after the frame.
  auto r = bus.communication_command(17, 0x0000, 5, true);
  EXPECT_EQ(r.error, ErrorCause::UnknownCommunicationAddress);
  EXPECT_FALSE(r.silent);
  EXPECT_EQ(r.instructions, Instructions::Keep);
  EXPECT_TRUE(bus.selected());
  bus.frame_ended();
  EXPECT_FALSE(bus.selected());
  EXPECT_FALSE(bus.drives(0x0000));
  // Not selected and not addressed: silent; its own address selects it again and it takes the
  // instruction at once.
  EXPECT_TRUE(bus.communication_command(17, 0x0000, 5, true).silent);
  bus.frame_ended();
  EXPECT_FALSE(bus.selected());
  r = bus.communication_command(5, 0x0004, 5, true);
  EXPECT_FALSE(r.error.has_value());
  EXPECT_EQ(r.instructions, Instructions::TakeNow);
  bus.frame_ended();
  EXPECT_TRUE(bus.selected());
  // A broadcast is carried out after its acknowledgment; the high-impedance instruction to all
  // is answered as cause 6 and carried out still.
  EXPECT_EQ(bus.communication_command(0, 0x0000, 5, true).instructions, Instructions::TakeAfterAcknowledgment);
  r = bus.communication_command(0, protocol::parameters::kInstructionHighImpedance, 5, true);
  EXPECT_EQ(r.error, ErrorCause::DataDriverHighImpedanceBroadcast);
  EXPECT_EQ(r.instructions, Instructions::TakeAfterAcknowledgment);
  EXPECT_EQ(bus.communication_command(5, 0x0000, 5, false).error, ErrorCause::CommunicationCommandNotPermitted);
}
