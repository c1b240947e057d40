#include "endatsim/master/additional_data_selection.hpp"

#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/mode_command.hpp"

namespace endatsim::master {

void AdditionalDataSelection::accepted(const FrameResult& f) {
  if (f.command == protocol::ModeCommand::EncoderReceiveReset) {
    mrs_ = {};
    return;
  }
  if (f.command != protocol::ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea) return;
  const auto mrs = protocol::payload_address(*f.supplement);
  if (!protocol::selects_additional_data(mrs)) return;
  const unsigned which = protocol::is_additional_data_2(protocol::information_of_mrs(mrs)) ? 1 : 0;
  const bool stop = mrs == protocol::kStopAdditionalData1 || mrs == protocol::kStopAdditionalData2;
  mrs_[which] = stop ? std::nullopt : std::optional{mrs};
}

std::optional<protocol::Information> AdditionalDataSelection::additional_data_1() const {
  if (!mrs_[0]) return std::nullopt;
  return protocol::information_of_mrs(*mrs_[0]);
}

std::vector<std::uint8_t> AdditionalDataSelection::take() {
  std::vector<std::uint8_t> codes;
  for (unsigned i : {1U, 0U})
    if (mrs_[i]) codes.push_back(*mrs_[i]);
  mrs_ = {};
  return codes;
}

}  // namespace endatsim::master
