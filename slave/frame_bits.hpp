#pragma once
// slave/frame_bits.hpp — the bits of one frame as the encoder's frame engine moves them: the
// answer it sends (D297403 2.3: start bit, error bits, data, CRC, then any additional data), and
// the master's bits it receives (protocol/master_bits.hpp: the 8 + 16 bits of a 2.1 payload or a
// 2.2 command supplement, and the search for the supplement's start bit).

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "endatsim/protocol/master_bits.hpp"
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

// The master's bits are read as a passive decoder reads them too (protocol/master_bits.hpp).
using protocol::ReceivedBits;
using protocol::SupplementStart;

}  // namespace endatsim::slave
