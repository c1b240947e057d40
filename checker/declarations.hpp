// What the checker is told rather than what it sees: the encoder's declared properties (a
// datasheet, a profile) and, optionally, what a cooperating master declares about its frames.
// The checker needs neither model: everything here is plain data, so a user's testbench, an HDL
// co-simulation or a capture can fill it in as well as endatsim's own models can.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

using sim::Hertz;
using sim::Time;

// The encoder as its datasheet declares it. The master is judged twice: against these values
// ("this encoder") and against the spec's envelope, what any compliant encoder may do (D297403
// 2.3.2: t_m up to 30 us, t_cal up to 1 ms ...).
struct EncoderDeclaration {
  unsigned position_bits = protocol::encoder_default::kPositionBits;  // word 13 (the decoder's width for position answers)
  Time output_delay = protocol::encoder_default::kClockToData;  // CLOCK in to DATA out inside the encoder (its share of t_D)
  Time t_cal = protocol::encoder_default::kCalculationTime;  // 2.3.2 note 7, word 39: the longest calculation time
  std::optional<Time> t_cal_22;        // ... for EnDat 2.2 mode commands where it differs
  std::optional<Time> t_cal_energy_saving;  // ... while energy-saving mode is on (3.6.5), if it differs
  std::optional<Time> t_ac;            // 2.3.2: the longest memory access time (<= 12 ms), if declared
  Time t_m = protocol::encoder_default::kRecoveryTime;  // 2.3.2 recovery time I, as declared (10 .. 30 us)
  std::optional<Time> t_m_short;       // 1.25 .. 3.75 us where word 3 may select it (3.4.4)
  bool short_t_m_selected = false;     // word 3 selected it before the capture or run began
  Time t_r = protocol::encoder_default::kRecoveryTime2;  // 2.3.2 recovery time II
  std::optional<Time> t_st_max;        // 2.3.2 t_ST maximum: "see encoder specifications"
  std::optional<Time> t_lo_max;        // 2.3.2 t_LO maximum: "see encoder specifications"
  std::optional<Hertz> f_c_max;        // word 25 (3.9.19): the encoder's highest clock
  // An EnDat 2.1 encoder: f_c at most 2 MHz. Not in D297403; HEIDENHAIN's EnDat 2.2 brochure
  // (newer edition) gives it with the ordering designation EnDat21.
  bool endat21_only = false;
  bool switched_on_in_run = false;     // the run (capture) begins with switching on (2.3.3)
  unsigned supplement_ignore_clocks = protocol::encoder_default::kSupplementIgnoredClocks;  // after a 2.2 supplement
};

// What a cooperating master declares about itself: the rows that need it (sampling window,
// t_D used, the delay-measurement procedure) are judged only with it.
struct MasterDeclaration {
  unsigned position_bits = protocol::encoder_default::kPositionBits;  // as configured (word 13)
  Hertz f_c = sim::MHz(1);       // the intended clock
  Hertz f_e = 0;                 // 2.1.2 delay counter clock; 0: eight times f_c
  unsigned measurements = protocol::limit::kMeasurementsMin;  // 2.1.2 delay measurements averaged
};

// One frame as the master declares it, at its FE1 (start), per sample and at its end.
struct DeclaredFrame {
  std::uint64_t index = 0;
  Time start{0};  // FE1 at the master logic
  Time end{0};    // the last rising edge
  protocol::ModeCommand command = protocol::ModeCommand::EncoderSendPositionValues;
  std::uint8_t mode_bits = 0;               // as sent
  std::optional<std::uint32_t> payload;     // 8 + 16 bits after the mode bits (2.1 parameter commands)
  std::optional<std::uint32_t> supplement;  // the 2.2 command supplement, 8 + 16 bits
  unsigned answer_bits = 0;                 // what the master expects: start bit .. CRC and additional data
  unsigned position_bits = 0;               // as the master clocks them; 0: MasterDeclaration's
  Hertz f_c = 0;
  bool measurement = false;  // part of a propagation-delay measurement (2.1.2)
  bool compensated = false;
  Time t_d_used{0};
  // At the end: an error handling (A2: type 1 error or no start bit) asks for the longest t_m.
  bool error_handling = false;
  bool ok = false;           // answer and CRC received as expected
  std::optional<bool> busy;  // additional data 1's Busy bit, if received
  unsigned start_bit_clock = 0;
};

}  // namespace endatsim::checker
