#pragma once
// An encoder's part in a bus of several encoders (D297403 2.10): whether the last communication
// command addressed it, whether it may drive DATA, and what a communication command asks of it.

#include <cstdint>
#include <optional>

#include "endatsim/protocol/error_handling.hpp"

namespace endatsim::slave {

class BusAddressing {
 public:
  // What the encoder does with a communication command ("Encoder receive communication command").
  struct Reaction {
    std::optional<protocol::ErrorCause> error;  // answered as a type II error (appendix A2)
    bool silent = false;                        // neither addressed nor selected: no answer at all
    // The instruction word (operating parameters word 5): the addressed encoder takes it at once
    // and acknowledges with it; a broadcast is acknowledged by the encoder active before it, then
    // carried out.
    enum class Instructions : std::uint8_t { Keep, TakeNow, TakeAfterAcknowledgment } instructions = Instructions::Keep;
  };

  // Addressed by the last communication command (every encoder is, until one names another).
  bool selected() const { return selected_; }
  // Word 5 bit 1, "data driver at high-impedance", keeps the driver off, and so does another
  // encoder's address.
  bool drives(std::uint16_t instructions) const;
  // `own`: the encoder's address (operating parameters word 4); `permitted`: whether the encoder
  // supports the command at all.
  Reaction communication_command(std::uint8_t address, std::uint16_t instruction, std::uint8_t own, bool permitted);
  // 2.10: "only the encoder with the previously selected address reacts ... until a new address
  // is given": a new address takes effect once the frame that gave it has ended.
  void frame_ended();

 private:
  bool selected_ = true;
  std::optional<bool> selected_after_frame_;
};

}  // namespace endatsim::slave
