#include "endatsim/master/additional_data_selection.hpp"

#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/mode_command.hpp"

namespace endatsim::master {

using N = protocol::AdditionalDataNumber;

void AdditionalDataSelection::accepted(const FrameResult& f) {
  if (f.command == protocol::ModeCommand::EncoderReceiveReset) {
    mrs_.clear();
    return;
  }
  if (f.command != protocol::ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea) return;
  const auto mrs = protocol::payload_address(*f.supplement);
  if (!protocol::selects_additional_data(mrs)) return;
  const N which = protocol::additional_data_number(protocol::information_of_mrs(mrs));
  mrs_[which] = protocol::stops_additional_data(mrs) ? std::nullopt : std::optional{mrs};
}

std::optional<protocol::Information> AdditionalDataSelection::additional_data_1() const {
  if (!mrs_[N::One]) return std::nullopt;
  return protocol::information_of_mrs(*mrs_[N::One]);
}

std::vector<std::uint8_t> AdditionalDataSelection::take() {
  std::vector<std::uint8_t> codes;
  for (const N which : {N::Two, N::One})
    if (mrs_[which]) codes.push_back(*mrs_[which]);
  mrs_.clear();
  return codes;
}

}  // namespace endatsim::master
