// The encoder's error messages and the operating status they come from (D297403 2.3.1: F1
// high-active, F2 low-active and sent with 2.2 mode commands only; 3.4.1 / 3.4.2 words 0 and 1):
// the error bits of word 0 each message supports (3.5.20 word 35, 3.9.8), an unlatched multiturn
// overflow (3.4.4), a bus address in word 4 (3.6.4), an EIB not yet initiated (A2 cause 5),
// forced dynamic sampling through the test port (3.5.3), and the faults a scenario sets (stuck
// error paths, error and warning sources). It latches words 0 and 1 as each frame begins.
#pragma once

#include <cstdint>

#include "endatsim/slave/additional_data.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/position_source.hpp"

namespace endatsim::slave {

class ErrorMessages {
 public:
  // The four belong to the encoder and outlive this part.
  ErrorMessages(const EncoderParams& params, Memory& memory, const PositionSource& positions,
                const AdditionalData& additional_data)
      : params_(params), memory_(memory), positions_(positions), additional_data_(additional_data) {}

  // FE1: the error and warning sources into words 0 and 1 (3.4.2: word 1 bit 5 reports cyclic
  // operation while word 3 activates it; bit 1 the internal temperature above word 6's threshold).
  void latch();
  // 2.3.1: error message 1 (F1, HIGH = error) and whether error message 2 is active (F2 LOW).
  bool error_message_1() const;
  bool error_message_2() const;
  // Ground truth: an error the encoder knows of, whether or not a message path shows it.
  bool error_present() const;

  // 3.6.4: "Error bit 1 is always set if a bit is set in this word [word 4]. This can only be
  // cleared by resetting the word to 0000h and switching the power off and on."
  void note_bus_address();
  void power_cycled();

 private:
  std::uint16_t error_word() const;
  bool temperature_exceeded() const;
  bool forced(std::uint8_t first_port) const;

  const EncoderParams& params_;
  Memory& memory_;
  const PositionSource& positions_;
  const AdditionalData& additional_data_;
  bool bus_address_error_ = false;
};

}  // namespace endatsim::slave
