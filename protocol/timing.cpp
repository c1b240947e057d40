#include "endatsim/protocol/timing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace endatsim::protocol {

namespace limit {

Time data_delay_max(double length_m) {
  return kDataDelayBase + Time{static_cast<std::int64_t>(std::llround(length_m * static_cast<double>(kDataDelayPerMetre.count())))};
}

Time uncompensated_period_min(double length_m) {
  return std::max(2 * data_delay_max(length_m), sim::period_of(kFcMaxWithoutCompensation));
}

Time start_delay(Hertz f_c) {
  const Hertz over = std::clamp<Hertz>(f_c - kFcMaxWithCompensation, 0, kFcMaxSpecial - kFcMaxWithCompensation);
  const Time span = kStartDelay - kStartDelayAt16MHz;
  return kStartDelay - Time{span.count() * over / (kFcMaxSpecial - kFcMaxWithCompensation)};
}

}  // namespace limit

std::size_t check::row_of(std::string_view name) {
  const auto it = std::find(kAll.begin(), kAll.end(), name);
  if (it == kAll.end()) throw std::out_of_range("not a check name: " + std::string(name));
  return static_cast<std::size_t>(it - kAll.begin());
}

std::string_view to_string(Evidence e) {
  return e == Evidence::Wires ? "wires" : "master's declaration";
}

namespace {

using E = Evidence;

// The spec's own words and numbers; the conditions say how a row is read where the text leaves
// room (docs/model.md §7 and docs/analyzer.md, "Reading of some rows", give the reasons).
constexpr std::array kRows{
    TimingRow{check::kClockFrequency, "f_c", "Frequency", "2.3.2 note 4, 2.1.1, 2.1.2, 3.9.19", "100 kHz",
              "2 MHz without, 8 MHz with delay compensation (16 MHz for special applications)",
              "fitted over each frame's rising edges from RE2 on; measurement frames have their own row; without "
              "compensation also 1 / (2 t_D max) for the cable (2.3.2 note 4 and 2.1.1, Figure 2); this encoder: word 25 "
              "(3.9.19), 2 MHz for EnDat 2.1",
              "encoder pins", E::Wires},
    TimingRow{check::kCalculationTime, "t_cal", "Calculation time", "2.3.2 note 7, 2.3.1.1", "10.5/f_c",
              "1 ms (per encoder)",
              "minimum as a count: the start bit on RE11 or later; maximum to the rising edge that carries the start "
              "bit; continuous clock: at most 7 LOW bits before a later word's start bit; the master polls while DATA "
              "is LOW for this encoder's t_cal and the envelope's 1 ms",
              "encoder pins", E::Wires},
    TimingRow{check::kMemoryAccess, "t_ac", "Memory access time for read/write parameters", "2.3.2, 2.5.1, 2.6.1", "0",
              "12 ms (per encoder: the longer of encoder.t_ac_read and encoder.t_ac_write)",
              "2.1 parameter frames: the last payload bit to the acknowledgment's start bit, and the master polls at "
              "least that long (this encoder's t_ac, 12 ms for any encoder); 2.2: Busy in additional data 1 after the "
              "command supplement",
              "encoder pins", E::Wires},
    TimingRow{check::kRecovery, "t_m, t_R", "Recovery time I and II", "2.3.2 notes 3, 5, 9",
              "t_m 10 us (1.25 us short, 2.2 commands) + t_R 500 ns", "t_m 30 us (3.75 us short)",
              "last rising edge of a frame to FE1 of the next, against this encoder's t_m as word 3 activates it and "
              "against the envelope's 30 us (3.75 us short) + 500 ns",
              "encoder pins", E::Wires},
    TimingRow{check::kShortRecoveryClock, "t_m", "Recovery time I, short", "2.3.2 note 3, 3.4.4", "f_c >= 1 MHz", "",
              "while word 3 selects 1.25 .. 3.75 us, 2.2 commands need a clock of at least 1 MHz", "encoder pins",
              E::Wires},
    TimingRow{check::kDataDelay, "t_D", "Data delay time", "2.3.2 notes 1, 2", "0", "(0.2 + 0.01 x L) us",
              "from the rising edge that carried the start bit to the start bit's edge, at the master", "master pins",
              E::Wires},
    TimingRow{check::kStartDelay, "t_ST", "Recovery time III", "2.3.2 note 8", "2 us (f_c 2 .. 8 MHz), 1 us at 16 MHz",
              "per encoder (encoder.t_st_max)", "FE1 to RE1 with delay compensation; the maximum counts against this encoder", "encoder pins", E::Wires},
    TimingRow{check::kPulseHigh, "t_HI", "Positive pulse width", "2.3.2", "0.2 us without delay compensation",
              "10 us", "every HIGH phase inside a frame; with compensation the on-off ratio row bounds it from below",
              "encoder pins", E::Wires},
    TimingRow{check::kPulseLow, "t_LO", "Negative pulse width", "2.3.2", "0.2 us without delay compensation",
              "per encoder (encoder.t_lo_max)",
              "every LOW phase inside a frame (after t_ST with compensation); with compensation the on-off ratio row "
              "bounds it from below; the maximum counts against this encoder",
              "encoder pins", E::Wires},
    TimingRow{check::kOnOffRatio, "", "On-off ratio error", "2.3.2, 2.1.1", "",
              "0 % without (2.1.1: f_c = 1/(2 t_min) for another duty cycle), +/-10 % with delay compensation",
              "with compensation every HIGH and LOW phase inside a frame (after t_ST) at least 50 % - 10 % of the "
              "frame's period T; without, where the cable and not the 2 MHz bounds f_c, the shorter phase t_min at "
              "least t_D max for the cable (Figure 2's 1/(2 t_D) read as 1/(2 t_min))",
              "encoder pins", E::Wires},
    TimingRow{check::kDriverOff, "t_z", "Clock low to data inactive", "2.3.2 note 6", "", "T = 1/f_c min",
              "FE1 to the encoder's driver off", "encoder pins", E::Wires},
    TimingRow{check::kDriverOn, "t_OE", "Clock low to data active", "2.3.2 note 6", "", "T",
              "FE9 (FE33 after a 2.1 payload) to the encoder's driver on, not before it", "encoder pins", E::Wires},
    TimingRow{check::kTimeBetweenCycles, "t_b", "Time between cycle", "2.3.2", "> 1 ms (EnDat 2.1 commands)", "",
              "last rising edge to FE1 of a 2.1 memory or parameter frame", "encoder pins", E::Wires},
    TimingRow{check::kMeasurementClock, "f_c", "Propagation-delay measurement clock", "2.1.2", "100 kHz", "200 kHz",
              "frames the master declares as measurements", "encoder pins", E::MasterDeclaration},
    TimingRow{check::kMeasurementProcedure, "t_D", "Propagation-delay measurement", "2.1.2",
              "3 measurements; counter f_e >= 8 f_c - 10 %", "",
              "measured before compensating, again after every change of the transmission path", "master pins",
              E::MasterDeclaration},
    TimingRow{check::kMeasurementSpread, "t_D", "Propagation-delay measurements agree", "2.1.2",
              "3 measurements before compensating", "each within T/8 of their mean (T at the compensated f_c)",
              "the t_D each measurement frame (000111 at 100 .. 200 kHz) shows, judged at the next compensated "
              "frame; the latest three or more must agree",
              "master pins", E::Wires},
    TimingRow{check::kDataDelayTolerance, "t_D", "Set data delay time", "2.3", "", "+/-10 % x T",
              "the t_D the master compensates with against the line's", "master pins", E::MasterDeclaration},
    TimingRow{check::kSamplingWindow, "t_D", "Data taken at the falling edge plus t_D", "2.3, 2.1.2", "", "",
              "each declared sampling instant inside its bit's data-valid window", "master pins",
              E::MasterDeclaration},
    TimingRow{check::kClockCount, "", "Number of clock pulses", "2.3.1, 2.4.1, 2.4.2.1", "the last bit of the answer",
              "one more (continuous clock only with 000111); none after a 2.2 command supplement's last bit",
              "counted from the start bit; the supplement's last bit as the wires show it", "encoder pins",
              E::Wires},
    TimingRow{check::kFloatingData, "", "Mode bits and data on a driven line", "2.3", "", "",
              "DATA undriven while the encoder takes a mode bit (RE3..RE8) or the master samples", "encoder pins",
              E::Wires},
    TimingRow{check::kContention, "", "One driver on DATA at a time", "2.3, 2.10", "", "0 ps",
              "both drivers on at one end's pins", "encoder pins", E::Wires},
    TimingRow{check::kErrorRecovery, "t_m", "Recovery after an error handling", "A2", "30 us (the maximum t_m)", "",
              "last rising edge of a frame with a type I error or no start bit to FE1 of the next", "encoder pins",
              E::Wires},
    TimingRow{check::kPowerOn, "t1, t2, t3", "Power-on conditions", "2.3.3",
              "t1 800 ms, t2 80 ms, a LOW pulse > 125 ns or a request cycle, t3 380 ms", "t2 120 ms, t3 420 ms",
              "CLOCK from each switch-on (the run's start, a power interruption, a recorded supply) to the first "
              "request",
              "encoder pins", E::Wires},
    TimingRow{check::kAccessWhileBusy, "", "No memory access while Busy", "2.5.1, 2.6.1, 2.3.1 note 1", "", "",
              "after a 2.2 memory access, no further read, write or reset (2.1 commands included) before a frame "
              "whose additional data 1 shows Busy = 0",
              "encoder pins", E::Wires},
};

constexpr bool rows_in_check_order() {
  if (kRows.size() != check::kAll.size()) return false;
  for (std::size_t i = 0; i < kRows.size(); ++i)
    if (kRows[i].check != check::kAll[i]) return false;
  return true;
}
static_assert(rows_in_check_order(), "check::kAll lists the rows' check names in the table's order");

std::string cell(std::string_view s) { return s.empty() ? std::string("-") : std::string(s); }

}  // namespace

std::span<const TimingRow> timing_rows() { return kRows; }

std::optional<TimingRow> timing_row(std::string_view check) {
  const auto it = std::find_if(kRows.begin(), kRows.end(), [&](const TimingRow& r) { return r.check == check; });
  if (it == kRows.end()) return std::nullopt;
  return *it;
}

std::string timing_table_markdown() {
  std::string out =
      "| check | symbol | designation | section | minimum | maximum | read as | observed at | needs |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const TimingRow& r : kRows) {
    out += "| `" + std::string(r.check) + "` | " + cell(r.symbol) + " | " + cell(r.designation) + " | " +
           cell(r.section) + " | " + cell(r.min) + " | " + cell(r.max) + " | " + cell(r.condition) + " | " +
           cell(r.observed) + " | " + std::string(to_string(r.evidence)) + " |\n";
  }
  return out;
}

}  // namespace endatsim::protocol
