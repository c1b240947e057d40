// Rows of table 2.3.2 seen on the DATA line: the encoder's driver turning off after FE1 (t_z)
// and on again at the turnaround (t_OE), the start bit no earlier and no later than t_cal allows,
// and the data delay t_D of the whole round trip. With a continuous clock (2.3.1) t_D and the
// start bit are judged for every word; t_z and t_OE belong to the mode command (see
// on_encoder_driver).
#include <algorithm>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/protocol/frame.hpp"

namespace endatsim::checker {
namespace {

using sim::format_time;

namespace limit = protocol::limit;
namespace position = protocol::frame_position;

// The spec's words for findings, from the limits; built once (some rows report in every frame).
const std::string& t_cal_max_spec() {
  static const std::string text = "2.3.2 t_cal maximum " + sim::format_time(limit::kCalculationTimeMax);
  return text;
}

const std::string& continuous_low_bits_spec() {
  static const std::string text = "2.3.1.1 continuous clock: at most " + std::to_string(limit::kContinuousClockMaxLowBits) +
                                  " LOW bits before the next word (in place of t_cal)";
  return text;
}

std::string if_carried_by(unsigned clock) { return " if RE" + std::to_string(clock) + " carried the start bit"; }

const std::string& t_ac_max_spec() {
  static const std::string text = "2.3.2 t_ac maximum " + sim::format_time(limit::kMemoryAccessMax);
  return text;
}

const std::string& data_delay_tolerance_spec() {
  static const std::string text =
      "2.3 (data delay time within +/-" + std::to_string(limit::kDataDelayTolerancePercent) + " % of the period)";
  return text;
}

}  // namespace

void TimingChecker::start_data_line_checks() {
  released_ = false;
  pending_release_.reset();
  driving_ = false;
  driven_low_ = false;
  start_clock_ = 0;
  word_start_clock_ = 0;
  word_ = 0;
  low_clock_ = 0;
}

// The encoder's LOW after the turnaround, seen as a falling edge or, when DATA was LOW already
// (fail-safe LOW), on a rising clock edge. Only a HIGH after it is a start bit: a type I answer
// that drives HIGH at once (A2, docs/model.md §10) is not.
void TimingChecker::note_encoder_low() {
  if (driving_ && !encoder_pins_.data.read()) driven_low_ = true;
}

std::optional<Time> TimingChecker::turnaround_bound() const {
  if (!params_.t_z_per_frame_period) return limit::kPeriodAtFcMin;
  if (current_.header.f_c > 0) return sim::period_of(current_.header.f_c);
  return std::nullopt;
}

void TimingChecker::judge_release(const Release& r, Time bound) {
  report_unless_passed(at_most(r.t_z, bound, params_.resolution),
      {.check = std::string(check::kDriverOff),
       .spec = "2.3.2 t_z (clock low to data inactive)",
       .where = ObservationPoint::EncoderPins,
       .time = r.at,
       .frame = current_.header.index,
       .clock = r.clock,
       .measured = format_time(r.t_z),
       .limit = "<= T = " + format_time(bound),
       .severity = Severity::Error,
       .message = "the encoder released DATA too late after FE1: the master drives from FE2"}, "FE1 release");
}

// On the wires alone the frame's f_c shows from its second rising edge, after the release: the
// release waits for it, and is judged against 10 us only in a frame that never shows one.
void TimingChecker::settle_pending_release() {
  if (!pending_release_) return;
  refresh_wire_header();
  const auto bound = turnaround_bound();
  judge_release(*pending_release_, bound.value_or(limit::kPeriodAtFcMin));
  pending_release_.reset();
}

// t_z and t_OE are the two turnarounds of DATA around the mode command: the encoder releases DATA
// for the master's mode bits and takes it back after them (2.3). A continuous clock sends the mode
// command once, "only with the first data query" (2.3.1), and the encoder drives on from word to
// word (HIGH bit, LOW bits, the next start bit; 2.3.1.1 Figure 15, docs/model.md §6): later words
// have no turnaround, so neither row applies to them. A driver that goes off between words leaves
// DATA undriven while the master samples, which floating_data reports.
void TimingChecker::on_encoder_driver(std::uint64_t enabled) {
  if (!in_frame_) return;
  refresh_wire_header();
  const Time now = kernel_.now();
  const auto clock = static_cast<unsigned>(current_.falling.size());
  if (enabled == 0 && !released_) {
    released_ = true;
    judge(protocol::check::row_index(check::kDriverOff));
    const Release r{now - current_.fe1, now, clock};
    if (const auto bound = turnaround_bound()) judge_release(r, *bound);
    else pending_release_ = r;
  } else if (enabled != 0 && released_ && !driving_) {
    driving_ = true;
    judge(protocol::check::row_index(check::kDriverOn));
    settle_pending_release();
    const Time period = turnaround_bound().value_or(limit::kPeriodAtFcMin);
    const unsigned turnaround = position::kTurnaround + current_.header.payload_bits;
    if (current_.falling.size() < turnaround) {
      report({.check = std::string(check::kDriverOn),
              .spec = "2.3.2 t_OE (clock low to data active)",
              .where = ObservationPoint::EncoderPins,
              .time = now,
              .frame = current_.header.index,
              .clock = clock,
              .measured = "before FE" + std::to_string(turnaround),
              .limit = "after FE" + std::to_string(turnaround),
              .severity = Severity::Error,
              .message = "the encoder drove DATA while the master still sends the mode command"}, "turnaround");
      return;
    }
    // Read from FE9, after which the master has released DATA; the alternative reading starts
    // at FE10 and would allow one more period.
    const Time t_oe = now - current_.falling[position::edge_index(turnaround)];
    report_unless_passed(at_most(t_oe, period, params_.resolution),
        {.check = std::string(check::kDriverOn),
         .spec = "2.3.2 t_OE (clock low to data active)",
         .where = ObservationPoint::EncoderPins,
         .time = now,
         .frame = current_.header.index,
         .clock = clock,
         .measured = format_time(t_oe),
         .limit = "<= T = " + format_time(period),
         .severity = Severity::Error,
         .message = "the encoder took longer than one clock period after FE" + std::to_string(turnaround)
                    + " to drive DATA"}, "turnaround");
  }
}

void TimingChecker::on_encoder_data(std::uint64_t level) {
  if (wires_only_ || !mode_decided_) decoder_.on_data(kernel_.now(), level != 0);
  if (level != 0) last_data_rise_ = kernel_.now();
  if (!in_frame_) return;
  if (level == 0) {
    note_encoder_low();
    low_clock_ = carrying_clock();
    return;
  }
  if (!driving_ || !driven_low_) return;
  if (start_clock_ == 0) {
    first_start_bit();
    return;
  }
  // The HIGH bit after the CRC (slot start + answer) may rise as well; it is no start bit.
  const unsigned clock = carrying_clock();
  if (current_.header.continuous && clock > word_start_clock_ + current_.header.answer_bits) next_word_start_bit(clock);
}

// The rising clock edge whose bit slot an edge on DATA at the encoder pins belongs to: the encoder
// puts its bits out on rising edges, which show on its pins one encoder-internal delay (receiver,
// logic, driver) later. The slot is the one whose bit the level from this edge on is taken for,
// as the decoder takes it (checker/frame_decoder.hpp): half a period after RE_k plus the declared
// delay. So an encoder a little faster or slower than declared (up to half a period) still has its
// start bit on the edge that carried it, as the decoded frame shows.
unsigned TimingChecker::carrying_clock() const {
  const auto& rising = current_.rising;
  const auto& lp = line_.params();
  const Time delay = measured_round_trip_ ? *measured_round_trip_
                         : lp.encoder.receiver_delay + encoder_.output_delay + lp.encoder.driver_delay;
  const std::size_t n = rising.size();
  if (n < 2) {
    // No period yet: the latest edge the declared delay allows. In a sampled capture each edge
    // shows up to one resolution late: a DATA edge may then look earlier than its clock edge plus
    // the delay by as much.
    const Time launched = kernel_.now() - delay + params_.resolution;
    return static_cast<unsigned>(std::upper_bound(rising.begin(), rising.end(), launched) - rising.begin());
  }
  const Time half = (rising[n - 1] - rising[n - 2]) / 2;
  const auto first = std::lower_bound(rising.begin(), rising.end(), kernel_.now() - delay - half);
  // After the last edge's slot (the clock stopped): that edge's.
  return static_cast<unsigned>(std::min<std::size_t>(static_cast<std::size_t>(first - rising.begin()) + 1, n));
}

// The start bit of the frame's first word: the first rising DATA edge the encoder drives after the
// turnaround.
void TimingChecker::first_start_bit() {
  refresh_wire_header();
  start_clock_ = carrying_clock();
  if (start_clock_ == 0) return;
  word_start_clock_ = start_clock_;
  note_start_bit_for_t_d();
  check_start_bit_timing();
}

// t_ac or t_cal, from the edge that carried the start bit.
void TimingChecker::check_start_bit_timing() {
  const bool parameter_frame = current_.header.payload_bits != 0;
  if (start_edge_unknown(current_.header.compensated) && !start_bit_timing_decided(parameter_frame)) {
    const Time after_fe1 = current_.rising[position::edge_index(start_clock_)] - current_.fe1;
    report_start_edge_unknown(parameter_frame ? protocol::check::row_index(check::kMemoryAccess)
                                              : protocol::check::row_index(check::kCalculationTime),
                              parameter_frame ? check::kMemoryAccess : check::kCalculationTime,
                              parameter_frame ? t_ac_max_spec() : t_cal_max_spec(), start_clock_, format_time(after_fe1) + if_carried_by(start_clock_),
                              kernel_.now(), "start bit");
    return;
  }
  if (parameter_frame) {
    check_memory_access_time();
    return;
  }
  check_calculation_time_minimum();
  check_calculation_time_maximum();
}

// At the master's connector the encoder's bits come one round trip after the edges that carried
// them. A capture that measures it (delay measurement frames) or a round trip the user gives
// places each bit on its edge; one estimated from the cable's length does so only to within the
// estimate's error, which the spec bounds only by t_D's maximum (2.3.2): more than half the period
// of a compensated clock. Then t_D, t_cal (t_ac) and the clock count, which hang on that edge, are
// undecided, never passed or failed on a guess.
// How far from the edge the estimate puts it the start bit's edge may lie: the real round trip
// lies between 0 and t_D's maximum (a conforming line), the estimate somewhere in between or above.
Time TimingChecker::start_edge_uncertainty() const {
  return std::max(encoder_.output_delay, limit::data_delay_max(cable_length_m()));
}

unsigned TimingChecker::start_edge_uncertainty_clocks() const {
  const Time period = sim::period_of(current_.header.f_c);
  const Time u = start_edge_uncertainty();
  return static_cast<unsigned>((u + period - Time{1}) / period);
}

// t_cal (t_ac) with the start bit's edge known only to within start_edge_uncertainty(): decided
// when every edge within it gives the same result (t_cal's 1 ms maximum almost always is).
bool TimingChecker::start_bit_timing_decided(bool parameter_frame) const {
  const Time u = start_edge_uncertainty();
  const Time carried = current_.rising[position::edge_index(start_clock_)];
  if (parameter_frame) {
    const unsigned last_payload = position::kTurnaround - 1 + current_.header.payload_bits;
    if (start_clock_ <= last_payload) return false;
    const Time t_ac = carried - current_.rising[position::edge_index(last_payload)];
    return at_most(t_ac, limit::kMemoryAccessMax + sim::period_of(current_.header.f_c), u).decision != Decision::Undecided;
  }
  const unsigned e = start_edge_uncertainty_clocks();
  const bool minimum = start_clock_ + e < position::kEarliestStartBit || start_clock_ >= position::kEarliestStartBit + e;
  const Time t_cal = carried - current_.fe1;
  const bool maximum =
      at_most(t_cal, limit::kCalculationTimeMax + sim::period_of(current_.header.f_c), u).decision != Decision::Undecided;
  return minimum && maximum;
}

bool TimingChecker::start_edge_unknown(bool compensated) const {
  return compensated && wires_only_ && !params_.round_trip_given && !measured_round_trip_ &&
         params_.recorded_at == ObservationPoint::MasterPins;
}

void TimingChecker::report_start_edge_unknown(std::size_t row_index, std::string_view row, const std::string& spec,
                                              unsigned clock, std::string measured, Time at, std::string_view field) {
  judge(row_index);
  report({.check = std::string(row),
          .spec = spec,
          .where = ObservationPoint::MasterPins,
          .time = at,
          .frame = current_.header.index,
          .clock = clock,
          .measured = std::move(measured),
          .limit = "the edge that carried the start bit",
          .severity = Severity::Undecided,
          .message = "the round trip at the master's connector is neither measured in the capture nor given (--t-d): "
                     "which rising edge carried the start bit is not known to within half a period of this "
                     "compensated clock"},
         field);
}

// The same from the decoder's sampled start bit (captures without driver enables). At the master's
// connector t_D runs from the rising edge that carried the start bit to the DATA edge that
// brought it, the latest rising one before the decoder sampled it.
void TimingChecker::start_bit_from_decoder(unsigned clock) {
  refresh_wire_header();
  start_clock_ = word_start_clock_ = clock;
  if (params_.round_trip_observable && clock <= master_rising_.size() && last_data_rise_ > master_rising_[position::edge_index(clock)]) {
    const StartBitInFlight s{last_data_rise_, master_rising_[position::edge_index(clock)], current_.header.index, clock,
                             current_.header.compensated, current_.header.t_d_used,
                             sim::period_of(current_.header.f_c), measures_delay(current_.header)};
    check_data_delay(s, last_data_rise_ - master_rising_[position::edge_index(clock)]);
  }
  check_start_bit_timing();
}

// t_cal ends no later than the rising edge that carried the start bit (the encoder answers on the
// first rising edge after its calculation), so that edge must come within t_cal max of FE1.
void TimingChecker::check_calculation_time_maximum() {
  judge(protocol::check::row_index(check::kCalculationTime));
  const Time t_cal = current_.rising[position::edge_index(start_clock_)] - current_.fe1;
  const Time bound = limit::kCalculationTimeMax + sim::period_of(current_.header.f_c);
  report_unless_passed(at_most(t_cal, bound, params_.resolution),
      {.check = std::string(check::kCalculationTime),
       .spec = t_cal_max_spec(),
       .where = ObservationPoint::EncoderPins,
       .time = kernel_.now(),
       .frame = current_.header.index,
       .clock = start_clock_,
       .measured = format_time(t_cal),
       .limit = "<= " + format_time(limit::kCalculationTimeMax) + " + T = " + format_time(bound),
       .severity = Severity::Error,
       .message = "the start bit came later than the longest calculation time allows"}, "start bit");
}

// 2.3.1.1, continuous clock: after the CRC the encoder drives one HIGH bit, LOW bits and the next
// word's start bit; "independently of the t_CAL, a maximum of 7 Low Bits (internal synchronization)
// are inserted" (Figure 15). The t_cal row runs from FE1 of a mode command and belongs to the first
// word: its minimum 10.5/f_c does not apply to later words, which follow after as little as one LOW
// bit (the continuous clock "reduces the length of the clock-pulse group by 10 periods per position
// value", HEIDENHAIN's encoder catalogue; docs/model.md §6), and this bound takes the place of its
// maximum. Counted as the LOW run before the start bit, so that a HIGH bit of two clocks (one
// published master's reading, docs/model.md §6) is not counted as LOW.
void TimingChecker::next_word_start_bit(unsigned clock) {
  ++word_;
  word_start_clock_ = clock;
  note_start_bit_for_t_d();
  judge(protocol::check::row_index(check::kCalculationTime));
  const unsigned low_bits = clock - low_clock_;
  if (low_bits <= limit::kContinuousClockMaxLowBits) return;
  report({.check = std::string(check::kCalculationTime),
          .spec = continuous_low_bits_spec(),
          .where = ObservationPoint::EncoderPins,
          .time = kernel_.now(),
          .frame = current_.header.index + word_,
          .clock = clock,
          .measured = std::to_string(low_bits) + " LOW bits",
          .limit = "<= " + std::to_string(limit::kContinuousClockMaxLowBits) + " LOW bits",
          .severity = Severity::Error,
          .message = "continuous word " + std::to_string(word_)
                     + ": the start bit came later than the encoder's internal synchronization allows"}, "start bit");
}

// 2.3.2 t_cal minimum 10.5/f_c: with the clock's first LOW half a period, RE11 comes 10.5 periods
// after FE1, so the row is read as a count (the start bit on RE11 or later) and holds for any
// duty cycle or t_ST (docs/model.md §1, §7).
void TimingChecker::check_calculation_time_minimum() {
  if (start_clock_ >= position::kEarliestStartBit) return;
  report({.check = std::string(check::kCalculationTime),
          .spec = "2.3.2 t_cal minimum 10.5/f_c",
          .where = ObservationPoint::EncoderPins,
          .time = kernel_.now(),
          .frame = current_.header.index,
          .clock = start_clock_,
          .measured = "RE" + std::to_string(start_clock_),
          .limit = "RE" + std::to_string(position::kEarliestStartBit) + " or later (10.5 periods after FE1)",
          .severity = Severity::Error,
          .message = "the start bit came before the shortest calculation time"}, "start bit");
}

// 2.1 parameter frames: the acknowledgment's start bit waits for the memory access, which
// begins with the last bit of the master's 8 + 16 (docs/model.md §7, "in the frame").
void TimingChecker::check_memory_access_time() {
  const unsigned last_payload = position::kTurnaround - 1 + current_.header.payload_bits;
  if (start_clock_ <= last_payload) return;
  judge(protocol::check::row_index(check::kMemoryAccess));
  const Time t_ac = current_.rising[position::edge_index(start_clock_)] - current_.rising[position::edge_index(last_payload)];
  const Time bound = limit::kMemoryAccessMax + sim::period_of(current_.header.f_c);
  report_unless_passed(at_most(t_ac, bound, params_.resolution),
      {.check = std::string(check::kMemoryAccess),
       .spec = t_ac_max_spec(),
       .where = ObservationPoint::EncoderPins,
       .time = kernel_.now(),
       .frame = current_.header.index,
       .clock = start_clock_,
       .measured = format_time(t_ac),
       .limit = "<= " + format_time(limit::kMemoryAccessMax) + " + T = " + format_time(bound),
       .severity = Severity::Error,
       .message = "the acknowledgment came later than the longest memory access time allows"}, "start bit");
}

// t_D ends where the start bit's edge reaches the master logic: one cable delay and one receiver
// delay after it showed at the encoder pins. Noted with the rising clock edge that carried it, at
// the master logic, for every word of a continuous clock.
void TimingChecker::note_start_bit_for_t_d() {
  const unsigned clock = word_start_clock_;
  if (clock > master_rising_.size()) return;  // an edge the master never sent (a glitch at the encoder pins)
  const auto& lp = line_.params();
  start_bits_in_flight_.push_back({kernel_.now() + line_.cable_delay() + lp.master.receiver_delay,
                                   master_rising_[position::edge_index(clock)], current_.header.index + word_, clock,
                                   current_.header.compensated, current_.header.t_d_used,
                                   sim::period_of(current_.header.f_c), word_ == 0 && measures_delay(current_.header)});
  drop_given_up_start_bits();
}

// The start bit's edge is the first rising edge at the master logic from half a slot before it is
// due: the rising edge before a start bit on DATA is at least two slots earlier (the HIGH bit after
// the previous word's CRC, or the fail-safe level before the turnaround) and may still be on the
// cable. A start bit that comes late at the master (a disturbed one) makes t_D long, as the master
// sees it. A start bit that never shows (a fault at the master's pins) is given up once the next
// one is due, or, half a slot overdue, once a later frame has begun at the encoder.
void TimingChecker::on_master_data(std::uint64_t level) {
  if (level == 0) return;
  const Time now = kernel_.now();
  drop_given_up_start_bits();
  auto& in_flight = start_bits_in_flight_;
  if (in_flight.empty() || now < in_flight.front().due - in_flight.front().period / 2) return;
  const StartBitInFlight start = in_flight.front();
  const Time t_d = now - start.carried_at;
  check_data_delay(start, t_d);
  check_delay_tolerance(start, t_d);
  in_flight.pop_front();  // after its findings: until then its frame is not settled
}

// Start bits given up as the comment above says. Whether one is given up only changes from no
// to yes as time passes and frames begin, so they are dropped as soon as they are, also when
// DATA never rises at the master logic again (a fault there): the queue stays a frame's worth.
void TimingChecker::drop_given_up_start_bits() {
  const Time now = kernel_.now();
  auto& in_flight = start_bits_in_flight_;
  const auto due = [&](const StartBitInFlight& s) { return now >= s.due - s.period / 2; };
  const auto given_up = [&](const StartBitInFlight& s) {
    const bool next_due = in_flight.size() > 1 && due(in_flight[1]);
    return next_due || (s.frame < current_.header.index && now > s.due + s.period / 2);
  };
  while (!in_flight.empty() && given_up(in_flight.front())) in_flight.pop_front();
}

// t_D (2.3.2, 2.1.2): from the rising clock edge that carried the start bit to the start bit's
// edge, both at the master logic; at most 0.2 us + 0.01 us/m x cable length.
void TimingChecker::check_data_delay(const StartBitInFlight& start, Time t_d) {
  if (!params_.round_trip_observable) return;
  // t_D is the DATA edge's time after the carrying edge, so an unknown edge leaves it unknown by
  // whole periods: only a t_D over the bound for the latest edge before the DATA edge is decided.
  const Time least = start.period > Time::zero() ? t_d % start.period : t_d;
  if (start_edge_unknown(start.compensated) && !start.measurement &&
      at_most(least, limit::data_delay_max(cable_length_m()), params_.resolution).decision != Decision::Fail) {
    report_start_edge_unknown(protocol::check::row_index(check::kDataDelay), check::kDataDelay,
                              "2.3.2 t_D maximum (0.2 + 0.01 x L) us", start.clock, format_time(t_d) + if_carried_by(start.clock), kernel_.now(), "start bit");
    return;
  }
  if (start.measurement) delay_measurements_.measured(start.frame, t_d);
  // Only a capture at the master's connector sees its "encoder pins" one round trip after the edges.
  if (start.measurement && params_.recorded_at == ObservationPoint::MasterPins && t_d < start.period / 2) {
    measured_round_trip_ = t_d;
    decoder_.set_clock_to_data(t_d);
  }
  judge(protocol::check::row_index(check::kDataDelay));
  const Time bound = limit::data_delay_max(cable_length_m());
  report_unless_passed(at_most(t_d, bound, params_.resolution),
      {.check = std::string(check::kDataDelay),
       .spec = "2.3.2 t_D maximum (0.2 + 0.01 x L) us",
       .where = ObservationPoint::MasterPins,
       .time = kernel_.now(),
       .frame = start.frame,
       .clock = start.clock,
       .measured = format_time(t_d),
       .limit = "<= " + format_time(bound),
       .severity = Severity::Error,
       .message = "the round trip of the line and the encoder is longer than the spec allows"}, "start bit");
}

// 2.3: "the set Data Delay Time with a tolerance of +/-10 % x f_c must not be exceeded": the t_D
// a compensating master uses may differ from the real one by at most a tenth of the period.
void TimingChecker::check_delay_tolerance(const StartBitInFlight& start, Time t_d) {
  if (!start.compensated || wires_only_) return;  // the t_D a master uses is not on the wires
  judge(protocol::check::row_index(check::kDataDelayTolerance));
  const Time error = start.t_d_used > t_d ? start.t_d_used - t_d : t_d - start.t_d_used;
  const Time tenth = start.period * limit::kDataDelayTolerancePercent / 100;
  note(check::kDataDelayTolerance, at_most(error, tenth, Time::zero()));
  if (error > tenth)
    report({.check = std::string(check::kDataDelayTolerance),
            .spec = data_delay_tolerance_spec(),
            .where = ObservationPoint::MasterPins,
            .time = kernel_.now(),
            .frame = start.frame,
            .clock = start.clock,
            .measured = format_time(error),
            .limit = "<= T/10 = " + format_time(tenth),
            .severity = Severity::Error,
            .message = "the master compensates with t_D = " + format_time(start.t_d_used) + " but the line's is "
                       + format_time(t_d)}, "start bit");
}

}  // namespace endatsim::checker

namespace endatsim::checker {

namespace {

// 2.3.2 note 8: t_ST = 2 us for f_c 2 .. 8 MHz, 1 us at 16 MHz, linear in between; "the 2 us
// relate to a cable length of 100 m and can be reduced with a shorter cable". The note's value
// scaled with the spec's t_D bound, t_D max(L) / t_D max(100 m) = (0.2 + 0.01 L) / 1.2, is what the cable needs: above 100 m
// it is longer (the encoder's release must reach the master before it drives) and always
// required; below 100 m it is shorter and accepted only with
// CheckerParams::t_st_reduced_for_cable, else the note's own value is required. Only with delay
// compensation (table column).
Time required_start_delay(sim::Hertz f_c, double cable_m, bool reduced_for_cable) {
  const Time note8 = limit::start_delay(f_c);
  const double share = static_cast<double>(limit::data_delay_max(cable_m).count()) /
                       static_cast<double>(limit::data_delay_max(limit::kCompensatedCableMaxMetres).count());
  const Time scaled{static_cast<std::int64_t>(static_cast<double>(note8.count()) * share + 0.5)};
  return reduced_for_cable ? scaled : std::max(note8, scaled);
}

}  // namespace

void TimingChecker::check_start_delay(const PinFrame& f) {
  if (!f.header.compensated || f.rising.empty()) return;
  judge(protocol::check::row_index(check::kStartDelay));
  const Time t_st = f.rising.front() - f.fe1;
  const bool reduced = params_.t_st_reduced_for_cable;
  const Time required = required_start_delay(f.header.f_c, cable_length_m(), reduced);
  report_unless_passed(at_least(t_st, required, params_.resolution),
      {.check = std::string(check::kStartDelay),
       .spec = reduced ? "2.3.2 t_ST and note 8, reduced for the cable (option t_st_reduced_for_cable)" : "2.3.2 "
               "t_ST and note 8",
       .where = ObservationPoint::EncoderPins,
       .time = f.fe1,
       .frame = f.header.index,
       .clock = 1U,
       .measured = format_time(t_st),
       .limit = ">= " + format_time(required),
       .severity = Severity::Error,
       .message = "first LOW phase shorter than t_ST for this clock" + std::string(reduced ? " and cable" : "")
                  + ": the encoder's driver may still be on when the master drives DATA"}, "first LOW phase");
  // The maximum is the encoder's own ("see encoder specifications"): no envelope to judge.
  if (!encoder_.t_st_max) return;
  report_unless_passed(at_most(t_st, *encoder_.t_st_max, params_.resolution),
      {.check = std::string(check::kStartDelay),
       .spec = "2.3.2 t_ST maximum (see encoder specifications)",
       .where = ObservationPoint::EncoderPins,
       .time = f.fe1,
       .frame = f.header.index,
       .clock = 1U,
       .measured = format_time(t_st),
       .limit = "<= " + format_time(*encoder_.t_st_max) + " (this encoder's t_ST maximum)",
       .severity = Severity::Error,
       .message = "first LOW phase longer than this encoder's datasheet allows",
       .verdict = Verdict::ThisEncoder}, "first LOW phase");
}

void TimingChecker::on_master_driven(std::uint64_t driven) {
  master_driven_.emplace_back(kernel_.now(), driven != 0);
  // A sample sees the pins one receiver delay before it, never before now's: a change with a
  // later one at or before that instant decides no sample to come (check_master_sample).
  const Time seen = kernel_.now() - line_.params().master.receiver_delay;
  while (master_driven_.size() > 1 && master_driven_[1].first <= seen) master_driven_.pop_front();
}

// The encoder takes the mode bits on RE3..RE8 (2.3); DATA must be driven at its pins then.
void TimingChecker::check_encoder_sample(unsigned clock) {
  if (clock < position::kFirstModeBit || clock > position::kLastModeBit) return;
  if (params_.driver_enables_observable && clock == position::kFirstModeBit) judge(protocol::check::row_index(check::kFloatingData));
  if (floating_reported_) return;
  if (encoder_pins_.data_driven.read()) return;
  floating_reported_ = true;
  report({.check = std::string(check::kFloatingData),
          .spec = "2.3 (mode bits taken on rising edges)",
          .where = ObservationPoint::EncoderPins,
          .time = kernel_.now(),
          .frame = current_.header.index,
          .clock = clock,
          .measured = "undriven",
          .limit = "driven by the master",
          .severity = Severity::Error,
          .message = "the encoder took a mode bit from an undriven line (fail-safe level)"}, "mode bits");
}

// The master's receiver output at its sampling instant shows its pins one receiver delay earlier.
void TimingChecker::check_master_sample(const DeclaredFrame& frame, unsigned clock) {
  if (floating_reported_) return;
  const Time at_pins = kernel_.now() - line_.params().master.receiver_delay;
  bool driven = master_driven_.empty() || master_driven_.front().second;
  for (const auto& [when, value] : master_driven_)
    if (when <= at_pins) driven = value;
  if (driven) return;
  floating_reported_ = true;
  report({.check = std::string(check::kFloatingData),
          .spec = "2.3 (observe the data line for the start bit)",
          .where = ObservationPoint::MasterPins,
          .time = kernel_.now(),
          .frame = frame.index,
          .clock = clock,
          .measured = "undriven",
          .limit = "driven by the encoder",
          .severity = Severity::Error,
          .message = "the master sampled DATA while no driver was on (fail-safe level)"}, field_of(frame, clock));
}

// The frame needs its last bit clocked out (RE_(s + width - 1)) and may have one more pulse,
// which carries the HIGH end of data (docs/model.md §5). Fewer leave the encoder hanging in
// the middle of the cycle; more are taken as a continuous clock (2.3.1), which only
// "Encoder send position values" supports (HEIDENHAIN's EnDat FAQ, docs/model.md §5), and make a 2.1
// parameter frame an error (2.4.1). A 2.2 command supplement runs on after the answer; a pulse
// after the one that takes its last bit makes the encoder answer with an error (2.4.2.1, A2).
// Where that bit was is known from the wires (frame_decoder.hpp).
// 2.3.2: "Polling the start bit must be independent of t_CAL; this means clock pulses must be
// continuously sent". A frame that ends without a start bit ended its polling after FE1 + the
// time its last rising edge shows; an encoder may take t_cal (declared, word 39) and any
// compliant one up to 1 ms (note 7); an encoder that calculates longer in energy-saving mode
// (3.6.5), whether or not the wires switched it on, the longer of the two. Only a frame whose DATA
// was still LOW at its last rising edge
// is judged: the encoder was calculating. An encoder that answers HIGH at once (a type I error
// handling, A2) lets the master stop. A 2.1 parameter frame waits in the same way for the memory
// access after the master's last payload bit: the declared t_ac, and up to 12 ms for any
// compliant encoder (2.3.2 t_ac; docs/model.md §7, the access "in the frame").
void TimingChecker::check_start_bit_polling(const PinFrame& f) {
  if (f.rising.empty() || f.header.answer_bits == 0 || f.header.measurement || !low_at_last_rise_ ||
      f.rising.size() <= protocol::frame_position::kTurnaround + 1 ||
      master_found_start_bit_ == f.header.index)  // a declaring master read a start bit: it did not give up
    return;
  if (f.header.payload_bits == 0) {
    const Time t_cal = f.header.command_type == protocol::EndatVersion::V2_2 ? encoder_.t_cal_22.value_or(encoder_.t_cal)
                                                                            : encoder_.t_cal;
    judge_polling(f, f.fe1, {check::kCalculationTime, "2.3.2 (start-bit polling independent of t_cal, note 7)",
                             "t_cal", std::max(t_cal, encoder_.t_cal_energy_saving.value_or(t_cal)),
                             limit::kCalculationTimeMax});
    return;
  }
  const unsigned last_payload = position::kTurnaround - 1 + f.header.payload_bits;
  if (f.rising.size() <= last_payload) return;  // the clock stopped inside the payload: clock_count says so
  judge_polling(f, f.rising[position::edge_index(last_payload)],
                {check::kMemoryAccess, "2.3.2 t_ac (start-bit polling through the memory access)", "t_ac",
                 encoder_.t_ac, limit::kMemoryAccessMax});
}

// The polling from `from` to the frame's last rising edge against this encoder's declared time
// (both verdicts when it fails) and the envelope's maximum (the envelope only).
void TimingChecker::judge_polling(const PinFrame& f, Time from, const PollingLimit& l) {
  judge(protocol::check::row_of(l.check));
  const Time polled = f.rising.back() - from;
  const Judgement to_envelope = at_least(polled, l.envelope, params_.resolution);
  note(l.check, to_envelope);
  Decision to_encoder = Decision::Fail;  // without a declaration the envelope's maximum is the only limit
  if (l.declared) {
    const Judgement j = at_least(polled, *l.declared, params_.resolution);
    note(l.check, j, LimitOf::ThisEncoder);
    to_encoder = j.decision;
  }
  if (to_envelope.decision == Decision::Pass) return;
  const bool encoder_fails = to_encoder != Decision::Pass;
  const std::string symbol(l.symbol);
  const std::string declared = l.declared ? format_time(*l.declared) : "";
  report_unless_passed(l.declared && encoder_fails ? to_encoder : to_envelope.decision,
      {.check = std::string(l.check),
       .spec = std::string(l.spec),
       .where = ObservationPoint::EncoderPins,
       .time = f.rising.back(),
       .frame = f.header.index,
       .clock = static_cast<unsigned>(f.rising.size()),
       .measured = format_time(polled),
       .limit = !encoder_fails ? ">= " + format_time(l.envelope) + " (spec envelope)" : l.declared ? ">= " + declared
                + " (this encoder's " + symbol + ")" : ">= " + format_time(l.envelope),
       .severity = Severity::Error,
       .message = !encoder_fails ? "the master stopped polling for the start bit after " + format_time(polled)
                  + ": suits this encoder (" + symbol + " " + declared
                  + "), but any compliant encoder may take up to "
                  + format_time(l.envelope) : l.declared ? "the master stopped polling for the start bit before "
                  "this encoder's " + symbol : "the master stopped polling for the start bit before " + symbol + " max",
       .verdict = encoder_fails ? Verdict::Both : Verdict::SpecEnvelope}, "start-bit polling");
}

void TimingChecker::check_clock_count(const PinFrame& f) {
  if (start_clock_ == 0) {  // no start bit: nothing to count against, but the polling itself
    check_start_bit_polling(f);
    return;
  }
  const bool v22 = f.header.command_type == protocol::EndatVersion::V2_2;
  const bool parameter_frame = f.header.payload_bits != 0;
  // "A continuous clock is only possible with the mode command 'Encoder send position value'"
  // (2.3.1): after any other frame's last bit, further pulses are beyond its end.
  const bool bounded = v22 || parameter_frame || !f.header.continuous;
  const unsigned last_bit = start_clock_ + f.header.answer_bits - 1;
  const auto clocks = static_cast<unsigned>(f.rising.size());
  if (start_edge_unknown(f.header.compensated)) {
    // With the start bit's edge known to within e clocks, too few or too many pulses for every
    // edge within them is still decided.
    const unsigned e = start_edge_uncertainty_clocks();
    const bool decided = clocks + e < last_bit || (bounded && !f.header.supplement && clocks > last_bit + e + 1);
    if (!decided) {
      report_start_edge_unknown(protocol::check::row_index(check::kClockCount), check::kClockCount,
                                "2.3.1 and 2.4.1 (the number of clock pulses)", clocks,
                                std::to_string(clocks) + " pulses" + if_carried_by(start_clock_), f.rising.back(),
                                "end of frame");
      return;
    }
  }
  judge(protocol::check::row_index(check::kClockCount));
  const std::string spec = "2.3.1 and 2.4.1 (the number of clock pulses)";
  note(check::kClockCount, clocks, last_bit, Bound::AtLeast, Unit::Count);
  if (bounded && !f.header.supplement)
    note(check::kClockCount, clocks, last_bit + 1, Bound::AtMost, Unit::Count);
  else if (f.header.supplement && f.header.supplement_last_clock != 0)
    note(check::kClockCount, clocks, f.header.supplement_last_clock, Bound::AtMost, Unit::Count);
  if (clocks < last_bit)
    report({.check = std::string(check::kClockCount),
            .spec = spec,
            .where = ObservationPoint::EncoderPins,
            .time = f.rising.back(),
            .frame = f.header.index,
            .clock = clocks,
            .measured = std::to_string(clocks) + " pulses",
            .limit = ">= " + std::to_string(last_bit),
            .severity = Severity::Error,
            .message = "the clock stopped before the encoder's last bit: the encoder hangs in the middle of the cycle"},
            "end of frame");
  else if (bounded && !f.header.supplement && clocks > last_bit + 1)
    report({.check = std::string(check::kClockCount),
            .spec = spec,
            .where = ObservationPoint::EncoderPins,
            .time = f.rising.back(),
            .frame = f.header.index,
            .clock = clocks,
            .measured = std::to_string(clocks) + " pulses",
            .limit = "<= " + std::to_string(last_bit + 1),
            .severity = parameter_frame ? Severity::Error : Severity::Warning,
            .message = parameter_frame ? "more clock pulses than required: the encoder discards the access "
                       "(2.4.1)" : "clock pulses beyond the end of the frame"}, "end of frame");
  else if (f.header.supplement && f.header.supplement_last_clock != 0 && clocks > f.header.supplement_last_clock)
    report({.check = std::string(check::kClockCount),
            .spec = "2.4.2.1 (more clock pulses than necessary after the command supplement)",
            .where = ObservationPoint::EncoderPins,
            .time = f.rising.back(),
            .frame = f.header.index,
            .clock = clocks,
            .measured = std::to_string(clocks) + " pulses",
            .limit = "<= " + std::to_string(f.header.supplement_last_clock) + " (the supplement's last bit)",
            .severity = Severity::Error,
            .message = "more clock pulses than necessary after the command supplement: the encoder outputs an error "
                       "message " "(A2)"}, "command supplement");
}

}  // namespace endatsim::checker
