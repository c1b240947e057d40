#include <gtest/gtest.h>

#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/mode_command.hpp"

using namespace endatsim::protocol;

namespace {
std::string bits_of(const std::vector<std::uint8_t>& v) {
  std::string s;
  for (auto b : v) s += b ? '1' : '0';
  return s;
}
}  // namespace

TEST(ModeCommands, AllFourteenWithTheirSpecBits) {
  ASSERT_EQ(mode_commands().size(), 14U);
  EXPECT_EQ(info(ModeCommand::EncoderSendPositionValues).bits, 0b000111);
  EXPECT_EQ(info(ModeCommand::EncoderSendPositionValuesWithAdditionalData).bits, 0b111000);
  EXPECT_EQ(info(ModeCommand::EncoderReceiveReset).bits, 0b101010);
  EXPECT_EQ(info(ModeCommand::EncoderReceiveCommunicationCommand).bits, 0b010010);
  for (const auto& m : mode_commands()) {
    EXPECT_EQ(decode_mode_bits(m.bits), m.command) << m.name;
    // 2.3: "the first three mode bits are transferred inverted or doubly".
    const unsigned high = m.bits >> 3, low = m.bits & 7U;
    EXPECT_TRUE(low == (~high & 7U) || low == high) << m.name;
  }
  EXPECT_FALSE(decode_mode_bits(0b000101).has_value());
}

TEST(PositionFrame, EnDat21IsStartF1PositionLsbFirstCrc) {
  // S=1, F1=0, 0xA5 LSB first = 10100101, CRC 11101 (worked by hand with the A4 generator).
  EXPECT_EQ(bits_of(encode_position_frame(EndatVersion::V2_1, 8, {false, true, 0xA5})), "1" "0" "10100101" "11101");
}

TEST(PositionFrame, EnDat22AddsLowActiveF2) {
  EXPECT_EQ(bits_of(encode_position_frame(EndatVersion::V2_2, 8, {false, true, 0xA5})),
            "1" "0" "1" "10100101" "01011");
}

TEST(PositionFrame, DecodeInvertsEncode) {
  const auto layout = position_frame_layout(EndatVersion::V2_2, 25);
  const auto bits = encode_position_frame(EndatVersion::V2_2, 25, {false, true, 104462});
  ASSERT_EQ(bits.size(), layout.width());
  const auto v = layout.decode(bits);
  EXPECT_EQ(v[static_cast<std::size_t>(Field::Position)], 104462U);
  EXPECT_EQ(v[static_cast<std::size_t>(Field::Crc)], 3U);  // the spec's MakeCrcPos example
  EXPECT_EQ(layout.field_at(0), Field::StartBit);
  EXPECT_EQ(layout.field_at(3), Field::Position);
  EXPECT_EQ(layout.field_at(28), Field::Crc);
}

// 2.3: the 8 + 16 bits after a 2.1 mode command (and in a 2.2 command supplement) are the
// address, MRS code or port, then the parameter: "Selection of memory area" A9h is A9 0000h.
TEST(Payload, AddressThenParameterAsOneNumber) {
  EXPECT_EQ(make_payload(0xA9, 0x0000), 0xA90000U);
  EXPECT_EQ(make_payload(0x0B, 0xA5B4), 0x0BA5B4U);
  EXPECT_EQ(payload_address(0x0BA5B4), 0x0B);
  EXPECT_EQ(payload_parameter(0x0BA5B4), 0xA5B4);
  EXPECT_EQ(payload_layout().width(), kPayloadBits);
  EXPECT_EQ(kPayloadBits, 24U);
}
