#include "endatsim/scenarios/operation_kinds.hpp"

#include <algorithm>
#include <array>

#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {
namespace {

using master::Operation;
using P = sim::Parameter<Operation>;
using O = OperationKindRow::OtherKey;
using K = Operation::Kind;
using MC = protocol::ModeCommand;

constexpr std::int64_t kMaxTime = Scenario::kMaxTime.count();
constexpr std::int64_t kMaxFrames = 1'000'000;

const std::array kCommon{
    P{"at", &Operation::at, 0, kMaxTime, "", "Absolute start, not before the previous operation's \"at\".", false, false,
      "when the previous operation has finished"},
};

// The keys of the frames an operation sends as the script asks (read_position, frame).
const P kAddress{"address", &Operation::address, 0, 0xFF, "2.3",
                 "The 8 bits after the mode bits of a 2.1 payload or a 2.2 command supplement (address, MRS code or "
                 "port)."};
const P kParameter{"parameter", &Operation::parameter, 0, 0xFFFF, "2.3", "The 16 bits after them."};
const P kClockAdjust{"clock_adjust", &Operation::clock_adjust, -64, 64, "2.3.1, 2.4.1",
                     "A fault: that many clock pulses more (+) or fewer (-) than the frame needs. More with "
                     "encoder_send_position_values are a continuous clock to the encoder, more after a 2.1 memory "
                     "access make it discard the access, fewer leave the answer incomplete and the encoder waiting "
                     "for t_m."};
const P kCount{"count", &Operation::count, 1, kMaxFrames, "", "Frames to send."};
const P kCycle{"cycle", &Operation::cycle, 0, kMaxTime, "",
               "Frame starts this far apart; a frame that cannot start on time starts as soon as the master is "
               "ready and counts as a cycle overrun.",
               false, false, "0: each as soon as the master is ready"};
const P kContinuousWords{"continuous_words", &Operation::continuous_words, 0, 100'000, "2.3.1",
                         "Only with encoder_send_position_values: the clock runs on through this many further words; "
                         "each word is reported as a frame with its word number."};
const std::array kReadPosition{kClockAdjust, kCount, kCycle, kContinuousWords};
const std::array kFrame{kAddress, kParameter, kClockAdjust, kCount, kCycle, kContinuousWords};
const std::array kWait{P{"duration", &Operation::duration, 0, kMaxTime, "", "How long.", true}};
const std::array kAwaitNotBusy{
    P{"max_polls", &Operation::count, 1, kMaxFrames, "", "Polls before the master gives up."},
    P{"cycle", &Operation::cycle, 0, kMaxTime, "", "Poll starts this far apart."},
};
const std::array kSelectMemoryArea{
    P{"block", &Operation::parameter, 0, 0xFF, "2.4.2", "With command_type 2.2: the block address (section 2)."}};
const P kParameterAddress{"address", &Operation::address, 0, 0xFF, "2.5, 2.6", "The word's address in the selected area.",
                          true};
const std::array kWriteParameter{kParameterAddress,
                                 P{"value", &Operation::parameter, 0, 0xFFFF, "2.6", "The word written.", true}};
const std::array kReadParameter{kParameterAddress};
const std::array kTestCommand{P{"port", &Operation::address, 0, 0xFF, "2.8", "The port address.", true}};
const std::array kCommunicationCommand{
    P{"address", &Operation::address, 0, 0xFF, "2.10", "The encoder's address (0: every encoder).", true},
    P{"instruction", &Operation::parameter, 0, 0xFFFF, "2.10, 3.6.5", "The instructions (operating parameters word 5).",
      true},
};

const O kPositionCommand{"command", false,
                         "a mode command that answers with a position (default encoder_send_position_values)"};
const O kModeBits{"mode_bits", false, "six other bits to send, such as \"000111\" (a disturbed mode command)"};
const O kCommandType{"command_type", false,
                     "\"2.1\" (default) or \"2.2\": the 2.1 frame, or the 2.2 position frame with the access in its "
                     "command supplement"};
const std::array kReadPositionKeys{kPositionCommand, kModeBits};
const std::array kFrameKeys{O{"command", true, "any of the 14 mode commands"}, kModeBits};
const std::array kSelectMemoryAreaKeys{
    O{"mrs", true, "an MRS code (a number or a hex string) or the key of a memory area such as \"manufacturer_3\""},
    kCommandType};
const std::array kAccessKeys{kCommandType};
const std::array kSelectAdditionalDataKeys{
    O{"additional_data", true,
      "an information code of 2.3.5 (temperature_1, memory_parameter_lsb, ... all 32) or stop_1 / stop_2"}};
const std::array kSafetyStartupKeys{
    O{"command", false, "the position command of the start-up reads (default encoder_send_position_values)"}};

Operation await_defaults() {
  Operation o;
  o.count = 1000;
  o.cycle = sim::us(50);
  return o;
}

const std::array kKinds{
    OperationKindRow{"measure_delay", K::MeasureDelay, "2.1.2",
                     "Measures the propagation delay as the master's delay_measurement says.", {}, {}, false},
    OperationKindRow{"read_position", K::ReadPosition, "2.3.1", "Position reads.", kReadPosition, kReadPositionKeys,
                     true},
    OperationKindRow{"frame", K::ReadPosition, "2.3",
                     "Frames of any mode command, with address and parameter as its 2.1 payload or 2.2 command "
                     "supplement.",
                     kFrame, kFrameKeys, true},
    OperationKindRow{"wait", K::Wait, "", "Nothing for a while.", kWait, {}, false},
    OperationKindRow{"await_not_busy", K::AwaitNotBusy, "2.5.1, 2.6.1",
                     "Frames of encoder_send_position_values_with_additional_data until additional data 1 shows "
                     "Busy = 0; a poll answered without additional data 1 ends the wait at once (select additional "
                     "data 1 first). The summary and the results report both kinds of giving up (busy_timeouts, "
                     "busy_unreadable).",
                     kAwaitNotBusy, {}, true, {}, {}, await_defaults()},
    OperationKindRow{"select_memory_area", K::ReadPosition, "2.4.1, 2.4.2", "Selects a memory area (or a block).",
                     kSelectMemoryArea, kSelectMemoryAreaKeys, true, MC::SelectionOfMemoryArea,
                     MC::EncoderSendPositionValuesAndSelectionOfMemoryArea},
    OperationKindRow{"write_parameter", K::ReadPosition, "2.6, 2.6.1", "Writes a word of the selected area.",
                     kWriteParameter, kAccessKeys, true, MC::EncoderReceiveParameters,
                     MC::EncoderSendPositionValuesAndReceiveParameter},
    OperationKindRow{"read_parameter", K::ReadPosition, "2.5, 2.5.1", "Reads a word of the selected area.",
                     kReadParameter, kAccessKeys, true, MC::EncoderSendParameters,
                     MC::EncoderSendPositionValuesAndSendParameter},
    OperationKindRow{"test_command", K::ReadPosition, "2.8, 2.8.1", "Selects the port whose test values follow.",
                     kTestCommand, kAccessKeys, true, MC::EncoderReceiveTestCommand,
                     MC::EncoderSendPositionValuesAndReceiveTestCommand},
    OperationKindRow{"select_additional_data", K::ReadPosition, "2.4.2.2",
                     "Selects additional data 1 or 2 by its MRS code (40h .. 5Fh), or stops one.", {},
                     kSelectAdditionalDataKeys, true, MC::EncoderSendPositionValuesAndSelectionOfMemoryArea},
    OperationKindRow{"communication_command", K::ReadPosition, "2.10",
                     "Addresses an encoder on a bus and gives it instructions.", kCommunicationCommand, {}, true,
                     MC::EncoderReceiveCommunicationCommand},
    OperationKindRow{"reset", K::ReadPosition, "2.7", "Resets the encoder; the master then waits its reset_wait.", {},
                     {}, true, MC::EncoderReceiveReset},
    OperationKindRow{"error_reset", K::ReadPosition, "2.7.1", "Resets the error messages.", {}, {}, true,
                     MC::EncoderSendPositionValuesAndReceiveErrorReset},
    OperationKindRow{"send_test_values", K::ReadPosition, "2.9", "Reads the test values of the selected port.", {}, {},
                     true, MC::EncoderSendTestValues},
    OperationKindRow{"power_on_sequence", K::PowerOnSequence, "2.3.3",
                     "CLOCK HIGH for t1 + t2, one LOW pulse, HIGH for t3, as after switching on.", {}, {}, false},
    OperationKindRow{"startup_routine", K::StartupRoutine, "3.4.1",
                     "The switch-on routine of an older edition of the brochure, with 2.1 commands only: reset, 50 ms, "
                     "read and clear alarms and warnings (0000h, then a reset and 50 ms), read words 13 and 37.",
                     {}, {}, true},
    OperationKindRow{"verify_checksum", K::VerifyChecksum, "3.5.26",
                     "Selects A1, A3, A5 and reads the encoder manufacturer's words 4 .. 47; word 47 against the sum of "
                     "words 4 .. 46 (expectation checksum ok | mismatch).",
                     {}, {}, true},
    OperationKindRow{"safety_startup", K::SafetyStartup, "",
                     "The switched-on safety start-up checks, then the axis release (docs/safety.md).", {},
                     kSafetyStartupKeys, true},
    OperationKindRow{"diagnosis_setup", K::DiagnosisSetup, "A3",
                     "Reads what the diagnosis needs, writes word 3 and resets if it differs, selects the diagnosis "
                     "(docs/diagnostics.md).",
                     {}, {}, true},
};

}  // namespace

std::span<const sim::Parameter<Operation>> operation_common_parameters() { return kCommon; }

std::span<const OperationKindRow> operation_kinds() { return kKinds; }

const OperationKindRow* operation_kind(std::string_view key) {
  const auto it = std::find_if(kKinds.begin(), kKinds.end(), [&](const OperationKindRow& r) { return r.key == key; });
  return it == kKinds.end() ? nullptr : &*it;
}

}  // namespace endatsim::scenarios
