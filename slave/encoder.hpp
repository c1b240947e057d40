#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/sim/int128.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {

using protocol::EndatVersion;
using protocol::Information;
using protocol::ModeCommand;
using sim::Time;

// Eib: an External Interface Box in factory delivery state (word 14 type Fh, slave/eib.hpp); it
// behaves as the connected encoder once initial commissioning is complete.
enum class EncoderKind : std::uint8_t { Singleturn, Multiturn, Linear, TouchProbe, Eib };

// What the encoder puts on DATA after a mode command with a broken redundancy or one it does
// not support (type I, appendix A2). The wire behaviour was in A2's Figures 55/56, which are
// lost (docs/model.md §10): A = abort with DATA HIGH until CLOCK stays HIGH for t_m;
// B = DATA stays LOW, no start bit ever comes.
enum class Type1Handling : std::uint8_t { AbortHigh, NoStartBit };

// Where the memory access time t_ac of a 2.1 parameter frame lies (docs/model.md §7: the figure
// is lost). InFrame: the acknowledgment's start bit waits for t_ac while the master keeps
// clocking. AfterFrame: the acknowledgment comes at once and the encoder is busy for t_ac after
// the frame; a 2.1 memory access meanwhile is answered with type II (2.3.1 note 1).
enum class MemoryAccessPlacement : std::uint8_t { InFrame, AfterFrame };

// What a word holds when the supply fails while the encoder programs it (a fault; the spec says
// nothing). KeepOld: the NVM programs a word at once at the end of t_ac, before that the old
// value stays. Torn: the high byte is programmed, the low byte is not. Either way write
// protection bits already stored survive (3.4.3: irreversible).
enum class InterruptedNvmWrite : std::uint8_t { KeepOld, Torn };

// What completes the initial commissioning of an EIB (3.5.7 says only that word 14 "must be
// modified during initial commissioning"; choice, docs/model-reference.md). Reset: "Encoder receive reset" or
// power-on, which activate the other parameters too (2.7, 3.4.3, 3.6). Word14Write: at once when
// the write of word 14 completes.
enum class EibActivation : std::uint8_t { Reset, Word14Write };

// What an EIB that is not yet initiated answers to a position request (choice, docs/model-reference.md: A2 gives
// type II, cause 5, for parameter frames only). ErrorBit: the frame in the width of
// EncoderParams::position_bits with error bit F1 set (F2 = 0) and every position bit 0, "no
// valid position" (2.3.1); additional data as for an incremental encoder before its reference
// run. NotSupported: the mode command is answered as not supported (type I, cause 1).
enum class EibPositionBeforeCommissioning : std::uint8_t { ErrorBit, NotSupported };

// Position source: fixed (counts_per_s = 0) or constant velocity, wrapping at 2^position_bits.
struct MotionProfile {
  std::uint64_t start = 0;
  std::int64_t counts_per_s = 0;
};

// The values behind the additional data (2.3.5).
struct Sensors {
  std::int64_t position2_offset = 0;         // position value 2 = position + offset (48 bits, 3.9.24)
  bool position2_reversed = false;           // ... or offset - position (3.9.13, word 16 of the 2.2 area)
  std::int64_t position2_fault = 0;          // a fault of the second position sensing: added to position value 2
  std::uint16_t temperature1 = 2982;         // 0.1 K steps (3.9.6): 25 degC
  std::uint16_t temperature2 = 2982;
  std::vector<std::uint16_t> additional_sensors{2982, 2982, 2982};  // 0.1 K; index = 4-bit address
  std::uint8_t commutation = 0;              // u v w, u the MSB
  std::uint16_t acceleration = 0;
  bool limit_position_1 = false;
  bool limit_position_2 = false;
  std::uint16_t operating_status_error_sources = 0;  // 2.3.5.3
  // A3: valuation numbers 1 .. 6 (addresses 1 .. 6), sent in turn as far as operating
  // parameters word 3 activates them (3.6.3).
  std::array<std::uint8_t, 6> valuation_numbers{100, 100, 100, 100, 100, 100};
  // A3 "system-specific data": address -> value, sent in turn after the valuation numbers while
  // word 3 bit 15 activates them; the subsequent electronics must ignore these addresses.
  std::map<std::uint8_t, std::uint8_t> system_data;
  std::map<std::uint8_t, std::uint64_t> test_values;  // port address -> 40-bit test value
  Time timestamp_unit = sim::us(1);
  std::vector<Information> not_updatable;    // A2 cause 16: answered with NOP (type IV)
};

// A change of what the encoder's sensors measure while running; unset fields stay.
struct SensorValues {
  std::optional<std::uint16_t> temperature1, temperature2;  // 0.1 K
  std::optional<std::vector<std::uint16_t>> additional_sensors;
  std::optional<std::array<std::uint8_t, 6>> valuation_numbers;
};

struct EncoderParams {
  EncoderKind kind = EncoderKind::Singleturn;
  EndatVersion version = EndatVersion::V2_2;  // a 2.1 encoder answers 2.2 commands as not supported
  unsigned position_bits = 25;                 // word 13: clock pulses for the position value
  unsigned multiturn_bits = 0;                 // upper bits of the position that count revolutions
  Time t_cal = sim::us(5);                     // 2.3.2: position calculation time, FE1 -> start bit (max 1 ms)
  // ... for EnDat 2.2 mode commands, where it differs (the German brochure: absolute linear
  // encoders take other calculation times for 2.1 and 2.2 mode commands); none: t_cal.
  std::optional<Time> t_cal_22;
  Time t_cal_for(EndatVersion command) const { return command == EndatVersion::V2_2 ? t_cal_22.value_or(t_cal) : t_cal; }
  Time t_m = sim::us(20);                      // 2.3.2: recovery time I, 10 .. 30 us
  std::optional<Time> t_m_short;               // 1.25 .. 3.75 us, 2.2 commands only (word 3, 3.4.4)
  bool short_t_m_selected = false;             // as if word 3 selected it at power-on
  Time t_r = sim::ns(500);                     // 2.3.2: t_R, time before the next query can be received
  // 2.3.2 t_ST and t_LO maxima, "see encoder specifications": a datasheet's values, judged by the
  // checker against this encoder; the model itself takes any longer LOW phase.
  std::optional<Time> t_st_max;
  std::optional<Time> t_lo_max;
  // 2.3.3, docs/model.md §8: run-up after switching on, about 1 s (the older brochures; 1.3 s in
  // the newer German edition); DATA is high-impedance and clocks are ignored meanwhile. 0: the
  // run starts with the encoder up.
  Time startup_time{0};
  // 2.7 "same reaction as switching the power off and on": the encoder restarts for this long
  // after "Encoder receive reset" (guess; the German brochure's start-up routine waits 50 ms).
  Time reset_time = sim::ms(20);
  Time t_ac_read = sim::us(500);               // 2.3.2: memory access time t_ac (0 .. 12 ms) for reads, selections
  Time t_ac_write = sim::ms(3);                // ... and for writes
  MemoryAccessPlacement t_ac_placement = MemoryAccessPlacement::InFrame;
  InterruptedNvmWrite interrupted_nvm_write = InterruptedNvmWrite::KeepOld;
  // docs/model.md §4 (guess): after the master's supplement the encoder drives the HIGH end
  // marker this long after the last supplement bit (the master has released DATA by then).
  Time supplement_end_marker_delay = sim::us(1);
  // ... and before it, ignores DATA for this many rising edges after handing the line over,
  // while its own last bit fades (guess; the master's lead bits must be more).
  unsigned supplement_ignore_clocks = 3;
  Time output_delay = sim::ns(20);             // clock input -> data output inside the encoder
  // 2.4.2.3 / 3.4.4 (guess: "the exact evaluation of the oversampling is described in the
  // specifications"): with oversampling activated, "time delay k" selects the position sampled
  // k steps of this length before the frame's latch.
  Time asynchronous_time_delay_step = sim::us(1);
  // 3.4.4 (guess): the word 0 bit (3.4.1) that a latched multiturn overflow sets; the spec names
  // none, 2^2 "position faulty" is the closest.
  unsigned multiturn_overflow_error_bit = 2;
  // The CRC generator's setup: the spec's (A4) for an encoder; an emulator built with a master's
  // wrong settings (docs/model.md §12) agrees with that master and with no real encoder.
  protocol::CrcConfig crc;
  unsigned continuous_low_bits = 1;            // 2.3.1.1: "a maximum of 7 Low Bits" between words
  unsigned driver_enable_edge = protocol::frame_position::kTurnaround;  // FE that turns its driver on (docs/model.md §1)
  // docs/model.md §1 (likely): the start bit comes no earlier than RE11 (2.3.2: t_cal >= 10.5/f_c);
  // encoders in the field differ (an emulator sends it after five zeros). RE11 + 24 after a payload.
  unsigned earliest_start_bit_clock = protocol::frame_position::kEarliestStartBit;
  Type1Handling type1 = Type1Handling::AbortHigh;
  bool communication_command_permitted = true;  // A2 cause 4 when false
  // An EIB (word 14 type Fh) is "not yet initiated" (A2 cause 5) until initial commissioning
  // has written the connected encoder's type into word 14 and this event activates it (3.5.7).
  EibActivation eib_activation = EibActivation::Reset;
  // ... and only if word 47 then checks (3.5.26: "to check the correctness of the saved data";
  // choice): an EIB whose saved parameters do not add up stays not initiated.
  bool eib_activation_checks_checksum = true;
  EibPositionBeforeCommissioning eib_position_before_commissioning = EibPositionBeforeCommissioning::ErrorBit;
  MotionProfile motion;
  // Incremental encoders (word 14, 3.5.7): positions of the reference marks within the range, in
  // measuring steps; one crossing (two with distance-coded marks) sets RM (2.3.4.3). Equidistant
  // marks (word 18 != 0 without distance coding) come from words 18/19 instead (3.5.10.2, 3.5.11).
  std::vector<std::uint64_t> reference_marks{0};
  // Equidistant marks: the one selected by hardware ("reference marks can be selected using the
  // hardware", 2.3.4.3), counted from the first mark (0). None: every mark references and the
  // first one crossed is taken as the first mark (guess: 2.3.4.3 needs "a reference mark").
  std::optional<std::uint64_t> selected_reference_mark;
  bool error1 = false;              // F1 = 1 / F2 = 0 regardless of word 0
  // A failed error path (a fault the safety functions catch): this error message stays at its inactive
  // level (F1 LOW, F2 HIGH) whatever the error sources and forced dynamic sampling (3.5.3) say.
  bool error_message_1_stuck = false;
  bool error_message_2_stuck = false;
  // The first this many position answers after switching on or a reset carry an unsettled value
  // (a fault that multiple transmission at start-up catches; the English brochure's "Safety Techniques").
  unsigned unsettled_positions = 0;
  std::uint16_t error_sources = 0;  // word 0 bits (3.4.1) that a fault keeps setting
  std::uint16_t warning_sources = 0;  // word 1 bits (3.4.2)
  Sensors sensors;
  std::optional<MemoryImage> memory;  // none: a consistent image made from these parameters

  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
  std::uint64_t position_at(Time t) const;
};

// A memory image consistent with the parameters: word 13 = position bits, word 39 = t_cal, an
// OEM area of 64 words in A9 and AB, EnDat 2.2 area for 2.2 encoders, checksums valid.
MemoryImage default_memory_image(const EncoderParams& p);

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
};

class Encoder {
 public:
  Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params);
  // An encoder on a bus tap of the line (line::Line::add_encoder(), 2.10).
  Encoder(sim::Kernel& kernel, line::Line::EncoderSide pins, const EncoderParams& params);
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  const EncoderParams& params() const { return params_; }
  // The frames this encoder saw, oldest first: every one, or with keep_frames(n) only the last
  // n to 2n (a long run matches each master frame to a recent one and keeps its memory bounded).
  const std::vector<EncoderFrame>& frames() const { return frames_; }
  void keep_frames(std::size_t n) { kept_frames_ = std::max<std::size_t>(n, 1); }
  std::uint64_t frame_count() const { return frame_count_; }
  std::uint64_t ignored_clock_edges() const { return ignored_edges_; }
  bool idle() const { return state_ == State::Idle; }
  bool started() const { return !offline_; }
  bool busy() const;
  const Memory& memory() const { return memory_; }
  std::optional<Information> additional_data_1() const { return selection_[0]; }
  std::optional<Information> additional_data_2() const { return selection_[1]; }
  // The transfer format in use: word 13 as activated (an EIB's changes at commissioning).
  unsigned position_bits() const { return position_bits_; }
  bool referenced() const { return referenced_ && !rm_reset_at_; }  // RM (2.3.4.3); always for absolute encoders
  const ReferenceScheme& reference_scheme() const { return reference_; }

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
  static constexpr Time kMaxFaultTime = sim::ms(10'000);

 private:
  enum class State : std::uint8_t {
    Idle, Header, Payload, Answer, EndOfData, ContinuousGap, Type1, SupplementHunt, Supplement, SupplementDone
  };
  // A memory operation decided during a frame and carried out when it completes.
  struct Pending {
    enum class Kind : std::uint8_t { None, Select, Write, Reset } kind = Kind::None;
    Selection selection;
    std::uint8_t address = 0;
    std::uint16_t value = 0;
  };

  void on_clock(std::uint64_t level);
  void on_falling_edge();
  void on_rising_edge();
  void on_recovery_time_elapsed();
  void on_memory_access_done();
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
  void reset();
  void restart_state();
  void adopt_encoder_type();
  void complete_commissioning();
  std::optional<protocol::ErrorCause> not_initiated(std::optional<MemoryArea> area) const;
  void note_nvm_write(const Selection& s, std::uint8_t address, std::uint16_t value, Time done_at);
  void interrupt_nvm_write();
  void latch_errors();
  bool temperature_exceeded() const;
  bool diagnosis_activated() const;
  std::uint16_t next_diagnosis_value();
  bool function_activated(protocol::parameters::EncoderFunction f) const;
  void activate_functions();
  void select(const Selection& s);
  std::uint64_t measured_position(Time t) const;
  std::uint64_t absolute_position(Time t) const;
  void note_commissioning_write(const Selection& s, std::uint8_t address);
  std::uint64_t latched_position(Time t) const;
  std::uint16_t error_word() const;
  std::uint16_t timestamp(Time frame_start) const;
  bool multiturn_overflowed(Time t) const;
  void check_multiturn_overflow();
  bool error_message_1() const;
  void latch_bus_address_error();
  void written(const Selection& s, std::uint8_t address);
  void clock_after_supplement();
  std::uint64_t output_position(std::uint64_t measured) const;
  void update_reference();
  sim::Int128 unwrapped_position(Time t) const;
  bool error_message_2() const;
  bool error_present() const;
  bool drives_bus() const;
  std::uint8_t status_byte(Information i) const;
  void append_additional_datum(Information selected, unsigned which);
  std::uint16_t additional_data_content(Information i);
  std::optional<protocol::ErrorCause> type3_cause(Information i, unsigned which) const;
  void start_memory_access(Time t_ac);
  Time recovery_time() const;
  void drive(bool level) { data_logic_.write(level); }
  void release() { enable_logic_.write(false); }
  void enable() { enable_logic_.write(drives_bus()); }

  sim::Kernel& kernel_;
  line::Line::EncoderSide pins_;
  EncoderParams params_;
  Memory memory_;
  sim::Signal data_logic_;
  sim::Signal enable_logic_;
  sim::TransportDelay data_out_delay_;
  sim::TransportDelay enable_out_delay_;
  sim::Timer recovery_timer_;
  sim::Timer memory_timer_;
  sim::Timer end_marker_timer_;
  sim::Timer startup_timer_;

  // Frame state.
  State state_ = State::Idle;
  Time ready_at_{0};
  unsigned clock_ = 0;  // index k of the current clock period: FE_k, RE_k
  std::uint8_t mode_bits_ = 0;
  const protocol::ModeCommandInfo* command_ = nullptr;
  std::uint32_t shift_ = 0;
  unsigned shifted_ = 0;
  unsigned first_answer_clock_ = 11;  // docs/model.md §1 / §3: RE11, or RE35 after a payload
  Time answer_not_before_{0};
  bool seen_low_ = false;
  unsigned release_clock_ = 0;  // RE at which the encoder handed DATA to the master's supplement
  std::vector<std::uint8_t> answer_;
  std::size_t next_bit_ = 0;
  unsigned gap_low_bits_ = 0;
  Pending pending_;

  // Encoder state that outlives frames.
  Selection selection_area_;
  bool area_selected_ = false;
  std::optional<Information> selection_[2];     // additional data 1 and 2 (2.4.2.2)
  std::optional<protocol::ErrorCause> type3_[2];  // A2: answered with I = 15 / 31 until reselected
  Time busy_until_{0};
  Pending in_progress_;                         // the 2.2 access finishing at busy_until_
  std::uint8_t last_mrs_ = 0, last_block_ = 0;  // I = 7 acknowledgment
  std::uint8_t test_port_22_ = 0;               // I = 8 acknowledgment; forced dynamic sampling (3.5.3)
  std::uint8_t test_port_21_ = 0;               // 2.8: port for "Encoder send test values"
  std::uint8_t memory_address_ = 0;             // I = 5 / 6
  std::uint16_t memory_value_ = 0;
  bool memory_error_ = false;
  bool transmission_incomplete_ = false;        // A2 cause 3, for the next acknowledgment
  std::uint64_t position2_latched_ = 0;
  std::uint64_t test_value_latched_ = 0;
  std::uint64_t async_latched_ = 0;
  std::uint8_t async_time_delay_ = 0;           // 2.4.2.3: 0 after switch-on or reset
  sim::Int128 counter_origin_ = 0;                 // 3.4.4: measuring steps where a counter reset zeroed the multiturn count
  bool multiturn_overflow_ = false;             // 3.4.4: overflow message (unlatched) in this frame
  // The word the NVM is programming (what a power interruption leaves).
  struct NvmWrite {
    Selection selection;
    std::uint8_t address = 0;
    std::uint16_t old_value = 0, new_value = 0;
    Time done_at{0};
    bool applied = false;
  };
  std::optional<NvmWrite> nvm_write_;
  std::size_t diagnosis_index_ = 0;
  unsigned sensor_address_ = 0;
  bool selected_on_bus_ = true;                 // 2.10: addressed by the last communication command
  std::optional<bool> bus_selection_after_frame_;
  bool offline_ = false;                        // running up after power-on or reset (2.3.3)
  bool incremental_ = false;                    // word 14: an incremental encoder
  bool touch_probe_ = false;                    // word 14: a touch probe (2.3.4.4)
  bool probe_deflected_ = false;
  std::int64_t slip_ = 0;                       // steps the coupling slipped
  unsigned unsettled_left_ = 0;                 // position answers still unsettled after start-up
  std::optional<Time> probe_switched_at_;       // the last trigger, for the timestamp (3.9.32)
  ReferenceScheme reference_;                   // from word 14 and words 18/19 (2.3.4.3)
  bool referenced_ = false;                     // RM (2.3.4.3)
  std::optional<std::uint64_t> frozen_position_;  // word 5 bit 2: the position sent while it is set (3.6.5)
  std::optional<Time> rm_reset_at_;             // RM reset by operating parameters 2 word 11 (3.10.5)
  bool bus_address_error_ = false;              // error bit 1 held by a bus address in word 4 (3.6.4)
  sim::Int128 reference_offset_ = 0;               // absolute = measured - offset (equidistant, first crossed)
  unsigned position_bits_ = 0;                  // word 13 as activated
  bool eib_not_initiated_ = false;              // word 14 type Fh (3.5.7, A2 cause 5)
  Time reference_origin_{0};                    // switch-on: where relative positions start
  Time reference_search_from_{0};               // since when crossings count (switch-on, reset)

  std::vector<EncoderFrame> frames_;
  std::size_t kept_frames_ = SIZE_MAX / 2;
  std::uint64_t frame_count_ = 0;
  std::uint64_t ignored_edges_ = 0;
};

}  // namespace endatsim::slave
