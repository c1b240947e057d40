#include "endatsim/slave/error_messages.hpp"

#include "endatsim/protocol/parameters.hpp"

namespace endatsim::slave {
namespace {

namespace pm = protocol::parameters;

}  // namespace

void ErrorMessages::latch() {
  const bool cyclic = memory_.function_activated(pm::EncoderFunction::CyclicOperation);
  const auto warnings = params_.warning_sources | (cyclic ? pm::kWarningCyclicOperation : 0) |
                        (temperature_exceeded() ? pm::kWarningTemperatureExceeded : 0);
  memory_.latch_errors(params_.error_sources, static_cast<std::uint16_t>(warnings));
}

bool ErrorMessages::error_message_1() const {
  return !params_.error_message_1_stuck &&
         (params_.error1 || forced(pm::kForcedError1FirstPort) || !positions_.valid() || bus_address_error_ ||
          (error_word() & memory_.manufacturer_word(word::kSupportedErrors)) != 0);
}

bool ErrorMessages::error_message_2() const {
  return !params_.error_message_2_stuck &&
         (params_.error1 || forced(pm::kForcedError2FirstPort) || !positions_.valid() ||
          (error_word() & memory_.endat22_word(word::kErrorMessage2Support)) != 0);
}

bool ErrorMessages::error_present() const {
  const auto supported = memory_.manufacturer_word(word::kSupportedErrors) | memory_.endat22_word(word::kErrorMessage2Support);
  return params_.error1 || !positions_.valid() || bus_address_error_ || (error_word() & supported) != 0;
}

void ErrorMessages::note_bus_address() {
  if (memory_.operating_parameter(word::kEncoderAddress) != 0) bus_address_error_ = true;
}

void ErrorMessages::power_cycled() {
  bus_address_error_ = false;
  note_bus_address();
}

// Word 0 as the error messages see it: the stored bits and an unlatched multiturn overflow.
std::uint16_t ErrorMessages::error_word() const {
  const auto overflow = positions_.multiturn_overflow() ? 1U << params_.multiturn_overflow_error_bit : 0U;
  return static_cast<std::uint16_t>(memory_.operating_status(word::kErrors) | overflow);
}

// 3.4.2 / 3.6.6: warning 2^1 is "only triggered by the internal temperature sensor" (temperature
// 2, on board: 3.9.2 word 0 bit 3) above the threshold of operating parameters word 6 (0: none),
// where word 36 says the warning is supported. "Exceeded" is read as strictly above.
bool ErrorMessages::temperature_exceeded() const {
  const std::uint16_t threshold = memory_.active_operating_parameters()[word::kTemperatureWarningThreshold];
  const bool supported = (memory_.manufacturer_word(word::kSupportedWarnings) & pm::kWarningTemperatureExceeded) != 0 &&
                         (memory_.endat22_word(word::kAdditionalData1Support) & pm::kSupportsTemperature2) != 0;
  return supported && threshold != 0 && params_.sensors.temperature2 > threshold;
}

bool ErrorMessages::forced(std::uint8_t first_port) const {
  const std::uint8_t port = additional_data_.test_port();
  return port >= first_port && port < first_port + pm::kForcedPortsPerMessage;
}

}  // namespace endatsim::slave
