#include "endatsim/slave/bus_addressing.hpp"

#include "endatsim/protocol/parameters.hpp"

namespace endatsim::slave {

using protocol::ErrorCause;
using protocol::parameters::kInstructionHighImpedance;

bool BusAddressing::drives(std::uint16_t instructions) const {
  return selected_ && (instructions & kInstructionHighImpedance) == 0;
}

BusAddressing::Reaction BusAddressing::communication_command(std::uint8_t address, std::uint16_t instruction,
                                                             std::uint8_t own, bool permitted) {
  Reaction r;
  if (!permitted) r.error = ErrorCause::CommunicationCommandNotPermitted;
  else if (address == 0 && (instruction & kInstructionHighImpedance) != 0) r.error = ErrorCause::DataDriverHighImpedanceBroadcast;
  else if (address != 0 && address != own && selected_) r.error = ErrorCause::UnknownCommunicationAddress;
  selected_after_frame_ = address == 0 || address == own;
  if (!selected_ && !*selected_after_frame_) {
    r.silent = true;
    return r;
  }
  if (address == own && address != 0) r.instructions = Reaction::Instructions::TakeNow;
  else if (address == 0) r.instructions = Reaction::Instructions::TakeAfterAcknowledgment;
  return r;
}

void BusAddressing::frame_ended() {
  if (selected_after_frame_) selected_ = *selected_after_frame_;
  selected_after_frame_.reset();
}

}  // namespace endatsim::slave
