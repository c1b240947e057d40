#include "endatsim/slave/parameter_commands.hpp"

#include "endatsim/protocol/error_handling.hpp"
#include "endatsim/protocol/parameters.hpp"

namespace endatsim::slave {
namespace {
using protocol::ErrorCause;
using MC = protocol::ModeCommand;
namespace word = protocol::word;
}  // namespace

ParameterCommands::ParameterCommands(const EncoderParams& params, Memory& memory, MemoryAccess& access,
                                     AdditionalData& additional_data, const EibCommissioning& eib, BusAddressing& bus)
    : params_(params), memory_(memory), access_(access), additional_data_(additional_data), eib_(eib), bus_(bus) {}

ParameterCommands::Decision ParameterCommands::decide(MC command, std::uint32_t payload, Time now) {
  const auto address = protocol::payload_address(payload);
  const auto parameter = protocol::payload_parameter(payload);
  std::uint16_t echo = parameter;
  std::optional<ErrorCause> error;
  Time t_ac{0};
  bool silent = false;
  pending_ = {};
  const bool memory_access = command != MC::EncoderReceiveTestCommand && command != MC::EncoderReceiveCommunicationCommand;
  const bool selection = command == MC::SelectionOfMemoryArea;
  const bool parameter_access = selection || command == MC::EncoderReceiveParameters || command == MC::EncoderSendParameters;
  const auto area = selection ? protocol::memory_area_from_mrs(address)
                              : access_.selection() ? std::optional{access_.selection()->area} : std::nullopt;
  if (const auto refused = parameter_access ? eib_.refuses(area) : std::nullopt) {
    error = refused;  // A2 cause 5; a reset still works: it completes the commissioning
  } else if (transmission_incomplete_) {
    // A2 cause 3: a transmission was not completed; "the error handling will be transferred with
    // the next query", the first that has an acknowledgment to carry it. The access is discarded.
    error = ErrorCause::TransmissionNotCompleted;
    transmission_incomplete_ = false;
  } else if (memory_access && access_.busy()) {
    // 2.3.1 note 1: a 2.1 access or reset with Busy = 1 gets type II; A2 cause 8 names it ("with
    // still set active busy bit").
    error = ErrorCause::ImpermissibleAddress;
  } else {
    error = carry_out(command, address, parameter, echo, t_ac, silent);
    if (silent) {
      Decision none;
      none.silent = true;
      return none;
    }
  }
  // A2 type II: "the address or parameter is returned inverted". The high-impedance broadcast
  // (cause 6) is still carried out: that is what it is for (2.10).
  if (error && error != ErrorCause::DataDriverHighImpedanceBroadcast) pending_ = {};
  if (!error && pending_.kind == Pending::Kind::Write)
    access_.begin_nvm_write(pending_.selection, pending_.address, pending_.value, now + t_ac);
  const bool in_frame = params_.t_ac_placement == MemoryAccessPlacement::InFrame;
  if (!in_frame && !error && memory_access) access_.busy_until(now + t_ac);
  return {.error = error,
          .address = protocol::acknowledged_address(address, error.has_value()),
          .parameter = protocol::acknowledged_parameter(echo, error.has_value()),
          .start_delay = in_frame && !error ? t_ac : Time::zero()};
}

// What each command does (2.4 .. 2.10), when nothing refuses it.
std::optional<ErrorCause> ParameterCommands::carry_out(MC command, std::uint8_t address, std::uint16_t parameter,
                                                       std::uint16_t& echo, Time& t_ac, bool& silent) {
  switch (command) {
    case MC::SelectionOfMemoryArea:  // 2.4.1
      pending_ = {Pending::Kind::Select, {protocol::memory_area_from_mrs(address).value_or(MemoryArea{}), 0}, address, parameter};
      t_ac = params_.t_ac_read;
      return memory_.check_selection(address, 0, false);
    case MC::EncoderReceiveParameters:  // 2.6
      pending_ = {Pending::Kind::Write, access_.selection().value_or(Selection{}), address, parameter};
      t_ac = params_.t_ac_write;
      return access_.check_write(address, parameter);
    case MC::EncoderSendParameters: {  // 2.5
      t_ac = params_.t_ac_read;
      const auto read = access_.read(address);
      if (!read) return read.error;
      echo = read.value;
      return std::nullopt;
    }
    case MC::EncoderReceiveReset:  // 2.7
      pending_ = {Pending::Kind::Reset, {}, address, parameter};
      return std::nullopt;
    case MC::EncoderReceiveTestCommand:  // 2.8
      test_port_ = address;
      return std::nullopt;
    case MC::EncoderReceiveCommunicationCommand: {  // 2.10
      using Instructions = BusAddressing::Reaction::Instructions;
      const auto own = static_cast<std::uint8_t>(memory_.operating_parameter(word::kEncoderAddress));
      const auto r = bus_.communication_command(address, parameter, own, params_.communication_command_permitted);
      silent = r.silent;  // not addressed: stays silent
      if (silent) return r.error;
      if (r.instructions == Instructions::TakeNow)
        memory_.write({MemoryArea::OperatingParameters, 0}, word::kInstructions, parameter);
      else if (r.instructions == Instructions::TakeAfterAcknowledgment)
        pending_ = {Pending::Kind::Write, {MemoryArea::OperatingParameters, 0}, word::kInstructions, parameter};
      return r.error;
    }
    default:
      return std::nullopt;
  }
}

ParameterCommands::SupplementDecision ParameterCommands::decide_supplement(MC command, std::uint32_t supplement) {
  const auto address = protocol::payload_address(supplement);
  const auto parameter = protocol::payload_parameter(supplement);
  const bool memory_access = command == MC::EncoderSendPositionValuesAndReceiveParameter ||
                             command == MC::EncoderSendPositionValuesAndSendParameter ||
                             (command == MC::EncoderSendPositionValuesAndSelectionOfMemoryArea &&
                              !protocol::selects_additional_data(address));
  if (memory_access && access_.busy()) return {.memory_access = false, .error = std::nullopt, .ignored = true};
  switch (command) {
    case MC::EncoderSendPositionValuesAndSelectionOfMemoryArea: {  // 2.4.2
      if (protocol::selects_additional_data(address)) {
        additional_data_.select(address);
        return {};
      }
      const auto block = protocol::block_address_of(parameter);
      auto error = eib_.refuses(protocol::memory_area_from_mrs(address));  // A2 cause 5
      if (!error) error = memory_.check_selection(address, block, true);
      // A2 type II: the MRS code (block address) is acknowledged inverted.
      additional_data_.acknowledge_mrs(protocol::acknowledged_address(address, error.has_value()),
                                       protocol::acknowledged_address(block, error.has_value()));
      if (!error) access_.start_selection({*protocol::memory_area_from_mrs(address), block}, address, parameter, params_.t_ac_read);
      return {.memory_access = true, .error = error, .ignored = false};
    }
    case MC::EncoderSendPositionValuesAndReceiveParameter:  // 2.6.1
      return {.memory_access = true, .error = access_.start_write(address, parameter, params_.t_ac_write), .ignored = false};
    case MC::EncoderSendPositionValuesAndSendParameter:  // 2.5.1
      return {.memory_access = true, .error = access_.start_read(address, parameter, params_.t_ac_read), .ignored = false};
    case MC::EncoderSendPositionValuesAndReceiveErrorReset:  // 2.7.1
      memory_.clear_errors_and_warnings();
      return {};
    case MC::EncoderSendPositionValuesAndReceiveTestCommand:  // 2.8.1, 3.5.3
      additional_data_.set_test_port(address);
      return {};
    default:
      return {};
  }
}

void ParameterCommands::selection_disrupted(std::uint32_t supplement) {
  additional_data_.acknowledge_mrs(
      protocol::acknowledged_address(protocol::payload_address(supplement), true),
      protocol::acknowledged_address(protocol::block_address_of(protocol::payload_parameter(supplement)), true));
  access_.cancel_selection();
}

ParameterCommands::Pending ParameterCommands::take_pending() {
  const Pending p = pending_;
  pending_ = {};
  return p;
}

}  // namespace endatsim::slave
