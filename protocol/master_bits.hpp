#pragma once
// protocol/master_bits.hpp — the bits the master sends after its mode bits, as whoever reads DATA
// takes them: the encoder model and a passive decoder alike. D297403 2.3: the 8 + 16 bits of a
// 2.1 payload (from RE9 on) or of a 2.2 command supplement, MSB first; and the search for the
// supplement's start bit after the encoder handed DATA over (docs/model.md §4).

#include <cstdint>

#include "endatsim/protocol/mode_command.hpp"

namespace endatsim::protocol {

// The 8 + 16 bits the master sends, MSB first (2.3: a 2.1 payload, a 2.2 command supplement).
class ReceivedBits {
 public:
  void clear() {
    value_ = 0;
    count_ = 0;
  }
  // True when `bit` was the last of the 8 + 16.
  bool take(bool bit) {
    value_ = value_ << 1 | (bit ? 1U : 0U);
    return ++count_ == kPayloadBits;
  }
  std::uint32_t value() const { return value_; }

 private:
  std::uint32_t value_ = 0;
  unsigned count_ = 0;
};

// docs/model.md §4: after the encoder hands DATA to the master for a command supplement, the line
// floats (fail-safe HIGH) until the master drives its lead bits. The encoder lets a few rising
// edges pass while its own last bit fades, waits for a LOW, and takes the next HIGH as the
// supplement's start bit.
class SupplementStart {
 public:
  void handed_over(unsigned clock) {
    release_clock_ = clock;
    seen_low_ = false;
  }
  // Whether `bit`, on rising edge `clock`, is the start bit.
  bool found(unsigned clock, bool bit, unsigned ignored_clocks) {
    if (clock <= release_clock_ + ignored_clocks) return false;
    if (!seen_low_) {
      seen_low_ = !bit;
      return false;
    }
    return bit;
  }

 private:
  unsigned release_clock_ = 0;  // the rising edge at which the encoder released DATA
  bool seen_low_ = false;
};

}  // namespace endatsim::protocol
