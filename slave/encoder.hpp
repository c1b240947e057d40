// The EnDat encoder (D297403 2, 3): a frame engine, the bit-level state machine that only talks
// through the line's encoder-side pins (the mode command on RE3 .. RE8, t_cal, the start bit,
// the answers of 2.3 .. 2.10, the command supplement, t_m), and the parts it hands the contents to:
// the bits it sends and receives (frame_bits.hpp), whether it takes a clock edge (readiness.hpp), its
// DATA driver (data_driver.hpp), the memory with its areas and write protection (memory.hpp), the accesses to it with the area
// selected, Busy and the word being programmed (memory_access.hpp), the position source
// (position_source.hpp), the additional data (additional_data.hpp), the error messages
// (error_messages.hpp), its part in a bus (bus_addressing.hpp), its decisions on the 2.1 commands
// with 8 + 16 bits (parameter_commands.hpp) and an EIB's initial commissioning (eib.hpp). What an encoder is comes from EncoderParams (encoder_params.hpp); every frame leaves
// an EncoderFrame as ground truth, the recent ones kept in a bounded log (sim/record_log.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "endatsim/line/line.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/record_log.hpp"
#include "endatsim/sim/tape.hpp"
#include "endatsim/slave/additional_data.hpp"
#include "endatsim/slave/bus_addressing.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/error_messages.hpp"
#include "endatsim/slave/frame_bits.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/memory_access.hpp"
#include "endatsim/slave/parameter_commands.hpp"
#include "endatsim/slave/position_source.hpp"
#include "endatsim/slave/data_driver.hpp"
#include "endatsim/slave/readiness.hpp"
#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {

// Ground truth of one frame as the encoder saw it.
struct EncoderFrame {
  Time start;                          // FE1 at the encoder logic
  std::uint8_t mode_bits = 0;
  std::optional<ModeCommand> command;  // none: redundancy broken
  bool type1_error = false;
  std::optional<protocol::ErrorCause> error;  // type I or II raised by this frame
  std::uint64_t position = 0;          // latched at FE1, as sent
  std::uint64_t true_position = 0;     // what the encoder measured (differs while unsettled)
  bool error_present = false;          // an error source or F1/F2 fault active (ground truth, 3.4.1)
  std::optional<std::uint32_t> payload;      // the 8 + 16 bits received after the mode bits
  std::optional<std::uint32_t> supplement;   // the 8 + 16 bits of a 2.2 command supplement
  bool supplement_ignored = false;           // 2.3.1 note 1: 2.2 access while busy
  bool too_many_clocks = false;
  std::vector<std::uint8_t> additional_data_status;  // byte 0 of each additional datum sent
  unsigned start_bit_clock = 0;        // RE index of the start bit, 0 if none was sent
  unsigned clocks = 0;                 // rising edges seen
  unsigned continuous_words = 0;       // further words sent with a continuous clock
  std::vector<std::uint64_t> continuous_positions;
  bool operator==(const EncoderFrame&) const = default;
};

// The same frame `shift` later (the frame-level fast path).
inline EncoderFrame moved(EncoderFrame f, Time shift) {
  f.start += shift;
  return f;
}

class Encoder final : private MemoryAccess::Client {
 public:
  Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params);
  // An encoder on a bus tap of the line (line::Line::add_encoder(), 2.10).
  Encoder(sim::Kernel& kernel, line::Line::EncoderSide pins, const EncoderParams& params);
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  const EncoderParams& params() const { return params_; }
  // The frames this encoder saw, oldest first: every one, or with keep_frames(n) only the last
  // n to 2n (a long run matches each master frame to a recent one and keeps its memory bounded).
  const std::vector<EncoderFrame>& frames() const { return frames_.records(); }
  void keep_frames(std::size_t n) { frames_.keep(n); }
  std::uint64_t frame_count() const { return frames_.count(); }
  std::uint64_t ignored_clock_edges() const { return readiness_.ignored_edges(); }
  bool idle() const { return state_ == State::Idle; }
  bool started() const { return !readiness_.running_up(); }
  bool busy() const { return access_.busy(); }
  const Memory& memory() const { return memory_; }
  std::optional<Information> additional_data_1() const { return additional_data_.selected(protocol::AdditionalDataNumber::One); }
  // The transfer format in use: word 13 as activated (an EIB's changes at commissioning).
  unsigned position_bits() const { return positions_.position_bits(); }
  bool referenced() const { return positions_.reference_mark(); }  // RM (2.3.4.3); always for absolute encoders

  // Faults, while running (scenario events).
  void set_error_sources(std::uint16_t errors, std::uint16_t warnings);  // words 0 and 1 (3.4.1, 3.4.2)
  void set_memory_access_times(Time read, Time write);                  // t_ac, also beyond 12 ms
  void set_t_cal(Time t_cal);                                           // also beyond 1 ms
  // The supply fails for `duration`; then the encoder runs up for its startup_time (2.3.3).
  void power_interruption(Time duration);
  void corrupt_word(const Selection& s, std::uint8_t address, std::uint16_t xor_mask);
  // A touch probe (word 14 type 5) deflected or released (2.3.4.4: the trigger status).
  void set_probe_deflected(bool deflected);
  // Error paths that fail (or recover) while running; a coupling that slips by `steps`; the second
  // position sensing drifting by `deviation` (faults the safety functions catch).
  void set_stuck_error_messages(bool error1_stuck, bool error2_stuck);
  void slip(std::int64_t steps);
  void set_position2_fault(std::int64_t deviation);
  // What the sensors measure from now on (diagnosis, appendix A3): temperatures, valuation numbers.
  void set_sensor_values(const SensorValues& values);
  static constexpr Time kMaxFaultTime = EncoderParams::kMaxFaultTime;

  // The frame-level fast path (docs/performance.md). While the kernel records (Kernel::tape()),
  // the encoder notes on the tape where each frame begins and ends, and keeps each frame's record
  // as it ended (take_recorded_frames()); replay() does to the encoder what the frame did.
  enum class Note : std::uint32_t { Begin, Finish };
  std::vector<EncoderFrame> take_recorded_frames() { return std::exchange(recorded_, {}); }
  void replay(const sim::TapeItem& item, const std::vector<EncoderFrame>& frames, Time shift);
  // A frame begun now would leave the encoder as it found it, apart from times and its record:
  // idle and ready, nothing pending, an absolute position, no data that roll or latch.
  bool frame_invariant() const;
  // A frame `shift` after `recorded`, over before `until`, latches what it latched: the recorded
  // frame latched one position throughout (at FE1 and for each word of a continuous clock), and
  // the axis stands on it from this frame's FE1 to `until` (a moving axis between two steps).
  bool latches_again(const EncoderFrame& recorded, Time shift, Time until) const;
  // The axis crosses no measuring step from `from` to `to`, so the position latched at any instant
  // between is the same. Steps are counted, not positions compared: a position that wraps
  // around (2^n steps) comes back to the same value.
  bool holds_position(Time from, Time to) const {
    return params_.motion.steps_by(from) == params_.motion.steps_by(to);
  }

 private:
  enum class State : std::uint8_t {
    Idle, Header, Payload, Answer, EndOfData, ContinuousGap, Type1, HandoverLevel, SupplementHunt, Supplement,
    SupplementDone
  };

  void on_clock(std::uint64_t level);
  void on_falling_edge();
  void on_rising_edge();
  void on_recovery_time_elapsed();
  void on_end_marker_due();
  void on_started();
  void go_offline(Time duration);
  void begin_frame();
  void decode_mode_command();
  void answer_position();
  void answer_parameter_frame();
  void process_supplement();
  void emit_answer_bit();
  void load_continuous_word();
  void abort_type1(protocol::ErrorCause cause);
  void finish_frame();
  void end_frame();
  void reset();
  void restart_state();
  void adopt_encoder_type(unsigned position_bits);
  void commissioned(std::optional<unsigned> position_bits);
  void written(const Selection& s, std::uint8_t address) override;
  void clock_after_supplement();
  void hand_over_for_supplement();
  bool drives_bus() const;
  Time recovery_time() const;
  void drive(bool level) { driver_.drive(level); }
  void release() { driver_.release(); }
  void enable() { driver_.enable(drives_bus()); }

  sim::Kernel& kernel_;
  line::Line::EncoderSide pins_;
  EncoderParams params_;
  Memory memory_;
  PositionSource positions_;
  AdditionalData additional_data_;
  ErrorMessages errors_;
  EibCommissioning eib_;
  MemoryAccess access_;
  BusAddressing bus_;
  ParameterCommands commands_;  // commands with 8 + 16 bits (2.1 payload, 2.2 supplement): decisions, test port
  DataDriver driver_;
  sim::Timer recovery_timer_;
  sim::Timer end_marker_timer_;
  Readiness readiness_;  // run-up (2.3.3), t_R (2.3.2), unsettled answers after start-up

  // Frame state.
  State state_ = State::Idle;
  unsigned clock_ = 0;  // index k of the current clock period: FE_k, RE_k
  std::uint8_t mode_bits_ = 0;
  const protocol::ModeCommandInfo* command_ = nullptr;
  ReceivedBits received_;        // a 2.1 payload or a 2.2 command supplement
  SupplementStart supplement_start_;
  AnswerBits answer_;
  unsigned gap_low_bits_ = 0;

  sim::RecordLog<EncoderFrame> frames_{sim::RecordLog<EncoderFrame>::Keep::Recent};
  std::vector<EncoderFrame> recorded_;  // frames as they ended, while the kernel records
};

}  // namespace endatsim::slave
