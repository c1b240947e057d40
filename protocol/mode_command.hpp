// The 14 mode commands of spec 2.3 with their six mode bits M2 M1 M0 (M2) (M1) (M0).
// 2.1 commands repeat the first three bits inverted, most 2.2 commands repeat them as they are.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace endatsim::protocol {

enum class EndatVersion : std::uint8_t { V2_1, V2_2 };

enum class ModeCommand : std::uint8_t {
  EncoderSendPositionValues,
  SelectionOfMemoryArea,
  EncoderReceiveParameters,
  EncoderSendParameters,
  EncoderReceiveReset,
  EncoderSendTestValues,
  EncoderReceiveTestCommand,
  EncoderSendPositionValuesWithAdditionalData,
  EncoderSendPositionValuesAndSelectionOfMemoryArea,
  EncoderSendPositionValuesAndReceiveParameter,
  EncoderSendPositionValuesAndSendParameter,
  EncoderSendPositionValuesAndReceiveErrorReset,
  EncoderSendPositionValuesAndReceiveTestCommand,
  EncoderReceiveCommunicationCommand,
};

// What the encoder answers with (2.3.1, 2.4–2.10; docs/model.md §3).
enum class AnswerFormat : std::uint8_t {
  Position,    // S F1 [F2] position CRC [AI2] [AI1]
  TestValues,  // S F1 test value (40 bits) CRC — 2.9, A4.4.2 "the data width is always 40 bits"
  Parameter,   // S, 8-bit address/MRS/port echo, 16 bits, CRC (MakeCrcNorm)
};

struct ModeCommandInfo {
  ModeCommand command;
  std::uint8_t bits;        // M2 is bit 5, (M0) is bit 0; sent M2 first
  EndatVersion version;     // the "type" of the mode command (2.1 or 2.2)
  std::string_view name;    // spec wording
  std::string_view key;     // snake_case name used in scenarios and reports
  unsigned payload_bits;    // master -> encoder right after the mode bits: 0 or 8 + 16
  AnswerFormat answer;
  bool supplement;          // 2.2: 8 + 16 bits from the master after the encoder's data (docs/model.md §4)
};

// The bits after the mode bits of a 2.1 parameter command, and of a 2.2 command supplement (2.3):
// address / MRS code / port first, then the parameter.
constexpr unsigned kPayloadAddressBits = 8, kPayloadParameterBits = 16;
constexpr unsigned kPayloadBits = kPayloadAddressBits + kPayloadParameterBits;

std::span<const ModeCommandInfo> mode_commands();
const ModeCommandInfo& info(ModeCommand command);
// Six mode bits as sent, M2 first: "000111".
std::string mode_bits_string(std::uint8_t bits);
// The command whose six mode bits are exactly `bits`; none when the redundancy is broken.
std::optional<ModeCommand> decode_mode_bits(std::uint8_t bits);
std::optional<ModeCommand> mode_command_from_key(std::string_view key);

}  // namespace endatsim::protocol
