// What the master is configured with (MasterParams): its clock, its waits, how it finds the start
// bit and checks CRCs, and what a careful master does when things go wrong (D297403 2.1 .. 2.3).
// The scalar keys come with their rows (sim/parameter.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "endatsim/master/delay_measurement.hpp"
#include "endatsim/master/diagnostics.hpp"
#include "endatsim/master/safety.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::master {

using sim::Hertz;
using sim::Time;

// How the master finds the start bit while it polls (2.3: "observe the data line to detect the
// start bit"). Fail-safe receivers read HIGH on the undriven line during the turnaround
// (docs/model.md §1, §11), so a careful master first waits for the encoder's LOW (a published
// sample's master: "wait 0, then wait 1"); a simple one takes the first HIGH sample after the mode bits.
enum class StartBitDetection : std::uint8_t { WaitLowThenHigh, FirstHigh };

// How the master checks CRCs (masters in the field got each of these wrong, docs/model.md §12).
// The defaults are the spec's (appendix A4).
struct CrcCheck {
  protocol::CrcConfig generator;     // preset and final inversion
  bool endat22_rule_for_21 = false;  // 2.1 frames checked with F2 included, as 2.2 frames are
  // A table-driven CRC whose loop ends one bit early at this position width (0 = none):
  // a library reported wrong only for 31 position clocks (docs/model.md §12).
  unsigned table_fault_width = 0;
  // A comparator stuck at "equal": every CRC passes (what the CRC self-test is for).
  bool accept_any = false;
};

// What a careful master does when things go wrong. Each reaction can be switched off
// to reproduce a careless master.
struct CarefulMaster {
  unsigned retries = 0;            // a failed frame of a script operation is repeated up to this often
  bool verify_echo = true;         // 2.1 parameter frames: an echo other than what was sent fails
  // 2.1.2: "a new measurement is necessary after power interruption or a change of the
  // transmission path" (with delay compensation).
  bool remeasure_after_line_change = true;
  bool remeasure_after_power_interruption = true;
  unsigned remeasure_after_crc_errors = 3;  // consecutive failed frames; 0 = never
  // After a power interruption the encoder has forgotten its additional data (2.4.2.2): select
  // them again before reading on.
  bool reselect_after_power_interruption = true;
};

struct MasterParams {
  Hertz f_c = sim::MHz(1);
  unsigned high_permille = 500;  // duty cycle: HIGH share of the period
  static constexpr unsigned kHighPermilleMin = 100, kHighPermilleMax = 900;  // duty_cycle 0.1 .. 0.9 (model)
  Time t_st{0};                  // first LOW phase stretched to t_ST (2.3.2 note 8); 0 = not stretched
  Time jitter{0};                // peak edge jitter, uniform in [-jitter, +jitter], seeded
  std::uint64_t seed = 1;
  bool delay_compensation = false;
  // A delay value set by hand instead of measured (compensation uses it from the first frame).
  std::optional<Time> fixed_t_d;
  DelayMeasurementParams measurement;
  unsigned position_bits = protocol::encoder_default::kPositionBits;  // word 13 as the master has it configured
  // docs/model.md §5: one more clock pulse after the last bit (its falling edge samples the
  // last bit) — or none, sampling the last bit half a period after the last rising edge.
  bool extra_clock_after_last_bit = true;
  Time t_m_wait = protocol::limit::kRecoveryTimeMax;  // CLOCK held HIGH after a frame: at least t_m of the encoder
  Time t_r_wait = protocol::limit::kRecoveryTime2Min;  // then t_R before the next FE1 (2.3.2)
  Time error_wait = protocol::limit::kErrorRecoveryWait;  // A2: "after an error handling, the maximum t_m of 30 us must be waited"
  Time reset_wait = sim::ms(50); // the German brochure's (older edition) start-up routine: "50 ms warten" after the reset
  // 2.3.2 t_b > 1 ms before a 2.1 memory or parameter frame (read as end of the previous frame
  // to FE1; see the checker's t_b row).
  Time t_b_wait = sim::us(1100);
  // 2.3.3 (the figure's labels in the German brochure, older edition, one published master's reading; docs/model.md §8): after
  // switching on, CLOCK stays at a valid level for t1 >= 800 ms and HIGH for t2 = 80 .. 120 ms,
  // then at least one LOW pulse > 125 ns, then HIGH for t3 = 380 .. 420 ms before the first request.
  struct PowerOnSequence {
    Time t1_t2 = sim::ms(900);
    Time pulse = sim::us(1);
    Time t3 = sim::ms(400);
  } power_on;
  // The start-up routine reads word 13 and from then on clocks that many position bits.
  bool adopt_word13 = true;
  // ... and runs at this clock: before t_D is known only a slow clock is safe on a long cable
  // (one published master's firmware runs the routine at 200 kHz).
  Hertz startup_f_c = sim::kHz(200);
  Time start_bit_timeout = protocol::limit::kCalculationTimeMax;  // t_cal max (2.3.2); polling gives up after this
  // 2.1 parameter frames: polling after the 24 bits gives up after t_ac max (12 ms, 2.3.2) + 1 ms.
  Time memory_access_timeout = protocol::limit::kMemoryAccessMax + sim::ms(1);
  // docs/model.md §4 (one published master's choice, "can optimize"): LOW bits the master drives
  // before the start bit of a 2.2 command supplement, from the first falling edge after it has
  // checked the answer.
  unsigned supplement_lead_bits = 7;
  // Of those, the master drives only the last ones: before them DATA is left undriven, so that
  // the encoder's release can travel the cable back first (a turnaround like t_ST's).
  unsigned supplement_driven_lead_bits = 2;
  unsigned type1_detect_samples = 8;    // HIGH samples after the turnaround, no LOW: type I (docs/model.md §10)
  StartBitDetection start_bit_detection = StartBitDetection::WaitLowThenHigh;
  CrcCheck crc;
  CarefulMaster careful;
  SafetyParams safety;
  DiagnosticsParams diagnostics;

  static constexpr Hertz kMinFc = protocol::limit::kFcMin;
  static constexpr Hertz kMaxFc = protocol::limit::kFcMaxSpecial;
  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
};

// The scalar keys of "master" and of its objects "power_on" and "careful", one row each
// (sim/parameter.hpp); validate() checks their ranges, the loader reads them, the schema and
// docs/parameters.md come from them.
std::span<const sim::Parameter<MasterParams>> master_parameters();
std::span<const sim::Parameter<MasterParams::PowerOnSequence>> power_on_parameters();
std::span<const sim::Parameter<CarefulMaster>> careful_parameters();
// "master.crc" besides protocol::crc_generator_parameters(), and "master.safety.setpoint".
std::span<const sim::Parameter<CrcCheck>> crc_check_parameters();
std::span<const sim::Parameter<MotionSetpoint>> setpoint_parameters();

}  // namespace endatsim::master
