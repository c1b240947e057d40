// The timing conditions of EnDat 2.2 specification D297403 2.3.2 and the rules around them
// (2.1.2 delay measurement, 2.3 sampling, 2.3.1 clock count, 2.3.3 power-on, appendix A2), as
// data: the limits once, as numbers, and one row per check with its spec symbol, section,
// minimum, maximum, condition and where it is observed. The checker judges against these rows;
// `endatsim checks` prints them, docs/checks.md and the schema's list of check names are
// generated from them (a test keeps both in step).
//
// Frame positions are counted from FE1, the master's first falling CLOCK edge of a frame, as
// the spec's figures count them: FEk is the k-th falling edge, REk the k-th rising edge.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "endatsim/sim/time.hpp"

namespace endatsim::protocol {

namespace frame_position {
// FE1: the frame begins; the encoder releases DATA (t_z runs from here).
inline constexpr unsigned kFrameStart = 1;
// RE2: the first rising edge a whole clock period after the one before it; the first period of a
// frame holds t_ST (2.3.2 note 8), so f_c is measured from RE2 on.
inline constexpr unsigned kFirstSteadyRise = 2;
// FE2: the master drives DATA (the dummy bit before the mode command, 2.3).
inline constexpr unsigned kMasterDrives = 2;
// RE3 .. RE8: the encoder takes the six mode bits M2 M1 M0 (M2) (M1) (M0) (2.3).
inline constexpr unsigned kFirstModeBit = 3;
inline constexpr unsigned kLastModeBit = 8;
inline constexpr unsigned kModeBits = kLastModeBit - kFirstModeBit + 1;
// FE9: the master has sent its mode bits and releases DATA, unless 8 + 16 payload bits of a
// 2.1 parameter command follow (then FE9 + 24); t_OE runs from here.
inline constexpr unsigned kTurnaround = 9;
// RE11: the earliest start bit; t_cal minimum 10.5/f_c counted from FE1 with a half-period
// first LOW phase ends on it, so the row is judged as a count for any duty cycle or t_ST.
inline constexpr unsigned kEarliestStartBit = 11;

// Where edge n (FEn or REn, counted from 1 as the spec does) is kept in a frame's list of edges.
constexpr std::size_t edge_index(unsigned n) { return n - 1; }
}  // namespace frame_position

// What the encoder model is by default where the spec leaves it to the encoder or its figures are
// lost (docs/model.md), shared with the checker's declarations of an encoder and its decoder.
namespace encoder_default {
// 2.3.2 recovery time I lies in 10 .. 30 us; an encoder in the middle of it.
inline constexpr sim::Time kRecoveryTime = sim::us(20);
// docs/model.md §4 (guess): after handing DATA over for a 2.2 command supplement the encoder
// lets this many rising edges pass, while its own last bit fades, before it hunts for the
// supplement's start bit (the master's lead bits must be more).
inline constexpr unsigned kSupplementIgnoredClocks = 3;
// Word 13 (3.5.6): a 25-bit position, the width of the spec's examples.
inline constexpr unsigned kPositionBits = 25;
// 2.3.2 t_cal (note 7: per encoder, word 39): 5 us, well inside the 1 ms the spec allows.
inline constexpr sim::Time kCalculationTime = sim::us(5);
// 2.3.2 recovery time II, t_R: the 500 ns the table gives.
inline constexpr sim::Time kRecoveryTime2 = sim::ns(500);
// CLOCK edge at the encoder's pins to DATA edge there: its receiver, logic and driver, 20 ns each
// (line/line.hpp's encoder transceiver and slave/encoder_params.hpp's output delay).
inline constexpr sim::Time kClockToData = sim::ns(60);
}  // namespace encoder_default

namespace limit {
using sim::Hertz;
using sim::Time;
// 2.3.2 f_c (note 4; 2.1.2): 8 MHz with delay compensation, 16 MHz "for special applications".
inline constexpr Hertz kFcMin = sim::kHz(100);
inline constexpr Hertz kFcMaxWithoutCompensation = sim::MHz(2);
inline constexpr Hertz kFcMaxWithCompensation = sim::MHz(8);
inline constexpr Hertz kFcMaxSpecial = sim::MHz(16);
// 2.1.2: 8 MHz with delay compensation "regardless of the cable length (maximum: 100 m)".
inline constexpr double kCompensatedCableMaxMetres = 100;
// 2.1.2: the propagation delay is measured at 100 .. 200 kHz, with a counter of at least eight
// times the intended f_c (f_e tolerance -10 %), averaged over at least three measurements.
inline constexpr Hertz kMeasurementFcMin = sim::kHz(100);
inline constexpr Hertz kMeasurementFcMax = sim::kHz(200);
inline constexpr unsigned kMeasurementCounterFactor = 8;
inline constexpr unsigned kMeasurementCounterTolerancePercent = 10;
inline constexpr unsigned kMeasurementsMin = 3;
// 2.1.2: each measured value within T/8 of their mean (T the period of the compensated f_c).
inline constexpr unsigned kMeasurementSpreadPeriodDivisor = 8;
// 2.3.2 t_cal: 10.5/f_c (as frame_position::kEarliestStartBit) .. 1 ms (note 7: per encoder).
inline constexpr Time kCalculationTimeMax = sim::ms(1);
// 2.3.1.1 Figure 15, continuous clock: at most 7 LOW bits before the next word's start bit.
inline constexpr unsigned kContinuousClockMaxLowBits = 7;
// 2.3.2 t_ac.
inline constexpr Time kMemoryAccessMax = sim::ms(12);
// 2.3.2 recovery time I, t_m: 10 .. 30 us; with type 2.2 mode commands and f_c >= 1 MHz it may
// be set to 1.25 .. 3.75 us (note 3; word 3, 3.4.4).
inline constexpr Time kRecoveryTimeMin = sim::us(10);
inline constexpr Time kRecoveryTimeMax = sim::us(30);
inline constexpr Time kShortRecoveryTimeMin = sim::ns(1250);
inline constexpr Time kShortRecoveryTimeMax = sim::ns(3750);
inline constexpr Hertz kShortRecoveryTimeFcMin = sim::MHz(1);
// 2.3.2 recovery time II, t_R: 500 ns (note 9: "time before the next query can be received").
inline constexpr Time kRecoveryTime2Min = sim::ns(500);
// 2.3.2 recovery time III, t_ST (note 8): 2 us recommended for f_c 2 .. 8 MHz, specified as
// 1 us at 16 MHz, linear in between.
inline constexpr Time kStartDelay = sim::us(2);
inline constexpr Time kStartDelayAt16MHz = sim::us(1);
// 2.3.2 t_D maximum (0.2 + 0.01 x L) us, L the cable length in metres.
inline constexpr Time kDataDelayBase = sim::ns(200);
inline constexpr Time kDataDelayPerMetre = sim::ns(10);
// 2.3: "the set Data Delay Time with a tolerance of +/-10 % x f_c must not be exceeded".
inline constexpr unsigned kDataDelayTolerancePercent = 10;
// 2.3.2 t_HI, t_LO minimum 0.2 us; t_HI maximum 10 us; on-off ratio error 0 .. +/-10 %.
inline constexpr Time kPulseWidthMin = sim::ns(200);
inline constexpr Time kPulseHighMax = sim::us(10);
inline constexpr unsigned kOnOffRatioErrorPercent = 10;
// 2.3.2 note 6: t_z and t_OE at most T = 1/f_c min.
inline constexpr Time kPeriodAtFcMin = sim::us(10);
// 2.3.2 t_b: EnDat 2.1 commands, t_b > 1 ms.
inline constexpr Time kTimeBetweenCyclesMin = sim::ms(1);
// A2: after an error handling, wait at least the maximum t_m.
inline constexpr Time kErrorRecoveryWait = kRecoveryTimeMax;
// 2.3.3 power-on (HEIDENHAIN Technical Information EnDat 2.2, German edition, older): CLOCK
// valid for t1 >= 800 ms, HIGH for t2 = 80 .. 120 ms, a LOW pulse > 125 ns, then t3 = 380 ..
// 420 ms before the first request.
inline constexpr Time kPowerOnT1Min = sim::ms(800);
inline constexpr Time kPowerOnT2Min = sim::ms(80);
inline constexpr Time kPowerOnT2Max = sim::ms(120);
inline constexpr Time kPowerOnPulseMin = sim::ns(125);
inline constexpr Time kPowerOnT3Min = sim::ms(380);
inline constexpr Time kPowerOnT3Max = sim::ms(420);

// t_D maximum for a cable of `length_m` metres, rounded to the picosecond.
Time data_delay_max(double length_m);
// 2.3.2 note 4 and 2.1.1 and Figure 2 (lost; docs/model.md §9): without delay compensation a bit launched
// on a rising edge must reach the master before the falling edge that takes it, so a 1:1 clock's
// period is at least 2 t_D max(L), and f_c at most min(2 MHz, 1 / (2 t_D max(L))).
Time uncompensated_period_min(double length_m);
// t_ST as note 8 gives it for the frame's f_c: 2 us up to 8 MHz, 1 us at 16 MHz, linear in
// between (and 1 us above, which f_c's own row forbids).
Time start_delay(Hertz f_c);
}  // namespace limit

// Names of the checks, as used in scenarios' expectations and in reports.
namespace check {
inline constexpr std::string_view kClockFrequency = "f_c";
inline constexpr std::string_view kMeasurementClock = "delay_measurement_f_c";
inline constexpr std::string_view kMeasurementProcedure = "delay_measurement";
inline constexpr std::string_view kMeasurementSpread = "delay_measurement_spread";
inline constexpr std::string_view kPulseHigh = "t_hi";
inline constexpr std::string_view kPulseLow = "t_lo";
inline constexpr std::string_view kOnOffRatio = "on_off_ratio";
inline constexpr std::string_view kSamplingWindow = "sampling_window";
inline constexpr std::string_view kRecovery = "t_m_t_r";
inline constexpr std::string_view kContention = "bus_contention";
inline constexpr std::string_view kDriverOff = "t_z";
inline constexpr std::string_view kDriverOn = "t_oe";
inline constexpr std::string_view kCalculationTime = "t_cal";
inline constexpr std::string_view kDataDelay = "t_d";
inline constexpr std::string_view kShortRecoveryClock = "t_m_short_f_c";
inline constexpr std::string_view kStartDelay = "t_st";
inline constexpr std::string_view kFloatingData = "floating_data";
inline constexpr std::string_view kErrorRecovery = "error_recovery";
inline constexpr std::string_view kDataDelayTolerance = "t_d_tolerance";
inline constexpr std::string_view kClockCount = "clock_count";
inline constexpr std::string_view kMemoryAccess = "t_ac";
inline constexpr std::string_view kPowerOn = "power_on";
inline constexpr std::string_view kTimeBetweenCycles = "t_b";
inline constexpr std::string_view kAccessWhileBusy = "busy_access";
// Every check name in the order of timing_rows() (timing.cpp asserts the two agree).
inline constexpr std::array kAll{kClockFrequency,  kCalculationTime,    kMemoryAccess,         kRecovery,
                                 kShortRecoveryClock, kDataDelay,       kStartDelay,           kPulseHigh,
                                 kPulseLow,        kOnOffRatio,         kDriverOff,          kDriverOn,             kTimeBetweenCycles,
                                 kMeasurementClock, kMeasurementProcedure, kMeasurementSpread, kDataDelayTolerance, kSamplingWindow,
                                 kClockCount,      kFloatingData,       kContention,           kErrorRecovery,
                                 kPowerOn,         kAccessWhileBusy};
// The row of a check name, at compile time.
consteval std::size_t row_index(std::string_view name) {
  for (std::size_t i = 0; i < kAll.size(); ++i)
    if (kAll[i] == name) return i;
  throw "not a check name";
}
// The row of a check name known only at run time; throws std::out_of_range for another name.
std::size_t row_of(std::string_view name);
}  // namespace check

// What a row needs to be judged: the wires alone, or also what the master declares about
// itself (its sampling instants, the t_D it uses, which frames measure the delay). A master
// that only drives pins is judged on every row of the first kind.
enum class Evidence : std::uint8_t { Wires, MasterDeclaration };
std::string_view to_string(Evidence e);

struct TimingRow {
  std::string_view check;        // the name in scenarios, reports and the schema
  std::string_view symbol;       // as the spec writes it: "t_cal", "f_c", "t_HI"
  std::string_view designation;  // the spec's wording of the row
  std::string_view section;      // "2.3.2", "2.3.2 note 8", "A2"
  std::string_view min;          // as the spec gives it; empty when there is none
  std::string_view max;
  std::string_view condition;    // when the row applies and how it is read here
  std::string_view observed;     // "encoder pins" or "master pins"
  Evidence evidence;
};

// Every row, in the order of table 2.3.2 and then the rules around it; one row per check name.
std::span<const TimingRow> timing_rows();
// The row of a check name; none for an unknown name.
std::optional<TimingRow> timing_row(std::string_view check);
// The rows as a Markdown table (docs/checks.md is this text).
std::string timing_table_markdown();

}  // namespace endatsim::protocol
