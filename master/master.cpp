#include "endatsim/master/master.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace endatsim::master {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

DiagnosisFrame diagnosis_frame(Operation::Purpose p) {
  using P = Operation::Purpose;
  return p == P::DiagnosisConfiguration ? DiagnosisFrame::ConfigurationWrite
         : p == P::DiagnosisWarnings    ? DiagnosisFrame::WarningsRead
                                        : DiagnosisFrame::Cyclic;
}

const MasterParams& validated(const MasterParams& p) {
  p.validate();
  return p;
}

}  // namespace

void MasterParams::validate() const {
  const auto in_range = [](const auto& rows, const auto& p, std::string_view owner) {
    if (auto why = sim::first_out_of_range(rows, p, owner)) throw std::invalid_argument(*why);
  };
  in_range(master_parameters(), *this, "master");
  in_range(power_on_parameters(), power_on, "master power_on");
  in_range(delay_measurement_parameters(), measurement, "master delay_measurement");
  in_range(careful_parameters(), careful, "master careful");
  require(high_permille >= 100 && high_permille <= 900,
          "master duty cycle must be 0.1 .. 0.9, got " + std::to_string(high_permille / 1000.0));
  const Time period = sim::period_of(f_c);
  const Time shorter = std::min(period * high_permille / 1000, period - period * high_permille / 1000);
  require(jitter * 2 < shorter, "master clock jitter must be below half the shorter clock phase (" +
                                    sim::format_time(shorter / 2) + "), got " + sim::format_time(jitter));
  require(supplement_driven_lead_bits <= supplement_lead_bits,
          "master supplement_driven_lead_bits must be 1 .. supplement_lead_bits (" +
              std::to_string(supplement_lead_bits) + "), got " + std::to_string(supplement_driven_lead_bits));
  require(crc.table_fault_width <= 48,
          "master crc table_fault_width must be 0 .. 48 (0: none), got " + std::to_string(crc.table_fault_width));
  safety.validate();
  diagnostics.validate();
}

Master::Master(sim::Kernel& kernel, line::Line& line, const MasterParams& params)
    : kernel_(kernel), params_(validated(params)), delay_(params.measurement, params.f_c),
      t_d_(params.fixed_t_d), engine_(kernel, line.master(), params_, delay_, *this, observers_),
      operation_timer_(kernel, sim::bind<&Master::next_operation>(this)), position_bits_(params.position_bits) {}

void Master::start() {
  finished_ = false;
  next_operation();
}

// ---- operations -------------------------------------------------------------------------

void Master::next_operation() {
  // Reads of words 0 / 1 that waited for the end of an expanded sequence come before the end.
  if (operations_.empty() && (safety_.error_sources_due() || diagnosis_.warnings_due()) && current_)
    push_status_reads(*current_);
  if (operations_.empty()) {
    current_.reset();
    finished_ = true;
    return;
  }
  current_ = operations_.front();
  operations_.pop_front();
  const Time begin = std::max(current_->at.value_or(kernel_.now()), kernel_.now());
  switch (current_->kind) {
    case Operation::Kind::Wait:
      operation_timer_.start(begin + current_->duration - kernel_.now());
      return;
    case Operation::Kind::PowerOnSequence:
      kernel_.schedule(begin + params_.power_on.t1_t2 - kernel_.now(), sim::bind<&Master::power_on_pulse>(this, 0));
      return;
    case Operation::Kind::StartupRoutine:
      expand(&Master::expand_startup_routine);
      return;
    case Operation::Kind::VerifyChecksum:
      expand(&Master::expand_checksum_check);
      return;
    case Operation::Kind::SafetyStartup:
      expand(&Master::expand_safety_startup);
      return;
    case Operation::Kind::CrcSelfTest:
      safety_.run_crc_self_test(params_.crc, position_bits_, kernel_.now());
      next_operation();
      return;
    case Operation::Kind::ReadEndat22Area:
      expand(&Master::expand_endat22_read);
      return;
    case Operation::Kind::DiagnosisSetup:
      expand(&Master::expand_diagnosis_setup);
      return;
    case Operation::Kind::DiagnosisActivate:
      expand(&Master::activate_diagnosis);
      return;
    case Operation::Kind::StartupPositions:
      frames_left_ = params_.safety.startup_positions ? params_.safety.startup_max_reads : 1;
      safety_.begin_startup_positions();
      break;
    case Operation::Kind::MeasureDelay:
      delay_.begin();
      frames_left_ = params_.measurement.count;
      break;
    case Operation::Kind::AwaitNotBusy:
      current_->command = ModeCommand::EncoderSendPositionValuesWithAdditionalData;
      frames_left_ = current_->count;
      break;
    case Operation::Kind::ReadPosition:
      frames_left_ = current_->count;
      retries_left_ = params_.careful.retries;
      break;
  }
  next_due_ = begin;
  const Time at = std::max(next_due_, ready_at_);
  kernel_.schedule(at - kernel_.now(), sim::bind<&Master::start_frame>(this));
}

void Master::run_first(const Sequence& s) { operations_.insert(operations_.begin(), s.ops.begin(), s.ops.end()); }

void Master::expand(void (Master::*expansion)()) {
  const std::size_t before = operations_.size();
  (this->*expansion)();
  for (std::size_t i = 0; i + before < operations_.size(); ++i) operations_[i].expanded = true;
  next_operation();
}

void Master::power_on_pulse(std::uint64_t phase) {
  // One LOW pulse, then CLOCK HIGH for t3 (2.3.3).
  if (phase == 0) {
    engine_.drive_clock(false);
    kernel_.schedule(params_.power_on.pulse, sim::bind<&Master::power_on_pulse>(this, 1));
    return;
  }
  engine_.drive_clock(true);
  ready_at_ = std::max(ready_at_, kernel_.now() + params_.power_on.t3);
  operation_timer_.start(params_.power_on.t3);
}

void Master::expand_startup_routine() {
  Sequence routine = sequence();
  routine_.plan(routine, params_.delay_compensation);
  run_first(routine);
}

void Master::expand_checksum_check() {
  Sequence reads = sequence();
  checksum_.plan(reads);
  run_first(reads);
}

// ---- a careful master ---------------------------------------------------------------------

void Master::line_changed() {
  if (params_.careful.remeasure_after_line_change && params_.delay_compensation) remeasure_due_ = true;
}

void Master::encoder_power_interrupted() {
  if (params_.careful.remeasure_after_power_interruption && params_.delay_compensation) remeasure_due_ = true;
  if (params_.careful.reselect_after_power_interruption && (selected_[0] || selected_[1])) reselect_due_ = true;
}

void Master::note_failures(const FrameResult& f) {
  if (f.measurement) return;
  const auto o = f.outcome;
  const bool failed = o == FrameOutcome::CrcError || o == FrameOutcome::NoStartBit || o == FrameOutcome::Type1Error ||
                      o == FrameOutcome::EchoMismatch || o == FrameOutcome::TooFewClocks;
  failures_in_a_row_ = failed ? failures_in_a_row_ + 1 : 0;
  const unsigned k = params_.careful.remeasure_after_crc_errors;
  if (k != 0 && failures_in_a_row_ >= k && params_.delay_compensation) {
    remeasure_due_ = true;
    failures_in_a_row_ = 0;
  }
}

bool Master::retry_frame(const FrameResult& f) {
  const auto o = f.outcome;
  const bool failed = o != FrameOutcome::Ok && o != FrameOutcome::Type2Error;
  if (current_->kind != Operation::Kind::ReadPosition || f.measurement || !failed ||
      retries_left_ == 0) {
    retries_left_ = params_.careful.retries;
    return false;
  }
  --retries_left_;
  ++retries_done_;
  kernel_.schedule(std::max(ready_at_, kernel_.now()) - kernel_.now(), sim::bind<&Master::start_frame>(this));
  return true;
}

// Before the next frame: select the additional data again (the encoder lost them) and measure
// t_D again (2.1.2); then the operation goes on where it was.
// 2.3.2 t_b: a 2.1 memory or parameter frame waits t_b_wait after the previous frame's end.
Time Master::time_between_cycles_left() const {
  const auto& c = protocol::info(current_->command);
  if (delay_.active() || frame_count_ == 0 || c.version != protocol::EndatVersion::V2_1 || c.payload_bits == 0) return Time::zero();
  return std::max(Time::zero(), engine_.frame().end + params_.t_b_wait - kernel_.now());
}

void Master::interrupt_for_measurement() {
  Operation rest = *current_;
  rest.count = frames_left_;
  rest.at.reset();
  operations_.push_front(rest);
  if (remeasure_due_) {
    Operation m;
    m.kind = Operation::Kind::MeasureDelay;
    m.script_index = current_->script_index;
    operations_.push_front(m);
    ++remeasurements_;
  }
  if (reselect_due_) {
    for (unsigned i : {1U, 0U}) {
      if (!selected_[i]) continue;
      Operation s = rest;
      s.count = 1;
      s.kind = Operation::Kind::ReadPosition;
      s.command = ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea;
      s.address = selection_mrs_[i];
      s.parameter = 0;
      s.purpose = Operation::Purpose::None;
      operations_.push_front(s);
      selected_[i] = false;
    }
  }
  if (!rest.expanded) push_status_reads(rest);
  remeasure_due_ = reselect_due_ = false;
  next_operation();
}

// 3.4.1 / 3.4.2: words 0 and 1 of the operating status say which error or warning it was.
void Master::push_status_reads(const Operation& base) {
  for (const auto& [due, address, purpose] : {std::tuple{safety_.error_sources_due(), 0, Operation::Purpose::ErrorSources},
                                              {diagnosis_.warnings_due(), 1, Operation::Purpose::DiagnosisWarnings}}) {
    if (!due) continue;
    Operation read = base;
    read.kind = Operation::Kind::ReadPosition;
    read.count = 1;
    read.at.reset();
    read.mode_bits.reset();
    read.clock_adjust = 0;
    read.continuous_words = 0;
    read.command = ModeCommand::EncoderSendParameters;
    read.address = static_cast<std::uint8_t>(address);
    read.purpose = purpose;
    operations_.push_front(read);
    read.command = ModeCommand::SelectionOfMemoryArea;
    read.address = protocol::info(protocol::MemoryArea::OperatingStatus).mrs;
    read.purpose = Operation::Purpose::None;
    operations_.push_front(read);
  }
  safety_.clear_error_sources_due();
  diagnosis_.clear_warnings_due();
}

void Master::operation_frame_done(const FrameResult& f) {
  if (current_->kind == Operation::Kind::AwaitNotBusy) {
    // 2.5.1 / 2.6.1: poll additional data 1 until the busy bit is reset.
    const auto& ai = f.additional_data;
    const bool ok = f.outcome == FrameOutcome::Ok;
    const auto is_1 = [](const AdditionalDatum& d) { return !protocol::is_additional_data_2(d.information()); };
    const bool ready = ok && std::any_of(ai.begin(), ai.end(), [&](const AdditionalDatum& d) { return is_1(d) && !d.busy(); });
    const bool unreadable = ok && std::none_of(ai.begin(), ai.end(), is_1);
    if (ready) frames_left_ = 1;
    else if (unreadable) {
      ++busy_unreadable_;
      frames_left_ = 1;
    } else if (frames_left_ == 1) ++busy_timeouts_;
  }
  if (current_->kind == Operation::Kind::StartupPositions && safety_.startup_position_read(f, position_bits_, frames_left_ == 1)) frames_left_ = 1;
  note_failures(f);
  if (retry_frame(f)) return;
  if (--frames_left_ > 0) {
    next_due_ += current_->kind != Operation::Kind::MeasureDelay ? current_->cycle : Time::zero();
    // The read cycle of a control loop; polls for the busy bit may come later than their interval.
    if (ready_at_ > next_due_ && current_->cycle > Time::zero() && current_->kind == Operation::Kind::ReadPosition)
      ++cycle_overruns_;
    const Time at = std::max(next_due_, ready_at_);
    kernel_.schedule(at - kernel_.now(), sim::bind<&Master::start_frame>(this));
    return;
  }
  if (delay_.active()) {
    finish_measurement_round();
    return;
  }
  next_operation();
}

// ---- one frame ----------------------------------------------------------------------------

void Master::start_frame(std::uint64_t) {
  const bool status_read_due = (safety_.error_sources_due() || diagnosis_.warnings_due()) && !current_->expanded;
  if ((remeasure_due_ || reselect_due_ || status_read_due) && !delay_.active()) {
    interrupt_for_measurement();
    return;
  }
  if (const Time wait = time_between_cycles_left(); wait > Time::zero()) {
    kernel_.schedule(wait, sim::bind<&Master::start_frame>(this));
    return;
  }
  engine_.start(frame_request());
}

// The next frame of the current operation: a delay measurement's while one runs (2.1.2).
FrameRequest Master::frame_request() {
  FrameRequest r;
  r.index = frame_count_;
  r.operation = current_->script_index;
  r.measurement = delay_.active();
  r.command = r.measurement ? ModeCommand::EncoderSendPositionValues : current_->command;
  r.payload = std::uint32_t{current_->address} << 16 | current_->parameter;
  if (!r.measurement) roll_additional_data_1(r);
  r.mode_bits = r.measurement || !current_->mode_bits ? protocol::info(r.command).bits : *current_->mode_bits;
  r.f_c = r.measurement                            ? params_.measurement.f_c
          : StartupRoutine::of_routine(current_->purpose) ? params_.startup_f_c
                                                  : params_.f_c;
  if (!r.measurement && params_.delay_compensation) r.t_d = t_d_;
  r.position_bits = position_bits_;
  r.continuous_words = r.measurement ? 0 : current_->continuous_words;
  r.clock_adjust = r.measurement ? 0 : current_->clock_adjust;
  return r;
}

// What the master expects after its own selections (2.4.2.2); a reset clears them (2.7).
void Master::answer_accepted(const FrameResult& f) {
  if (f.command == ModeCommand::EncoderReceiveReset) {
    selected_[0] = selected_[1] = false;
    return;
  }
  if (f.command != ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea) return;
  const auto mrs = static_cast<std::uint8_t>(*f.supplement >> 16);
  if (!protocol::selects_additional_data(mrs)) return;
  const unsigned which = protocol::is_additional_data_2(protocol::information_of_mrs(mrs)) ? 1 : 0;
  selected_[which] = mrs != protocol::kStopAdditionalData1 && mrs != protocol::kStopAdditionalData2;
  selection_mrs_[which] = mrs;
}

void Master::record(const FrameResult& f) {
  ++frame_count_;
  if (frames_.size() < kept_frames_) frames_.push_back(f);
  recent_starts_.push_back(f.start);
  while (recent_starts_.size() > std::max<std::size_t>(params_.measurement.count, 1)) recent_starts_.pop_front();
}

void Master::word_done(const FrameResult& f) {
  record(f);
  for (auto* o : observers_) o->on_result(f);
}

void Master::frame_done(FrameResult& f) {
  const bool error_handling = f.outcome == FrameOutcome::NoStartBit || f.outcome == FrameOutcome::Type1Error;
  ready_at_ = f.end + (error_handling ? params_.error_wait : params_.t_m_wait) + params_.t_r_wait;
  if (f.command == ModeCommand::EncoderReceiveReset && f.outcome == FrameOutcome::Ok)
    ready_at_ = std::max(ready_at_, f.end + params_.reset_wait);
  if (!f.measurement) {
    book_.note(f);
    diagnosis_.on_frame(f, diagnosis_frame(current_->purpose));
    note_safety(f);  // sets error_detected: what the master made of F1 and F2
    if (const auto bits = routine_.note(current_->purpose, f); bits && params_.adopt_word13) position_bits_ = *bits;
    checksum_.note(*current_, f);
  }
  record(f);
  for (auto* o : observers_) o->on_frame_end(f);
  for (auto* o : observers_) o->on_result(f);
  operation_frame_done(f);
}

// ---- propagation-delay measurement (2.1.2) -----------------------------------------------

void Master::finish_measurement_round() {
  const auto& m = params_.measurement;
  const auto& r = delay_.finish_round(recent_starts_.size() >= m.count && m.count != 0 ? recent_starts_.front()
                                                                                     : kernel_.now());
  if (r.accepted) t_d_ = r.t_d;
  if (delay_.next_round()) {
    frames_left_ = m.count;
    next_due_ = kernel_.now();
    kernel_.schedule(std::max(ready_at_, kernel_.now()) - kernel_.now(), sim::bind<&Master::start_frame>(this));
    return;
  }
  next_operation();
}

}  // namespace endatsim::master
