#include "endatsim/checker/activated_settings.hpp"

#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/parameters.hpp"

namespace endatsim::checker {

void ActivatedSettings::on_frame(protocol::ModeCommand command, std::optional<std::uint32_t> payload,
                                 std::optional<std::uint32_t> supplement) {
  using MC = protocol::ModeCommand;
  const auto address = [](std::uint32_t bits) { return protocol::payload_address(bits); };
  const auto value = [](std::uint32_t bits) { return protocol::payload_parameter(bits); };
  switch (command) {
    case MC::SelectionOfMemoryArea:
      if (payload) select(address(*payload));
      break;
    case MC::EncoderSendPositionValuesAndSelectionOfMemoryArea:
      // 2.4.2.2: MRS codes 40h .. 5Fh select additional data, not a memory area.
      if (supplement && !protocol::selects_additional_data(address(*supplement))) select(address(*supplement));
      break;
    case MC::EncoderReceiveParameters:
      if (payload) write(address(*payload), value(*payload));
      break;
    case MC::EncoderSendPositionValuesAndReceiveParameter:
      if (supplement) write(address(*supplement), value(*supplement));
      break;
    case MC::EncoderReceiveReset:
      activate();
      break;
    default: break;
  }
}

void ActivatedSettings::on_switched_on() {
  activate();
  area_.reset();
}

void ActivatedSettings::activate() {
  if (written_)
    short_t_m_ = protocol::parameters::function_activated(*written_, protocol::parameters::EncoderFunction::ShortRecoveryTime);
  written_.reset();
}

void ActivatedSettings::select(std::uint8_t mrs) { area_ = mrs; }

void ActivatedSettings::write(std::uint8_t address, std::uint16_t value) {
  // 3.4: the operating status (MRS B9) holds words 0 .. 3 at addresses 0 .. 3.
  if (area_ == protocol::info(protocol::MemoryArea::OperatingStatus).mrs && address == protocol::word::kFunctionInitialization)
    written_ = value;
}

}  // namespace endatsim::checker
