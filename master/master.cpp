#include "endatsim/master/master.hpp"
#include "endatsim/sim/parameter.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "endatsim/protocol/crc_parameters.hpp"
#include "endatsim/protocol/parameters.hpp"

namespace endatsim::master {
namespace {

using MC = protocol::ModeCommand;
using I = protocol::Information;
using P = Operation::Purpose;

using sim::require;

// The operations the scheduler leaves to the functions on top of it.
const char* name_of_function_operation(Operation::Kind k) {
  switch (k) {
    case Operation::Kind::SafetyStartup: return "safety_startup";
    case Operation::Kind::CrcSelfTest: return "crc_self_test";
    case Operation::Kind::StartupPositions: return "startup_positions";
    case Operation::Kind::DiagnosisSetup: return "diagnosis_setup";
    case Operation::Kind::DiagnosisActivate: return "diagnosis_activate";
    default: return "?";
  }
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
  in_range(crc_check_parameters(), crc, "master crc");
  in_range(protocol::crc_generator_parameters(), crc.generator, "master crc");
  in_range(setpoint_parameters(), safety.setpoint, "master safety setpoint");
  require(high_permille >= kHighPermilleMin && high_permille <= kHighPermilleMax,
          "master duty cycle must be 0.1 .. 0.9, got " + std::to_string(high_permille / 1000.0));
  const Time period = sim::period_of(f_c);
  const Time shorter = std::min(period * high_permille / 1000, period - period * high_permille / 1000);
  require(jitter * 2 < shorter, "master clock jitter must be below half the shorter clock phase (" +
                                    sim::format_time(shorter / 2) + "), got " + sim::format_time(jitter));
  require(supplement_driven_lead_bits <= supplement_lead_bits,
          "master supplement_driven_lead_bits must be 1 .. supplement_lead_bits (" +
              std::to_string(supplement_lead_bits) + "), got " + std::to_string(supplement_driven_lead_bits));
  safety.validate();
  diagnostics.validate();
}

Master::Master(sim::Kernel& kernel, line::Line& line, const MasterParams& params)
    : kernel_(kernel), params_(validated(params)), delay_(params.measurement, params.f_c),
      t_d_(params.fixed_t_d), engine_(kernel, line.master(), params_, delay_, *this, observers_),
      operation_timer_(kernel, sim::bind<&Master::next_operation>(this)),
      careful_(params.careful, params.delay_compensation), position_bits_(params.position_bits) {}

void Master::start() {
  finished_ = false;
  next_operation();
}

// ---- operations -------------------------------------------------------------------------

void Master::next_operation() {
  // Reads of words 0 / 1 that waited for the end of an expanded sequence come before the end.
  if (operations_.empty() && status_read_due() && current_)
    push_status_reads(*current_);
  if (operations_.empty()) {
    current_.reset();
    finished_ = true;
    return;
  }
  current_ = operations_.take();
  const Time begin = std::max(current_->at.value_or(kernel_.now()), kernel_.now());
  switch (current_->kind) {
    case Operation::Kind::Wait:
      operation_timer_.start(begin + current_->duration - kernel_.now());
      return;
    case Operation::Kind::PowerOnSequence:
      kernel_.schedule(begin + params_.power_on.t1_t2 - kernel_.now(), sim::bind<&Master::power_on_pulse>(this, 0));
      return;
    case Operation::Kind::StartupRoutine: {
      Sequence routine = sequence();
      routine_.plan(routine, params_.delay_compensation);
      expand(std::move(routine));
      return;
    }
    case Operation::Kind::VerifyChecksum: {
      Sequence reads = sequence();
      checksum_.plan(reads);
      expand(std::move(reads));
      return;
    }
    case Operation::Kind::ReadEndat22Area:
      expand(endat22_read_plan());
      return;
    case Operation::Kind::SafetyStartup:
    case Operation::Kind::CrcSelfTest:
    case Operation::Kind::StartupPositions:
    case Operation::Kind::DiagnosisSetup:
    case Operation::Kind::DiagnosisActivate:
      offer_to_functions(begin);
      return;
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
      careful_.position_read_started();
      break;
  }
  start_frames(begin);
}

void Master::start_frames(Time begin) {
  pacing_.start(begin);
  kernel_.schedule(pacing_.due() - kernel_.now(), sim::bind<&Master::start_frame>(this));
}

FunctionContext Master::context() const {
  return {*current_, params_, book_, checksum_, position_bits_, kernel_.now()};
}

// The operations of a sequence run before what is queued.
void Master::expand(Sequence s) {
  for (Operation& o : s.ops) o.expanded = true;
  operations_.insert_front(s.ops);
  next_operation();
}

// An operation the scheduler does not plan itself goes to the functions on top of it.
void Master::offer_to_functions(Time begin) {
  Sequence plan = sequence();
  for (MasterFunction* function : functions_) {
    const Planned p = function->plan(context(), plan);
    switch (p.what) {
      case Planned::What::NotMine: continue;
      case Planned::What::Expanded: expand(std::move(plan)); return;
      case Planned::What::Done: next_operation(); return;
      case Planned::What::Frames:
        frames_left_ = p.frames;
        start_frames(begin);
        return;
    }
  }
  throw std::logic_error(std::string("operation ") + name_of_function_operation(current_->kind) +
                         ": no function on this master plans it (master/functions.hpp attaches them)");
}

void Master::power_on_pulse(std::uint64_t phase) {
  // One LOW pulse, then CLOCK HIGH for t3 (2.3.3).
  if (phase == 0) {
    engine_.drive_clock(false);
    kernel_.schedule(params_.power_on.pulse, sim::bind<&Master::power_on_pulse>(this, 1));
    return;
  }
  engine_.drive_clock(true);
  pacing_.not_before(kernel_.now() + params_.power_on.t3);
  operation_timer_.start(params_.power_on.t3);
}

// ---- a careful master ---------------------------------------------------------------------

void Master::line_changed() { careful_.line_changed(); }

void Master::encoder_power_interrupted() { careful_.power_interrupted(selection_.count() != 0); }

bool Master::retry_frame(const FrameResult& f) {
  if (!careful_.retry(f, current_->kind == Operation::Kind::ReadPosition)) return false;
  kernel_.schedule(std::max(pacing_.ready_at(), kernel_.now()) - kernel_.now(), sim::bind<&Master::start_frame>(this));
  return true;
}

// 2.3.2 t_b: a 2.1 memory or parameter frame waits t_b_wait after the previous frame's end.
Time Master::time_between_cycles_left() const {
  const auto& c = protocol::info(current_->command);
  if (delay_.active() || frames_.count() == 0 || c.version != protocol::EndatVersion::V2_1 || c.payload_bits == 0) return Time::zero();
  return std::max(Time::zero(), engine_.frame().end + params_.t_b_wait - kernel_.now());
}

// Before the next frame: select the additional data again (the encoder lost them) and measure
// t_D again (2.1.2); then the operation goes on where it was.
void Master::interrupt_for_measurement() {
  Operation rest = *current_;
  rest.count = frames_left_;
  rest.at.reset();
  operations_.push_front(rest);
  const auto due = careful_.take_interruption();
  if (due.remeasure) {
    Operation m;
    m.kind = Operation::Kind::MeasureDelay;
    m.script_index = current_->script_index;
    operations_.push_front(m);
  }
  if (due.reselect) {
    for (const std::uint8_t mrs : selection_.take()) {
      Operation s = rest;
      s.count = 1;
      s.kind = Operation::Kind::ReadPosition;
      s.command = ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea;
      s.address = mrs;
      s.parameter = 0;
      s.purpose = Operation::Purpose::None;
      operations_.push_front(s);
    }
  }
  if (!rest.expanded) push_status_reads(rest);
  next_operation();
}

bool Master::status_read_due() const {
  return std::any_of(functions_.begin(), functions_.end(), [](const MasterFunction* f) { return f->status_read_due().has_value(); });
}

// 3.4.1 / 3.4.2: words 0 and 1 of the operating status say which error or warning it was; the
// reads come in the order of the functions that asked for them.
void Master::push_status_reads(const Operation& base) {
  std::vector<StatusRead> reads;
  for (const MasterFunction* f : functions_)
    if (auto r = f->status_read_due()) reads.push_back(*r);
  for (auto r = reads.rbegin(); r != reads.rend(); ++r) {
    Operation read = base;
    read.kind = Operation::Kind::ReadPosition;
    read.count = 1;
    read.at.reset();
    read.mode_bits.reset();
    read.clock_adjust = 0;
    read.continuous_words = 0;
    read.command = ModeCommand::EncoderSendParameters;
    read.address = r->address;
    read.purpose = r->purpose;
    operations_.push_front(read);
    read.command = ModeCommand::SelectionOfMemoryArea;
    read.address = protocol::info(protocol::MemoryArea::OperatingStatus).mrs;
    read.purpose = Operation::Purpose::None;
    operations_.push_front(read);
  }
  for (MasterFunction* f : functions_) f->status_read_planned();
}

void Master::operation_frame_done(const FrameResult& f) {
  if (current_->kind == Operation::Kind::AwaitNotBusy && busy_polling_.poll_ends_wait(f, frames_left_ == 1))
    frames_left_ = 1;
  for (MasterFunction* function : functions_)
    if (function->ends_operation(f, context(), frames_left_ == 1)) frames_left_ = 1;
  careful_.frame_done(f);
  if (retry_frame(f)) return;
  if (--frames_left_ > 0) {
    // The read cycle of a control loop; polls for the busy bit may come later than their interval.
    pacing_.next_cycle(current_->kind != Operation::Kind::MeasureDelay ? current_->cycle : Time::zero(),
                       current_->cycle > Time::zero() && current_->kind == Operation::Kind::ReadPosition);
    kernel_.schedule(pacing_.due() - kernel_.now(), sim::bind<&Master::start_frame>(this));
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
  const bool status_reads = status_read_due() && !current_->expanded;
  if ((careful_.interruption_due() || status_reads) && !delay_.active()) {
    interrupt_for_measurement();
    return;
  }
  if (const Time wait = time_between_cycles_left(); wait > Time::zero()) {
    kernel_.schedule(wait, sim::bind<&Master::start_frame>(this));
    return;
  }
  const FrameRequest request = frame_request();
  if (shortcut_ != nullptr && shortcut_->replayed(request)) return;
  engine_.start(request);
}

// The next frame of the current operation: a delay measurement's while one runs (2.1.2).
FrameRequest Master::frame_request() {
  FrameRequest r;
  r.index = frames_.count();
  r.operation = current_->script_index;
  r.measurement = delay_.active();
  r.command = r.measurement ? ModeCommand::EncoderSendPositionValues : current_->command;
  r.payload = protocol::make_payload(current_->address, current_->parameter);
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

void Master::answer_accepted(const FrameResult& f) { selection_.accepted(f); }

void Master::record(const FrameResult& f) {
  frames_.add(f);
  delay_.frame_recorded(f.start);
}

void Master::word_done(const FrameResult& f) {
  record(f);
  for (auto* o : observers_) o->on_result(f);
}

void Master::frame_done(FrameResult& f) {
  const bool error_handling = f.outcome == FrameOutcome::NoStartBit || f.outcome == FrameOutcome::Type1Error;
  pacing_.ready_at(f.end + (error_handling ? params_.error_wait : params_.t_m_wait) + params_.t_r_wait);
  if (f.command == ModeCommand::EncoderReceiveReset && f.outcome == FrameOutcome::Ok)
    pacing_.not_before(f.end + params_.reset_wait);
  if (!f.measurement) {
    book_.note(f);
    note_endat22_word(f);
    // 2.3.1: an error message; the safety functions may evaluate F2 as well.
    if (protocol::info(f.command).answer == protocol::AnswerFormat::Position && f.outcome == FrameOutcome::Ok)
      f.error_detected = f.error1;
    const FunctionContext ctx = context();
    if (current_->purpose == Operation::Purpose::Endat22Msb && current_->manufacturer_word == protocol::word::kEndat22Checksum &&
        f.outcome == FrameOutcome::Ok && !f.additional_data.empty())
      for (MasterFunction* function : functions_) function->endat22_area_read(ctx, true);
    for (MasterFunction* function : functions_) function->on_frame(f, ctx);
    if (const auto bits = routine_.note(current_->purpose, f); bits && params_.adopt_word13) position_bits_ = *bits;
    checksum_.note(*current_, f);
  }
  record(f);
  for (auto* o : observers_) o->on_frame_end(f);
  for (auto* o : observers_) o->on_result(f);
  operation_frame_done(f);
}

// ---- the EnDat 2.2 area and additional data 1 ------------------------------------------------

// 2.5.1: the words of the 2.2 area the operation names (plan_endat22_read); a function that asked
// for the whole area hears when the encoder has none.
Sequence Master::endat22_read_plan() {
  book_.begin_endat22_read();
  const auto word37 = parameter(mrs_of(protocol::MemoryArea::Manufacturer3), protocol::word::manufacturer_address(protocol::word::kCommandSet));
  Sequence plan = sequence();
  if (!plan_endat22_read(plan, current_->endat22_words, word37) && current_->endat22_words == ~std::uint64_t{0})
    for (MasterFunction* function : functions_) function->endat22_area_read(context(), false);
  return plan;
}

// A byte of a word of the 2.2 area, as the plan above asked for it.
void Master::note_endat22_word(const FrameResult& f) {
  const Operation::Purpose purpose = current_->purpose;
  if (purpose != Operation::Purpose::Endat22Lsb && purpose != Operation::Purpose::Endat22Msb) return;
  if (f.outcome != FrameOutcome::Ok || f.additional_data.empty()) return;
  book_.note_endat22_byte(f, current_->manufacturer_word, purpose == Operation::Purpose::Endat22Msb);
}

// Each cyclic read with additional data may select, with "Encoder send position values and
// selection of memory area" (2.4.2.2), what the next frame is to carry, as a function on top
// asks. Additional data 1 selected for something else (a memory read, a script's own choice) is
// left alone.
void Master::roll_additional_data_1(FrameRequest& request) {
  if (current_->purpose != Operation::Purpose::None || current_->kind == Operation::Kind::AwaitNotBusy ||
      request.command != ModeCommand::EncoderSendPositionValuesWithAdditionalData)
    return;
  const std::optional<I> now = selection_.additional_data_1();
  for (MasterFunction* function : functions_) {
    const auto next = function->next_additional_data_1(context(), now);
    if (!next) continue;
    request.command = ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea;
    request.payload = protocol::make_payload(protocol::selection_mrs(*next), 0);
    return;
  }
}



// ---- propagation-delay measurement (2.1.2) -----------------------------------------------

void Master::finish_measurement_round() {
  const auto& m = params_.measurement;
  const auto& r = delay_.finish_round(delay_.round_start(kernel_.now()));
  if (r.accepted) t_d_ = r.t_d;
  if (delay_.next_round()) {
    frames_left_ = m.count;
    pacing_.start(kernel_.now());
    kernel_.schedule(std::max(pacing_.ready_at(), kernel_.now()) - kernel_.now(), sim::bind<&Master::start_frame>(this));
    return;
  }
  next_operation();
}

}  // namespace endatsim::master
