// The encoder's declared parameters (EncoderParams): what a datasheet and the memory image say
// an encoder is, and the choices the model makes where D297403 leaves a behaviour open
// (docs/model.md). The running encoder is slave/encoder.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "endatsim/sim/int128.hpp"
#include "endatsim/sim/parameter.hpp"
#include "endatsim/sim/time.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/slave/memory.hpp"

namespace endatsim::slave {

using protocol::EndatVersion;
using protocol::Information;
using protocol::ModeCommand;
using sim::Time;

// Eib: an External Interface Box in factory delivery state (word 14 type Fh, slave/eib.hpp); it
// behaves as the connected encoder once initial commissioning is complete.
enum class EncoderKind : std::uint8_t { Singleturn, Multiturn, Linear, TouchProbe, Eib };
// How scenarios and profiles name the kinds and the versions, in the order of their values.
inline constexpr std::array<std::string_view, 5> kEncoderKindNames{"singleturn", "multiturn", "linear", "touch_probe", "eib"};
static_assert(static_cast<std::size_t>(EncoderKind::Eib) == kEncoderKindNames.size() - 1);
inline constexpr std::array<std::string_view, 2> kEndatVersionNames{"2.1", "2.2"};
static_assert(static_cast<std::size_t>(protocol::EndatVersion::V2_2) == kEndatVersionNames.size() - 1);

// What the default memory image (default_memory_image) and the bundled profiles take where a
// scenario gives nothing: an EnDat 2.x interface (3.5.4: word 8 keeps the integer part of the
// version), OEM areas 1 and 2 at addresses 0 .. 63 (3.5.5), and the accuracy ranges of 3.5.19's
// example (c_1 = 40 for a_1 = 16 LSB, c_2 = 1 for a_2 = 64 LSB; 3.9.11 for the 2.2 area).
namespace image_default {
inline constexpr unsigned kInterfaceVersion = 2;
inline constexpr protocol::parameters::AddressRange kOemArea{0, 63};
inline constexpr unsigned kAccuracyC1 = 40, kAccuracyA1 = 16, kAccuracyC2 = 1, kAccuracyA2 = 64;
// A linear encoder's measuring step in nm (words 20/21, 3.5.12), and what a rotary encoder whose
// steps per revolution do not fit words 20/21's 32 bits declares instead.
inline constexpr std::uint32_t kLinearMeasuringStepNm = 100;
inline constexpr unsigned kStepsPerRevolutionBitsMax = 31;
// Word 32's maximum velocity (3.5.18): 12 000 rpm rotary, 120 m/min linear.
inline constexpr std::uint16_t kMaxVelocityRpm = 12000, kMaxVelocityMetresPerMinute = 120;
}  // namespace image_default

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

// What DATA shows after the answer of a 2.2 mode command with a command supplement (2.3: "following
// transfer of the data and the CRC, it can then be decided whether and to what extent additional
// data follows by determining the logic level on the data line"; the figures of 2.4.2 ff. are
// lost, docs/model.md §4). Release: the encoder releases DATA after its last bit, for the
// master's supplement. EndLevel: it first drives the level that ends its answer (HIGH: nothing
// follows) for one clock period, as after any other answer, then releases.
enum class SupplementHandover : std::uint8_t { Release, EndLevel };

// Position source: fixed (counts_per_s = 0) or constant velocity, wrapping at 2^position_bits.
struct MotionProfile {
  std::uint64_t start = 0;
  std::int64_t counts_per_s = 0;
  // The whole measuring steps the axis has moved by `t`. A count changes when the axis crosses a
  // step, so a negative velocity rounds toward minus infinity, as an encoder counting down does.
  sim::Int128 steps_by(Time t) const;
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
  using ValuationNumbers = std::array<std::uint8_t, protocol::diagnosis::kValuationNumbers>;
  static constexpr std::uint8_t kValuationNumberDefault = 100;  // a model default
  ValuationNumbers valuation_numbers = [] {
    ValuationNumbers v{};
    v.fill(kValuationNumberDefault);
    return v;
  }();
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
  std::optional<Sensors::ValuationNumbers> valuation_numbers;
};

struct EncoderParams {
  EncoderKind kind = EncoderKind::Singleturn;
  EndatVersion version = EndatVersion::V2_2;  // a 2.1 encoder answers 2.2 commands as not supported
  unsigned position_bits = protocol::encoder_default::kPositionBits;  // word 13: clock pulses for the position value
  static constexpr unsigned kMaxPositionBits = protocol::kPositionBitsMax;  // the model's widest position
  static constexpr std::uint64_t kMaxPosition = (std::uint64_t{1} << kMaxPositionBits) - 1;
  // The latest rising edge a scenario may put the earliest start bit on (the model's bound).
  static constexpr unsigned kEarliestStartBitClockMax = 32;
  unsigned multiturn_bits = 0;                 // upper bits of the position that count revolutions
  Time t_cal = protocol::encoder_default::kCalculationTime;  // 2.3.2: position calculation time, FE1 -> start bit (max 1 ms)
  // The model takes calculation times (and the encoder's other times) up to this, far beyond the
  // spec, so that an overrun shows.
  static constexpr Time kMaxModelTime = sim::ms(100);
  // The longest run-up, power interruption or fault time (t_ac set by an event) the model takes.
  static constexpr Time kMaxFaultTime = sim::ms(10'000);
  // ... for EnDat 2.2 mode commands, where it differs (the German brochure, both editions: absolute linear
  // encoders take other calculation times for 2.1 and 2.2 mode commands); none: t_cal.
  std::optional<Time> t_cal_22;
  // ... while the instruction "energy-saving mode" (operating parameters word 5 bit 0, 3.6.5) is in
  // effect, where the encoder declares one; none: unchanged. The spec does not say what the mode
  // saves; a slower calculation is the one effect it can have on the wires (docs/model-reference.md).
  std::optional<Time> t_cal_energy_saving;
  Time t_cal_for(EndatVersion command, bool energy_saving = false) const {
    if (energy_saving && t_cal_energy_saving) return *t_cal_energy_saving;
    return command == EndatVersion::V2_2 ? t_cal_22.value_or(t_cal) : t_cal;
  }
  Time t_m = protocol::encoder_default::kRecoveryTime;  // 2.3.2: recovery time I, 10 .. 30 us
  std::optional<Time> t_m_short;               // 1.25 .. 3.75 us, 2.2 commands only (word 3, 3.4.4)
  bool short_t_m_selected = false;             // as if word 3 selected it at power-on
  Time t_r = protocol::encoder_default::kRecoveryTime2;  // 2.3.2: t_R, time before the next query can be received
  // 2.3.2 t_ST and t_LO maxima, "see encoder specifications": a datasheet's values, judged by the
  // checker against this encoder; the model itself takes any longer LOW phase.
  std::optional<Time> t_st_max;
  std::optional<Time> t_lo_max;
  // 2.3.3, docs/model.md §8: run-up after switching on, about 1 s (the older brochures; 1.3 s in
  // the newer German edition); DATA is high-impedance and clocks are ignored meanwhile. 0: the
  // run starts with the encoder up.
  Time startup_time{0};
  // 2.7 "same reaction as switching the power off and on": the encoder restarts for this long
  // after "Encoder receive reset" (guess; the start-up routine of the German brochure, older edition, waits 50 ms).
  Time reset_time = sim::ms(20);
  Time t_ac_read = sim::us(500);               // 2.3.2: memory access time t_ac (0 .. 12 ms) for reads, selections
  Time t_ac_write = sim::ms(3);                // ... and for writes
  MemoryAccessPlacement t_ac_placement = MemoryAccessPlacement::InFrame;
  InterruptedNvmWrite interrupted_nvm_write = InterruptedNvmWrite::KeepOld;
  // docs/model.md §4 (guess): after the master's supplement the encoder drives the HIGH end
  // marker this long after the last supplement bit (the master has released DATA by then).
  Time supplement_end_marker_delay = sim::us(1);
  // ... and before it, ignores DATA for this many rising edges after handing the line over.
  unsigned supplement_ignore_clocks = protocol::encoder_default::kSupplementIgnoredClocks;
  SupplementHandover supplement_handover = SupplementHandover::Release;
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

// The scalar keys of a scenario's "encoder" object, one row each (sim/parameter.hpp): the loader
// reads them, EncoderParams::validate() checks their ranges, the schema and docs/parameters.md
// are generated from them. Structured keys (profile, reference_marks, memory, and the arrays and
// maps of "sensors") are read by the loader itself.
std::span<const sim::Parameter<EncoderParams>> encoder_parameters();
// The single-value keys of "encoder.sensors" and "encoder.motion"; "encoder.crc" is
// protocol::crc_generator_parameters().
std::span<const sim::Parameter<Sensors>> sensor_parameters();
std::span<const sim::Parameter<MotionProfile>> motion_parameters();

// A memory image consistent with the parameters: word 13 = position bits, word 39 = t_cal, an
// OEM area of 64 words in A9 and AB, EnDat 2.2 area for 2.2 encoders, checksums valid.
MemoryImage default_memory_image(const EncoderParams& p);

}  // namespace endatsim::slave
