#pragma once
// slave/frame_bits.hpp — the bits of one frame as the encoder's frame engine moves them: the
// answer it sends (D297403 2.3: start bit, error bits, data, CRC, then any additional data), the
// 8 + 16 bits it receives from the master (a 2.1 payload after the mode bits, or a 2.2 command
// supplement), and the search for the supplement's start bit after the encoder handed DATA over.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::slave {

// The answer of a frame, one bit per rising edge from its start bit on.
class AnswerBits {
 public:
  // Nothing to send yet (FE1 of a new frame).
  void clear() {
    bits_.clear();
    next_ = 0;
  }
  // The bits protocol encoded, sent from the start; the start bit goes no earlier than rising edge
  // `first_clock` and time `not_before` (docs/model.md §1: RE11 or RE35, t_cal or t_ac).
  void load(std::vector<std::uint8_t> bits) {
    bits_ = std::move(bits);
    next_ = 0;
  }
  void not_before(unsigned first_clock, sim::Time not_before) {
    first_clock_ = first_clock;
    not_before_ = not_before;
  }
  // The bits to send, for additional data to append to (2.3.5).
  std::vector<std::uint8_t>& bits() { return bits_; }

  bool started() const { return next_ != 0; }
  bool start_due(unsigned clock, sim::Time now) const { return clock >= first_clock_ && now >= not_before_; }
  bool sent() const { return next_ >= bits_.size(); }
  bool next() { return bits_[next_++] != 0; }

 private:
  std::vector<std::uint8_t> bits_;
  std::size_t next_ = 0;
  unsigned first_clock_ = protocol::frame_position::kEarliestStartBit;
  sim::Time not_before_{0};
};

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
    return ++count_ == protocol::kPayloadBits;
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

}  // namespace endatsim::slave
