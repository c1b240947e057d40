#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/indexed_table.hpp"

#include <array>

namespace endatsim::protocol {
namespace {

using enum Information;

// Names from the tables of 2.3.5.1, 2.3.5.2 and 2.4.2.2; support bits from 3.9.2 and 3.9.3.
constexpr std::array kCodes{
    InformationInfo{Nop1, "No data content (NOP)", "nop_1", true, std::nullopt},
    InformationInfo{Diagnosis, "Diagnosis", "diagnosis", true, std::nullopt},
    InformationInfo{PositionValue2Word1, "Position value 2 word 1 LSB", "position_value_2_word_1", true, 0},
    InformationInfo{PositionValue2Word2, "Position value 2 word 2", "position_value_2_word_2", true, 0},
    InformationInfo{PositionValue2Word3, "Position value 2 word 3 MSB", "position_value_2_word_3", true, 0},
    InformationInfo{MemoryParameterLsb, "Memory parameters LSB", "memory_parameter_lsb", true, std::nullopt},
    InformationInfo{MemoryParameterMsb, "Memory parameters MSB", "memory_parameter_msb", true, std::nullopt},
    InformationInfo{MrsCodeAcknowledgment, "MRS code acknowledgment", "mrs_code_acknowledgment", true, std::nullopt},
    InformationInfo{TestCommandAcknowledgment, "Acknowledgment of test command", "test_command_acknowledgment",
                    true, std::nullopt},
    InformationInfo{TestValuesWord1, "Test values word 1 LSB", "test_values_word_1", true, 1},
    InformationInfo{TestValuesWord2, "Test values word 2", "test_values_word_2", true, 1},
    InformationInfo{TestValuesWord3, "Test values word 3 MSB", "test_values_word_3", true, 1},
    InformationInfo{Temperature1, "Temperature sensor 1", "temperature_1", true, 2},
    InformationInfo{Temperature2, "Temperature sensor 2", "temperature_2", true, 3},
    InformationInfo{AdditionalSensors, "Additional sensors", "additional_sensors", true, 4},
    InformationInfo{Type3Error1, "Type III error handling (additional data 1)", "type3_error_1", false,
                    std::nullopt},
    InformationInfo{Nop2, "No data content (NOP)", "nop_2", true, std::nullopt},
    InformationInfo{Commutation, "Commutation", "commutation", true, 0},
    InformationInfo{Acceleration, "Acceleration", "acceleration", true, 1},
    InformationInfo{CommutationAndAcceleration, "Commutation & acceleration", "commutation_and_acceleration", true,
                    0},
    InformationInfo{LimitPositionSignals, "Limit position signals", "limit_position_signals", true, 2},
    InformationInfo{LimitPositionSignalsAndAcceleration, "Limit position signals & acceleration",
                    "limit_position_signals_and_acceleration", true, 2},
    InformationInfo{AsynchronousPositionWord1, "Asynchronous position value / position value 2 word 1 LSB",
                    "asynchronous_position_word_1", true, 3},
    InformationInfo{AsynchronousPositionWord2, "Asynchronous position value / position value 2 word 2",
                    "asynchronous_position_word_2", true, 3},
    InformationInfo{AsynchronousPositionWord3, "Asynchronous position value / position value 2 word 3 MSB",
                    "asynchronous_position_word_3", true, 3},
    InformationInfo{OperatingStatusErrorSources, "Operating status error sources", "operating_status_error_sources",
                    true, 4},
    InformationInfo{Reserved26, "Currently not assigned", "reserved_26", false, std::nullopt},
    InformationInfo{Timestamp, "Timestamp", "timestamp", true, 7},
    InformationInfo{Reserved28, "Currently not assigned", "reserved_28", false, std::nullopt},
    InformationInfo{Reserved29, "Currently not assigned", "reserved_29", false, std::nullopt},
    InformationInfo{Reserved30, "Currently not assigned", "reserved_30", false, std::nullopt},
    InformationInfo{Type3Error2, "Type III error handling (additional data 2)", "type3_error_2", false,
                    std::nullopt},
};
static_assert(indexed_by(kCodes, &InformationInfo::code, Information::Type3Error2),
              "kCodes: one row per information code, in order");

}  // namespace

std::span<const InformationInfo> information_codes() { return kCodes; }

const InformationInfo& info(Information code) { return kCodes[static_cast<std::size_t>(code)]; }

std::optional<Information> information_from_key(std::string_view key) {
  for (const auto& c : kCodes)
    if (c.key == key) return c.code;
  return std::nullopt;
}

}  // namespace endatsim::protocol
