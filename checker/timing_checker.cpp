#include "endatsim/checker/timing_checker.hpp"

#include <algorithm>
#include <sstream>
#include <array>
#include <charconv>
#include <cmath>
#include <numeric>
#include <tuple>

#include "endatsim/checker/clock_fit.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::checker {

namespace {
const std::array kCheckerRows{
    sim::Parameter<CheckerParams>{"sample_setup", &CheckerParams::sample_setup, 0, sim::us(1).count(), "2.3",
                                  "The master's sampling flip-flop: DATA stable this long before the instant."},
    sim::Parameter<CheckerParams>{"sample_hold", &CheckerParams::sample_hold, 0, sim::us(1).count(), "2.3",
                                  "... and this long after it."},
    sim::Parameter<CheckerParams>{"t_z_per_frame_period", &CheckerParams::t_z_per_frame_period, 0, 0, "2.3.2 note 6",
                                  "t_z and t_OE \"max T = 1/f_c min\" read as one period of the frame's own clock; false: "
                                  "the period at the lowest f_c, 10 us."},
    sim::Parameter<CheckerParams>{"t_st_reduced_for_cable", &CheckerParams::t_st_reduced_for_cable, 0, 0, "2.3.2 note 8",
                                  "Accept a t_ST scaled by the cable's share of the t_D bound (\"can be reduced with a "
                                  "shorter cable\"), named in every t_st finding."},
    sim::Parameter<CheckerParams>{"f_c_tolerance_ppm", &CheckerParams::f_c_tolerance_ppm, 0, 100'000, "2.3.2",
                                  "f_c limits are applied with this allowance for the oscillator; 0 checks them exactly."},
};
}  // namespace

std::span<const sim::Parameter<CheckerParams>> checker_parameters() { return kCheckerRows; }
namespace {

using sim::format_frequency;
using sim::format_time;

namespace limit = protocol::limit;
namespace position = protocol::frame_position;

// The spec's words for findings, from the limits; built once (some rows report in every frame).
const std::string& short_t_m_spec() {
  static const std::string text = "2.3.2 note 3 (t_m " +
                                  sim::format_time_range(limit::kShortRecoveryTimeMin, limit::kShortRecoveryTimeMax) +
                                  " only with f_c >= " + format_frequency(limit::kShortRecoveryTimeFcMin) + ")";
  return text;
}

const std::string& special_fc_spec() {
  static const std::string text =
      "2.1.2 (" + sim::format_frequency_range(limit::kFcMaxWithCompensation, limit::kFcMaxSpecial) + " for special applications)";
  return text;
}

const std::string& compensated_cable_spec() {
  static const std::string text = "2.1.2 (with delay compensation up to " +
                                  std::to_string(static_cast<int>(limit::kCompensatedCableMaxMetres)) + " m of cable)";
  return text;
}

const std::string& t_b_spec() {
  static const std::string text = "2.3.2 t_b (EnDat 2.1 commands: t_b > " + format_time(limit::kTimeBetweenCyclesMin) + ")";
  return text;
}

}  // namespace

std::span<const std::string_view> check::all() { return protocol::check::kAll; }

// The field of bit slot `clock` as the master counts the frame.
std::string TimingChecker::field_of(const DeclaredFrame& frame, unsigned clock) const {
  if (frame.start_bit_clock == 0 || clock < frame.start_bit_clock) return "start-bit polling";
  const auto layout = protocol::answer_layout(protocol::info(frame.command), bits_of(frame));
  const unsigned bit = clock - frame.start_bit_clock;
  if (bit < layout.width()) return std::string(protocol::field_name(layout.field_at(bit)));
  return bit < frame.answer_bits ? "additional data" : "after the CRC";
}

unsigned TimingChecker::bits_of(const DeclaredFrame& frame) const {
  return frame.position_bits != 0 ? frame.position_bits : master_.position_bits;
}

std::string_view to_string(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Undecided: return "undecided";
  }
  return "?";
}

void TimingChecker::report(Finding f, std::string_view field) {
  report(Violation{std::move(f), std::string(field)}, std::nullopt);
}

// `contention`: the line's sequence number of the contention reported (Contention::sequence).
void TimingChecker::report(Violation v, std::optional<std::uint64_t> contention) {
  if (sim::Tape* tape = kernel_.tape()) {  // the frame-level fast path records (checker_snapshot.cpp)
    contention_recorded_ = contention_recorded_ || contention.has_value();
    recorded_.push_back(v);
    tape->add(sim::TapeItem::Kind::Model, kernel_.now(), this, 0, recorded_.size() - 1);
  }
  Tally& t = tally_.at(protocol::check::row_of(v.check));
  const std::uint64_t kept = t.errors + t.warnings + t.undecided;
  ++(v.severity == Severity::Error ? t.errors : v.severity == Severity::Warning ? t.warnings : t.undecided);
  conclusion_.count(v.severity, v.verdict);
  if (listener_) listener_(v);
  if (kept >= params_.max_findings_per_check) {
    ++not_kept_;
    // Contentions are reported as they end, not in the order they began: the row keeps the ones
    // that began first, as when finish() reported them all in that order.
    const auto& latest = latest_contention_kept_;
    if (!contention || !latest || *contention_of_[*latest] < *contention) return;
    violations_[*latest] = std::move(v);
    contention_of_[*latest] = contention;
    find_latest_contention_kept();
    return;
  }
  violations_.push_back(std::move(v));
  contention_of_.push_back(contention);
  if (contention && (!latest_contention_kept_ || *contention_of_[*latest_contention_kept_] < *contention))
    latest_contention_kept_ = violations_.size() - 1;
}

void TimingChecker::find_latest_contention_kept() {
  latest_contention_kept_.reset();
  for (std::size_t i = 0; i < violations_.size(); ++i)
    if (contention_of_[i] && (!latest_contention_kept_ || *contention_of_[*latest_contention_kept_] < *contention_of_[i]))
      latest_contention_kept_ = i;
}

bool TimingChecker::report_unless_passed(Decision d, Finding f, std::string_view field) {
  if (d == Decision::Pass) return false;
  if (d == Decision::Undecided) {
    f.severity = Severity::Undecided;
    f.message = "undecided at the capture's resolution of " + format_time(params_.resolution) + " (" + f.message + ")";
  }
  report(std::move(f), field);
  return true;
}

bool TimingChecker::report_unless_passed(const Judgement& j, Finding f, std::string_view field) {
  note(f.check, j, f.verdict == Verdict::ThisEncoder ? LimitOf::ThisEncoder : LimitOf::Spec);
  return report_unless_passed(j.decision, std::move(f), field);
}

std::string_view to_string(Verdict v) {
  switch (v) {
    case Verdict::Both: return "both";
    case Verdict::SpecEnvelope: return "spec envelope";
    case Verdict::ThisEncoder: return "this encoder";
  }
  return "?";
}

void Conclusion::count(Severity severity, Verdict verdict) {
  const bool envelope = verdict != Verdict::ThisEncoder, encoder = verdict != Verdict::SpecEnvelope;
  if (severity == Severity::Error) {
    spec_envelope = spec_envelope && !envelope;
    this_encoder = this_encoder && !encoder;
  } else if (severity == Severity::Undecided) {
    spec_envelope_undecided = spec_envelope_undecided || envelope;
    this_encoder_undecided = this_encoder_undecided || encoder;
  }
}

Conclusion conclude(std::span<const Violation> violations) {
  Conclusion c;
  for (const Violation& v : violations) c.count(v.severity, v.verdict);
  return c;
}

std::vector<Relaxation> relaxations(const CheckerParams& params) {
  std::vector<Relaxation> out;
  // 2.3.2 note 8: "the 2 us relate to a cable length of 100 m and can be reduced with a shorter cable".
  if (params.t_st_reduced_for_cable)
    out.push_back({std::string(check::kStartDelay),
                   "t_st_reduced_for_cable: a t_ST shorter than note 8's 2 us accepted for a cable under 100 m"});
  return out;
}

std::string_view to_string(RowConformance::Status s) {
  switch (s) {
    case RowConformance::Status::Judged: return "judged";
    case RowConformance::Status::NotApplicable: return "not applicable";
    case RowConformance::Status::NotObservable: return "not observable";
  }
  return "?";
}

std::vector<RowConformance> TimingChecker::conformance() const {
  std::vector<RowConformance> out;
  for (const protocol::TimingRow& row : protocol::timing_rows()) {
    RowConformance c;
    c.check = std::string(row.check);
    c.judged = judged_[out.size()];
    const Tally& t = tally_[out.size()];
    c.violations = t.errors;
    c.warnings = t.warnings;
    c.undecided = t.undecided;
    const bool needs_enables = row.check == check::kDriverOff || row.check == check::kDriverOn ||
                               row.check == check::kFloatingData || row.check == check::kContention;
    if (c.judged != 0 || c.violations + c.warnings + c.undecided != 0) {
      c.status = RowConformance::Status::Judged;
    } else if (row.evidence == protocol::Evidence::MasterDeclaration && wires_only_) {
      c.status = RowConformance::Status::NotObservable;
      c.reason = "needs the master's declaration (sampling instants, t_D used, measurement frames)";
    } else if (needs_enables && !params_.driver_enables_observable) {
      c.status = RowConformance::Status::NotObservable;
      c.reason = "needs the DATA drivers' enables";
    } else if ((row.check == check::kDataDelay || row.check == check::kMeasurementSpread) &&
               !params_.round_trip_observable) {
      c.status = RowConformance::Status::NotObservable;
      c.reason = "the round trip shows only at the master's connector";
    } else if (row.check == check::kMeasurementSpread && measurements_may_precede_) {
      c.status = RowConformance::Status::NotObservable;
      c.reason = "the master compensates, but no delay measurement is in the recording and it does not show the "
                 "encoder switching on: the measurements may precede it (record the supply with --power)";
    } else if (row.check == check::kContention && !params_.master_enable_observable) {
      c.status = RowConformance::Status::NotObservable;
      c.reason = "needs the master's DATA driver enable as well as the encoder's";
    } else {
      c.reason = "no frame or event it applies to";
    }
    c.worst = margins_.worst(out.size());
    for (const Relaxation& r : relaxations(params_))
      if (r.check == row.check) c.relaxed_by = r.by;
    out.push_back(std::move(c));
  }
  return out;
}

TimingChecker::TimingChecker(sim::Kernel& kernel, line::Line& line, const EncoderDeclaration& encoder,
                             const MasterDeclaration& master, const CheckerParams& params)
    : kernel_(kernel),
      line_(line),
      encoder_pins_(line.pins(ObservationPoint::EncoderPins)),
      master_pins_(line.pins(ObservationPoint::MasterPins)),
      encoder_(encoder),
      master_(master),
      params_(params),
      decoder_(DecoderParams{
          .position_bits = encoder.position_bits,
          .clock_to_data = line.params().encoder.receiver_delay + encoder.output_delay + line.params().encoder.driver_delay,
          .t_m = encoder.short_t_m_selected && encoder.t_m_short ? std::min(encoder.t_m, *encoder.t_m_short) : encoder.t_m,
          .supplement_ignore_clocks = encoder.supplement_ignore_clocks,
      }),
      settings_(encoder.short_t_m_selected),
      judged_(protocol::timing_rows().size(), 0),
      tally_(protocol::timing_rows().size()),
      margins_(protocol::timing_rows().size()),
      power_on_(params.resolution) {
  if (encoder.switched_on_in_run) power_on_.switched_on(kernel.now());
  line.master().clock_out.on_change_monitor(sim::bind<&TimingChecker::on_master_clock>(this));
  encoder_pins_.clock.on_change_monitor(sim::bind<&TimingChecker::on_encoder_clock>(this));
  encoder_pins_.driver_enable.on_change_monitor(sim::bind<&TimingChecker::on_encoder_driver>(this));
  encoder_pins_.data.on_change_monitor(sim::bind<&TimingChecker::on_encoder_data>(this));
  line.master().data_in.on_change_monitor(sim::bind<&TimingChecker::on_master_data>(this));
  master_pins_.data_driven.on_change_monitor(sim::bind<&TimingChecker::on_master_driven>(this));
  encoder_pins_.data_driven.read_by_monitor(this);  // floating DATA at the encoder's sampling instants
  // Contentions that began before the checker (those the line has logged) are judged too.
  for (const line::Contention& c : line.contentions())
    if (contentions_reported() && (!params_.recorded_at || c.where == *params_.recorded_at))
      contentions_.push_back({c, std::nullopt});
  line.on_contention([this](const line::Contention& c) { on_contention(c); });
}

void TimingChecker::check_measurement_procedure(const DeclaredFrame& frame) {
  // 2.1.2: a counter at least eight times the intended f_c (f_e tolerance +/-10 %), and at
  // least three measurements averaged.
  const sim::Hertz intended = limit::kMeasurementCounterFactor * master_.f_c;
  const sim::Hertz f_e = master_.f_e != 0 ? master_.f_e : intended;
  const std::string spec = "2.1.2 propagation-delay measurement";
  judge(protocol::check::row_index(check::kMeasurementProcedure));
  if (f_e * 100 < intended * (100 - limit::kMeasurementCounterTolerancePercent))
    report({.check = std::string(check::kMeasurementProcedure),
            .spec = spec,
            .where = ObservationPoint::MasterPins,
            .time = frame.start,
            .frame = frame.index,
            .clock = std::nullopt,
            .measured = format_frequency(f_e),
            .limit = ">= " + format_frequency(intended) + " - " + std::to_string(limit::kMeasurementCounterTolerancePercent) + " %",
            .severity = Severity::Error,
            .message = "counter clock f_e below eight times the intended f_c"});
  if (master_.measurements < limit::kMeasurementsMin)
    report({.check = std::string(check::kMeasurementProcedure),
            .spec = spec,
            .where = ObservationPoint::MasterPins,
            .time = frame.start,
            .frame = frame.index,
            .clock = std::nullopt,
            .measured = std::to_string(master_.measurements) + " measurement(s)",
            .limit = ">= " + std::to_string(limit::kMeasurementsMin),
            .severity = Severity::Error,
            .message = "fewer than three measurements averaged"});
}

// A frame that measures t_D (2.1.2): declared so by the master, or, on the wires, an "Encoder send
// position values" frame at the reduced clock of at most 200 kHz.
bool TimingChecker::measures_delay(const FrameHeader& h) const {
  if (!wires_only_) return h.measurement;
  const sim::Hertz allowance = limit::kMeasurementFcMax * params_.f_c_tolerance_ppm / 1'000'000;
  return h.continuous && h.f_c > 0 && h.f_c <= limit::kMeasurementFcMax + allowance;
}

// 2.1.2: at least three measurements, each within T/8 of their mean, before compensating; judged
// at the master's pins from the t_D each measurement frame shows there (delay_measurements.hpp).
void TimingChecker::check_measurement_spread(const PinFrame& f) {
  if (!f.header.compensated || f.header.f_c == 0 || !params_.round_trip_observable) return;
  const std::string spec = "2.1.2 (at least three measurements, each within T/8 of their mean)";
  if (!delay_measurements_.any()) {
    // Without a master's declaration (delay_measurement) the wires say it, when the run shows
    // the encoder switched on: a capture that begins later may have missed the measurements.
    // Compensated frames with no measurement before them in a capture that does not show the
    // switch-on: the measurements may precede the capture, so the row cannot be told either way.
    if (wires_only_ && !encoder_.switched_on_in_run) measurements_may_precede_ = true;
    if (!wires_only_ || !encoder_.switched_on_in_run || unmeasured_on_wires_reported_) return;
    unmeasured_on_wires_reported_ = true;
    judge(protocol::check::row_index(check::kMeasurementSpread));
    report({.check = std::string(check::kMeasurementSpread),
            .spec = spec,
            .where = ObservationPoint::MasterPins,
            .time = f.fe1,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = "no measurement",
            .limit = ">= " + std::to_string(limit::kMeasurementsMin) + " measurements at " +
                     sim::format_frequency_range(limit::kMeasurementFcMin, limit::kMeasurementFcMax),
            .severity = Severity::Error,
            .message = "the master compensates (f_c " + format_frequency(f.header.f_c)
                       + ") without measuring t_D after switching on"});
    return;
  }
  const auto j = delay_measurements_.compensated(sim::period_of(f.header.f_c), params_.resolution);
  if (!j) return;
  judge(protocol::check::row_index(check::kMeasurementSpread));
  // A capture that begins inside the measurements may hold only the last of them.
  const bool count_observable = encoder_.switched_on_in_run || j->first_frame != first_frame_;
  if (!j->enough && count_observable)
    report({.check = std::string(check::kMeasurementSpread),
            .spec = spec,
            .where = ObservationPoint::MasterPins,
            .time = f.fe1,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = std::to_string(j->measurements) + " measurement(s)",
            .limit = ">= " + std::to_string(limit::kMeasurementsMin),
            .severity = Severity::Error,
            .message = "the master compensates after fewer than three measurements of t_D"});
  note(check::kMeasurementSpread, at_most(j->deviation, j->limit, params_.resolution));
  if (j->consistent) return;
  const std::string which = "measurement " + std::to_string(j->worst + 1) + " of " + std::to_string(j->measurements) +
                            " (frame " + std::to_string(j->worst_frame) + ")";
  report_unless_passed(j->undecided ? Decision::Undecided : Decision::Fail,
      {.check = std::string(check::kMeasurementSpread),
       .spec = spec,
       .where = ObservationPoint::MasterPins,
       .time = f.fe1,
       .frame = f.header.index,
       .clock = std::nullopt,
       .measured = format_time(j->deviation) + " from the mean",
       .limit = "<= T/8 = " + format_time(j->limit) + " (f_c " + format_frequency(f.header.f_c) + ")",
       .severity = Severity::Error,
       .message = "the master compensates with delay measurements that disagree: " + which
                  + " deviates from the mean of the latest three"});
}

// 2.3.3, judged at the encoder's pins (power_on.hpp) after each switch-on the run shows.
void TimingChecker::on_switched_on(bool judge_power_on) {
  if (judge_power_on) power_on_.switched_on(kernel_.now());
  settings_.on_switched_on();
  t_d_stale_ = true;
}

void TimingChecker::power_on_request(std::uint64_t index, Time start) {
  if (!power_on_.due()) return;
  held_frame_ = power_on_.waiting_request();  // the wake-up request cycle the judgement may name
  report_power_on(power_on_.request(index, start));
  held_frame_.reset();
}

void TimingChecker::report_power_on(const std::optional<PowerOnSequence::Judgement>& j) {
  if (!j) return;
  judge(protocol::check::row_index(check::kPowerOn));
  for (const auto& f : *j)
    report_unless_passed(f.decision,
        {.check = std::string(check::kPowerOn),
         .spec = "2.3.3 power-on conditions (t1, t2, pulse > 125 ns or a request cycle, t3)",
         .where = ObservationPoint::EncoderPins,
         .time = f.at,
         .frame = f.frame,
         .clock = std::nullopt,
         .measured = f.measured,
         .limit = f.bound,
         .severity = Severity::Error,
         .message = f.message}, "power-on");
}

void TimingChecker::on_frame_start(const DeclaredFrame& frame) {
  if (wires_only_) {
    // The master declares its frames after all: what came before (a power-on pulse, taken for
    // an aborted frame) was no frame of its own.
    wires_only_ = false;
    in_frame_ = false;
    frame_starts_.clear();
    for (PendingContention& p : contentions_) p.frame.reset();
    previous_end_.reset();
    error_handling_frame_.reset();
  }
  last_declared_ = frame.index;
  declared_running_ = true;
  power_on_request(frame.index, frame.start + clock_path());
  if (frame.measurement && !last_frame_was_measurement_) check_measurement_procedure(frame);
  if (frame.measurement) {
    t_d_stale_ = false;
    measured_ = true;
  }
  if (frame.compensated) judge(protocol::check::row_index(check::kMeasurementProcedure));
  if (frame.compensated && !measured_ && !unmeasured_reported_) {
    unmeasured_reported_ = true;
    report({.check = std::string(check::kMeasurementProcedure),
            .spec = "2.1.2 (measure the propagation delay, after each power interruption)",
            .where = ObservationPoint::MasterPins,
            .time = frame.start,
            .frame = frame.index,
            .clock = std::nullopt,
            .measured = "no measurement",
            .limit = "a measurement before compensating",
            .severity = Severity::Error,
            .message = "the master compensates with a delay it never measured on this line"});
  }
  if (frame.compensated && t_d_stale_) {
    t_d_stale_ = false;  // one report per change
    report({.check = std::string(check::kMeasurementProcedure),
            .spec = "2.1.2 (measure again after every change of the transmission path)",
            .where = ObservationPoint::MasterPins,
            .time = frame.start,
            .frame = frame.index,
            .clock = std::nullopt,
            .measured = "t_D from before the change",
            .limit = "a new measurement",
            .severity = Severity::Error,
            .message = "the master compensates with a delay measured on the old line"});
  }
  last_frame_was_measurement_ = frame.measurement;
  contention_frame_started(frame.start, frame.index);
  if (!first_frame_) first_frame_ = frame.index;
  // The answer as the encoder sends it: its own position width, the additional data the master
  // selected.
  // (A FrameResult from another master may leave answer_bits and position_bits at 0.)
  const auto& command = protocol::info(frame.command);
  const unsigned master_width = protocol::answer_layout(command, bits_of(frame)).width();
  const unsigned additional = frame.answer_bits > master_width ? frame.answer_bits - master_width : 0;
  const unsigned answer = protocol::answer_layout(command, encoder_.position_bits).width() + additional;
  // 2.3.1: only the mode bits 000111 allow a continuous clock (the encoder goes by what it got).
  const bool continuous = frame.mode_bits == protocol::info(protocol::ModeCommand::EncoderSendPositionValues).bits;
  const FrameHeader h{frame.index,          frame.measurement, frame.compensated, command.version,
                      command.payload_bits, answer,            command.supplement, continuous,
                      frame.f_c,            frame.t_d_used};
  if (!fe1_lost_) pending_.emplace_back(master_falling_edges_ + 1, h);
  master_rising_.clear();
  sampling_reported_ = false;
}

void TimingChecker::on_master_clock(std::uint64_t level) {
  if (level == 0) ++master_falling_edges_;
  else master_rising_.push_back(kernel_.now());
}

void TimingChecker::on_encoder_clock(std::uint64_t level) {
  const Time now = kernel_.now();
  if (!contentions_.empty()) settle_contentions();
  power_on_.clock(now, level != 0);
  if (!mode_decided_ && level == 0) {  // a master declares its frames before their FE1 gets here
    mode_decided_ = true;
    wires_only_ = pending_.empty() && frame_starts_.empty();
  }
  const bool wire_fe1 = wires_only_ && decoder_.on_clock(now, level != 0);
  if (level != 0) {
    if (!in_frame_) return;
    current_.rising.push_back(now);
    low_at_last_rise_ = !encoder_pins_.data.read();
    note_encoder_low();
    check_encoder_sample(static_cast<unsigned>(current_.rising.size()));
    // The decoder has taken the last mode bit (on RE8) once the next edge comes.
    // Without the encoder's driver enable the fail-safe level between the master's release and
    // the encoder's LOW looks like a start bit on DATA: the decoder's sampled start bit is used.
    if (wires_only_ && !params_.driver_enables_observable && start_clock_ == 0) {
      const WireFrame* w = decoder_.current();
      if (w != nullptr && w->start_bit_clock != 0) start_bit_from_decoder(w->start_bit_clock);
    }
    if (wires_only_ && !recovery_checked_ && current_.rising.size() == position::kLastModeBit + 1) {
      recovery_checked_ = true;
      refresh_wire_header();
      check_recovery(current_);
    }
    // 2.3.3: a frame that carries a mode command is a request.
    if (wires_only_ && current_.rising.size() == position::kLastModeBit) {
      power_on_request(current_.header.index, current_.fe1);
      wire_request_seen_ = true;
    }
    return;
  }
  if (wires_only_) {
    ++encoder_falling_edges_;
    if (wire_fe1) begin_wire_frame(now);
    if (!in_frame_) return;
    current_.falling.push_back(now);
    return;
  }
  ++encoder_falling_edges_;
  if (!pending_.empty() && pending_.front().first == encoder_falling_edges_) {
    master_driven_.assign(1, {now, master_pins_.data_driven.read()});
    floating_reported_ = false;
    if (in_frame_) evaluate(current_);
    current_.header = pending_.front().second;
    current_.fe1 = now;
    current_.rising.clear();
    current_.falling.clear();
    pending_.pop_front();
    in_frame_ = true;
    start_data_line_checks();
    check_recovery(current_);
  } else if (!pending_.empty() && pending_.front().first < encoder_falling_edges_) {
    // The encoder pins have counted past the next declared FE1 (a clock glitch there): it is never
    // found, nor any declared frame after it.
    fe1_lost_ = true;
    pending_.clear();
  }
  if (in_frame_) current_.falling.push_back(now);
}

// The master's CLOCK edge reaches the encoder pins through its driver and the cable.
Time TimingChecker::clock_path() const { return line_.params().master.driver_delay + line_.cable_delay(); }

// A frame found on the wires (no master declares its own): the frame before it is judged with
// what the decoder made of it; the new one starts like a declared one.
void TimingChecker::begin_wire_frame(Time now) {
  auto finished = decoder_.take_finished();
  if (!finished.empty()) last_wire_ = std::move(finished.back());
  if (in_frame_) {
    refresh_wire_header();
    if (!recovery_checked_) check_recovery(current_);  // a frame that ended before its mode command
    recovery_checked_ = true;
    if (start_clock_ == 0) error_handling_frame_ = current_.header.index;  // A2: no start bit
    evaluate(current_);
    if (last_wire_ && last_wire_->index == current_.header.index && last_wire_->command) {
      const WireFrame& w = *last_wire_;
      const auto ai1 = std::find_if(w.additional_data.begin(), w.additional_data.end(),
                                    [](const DecodedDatum& d) { return d.number() == protocol::AdditionalDataNumber::One; });
      const bool data_ok = std::all_of(w.additional_data.begin(), w.additional_data.end(),
                                       [](const DecodedDatum& d) { return d.crc_ok; });
      if (w.clean()) settings_.on_frame(*w.command, w.payload, w.supplement);
      check_busy_time({w.index, w.fe1, w.last_rise, *w.command, w.supplement, w.clean() && data_ok,
                       ai1 == w.additional_data.end() ? std::nullopt : std::optional<bool>(ai1->busy()),
                       current_.header.f_c});
    }
  }
  const WireFrame* started = decoder_.current();
  if (started == nullptr) return;  // the end of the run
  master_driven_.assign(1, {now, master_pins_.data_driven.read()});
  floating_reported_ = false;
  current_.header = FrameHeader{};
  current_.header.index = started->index;
  current_.fe1 = now;
  current_.rising.clear();
  current_.falling.clear();
  in_frame_ = true;
  // The master's edges of this frame at its logic: from its FE1, one clock path earlier.
  const Time master_fe1 = now - clock_path();
  std::erase_if(master_rising_, [&](Time t) { return t < master_fe1; });
  contention_frame_started(master_fe1, started->index);
  if (!first_frame_) first_frame_ = started->index;
  start_data_line_checks();
  recovery_checked_ = false;  // once the mode command is known (t_b depends on it)
}

// What the wires have shown of the current frame so far: its mode command and what follows
// from it, and its clock. Without a master's declaration a frame clocked above 2 MHz is judged
// against the table's "with delay compensation" column: only with it is such a clock allowed.
void TimingChecker::refresh_wire_header() {
  if (!wires_only_) return;
  FrameHeader& h = current_.header;
  const WireFrame* w = decoder_.current();
  if (w == nullptr || w->index != h.index) w = last_wire_ && last_wire_->index == h.index ? &*last_wire_ : nullptr;
  if (w != nullptr && w->command) {
    const auto& info = protocol::info(*w->command);
    h.command_type = info.version;
    h.payload_bits = info.payload_bits;
    h.answer_bits = w->answer_bits;
    h.supplement = info.supplement;
    h.supplement_last_clock = w->supplement_last_clock;
    h.continuous = *w->command == protocol::ModeCommand::EncoderSendPositionValues;
  }
  const auto& rising = current_.rising;
  if (rising.size() >= 3) {
    const FittedFrequency fit = fit_frequency(rising);
    if (fit.num > 0) {
      h.f_c = fit.hertz();
      h.compensated = fit.above(limit::kFcMaxWithoutCompensation, params_.f_c_tolerance_ppm);
    }
  } else if (rising.size() == 2 && rising[1] > rising[0]) {  // RE1 and RE2 only: one period
    h.f_c = sim::frequency_of(rising[1] - rising[0]);
    h.compensated = h.f_c > limit::kFcMaxWithoutCompensation;
  }
}

void TimingChecker::evaluate(const PinFrame& f) {
  settle_pending_release();
  if (params_.driver_enables_observable && params_.master_enable_observable)
    judge(protocol::check::row_index(check::kContention));
  check_pulse_widths(f);
  check_on_off_ratio(f);
  check_frequency(f);
  check_start_delay(f);
  // A frame the capture's end cut may have had more clocks, or its start bit, after it.
  if (frame_cut_by_end_ != f.header.index) check_clock_count(f);
  check_measurement_spread(f);
  if (!f.rising.empty()) previous_end_ = FrameEnd{f.rising.back(), f.header.command_type, f.header.index};
}

void TimingChecker::check_frequency(const PinFrame& f) {
  if (f.rising.size() < 3) return;
  const FittedFrequency fit = fit_frequency(f.rising);
  if (fit.num <= 0) return;
  const sim::Hertz fc = fit.hertz();
  const std::int64_t tol = params_.f_c_tolerance_ppm;
  const Time at = f.rising[position::edge_index(position::kFirstSteadyRise)];
  judge(f.header.measurement ? protocol::check::row_index(check::kMeasurementClock) : protocol::check::row_index(check::kClockFrequency));
  if (measures_delay(f.header)) measurement_seen_ = true;
  const auto note_range = [&](std::string_view row, sim::Hertz lo, sim::Hertz hi) {
    note(row, fc, lo, Bound::AtLeast, Unit::Frequency);
    note(row, fc, hi, Bound::AtMost, Unit::Frequency);
  };
  if (f.header.measurement) {
    note_range(check::kMeasurementClock, limit::kMeasurementFcMin, limit::kMeasurementFcMax);
    if (fit.below(limit::kMeasurementFcMin, tol) || fit.above(limit::kMeasurementFcMax, tol))
      report({.check = std::string(check::kMeasurementClock),
              .spec = "2.1.2 propagation-delay measurement at " +
                      sim::format_frequency_range(limit::kMeasurementFcMin, limit::kMeasurementFcMax),
              .where = ObservationPoint::EncoderPins,
              .time = at,
              .frame = f.header.index,
              .clock = std::nullopt,
              .measured = format_frequency(fc),
              .limit = sim::format_frequency(limit::kMeasurementFcMin) + " .. " + sim::format_frequency(limit::kMeasurementFcMax),
              .severity = Severity::Error,
              .message = "delay measured with a clock outside the prescribed range"});
    return;
  }
  const bool short_tm = f.header.command_type == protocol::EndatVersion::V2_2 && settings_.short_t_m();
  if (short_tm) {
    judge(protocol::check::row_index(check::kShortRecoveryClock));
    note(check::kShortRecoveryClock, fc, limit::kShortRecoveryTimeFcMin, Bound::AtLeast, Unit::Frequency);
  }
  if (short_tm &&
      fit.below(limit::kShortRecoveryTimeFcMin, tol))
    report({.check = std::string(check::kShortRecoveryClock),
            .spec = short_t_m_spec(),
            .where = ObservationPoint::EncoderPins,
            .time = at,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = format_frequency(fc),
            .limit = ">= " + format_frequency(limit::kShortRecoveryTimeFcMin),
            .severity = Severity::Error,
            .message = "the short recovery time is selected but the clock is slower than 1 MHz"});
  check_frequency_for_encoder(f, fit);
  check_frequency_for_cable(f, fit);
  const bool compensated = f.header.compensated;
  const sim::Hertz max = compensated ? limit::kFcMaxWithCompensation : limit::kFcMaxWithoutCompensation;
  const std::string range = format_frequency(limit::kFcMin) + " .. " + format_frequency(max);
  const std::string spec = compensated ? "2.3.2 f_c (with delay compensation)" : "2.3.2 f_c (without delay compensation)";
  // The worst case against the bound a violation would break (above 8 MHz is a warning only).
  note_range(check::kClockFrequency, limit::kFcMin, compensated ? limit::kFcMaxSpecial : max);
  if (fit.below(limit::kFcMin, tol) || (fit.above(max, tol) && (!compensated || fit.above(limit::kFcMaxSpecial, tol)))) {
    const std::string applied = compensated ? format_frequency(limit::kFcMin) + " .. " + format_frequency(limit::kFcMaxSpecial) +
                                                  " (above 8 MHz only for special applications)"
                                            : range;
    report({.check = std::string(check::kClockFrequency),
            .spec = spec,
            .where = ObservationPoint::EncoderPins,
            .time = at,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = format_frequency(fc),
            .limit = applied,
            .severity = Severity::Error,
            .message = "clock frequency outside the table's range"});
  } else if (fit.above(max, tol)) {
    report({.check = std::string(check::kClockFrequency),
            .spec = special_fc_spec(),
            .where = ObservationPoint::EncoderPins,
            .time = at,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = format_frequency(fc),
            .limit = range,
            .severity = Severity::Warning,
            .message = "clock above 8 MHz: only for special applications with short cables (t_ST 1 us at 16 MHz)"});
  }
}

// Without delay compensation the cable bounds f_c (2.3.2 note 4 and 2.1.1, Figure 2 as docs/model.md §9
// derives it): a master that samples on its falling edge takes bits before they arrive. On the
// wires, a clock of 2 MHz or less with no delay measurement before it is taken as uncompensated:
// a master that compensates with a t_D it never measured breaks 2.1.2 instead.
namespace {
// The length as given, to its last digit (100.5 m, not 100 m): the shortest text that reads back
// as the same double.
std::string format_length(double metres) {
  std::array<char, 32> text{};
  const auto [end, ec] = std::to_chars(text.data(), text.data() + text.size(), metres);
  return std::string(text.data(), ec == std::errc() ? end : text.data()) + " m";
}
}  // namespace

void TimingChecker::check_frequency_for_cable(const PinFrame& f, const FittedFrequency& fit) {
  if (f.header.compensated || (wires_only_ && measurement_seen_)) return;
  const double cable = cable_length_m();
  const Time min = limit::uncompensated_period_min(cable);
  // Up to the cable where 2 t_D reaches 500 ns, and above 2 MHz, the f_c row's 2 MHz says it.
  const auto tol = params_.f_c_tolerance_ppm;
  if (min <= sim::period_of(limit::kFcMaxWithoutCompensation) || fit.above(limit::kFcMaxWithoutCompensation, tol))
    return;
  const auto fc = fit.hertz();
  note(check::kClockFrequency, fc, sim::frequency_of(min), Bound::AtMost, Unit::Frequency);
  if (!fit.period_below(min, tol)) return;
  report({.check = std::string(check::kClockFrequency),
          .spec = "2.3.2 note 4 and 2.1.1, Figure 2 (without delay compensation: f_c <= 1 / (2 t_D(L)))",
          .where = ObservationPoint::EncoderPins,
          .time = f.rising[position::edge_index(position::kFirstSteadyRise)],
          .frame = f.header.index,
          .clock = std::nullopt,
          .measured = format_frequency(fc) + " over " + format_length(cable),
          .limit = "period >= 2 t_D = " + format_time(min),
          .severity = Severity::Error,
          .message = wires_only_ ? "a clock too fast for the cable without delay compensation, and no delay "
                     "measurement before it: " "the master samples before the data arrive" : "a clock too fast for "
                     "the cable without delay compensation: the master samples before the data " "arrive"});
}

// What the declared encoder allows of f_c beyond the table: word 25's maximum (3.9.19), 2 MHz for
// an EnDat 2.1 encoder (2.1.1: without delay compensation), and the cable the table's 8 MHz with
// compensation is given for (2.1.2: "maximum: 100 m"; longer only after consulting the maker).
void TimingChecker::check_frequency_for_encoder(const PinFrame& f, const FittedFrequency& fit) {
  const sim::Hertz fc = fit.hertz();
  const std::int64_t tol = params_.f_c_tolerance_ppm;
  const Time at = f.rising[position::edge_index(position::kFirstSteadyRise)];
  const auto exceeds = [&](sim::Hertz bound, std::string spec, std::string message) {
    report({.check = std::string(check::kClockFrequency),
            .spec = std::move(spec),
            .where = ObservationPoint::EncoderPins,
            .time = at,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = format_frequency(fc),
            .limit = "<= " + format_frequency(bound),
            .severity = Severity::Error,
            .message = std::move(message),
            .verdict = Verdict::ThisEncoder});
  };
  if (encoder_.f_c_max)
    note(check::kClockFrequency, fc, *encoder_.f_c_max, Bound::AtMost, Unit::Frequency, LimitOf::ThisEncoder);
  if (encoder_.endat21_only)
    note(check::kClockFrequency, fc, limit::kFcMaxWithoutCompensation, Bound::AtMost, Unit::Frequency,
         LimitOf::ThisEncoder);
  if (encoder_.f_c_max && fit.above(*encoder_.f_c_max, tol))
    exceeds(*encoder_.f_c_max, "3.9.19 word 25 (the encoder's maximum clock frequency)",
            "clock above the maximum this encoder declares in word 25");
  if (encoder_.endat21_only && fit.above(limit::kFcMaxWithoutCompensation, tol))
    exceeds(limit::kFcMaxWithoutCompensation, "HEIDENHAIN EnDat 2.2 brochure, ordering designation EnDat21: 2 MHz",
            "clock above 2 MHz for an EnDat 2.1 encoder, which knows no delay compensation");
  const double cable = cable_length_m();
  if (f.header.compensated && cable > limit::kCompensatedCableMaxMetres && fit.above(limit::kFcMaxWithoutCompensation, tol))
    report({.check = std::string(check::kClockFrequency),
            .spec = compensated_cable_spec(),
            .where = ObservationPoint::EncoderPins,
            .time = at,
            .frame = f.header.index,
            .clock = std::nullopt,
            .measured = format_frequency(fc) + " over " + format_length(cable),
            .limit = "100 m",
            .severity = Severity::Warning,
            .message = "a compensated clock above 2 MHz over more than 100 m of cable: only after consulting the "
                       "encoder's maker"});
}

// 2.3.2 "time between cycle t_b, EnDat 2.1 commands: t_b > 1 ms". UNCERTAIN (docs/model.md §7):
// read as the gap from the previous frame's last rising edge to FE1 of a 2.1 memory or parameter
// frame (mode commands with 8 + 16 bits). The alternatives (start to start; every 2.1 command,
// position reads too) are named in the report: the latter would forbid the 2.1 continuous clock.
void TimingChecker::check_time_between_cycles(const PinFrame& next, Time last_rise) {
  if (next.header.command_type != protocol::EndatVersion::V2_1 || next.header.payload_bits == 0) return;
  judge(protocol::check::row_index(check::kTimeBetweenCycles));
  const Time gap = next.fe1 - last_rise;
  report_unless_passed(more_than(gap, limit::kTimeBetweenCyclesMin, params_.resolution),
      {.check = std::string(check::kTimeBetweenCycles),
       .spec = t_b_spec(),
       .where = ObservationPoint::EncoderPins,
       .time = next.fe1,
       .frame = next.header.index,
       .clock = 1U,
       .measured = format_time(gap),
       .limit = "> " + format_time(limit::kTimeBetweenCyclesMin),
       .severity = Severity::Error,
       .message = "a 2.1 memory or parameter frame followed the previous frame too soon (read here: last rising "
                  "edge to FE1 of 2.1 frames with 8 + 16 bits; other readings: start to start, or "
                  "every 2.1 command)"},
                  "between frames");
}

void TimingChecker::check_recovery(const PinFrame& next) {
  if (!previous_end_) return;
  const auto [last_rise, type, index] = *previous_end_;
  judge(protocol::check::row_index(check::kRecovery));
  if (error_handling_frame_ == index) judge(protocol::check::row_index(check::kErrorRecovery));
  // A2: "After an error handling, the maximum t_m of 30 us must at least be waited".
  if (error_handling_frame_ == index)
    report_unless_passed(at_least(next.fe1 - last_rise, limit::kErrorRecoveryWait, params_.resolution),
        {.check = std::string(check::kErrorRecovery),
         .spec = "A2 (wait the maximum t_m after an error handling)",
         .where = ObservationPoint::EncoderPins,
         .time = next.fe1,
         .frame = next.header.index,
         .clock = 1U,
         .measured = format_time(next.fe1 - last_rise),
         .limit = ">= " + format_time(limit::kErrorRecoveryWait),
         .severity = Severity::Error,
         .message = "the next frame followed an error handling too soon"}, "between frames");
  check_time_between_cycles(next, last_rise);
  // The declared encoder's t_m (short where word 3 has activated it) against the envelope's
  // longest t_m for the same setting; t_R is "500 ns .. any" (note 9): the envelope takes 500 ns.
  const bool short_tm = type == protocol::EndatVersion::V2_2 && settings_.short_t_m();
  const Time declared = (short_tm && encoder_.t_m_short ? *encoder_.t_m_short : encoder_.t_m) + encoder_.t_r;
  const Time envelope = (short_tm ? limit::kShortRecoveryTimeMax : limit::kRecoveryTimeMax) + limit::kRecoveryTime2Min;
  const Time gap = next.fe1 - last_rise;
  const Judgement to_encoder = at_least(gap, declared, params_.resolution);
  const Judgement to_envelope = at_least(gap, envelope, params_.resolution);
  note(check::kRecovery, to_envelope);
  note(check::kRecovery, to_encoder, LimitOf::ThisEncoder);
  if (to_encoder == Decision::Pass && to_envelope == Decision::Pass) return;
  // A failed bound is reported; an undecided one only where nothing failed.
  const bool failed = to_encoder == Decision::Fail || to_envelope == Decision::Fail;
  const Decision shown = failed ? Decision::Fail : Decision::Undecided;
  const bool fails_encoder = to_encoder == shown, fails_envelope = to_envelope == shown;
  std::string bound = fails_encoder ? ">= " + format_time(declared) + " (this encoder)" : "";
  if (fails_envelope) bound += (fails_encoder ? ", " : "") + (">= " + format_time(envelope) + " (spec envelope)");
  const Verdict verdict = fails_encoder && fails_envelope ? Verdict::Both
                          : fails_encoder                 ? Verdict::ThisEncoder
                                                          : Verdict::SpecEnvelope;
  const std::string setting = short_tm ? " (short t_m, word 3)" : "";
  std::string message = "next frame began " + format_time(gap) + " after the last rising edge";
  if (fails_encoder)
    message += ", before this encoder's t_m + t_R (" + format_time(declared) + ")" + setting + " had elapsed";
  if (fails_envelope)
    message += std::string(fails_encoder ? "; " : ": suits this encoder (t_m + t_R " + format_time(declared) + "), but ") +
               "any compliant encoder may need t_m " + format_time(envelope - limit::kRecoveryTime2Min) + setting +
               " + t_R " + format_time(limit::kRecoveryTime2Min) + " = " + format_time(envelope);
  report_unless_passed(shown,
      {.check = std::string(check::kRecovery),
       .spec = "2.3.2 recovery time I (t_m) and II (t_R)",
       .where = ObservationPoint::EncoderPins,
       .time = next.fe1,
       .frame = next.header.index,
       .clock = 1U,
       .measured = format_time(gap),
       .limit = bound,
       .severity = Severity::Error,
       .message = message,
       .verdict = verdict}, "between frames");
}

void TimingChecker::on_sample(const DeclaredFrame& frame, unsigned clock) {
  last_declared_ = std::max(last_declared_.value_or(0), frame.index);
  if (frame.index != sampled_frame_) {  // a new frame or a new continuous-clock word
    sampled_frame_ = frame.index;
    sampling_reported_ = false;
  }
  check_master_sample(frame, clock);
  // Measurement frames are for the counter (2.1.2), taken without compensation by design.
  if (frame.measurement || clock == 0) return;
  if (sample_judged_frame_ != frame.index) {  // once per frame or continuous-clock word
    sample_judged_frame_ = frame.index;
    judge(protocol::check::row_index(check::kSamplingWindow));
    judge(protocol::check::row_index(check::kFloatingData));
  }
  if (sampling_reported_) return;
  // Bit slot k leaves the encoder after RE_k and reaches the master logic one round trip later.
  // Both sides of the comparison are at the master logic; removing the master's driver and
  // receiver delays from both gives the same inequality at the master's pins.
  const Time rt = line_.round_trip(encoder_.output_delay);
  const Time now = kernel_.now();
  const auto arrival = [&](std::size_t k) { return master_rising_[k - 1] + rt; };
  std::size_t latest = 0;
  for (std::size_t k = master_rising_.size(); k >= 1; --k) {
    if (arrival(k) + params_.sample_setup <= now) {
      latest = k;
      break;
    }
  }
  const bool next_ok = clock >= master_rising_.size() || arrival(clock + 1) - now >= params_.sample_hold;
  constexpr std::size_t window_row = protocol::check::row_index(check::kSamplingWindow);
  if (clock <= master_rising_.size()) {  // how far inside its bit's window the master sampled
    margins_.note(window_row, at_least(now - arrival(clock), params_.sample_setup, Time::zero()));
    if (clock < master_rising_.size())
      margins_.note(window_row, at_most(now - arrival(clock), arrival(clock + 1) - arrival(clock) - params_.sample_hold,
                                        Time::zero()));
  }
  if (latest == clock && next_ok) return;
  sampling_reported_ = true;
  const Time slot = clock < master_rising_.size() ? arrival(clock + 1) - arrival(clock) : sim::period_of(frame.f_c);
  const Time offset = clock <= master_rising_.size() ? now - arrival(clock) : Time::zero();
  report({.check = std::string(check::kSamplingWindow),
          .spec = "2.3 (data taken at the falling edge + t_D) and 2.1.2",
          .where = ObservationPoint::MasterPins,
          .time = now,
          .frame = frame.index,
          .clock = clock,
          .measured = format_time(offset),
          .limit = format_time(params_.sample_setup) + " .. " + format_time(slot - params_.sample_hold),
          .severity = Severity::Error,
          .message = "master sampled bit slot " + std::to_string(clock) + " outside its data-valid window ("
                     + (latest == 0 ? std::string("no bit had arrived yet") : "the line carried slot "
                     + std::to_string(latest)) + "; true round trip " + format_time(rt) + ", t_D used "
                     + format_time(frame.t_d_used) + ")"}, field_of(frame, clock));
}

void TimingChecker::on_frame_end(const DeclaredFrame& frame) {
  last_declared_ = std::max(last_declared_.value_or(0), frame.index);  // a continuous clock's last word
  if (frame.error_handling) error_handling_frame_ = frame.index;
  if (frame.start_bit_clock != 0) master_found_start_bit_ = frame.index;
  if (frame.ok) settings_.on_frame(frame.command, frame.payload, frame.supplement);
  check_busy_time({frame.index, frame.start, frame.end, frame.command, frame.supplement, frame.ok, frame.busy, frame.f_c});
  declared_running_ = false;
}

// 2.3.2 t_ac maximum 12 ms with EnDat 2.2 commands: the access runs after the command supplement
// and additional data 1 shows Busy until it is done (2.5.1, 2.6.1). A frame that begins more than
// 12 ms + T after the supplement and still shows Busy = 1 is reported, once per access.
// 2.5.1, 2.6.1: while the encoder processes a 2.2 memory access, "no further write access, read
// access or reset, also not after type 2.1 mode commands, must be performed"; the master must
// query additional data 1 between the commands until Busy = 0. The answer of a frame comes
// before its own supplement, so its Busy bit speaks for the accesses before it. An encoder
// ignores such a 2.2 access silently (2.3.1 note 1), so it is reported here.
void TimingChecker::check_access_while_busy(const AccessEvidence& frame) {
  using MC = protocol::ModeCommand;
  if (frame.ok && frame.busy && !*frame.busy) awaiting_not_busy_.reset();
  const auto& info = protocol::info(frame.command);
  const bool access_21 = info.version == protocol::EndatVersion::V2_1 &&
                         (frame.command == MC::SelectionOfMemoryArea || frame.command == MC::EncoderReceiveParameters ||
                          frame.command == MC::EncoderSendParameters || frame.command == MC::EncoderReceiveReset);
  bool access_22 = false;
  if (frame.supplement) {
    const auto mrs = protocol::payload_address(*frame.supplement);
    access_22 = frame.command == MC::EncoderSendPositionValuesAndReceiveParameter ||
                frame.command == MC::EncoderSendPositionValuesAndSendParameter ||
                (frame.command == MC::EncoderSendPositionValuesAndSelectionOfMemoryArea &&
                 !protocol::selects_additional_data(mrs));
  }
  if (!access_21 && !access_22) return;
  if (awaiting_not_busy_) {
    judge(protocol::check::row_index(check::kAccessWhileBusy));
    report({.check = std::string(check::kAccessWhileBusy),
            .spec = "2.5.1, 2.6.1 (no access while Busy)",
            .where = ObservationPoint::EncoderPins,
            .time = frame.start,
            .frame = frame.index,
            .clock = std::nullopt,
            .measured = std::string(info.key),
            .limit = "a frame with Busy = 0 after the access of frame #" + std::to_string(*awaiting_not_busy_),
            .severity = Severity::Error,
            .message = "a memory access or reset while the encoder may still be busy with the 2.2 access of frame #"
                       + std::to_string(*awaiting_not_busy_) + ": no frame since showed Busy = 0 in additional data 1"},
                       access_22 ? "command supplement" : "mode command");
  } else if (access_22 || awaiting_known_) {
    judge(protocol::check::row_index(check::kAccessWhileBusy));
  }
  if (access_22) {
    awaiting_not_busy_ = frame.index;
    awaiting_known_ = true;
  }
}

void TimingChecker::check_busy_time(const AccessEvidence& frame) {
  using MC = protocol::ModeCommand;
  check_access_while_busy(frame);
  if (frame.supplement) {
    const auto mrs = protocol::payload_address(*frame.supplement);
    const bool access = frame.command == MC::EncoderSendPositionValuesAndReceiveParameter ||
                        frame.command == MC::EncoderSendPositionValuesAndSendParameter ||
                        (frame.command == MC::EncoderSendPositionValuesAndSelectionOfMemoryArea &&
                         !protocol::selects_additional_data(mrs));
    if (access) {
      busy_since_ = frame.end;
      busy_reported_ = false;
    }
    return;
  }
  if (!busy_since_ || !frame.ok || !frame.busy) return;
  judge(protocol::check::row_index(check::kMemoryAccess));
  if (!*frame.busy) {
    busy_since_.reset();
    return;
  }
  const Time busy_for = frame.start - *busy_since_;
  const Time bound = limit::kMemoryAccessMax + sim::period_of(frame.f_c);
  if (busy_reported_) return;
  busy_reported_ = report_unless_passed(at_most(busy_for, bound, params_.resolution),
      {.check = std::string(check::kMemoryAccess),
       .spec = "2.3.2 t_ac maximum 12 ms (EnDat 2.2: busy bit)",
       .where = ObservationPoint::MasterPins,
       .time = frame.start,
       .frame = frame.index,
       .clock = std::nullopt,
       .measured = "busy after " + format_time(busy_for),
       .limit = "<= " + format_time(limit::kMemoryAccessMax) + " + T = " + format_time(bound),
       .severity = Severity::Error,
       .message = "the encoder's memory access outlasts the longest access time: Busy is still set"},
       "additional data 1");
}

void TimingChecker::begin_capture(Time start, bool at_rest) {
  capture_ = true;
  if (!at_rest) decoder_.begin_capture(start);
}

void TimingChecker::finish() {
  frozen_mark_ = settled_frames();  // what finish() reports was all still open
  if (run_cut_at_ && in_frame_ && (wires_only_ ? decoder_.cuts_frame(*run_cut_at_) : declared_running_)) {
    frame_cut_by_end_ = current_.header.index;
    cut_at_ = *run_cut_at_;
  }
  if (wires_only_) {
    const Time end = std::max(kernel_.now(), capture_end_);
    if (capture_ && in_frame_ && decoder_.cuts_frame(end)) {
      frame_cut_by_end_ = current_.header.index;
      cut_at_ = end;
    }
    decoder_.finish(capture_ ? end : Time::max());
    if (in_frame_) begin_wire_frame(kernel_.now());  // evaluates the last frame
    in_frame_ = false;
  }
  if (in_frame_) {
    evaluate(current_);
    in_frame_ = false;
  }
  report_power_on(power_on_.finish());
  settle_contentions(true);
  // In time order; among findings of the same time in the order reported, but contentions after
  // the others in the order they began: where they stood when finish() reported every contention
  // (before any listener), so the order is the same whenever they are reported.
  std::vector<std::size_t> order(violations_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (violations_[a].time != violations_[b].time) return violations_[a].time < violations_[b].time;
    const auto& ca = contention_of_[a];
    const auto& cb = contention_of_[b];
    if (ca.has_value() != cb.has_value()) return !ca.has_value();
    return ca.has_value() && *ca < *cb;
  });
  std::vector<Violation> sorted;
  std::vector<std::optional<std::uint64_t>> sorted_of;
  sorted.reserve(order.size());
  sorted_of.reserve(order.size());
  for (const std::size_t i : order) {
    sorted.push_back(std::move(violations_[i]));
    sorted_of.push_back(contention_of_[i]);
  }
  violations_ = std::move(sorted);
  contention_of_ = std::move(sorted_of);
  find_latest_contention_kept();
  frozen_mark_.reset();
  finished_ = true;
}

// 2.3: one driver on DATA at a time. The line tells each contention as it begins and ends; it is
// reported when it ends (at finish() if it goes on), against the frame that had begun (FE1 at
// the master logic) when it began, and between frames against none.
void TimingChecker::on_contention(const line::Contention& c) {
  if (finished_) return;
  // One recorded DATA wire shows no collision; a capture shows one connector's contentions.
  if (!contentions_reported() || (params_.recorded_at && c.where != *params_.recorded_at)) return;
  if (c.end == Time::max()) {
    std::optional<std::uint64_t> frame;
    for (auto it = frame_starts_.rbegin(); it != frame_starts_.rend(); ++it)
      if (it->first <= c.start) {
        frame = it->second;
        break;
      }
    contentions_.push_back({c, frame});
  } else {
    for (PendingContention& p : contentions_)
      if (p.contention.sequence == c.sequence) p.contention.end = c.end;
  }
  settle_contentions();
}

// A frame begins at `start` (FE1 at the master logic): the frame of every contention that has
// begun since. Only the latest start at or before now is kept for contentions to come.
void TimingChecker::contention_frame_started(Time start, std::uint64_t index) {
  frame_starts_.emplace_back(start, index);
  const Time now = kernel_.now();
  while (frame_starts_.size() > 1 && frame_starts_[1].first <= now) frame_starts_.pop_front();
  for (PendingContention& p : contentions_)
    if (start <= p.contention.start) p.frame = index;
  settle_contentions();
}

// Reports the contentions that have ended and whose frame is known for good. A master declares
// each frame at its FE1 (at its logic), so by a contention's end every frame that had begun before
// it has been declared. A frame found on the wires is noted at its FE1 at the encoder pins, one
// clock path (the master's driver and the cable) after its FE1 at the master logic: until the
// longest path the line allows has passed since the contention began, a frame may still be found
// that had begun before it. `finishing`: the run is over, every contention is reported (one that
// goes on ends now).
void TimingChecker::settle_contentions(bool finishing) {
  static constexpr Time kLongestClockPath =
      line::LineParams::kMaxTransceiverDelay +
      Time{static_cast<std::int64_t>(line::LineParams::kMaxCableLengthM *
                                     static_cast<double>(line::LineParams::kMaxCableDelayPerM.count()))};
  const Time now = kernel_.now();
  const bool declared = !wires_only_ && !frame_starts_.empty();
  for (auto it = contentions_.begin(); it != contentions_.end();) {
    const line::Contention& c = it->contention;
    const bool ended = c.end != Time::max();
    if (!finishing && (!ended || (!declared && now - c.start <= kLongestClockPath))) {
      ++it;
      continue;
    }
    const Time end = ended ? c.end : now;
    // Two drivers handing over at the same picosecond do not collide.
    if (end != c.start)
      report(Violation{{.check = std::string(check::kContention),
                        .spec = "2.3 (collision between the data drivers)",
                        .where = c.where,
                        .time = c.start,
                        .frame = it->frame,
                        .clock = std::nullopt,
                        .measured = format_time(end - c.start),
                        .limit = "0 ps (one driver at a time)",
                        .severity = Severity::Error,
                        .message = c.between_encoders ? "two encoders on the bus drove DATA at the same time (2.10)"
                                                      : "master and encoder drove DATA at the same time"},
                       it->frame ? "inside a frame" : "between frames"},
             c.sequence);
    it = contentions_.erase(it);  // after reporting: until then its frame is not settled
  }
}

std::uint64_t TimingChecker::settled_frames() const {
  if (finished_) return UINT64_MAX;
  if (frozen_mark_) return *frozen_mark_;
  std::uint64_t mark = UINT64_MAX;
  const auto below = [&](std::uint64_t frame) { mark = std::min(mark, frame); };
  if (wires_only_ || (!mode_decided_ && !last_declared_)) {
    // Frames found on the wires: the one being clocked at the encoder pins is judged when the
    // next begins; the next has the decoder's next index.
    below(in_frame_ ? current_.header.index : decoder_.frames_begun());
    // A live run: a master may declare its frames after its power-on pulse (on_frame_start) and
    // number them from 0.
    if (!capture_ && !wire_request_seen_) below(0);
  } else {
    // The master's frames: the one it is running (samples, its end), the next, and those
    // declared but not yet judged at the encoder pins (evaluate(), when the next FE1 arrives).
    if (last_declared_) below(declared_running_ ? *last_declared_ : *last_declared_ + 1);
    else below(0);
    if (in_frame_) below(current_.header.index);
    if (!pending_.empty()) below(pending_.front().second.index);
  }
  // A contention that begins from now on belongs to the latest frame begun, or a later one.
  if (contentions_reported())
    for (const auto& start : frame_starts_) below(start.second);
  for (const PendingContention& p : contentions_)
    if (p.frame) below(*p.frame);
  for (const StartBitInFlight& s : start_bits_in_flight_) below(s.frame);  // t_D, at the master logic
  if (const auto wake = power_on_.waiting_request()) below(*wake);
  if (held_frame_) below(*held_frame_);
  return mark;
}

TimingChecker::Backlog TimingChecker::backlog() const {
  return {.frames_not_at_encoder = pending_.size(),
          .frame_starts = frame_starts_.size(),
          .contentions = contentions_.size(),
          .start_bits_in_flight = start_bits_in_flight_.size(),
          .master_rising_edges = master_rising_.size(),
          .master_driven_changes = master_driven_.size(),
          .encoder_edges = current_.rising.size() + current_.falling.size(),
          .delay_measurements = delay_measurements_.kept(),
          .findings_kept = violations_.size()};
}

}  // namespace endatsim::checker
