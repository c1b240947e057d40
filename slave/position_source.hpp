// The encoder's position source (D297403 2.3.4): the measuring steps the axis has moved (its
// motion profile plus slips of the coupling), the multiturn counter with its reset and overflow
// (3.4.4), an incremental encoder's reference marks and RM (2.3.4.3), a touch probe's trigger
// (2.3.4.4), and the position value as sent: direction (3.5.16), datum shift (3.6.2) and the
// "no updating of position values" instruction (3.6.5). It reads and latches words of the
// encoder's memory and knows nothing of frames or pins: every time is passed in.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/sim/int128.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {

class PositionSource {
 public:
  // `params` and `memory` belong to the encoder and outlive this source.
  PositionSource(const EncoderParams& params, Memory& memory);

  // What word 14 says the encoder is (3.5.7), sending `position_bits` (word 13 as activated):
  // absolute, incremental with its reference marks, a touch probe (16 bits, 2.3.4.4), or an EIB
  // not yet initiated, which has no valid position. Throws std::invalid_argument when the words
  // do not add up. The reference found so far is forgotten.
  void adopt(protocol::parameters::EncoderType type, unsigned position_bits);
  // Relative positions count from `now`, and reference marks crossed from then on (switch-on,
  // the end of an EIB's commissioning).
  void count_from(Time now);
  // "Encoder receive reset" or power-on (2.7): RM is 0 again for an incremental encoder and the
  // search for a reference mark starts anew; the positions are not influenced.
  void restart_reference_search(Time now);
  // 3.4.4: a multiturn counter reset, when word 3 activates it, zeroes the revolutions at `now`
  // and keeps the position within the revolution.
  void apply_function_initialization(Time now);

  // Called as each frame latches its position (FE1).
  void update_reference(Time now);
  void check_multiturn_overflow(Time now);

  // The position the encoder latches at `t` (relative for an incremental encoder, the trigger
  // status for a touch probe, 0 without a valid position) and, under 3.6.5 word 5 bit 2, what it
  // sends instead: the position of the first frame after the instruction.
  std::uint64_t latched(Time t) const;
  std::uint64_t sent(std::uint64_t latched);
  // 2.3.4.3: the absolute position of a referenced incremental encoder (position value 2), as sent.
  std::uint64_t absolute_output(Time t) const;

  // 3.10.5: operating parameters 2 word 11 resets RM; the reference found stays in use.
  void reset_reference_mark(Time now);
  void set_probe_deflected(bool deflected, Time now);
  void slip(std::int64_t steps) { slip_ += steps; }
  // 3.9.32: a touch probe's switching time, or the frame's, in the timestamp unit.
  std::uint16_t timestamp(Time frame_start) const;

  // A frame changes nothing here: an absolute encoder with no multiturn overflow reported (the
  // frame-level fast path, docs/performance.md). Which position it latches is latches_again()'s.
  bool frame_invariant() const { return valid_ && !incremental_ && !touch_probe_ && !multiturn_overflow_; }
  // A frame latching at `t` latches `true_position` and reports no multiturn overflow: the axis
  // stands still, or has not crossed a measuring step since `true_position` was latched.
  bool latches_again(Time t, std::uint64_t true_position) const;
  unsigned position_bits() const { return position_bits_; }
  // False for an EIB not yet initiated: "no valid position" (2.3.1), no position value 2.
  bool valid() const { return valid_; }
  bool incremental() const { return incremental_; }
  bool touch_probe() const { return touch_probe_; }
  // RM of the status byte (2.3.1, 2.3.4.3); an absolute encoder has it from switching on.
  bool reference_mark() const { return referenced_ && !rm_reset_at_; }
  // An absolute position is known (position value 2 of an incremental encoder, 2.3.4.3).
  bool absolute_known() const { return !incremental_ || referenced_; }
  // 3.4.4: the revolution count this frame latched has overflowed (the unlatched message).
  bool multiturn_overflow() const { return multiturn_overflow_; }

 private:
  sim::Int128 unwrapped(Time t) const;
  std::uint64_t measured(Time t) const;
  std::uint64_t output(std::uint64_t measured) const;
  bool multiturn_overflowed(Time t) const;

  const EncoderParams& params_;
  Memory& memory_;
  unsigned position_bits_ = 0;
  bool valid_ = true;              // false: an EIB not yet initiated ("no valid position", 2.3.1)
  bool incremental_ = false;
  bool touch_probe_ = false;
  bool probe_deflected_ = false;
  std::optional<Time> probe_switched_at_;
  std::int64_t slip_ = 0;
  sim::Int128 counter_origin_ = 0;         // 3.4.4: where a counter reset zeroed the multiturn count
  bool multiturn_overflow_ = false;
  ReferenceScheme reference_;
  bool referenced_ = false;
  std::optional<Time> rm_reset_at_;        // 3.10.5
  sim::Int128 reference_offset_ = 0;       // absolute = measured - offset (equidistant, first crossed)
  Time reference_origin_{0};               // where relative positions start
  Time reference_search_from_{0};          // since when crossings count
  std::optional<std::uint64_t> frozen_;    // 3.6.5 word 5 bit 2
};

}  // namespace endatsim::slave
