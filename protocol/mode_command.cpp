#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/indexed_table.hpp"
#include "endatsim/protocol/timing.hpp"

#include <array>

namespace endatsim::protocol {
namespace {

using enum ModeCommand;
using enum EndatVersion;
using enum AnswerFormat;

// Spec 2.3, mode command table.
constexpr std::array kModeCommands{
    ModeCommandInfo{EncoderSendPositionValues, 0b000111, V2_1, "Encoder send position values",
                    "encoder_send_position_values", 0, Position, false},
    ModeCommandInfo{SelectionOfMemoryArea, 0b001110, V2_1, "Selection of memory area", "selection_of_memory_area", kPayloadBits, Parameter, false},
    ModeCommandInfo{EncoderReceiveParameters, 0b011100, V2_1, "Encoder receive parameters",
                    "encoder_receive_parameters", kPayloadBits, Parameter, false},
    ModeCommandInfo{EncoderSendParameters, 0b100011, V2_1, "Encoder send parameters", "encoder_send_parameters", kPayloadBits, Parameter, false},
    ModeCommandInfo{EncoderReceiveReset, 0b101010, V2_1, "Encoder receive reset", "encoder_receive_reset", kPayloadBits, Parameter, false},
    ModeCommandInfo{EncoderSendTestValues, 0b010101, V2_1, "Encoder send test values", "encoder_send_test_values", 0, TestValues, false},
    ModeCommandInfo{EncoderReceiveTestCommand, 0b110001, V2_1, "Encoder receive test command",
                    "encoder_receive_test_command", kPayloadBits, Parameter, false},
    ModeCommandInfo{EncoderSendPositionValuesWithAdditionalData, 0b111000, V2_2,
                    "Encoder send position values with additional data",
                    "encoder_send_position_values_with_additional_data", 0, Position, false},
    ModeCommandInfo{EncoderSendPositionValuesAndSelectionOfMemoryArea, 0b001001, V2_2,
                    "Encoder send position values and selection of memory area or of the additional data",
                    "encoder_send_position_values_and_selection_of_memory_area", 0, Position, true},
    ModeCommandInfo{EncoderSendPositionValuesAndReceiveParameter, 0b011011, V2_2,
                    "Encoder send position values and receive parameter",
                    "encoder_send_position_values_and_receive_parameter", 0, Position, true},
    ModeCommandInfo{EncoderSendPositionValuesAndSendParameter, 0b100100, V2_2,
                    "Encoder send position values and send parameter",
                    "encoder_send_position_values_and_send_parameter", 0, Position, true},
    ModeCommandInfo{EncoderSendPositionValuesAndReceiveErrorReset, 0b101101, V2_2,
                    "Encoder send position values and receive error reset",
                    "encoder_send_position_values_and_receive_error_reset", 0, Position, true},
    ModeCommandInfo{EncoderSendPositionValuesAndReceiveTestCommand, 0b110110, V2_2,
                    "Encoder send position values and receive test command",
                    "encoder_send_position_values_and_receive_test_command", 0, Position, true},
    ModeCommandInfo{EncoderReceiveCommunicationCommand, 0b010010, V2_2, "Encoder receive communication command",
                    "encoder_receive_communication_command", kPayloadBits, Parameter, false},
};
static_assert(indexed_by(kModeCommands, &ModeCommandInfo::command, ModeCommand::EncoderReceiveCommunicationCommand),
              "kModeCommands: one row per mode command, in order");

}  // namespace

std::span<const ModeCommandInfo> mode_commands() { return kModeCommands; }

const ModeCommandInfo& info(ModeCommand command) { return kModeCommands[static_cast<std::size_t>(command)]; }

std::optional<ModeCommand> decode_mode_bits(std::uint8_t bits) {
  for (const auto& m : kModeCommands)
    if (m.bits == bits) return m.command;
  return std::nullopt;
}

std::optional<ModeCommand> mode_command_from_key(std::string_view key) {
  for (const auto& m : kModeCommands)
    if (m.key == key) return m.command;
  return std::nullopt;
}

std::string mode_bits_string(std::uint8_t bits) {
  std::string text;
  for (unsigned b = frame_position::kModeBits; b-- > 0;) text += ((bits >> b) & 1U) != 0 ? '1' : '0';
  return text;
}

}  // namespace endatsim::protocol
