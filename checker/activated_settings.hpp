// What the master has set in the encoder, as the wires show it: the memory area selected, word 3
// of the operating status written, and its activation by "Encoder receive reset" (D297403
// 3.4.4: "Word 3 is only activated after the mode command Encoder receive reset is sent").
// The checker judges recovery times against the recovery time I that is active, not the one the
// encoder was declared with.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/protocol/mode_command.hpp"

namespace endatsim::checker {

class ActivatedSettings {
 public:
  explicit ActivatedSettings(bool short_t_m) : short_t_m_(short_t_m) {}

  // A frame the encoder accepted (answer and CRC as expected): its mode command, the 8 + 16 bits
  // after the mode bits (2.1 parameter commands) and the 2.2 command supplement.
  void on_frame(protocol::ModeCommand command, std::optional<std::uint32_t> payload,
                std::optional<std::uint32_t> supplement);
  // Switching the supply off and on activates word 3 as a reset does (D297403 3.4.3 and 3.4.4:
  // "send the Encoder receive reset mode command or switch the power supply off and on") and
  // forgets the selected memory area.
  void on_switched_on();
  // Recovery time I 1.25 .. 3.75 us for 2.2 mode commands (3.4.4 bits 0 and 1).
  bool short_t_m() const { return short_t_m_; }
  // Word 3 has been written since the last activation: a reset would change the setting.
  bool pending() const { return written_.has_value(); }
  bool operator==(const ActivatedSettings&) const = default;

 private:
  void activate();
  void select(std::uint8_t mrs);
  void write(std::uint8_t address, std::uint16_t value);

  bool short_t_m_;
  std::optional<std::uint8_t> area_;      // MRS code of the selected memory area
  std::optional<std::uint16_t> written_;  // word 3 as written, not yet activated
};

}  // namespace endatsim::checker
