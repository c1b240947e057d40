#include "endatsim/slave/position_source.hpp"

#include <stdexcept>
#include <string>

namespace endatsim::slave {
namespace {

namespace pm = protocol::parameters;
using pm::EncoderFunction;

sim::Int128 wrapped(sim::Int128 p, unsigned bits) {
  const sim::Int128 range = sim::Int128{1} << bits;
  p %= range;
  return p < 0 ? p + range : p;
}

}  // namespace

sim::Int128 MotionProfile::steps_by(Time t) const {
  return sim::counts_after(counts_per_s, t.count());
}

PositionSource::PositionSource(const EncoderParams& params, Memory& memory) : params_(params), memory_(memory) {}

void PositionSource::adopt(pm::EncoderType type, unsigned position_bits) {
  touch_probe_ = type == pm::EncoderType::TouchProbe;
  if (touch_probe_ && position_bits != protocol::kTouchProbeBits)
    throw std::invalid_argument("a touch probe (word 14 type 5) sends " + std::to_string(protocol::kTouchProbeBits) +
                                " bits (2.3.4.4), but position_bits is " +
                                std::to_string(position_bits));
  reference_ = slave::reference_scheme(memory_, params_.reference_marks, params_.selected_reference_mark, position_bits);
  position_bits_ = position_bits;
  valid_ = type != pm::EncoderType::ExternalInterfaceBox;
  incremental_ = reference_.marks != pm::ReferenceMarks::None;
  referenced_ = !incremental_;
  rm_reset_at_.reset();
  reference_offset_ = 0;
}

void PositionSource::count_from(Time now) { reference_origin_ = reference_search_from_ = now; }

void PositionSource::restart_reference_search(Time now) {
  // 2.7: "this bit is set to 0 via Encoder receive reset ... Position value 1 and position value 2
  // are not influenced by this."
  referenced_ = !incremental_;
  rm_reset_at_.reset();
  reference_search_from_ = now;
}

void PositionSource::apply_function_initialization(Time now) {
  if (params_.multiturn_bits == 0 || !memory_.function_activated(EncoderFunction::MultiturnCounterReset)) return;
  const sim::Int128 steps_per_revolution = sim::Int128{1} << (position_bits_ - params_.multiturn_bits);
  counter_origin_ = sim::floor_div(unwrapped(now), steps_per_revolution) * steps_per_revolution;
}

// 2.3.4.3: RM is set once the axis has crossed a reference mark as the scheme needs it (two with
// distance-coded marks, the selected one of equidistant marks) since switching on or the last
// reset; until then word 1 bit 4 warns "reference point not reached".
void PositionSource::update_reference(Time now) {
  if (referenced_ && rm_reset_at_) {
    if (find_reference(reference_, unwrapped(*rm_reset_at_), unwrapped(now), position_bits_)) rm_reset_at_.reset();
    return;
  }
  if (referenced_) return;
  if (const auto offset = find_reference(reference_, unwrapped(reference_search_from_), unwrapped(now), position_bits_)) {
    referenced_ = true;
    reference_offset_ = *offset;
  } else {
    memory_.latch_errors(0, pm::kWarningReferencePointNotReached);
  }
}

// UNCERTAIN reading of 3.4.4: the overflow error message sets F1/F2 in the frames that latch an
// overflowed count; with the overflow latch, the error goes into word 0 (bit
// multiturn_overflow_error_bit) and stays until cleared as 3.4.1 says.
void PositionSource::check_multiturn_overflow(Time now) {
  multiturn_overflow_ = false;
  if (!memory_.function_activated(EncoderFunction::MultiturnOverflowErrorMessage) || !multiturn_overflowed(now)) return;
  if (memory_.function_activated(EncoderFunction::MultiturnOverflowLatch))
    memory_.latch_errors(static_cast<std::uint16_t>(1U << params_.multiturn_overflow_error_bit), 0);
  else
    multiturn_overflow_ = true;
}

// 2.3.4.3: incremental encoders send relative positions, counted from switching on. 2.3.4.4: a
// touch probe sends 16 bits, the LSB its trigger status; the other 15 are "TBD" and sent as 0.
std::uint64_t PositionSource::latched(Time t) const {
  if (!valid_) return 0;  // EibPositionBeforeCommissioning::ErrorBit: no valid position
  if (touch_probe_) return probe_deflected_ ? 1 : 0;
  if (incremental_) return output(static_cast<std::uint64_t>(unwrapped(t) - unwrapped(reference_origin_)));
  return output(measured(t));
}

// 3.6.5 word 5 bit 2, "no updating of position values": from the first frame after the
// instruction the encoder keeps sending the position it latched then (our reading: the spec
// names the instruction only), until the bit is cleared.
std::uint64_t PositionSource::sent(std::uint64_t latched) {
  if ((memory_.instructions() & pm::kInstructionNoPositionUpdate) == 0) {
    frozen_.reset();
    return latched;
  }
  if (!frozen_) frozen_ = latched;
  return *frozen_;
}

bool PositionSource::latches_again(Time t, std::uint64_t true_position) const {
  if (memory_.function_activated(EncoderFunction::MultiturnOverflowErrorMessage) && multiturn_overflowed(t)) return false;
  return latched(t) == true_position;
}

std::uint64_t PositionSource::absolute_output(Time t) const {
  return output(static_cast<std::uint64_t>(wrapped(static_cast<sim::Int128>(measured(t)) - reference_offset_, position_bits_)));
}

void PositionSource::reset_reference_mark(Time now) {
  if (!incremental_) return;
  rm_reset_at_ = now;
  memory_.latch_errors(0, pm::kWarningReferencePointNotReached);
}

void PositionSource::set_probe_deflected(bool deflected, Time now) {
  if (!touch_probe_) throw std::invalid_argument("only a touch probe (word 14 type 5) can be deflected");
  if (deflected && !probe_deflected_) probe_switched_at_ = now;
  probe_deflected_ = deflected;
  // UNCERTAIN (3.10.1 names operating parameters 2 word 2 "status of touch probes", no bits):
  // bit 0 follows the trigger status.
  const Selection status{MemoryArea::OperatingParameters2, 0};
  if (const auto read = memory_.read(status, word::kTouchProbeStatus))
    memory_.force(status, word::kTouchProbeStatus, static_cast<std::uint16_t>((read.value & ~pm::kTouchProbeTriggered) | (deflected ? pm::kTouchProbeTriggered : 0U)));
}

std::uint16_t PositionSource::timestamp(Time frame_start) const {
  if (touch_probe_ && probe_switched_at_) {
    if (const auto unit = pm::timestamp_unit_duration(pm::decode_timestamp_unit(memory_.endat22_word(word::kTimestampUnit))))
      return static_cast<std::uint16_t>(*probe_switched_at_ / *unit);
  }
  return static_cast<std::uint16_t>(frame_start / params_.sensors.timestamp_unit);
}

sim::Int128 PositionSource::unwrapped(Time t) const {
  return static_cast<sim::Int128>(params_.motion.start) + slip_ + params_.motion.steps_by(t);
}

std::uint64_t PositionSource::measured(Time t) const {
  return static_cast<std::uint64_t>(wrapped(unwrapped(t) - counter_origin_, position_bits_));
}

// The position as sent: the measured value in the direction word 30 chooses (3.5.16), plus the
// datum shift of operating parameters words 0..2 as activated by the last reset (3.6.2: "the
// value must be added"; 3.5.13: words 22/23 have no effect on the output), modulo 2^n ("after
// the zero position follows 2^x - 1").
std::uint64_t PositionSource::output(std::uint64_t measured) const {
  const unsigned n = position_bits_;
  const std::uint64_t mask = protocol::position_mask(n);
  const bool falling = pm::decode_direction_falling(memory_.manufacturer_word(word::kDirection));
  const std::uint64_t p = falling ? (0 - measured) & mask : measured;
  const auto& op = memory_.active_operating_parameters();
  const unsigned w = word::kDatumShift;
  const std::int64_t shift = pm::datum_shift_has_48_bits(n) ? pm::decode_datum_shift48(op[w], op[w + 1], op[w + 2]) : pm::decode_datum_shift32(op[w], op[w + 1]);
  return (p + static_cast<std::uint64_t>(shift)) & mask;
}

// The revolution counter has left 0 .. 2^M - 1 (counting up past the top or down past 0).
bool PositionSource::multiturn_overflowed(Time t) const {
  const sim::Int128 p = unwrapped(t) - counter_origin_;
  return params_.multiturn_bits > 0 && (p < 0 || p >= (sim::Int128{1} << position_bits_));
}

}  // namespace endatsim::slave
