// What the master made of one frame (FrameResult): what it sent, what it received and how it
// judged it (FrameOutcome), with each additional datum as received (D297403 2.3.5). Monitors,
// reports and the parts of the master that read the encoder's memory work from these.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "endatsim/protocol/indexed_table.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

using protocol::ModeCommand;
using sim::Hertz;
using sim::Time;

// Type2Error: a 2.1 parameter frame whose echo came back inverted (A2 type II). EchoMismatch:
// one whose echo differs from what was sent otherwise (CarefulMaster::verify_echo).
// TooFewClocks: the master's clock pulses ended before the answer it expected was complete (the
// start bit came later than the pulses it gives allow); no CRC was judged.
enum class FrameOutcome : std::uint8_t { Ok, CrcError, NoStartBit, Type1Error, Type2Error, EchoMismatch, TooFewClocks };
inline constexpr std::array kFrameOutcomes{FrameOutcome::Ok,         FrameOutcome::CrcError,   FrameOutcome::NoStartBit,
                                           FrameOutcome::Type1Error, FrameOutcome::Type2Error, FrameOutcome::EchoMismatch,
                                           FrameOutcome::TooFewClocks};
static_assert(protocol::lists_in_order(kFrameOutcomes, FrameOutcome::TooFewClocks),
              "kFrameOutcomes: the outcomes in the order of their values up to the last one, TooFewClocks (tables are "
              "indexed by them); a new outcome goes after it, in the list and in this check");
std::string_view to_string(FrameOutcome o);

// One additional datum as received (2.3.5).
struct AdditionalDatum {
  std::uint8_t status = 0;  // WRN RM Busy I4..I0
  std::uint16_t data = 0;   // bytes 1 and 2
  std::uint8_t crc_received = 0;
  std::uint8_t crc_expected = 0;  // over status and data (appendix A4)
  bool crc_ok = false;            // the CRCs agree and the datum's leading bit is LOW
  protocol::Information information() const {
    return static_cast<protocol::Information>(status & protocol::AdditionalDataStatus::kInformation);
  }
  bool busy() const { return (status & protocol::AdditionalDataStatus::kBusy) != 0; }
  bool operator==(const AdditionalDatum&) const = default;
};

struct FrameResult {
  std::uint64_t index = 0;
  std::size_t operation = 0;  // index of the operation in the order enqueued (Operation::script_index)
  unsigned word = 0;        // 0: the word after the mode command; k: the k-th continuous-clock word
  Time start{0};            // FE1 at the master logic
  Time end{0};              // last rising edge
  ModeCommand command = ModeCommand::EncoderSendPositionValues;
  std::uint8_t mode_bits = 0;  // as sent
  std::optional<std::uint32_t> payload;     // 8 + 16 bits sent after the mode bits (2.1 parameter frames)
  std::optional<std::uint32_t> supplement;  // 8 + 16 bits sent as the 2.2 command supplement
  unsigned answer_bits = 0;                 // the answer the master expects: S .. CRC and additional data
  unsigned position_bits = 0;               // as the master clocks them (configured, or word 13)
  Hertz f_c = 0;
  bool measurement = false;     // part of a propagation-delay measurement
  bool compensated = false;
  Time t_d_used{0};
  FrameOutcome outcome = FrameOutcome::NoStartBit;
  bool error1 = false;
  bool error2 = true;
  // An error message as the master evaluates it: F1, and with SafetyParams::error_messages also
  // F2 of 2.2 frames (2.3.1: two independent error messages).
  bool error_detected = false;
  std::uint64_t position = 0;
  std::uint64_t test_value = 0;        // "Encoder send test values"
  std::uint8_t echo_address = 0;       // parameter frames: address / MRS code / port as answered
  std::uint16_t echo_parameter = 0;    // ... and the 16 bits (the parameter read)
  std::vector<AdditionalDatum> additional_data;  // in wire order: additional data 2 first
  std::uint8_t crc_received = 0;
  std::uint8_t crc_expected = 0;
  unsigned start_bit_clock = 0;  // as the master counted it
  unsigned clocks = 0;
  std::optional<Time> delay_count_time;  // measurement frames: counter value x 1/f_e
  bool operator==(const FrameResult&) const = default;
};

// The same frame `shift` later with an index `index_shift` higher (the frame-level fast path):
// what a frame played from a recording reports. `end` stays zero until the first rising edge.
inline FrameResult moved(FrameResult f, Time shift, std::uint64_t index_shift) {
  f.index += index_shift;
  f.start += shift;
  if (f.end != Time::zero()) f.end += shift;
  return f;
}

// What monitors and reports can observe of the master's intentions.
class MasterObserver {
 public:
  virtual ~MasterObserver() = default;
  virtual void on_frame_start(const FrameResult& frame) = 0;
  // The master samples DATA for bit slot `clock` (the bit the encoder sent after RE_clock).
  virtual void on_sample(const FrameResult& frame, unsigned clock, bool value, bool in_data) = 0;
  // Whether on_sample does anything: a frame played from a recording (the frame-level fast path,
  // docs/performance.md) skips the sampling instants when no observer wants them.
  virtual bool wants_samples() const { return true; }
  virtual void on_frame_end(const FrameResult& frame) = 0;
  // A result recorded: each frame as it ends (after on_frame_end), and each further word of a
  // continuous clock (2.3.1) as its CRC arrives, which ends no frame. For outputs written while
  // the run goes.
  virtual void on_result(const FrameResult&) {}
};

}  // namespace endatsim::master
