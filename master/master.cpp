#include "endatsim/master/master.hpp"

#include <algorithm>
#include <boost/random/uniform_int_distribution.hpp>
#include <stdexcept>
#include <tuple>

namespace endatsim::master {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

namespace position = protocol::frame_position;
// The encoder drives DATA from the turnaround (docs/model.md §1).
constexpr unsigned kFirstPolledClock = position::kTurnaround;

bool of_startup_routine(Operation::Purpose p) {
  using P = Operation::Purpose;
  return p == P::Step || p == P::Errors || p == P::Warnings || p == P::Word13 || p == P::Word37;
}

DiagnosisFrame diagnosis_frame(Operation::Purpose p) {
  using P = Operation::Purpose;
  return p == P::DiagnosisConfiguration ? DiagnosisFrame::ConfigurationWrite
         : p == P::DiagnosisWarnings    ? DiagnosisFrame::WarningsRead
                                        : DiagnosisFrame::Cyclic;
}

// Sample tags carry the frame's epoch in the upper and the clock slot in the lower 32 bits.
std::uint64_t sample_tag(std::uint64_t epoch, unsigned clock) { return epoch << 32 | clock; }

}  // namespace

std::string_view to_string(FrameOutcome o) {
  switch (o) {
    case FrameOutcome::Ok: return "ok";
    case FrameOutcome::CrcError: return "crc_error";
    case FrameOutcome::NoStartBit: return "no_start_bit";
    case FrameOutcome::Type1Error: return "type1_error";
    case FrameOutcome::Type2Error: return "type2_error";
    case FrameOutcome::EchoMismatch: return "echo_mismatch";
    case FrameOutcome::TooFewClocks: return "too_few_clocks";
  }
  return "?";
}

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
  require(measurement.f_e == 0 || measurement.f_e >= sim::MHz(1),
          "master delay_measurement f_e must be 0 (8 x f_c) or 1 MHz .. 2 GHz, got " +
              sim::format_frequency(measurement.f_e));
  require(supplement_driven_lead_bits <= supplement_lead_bits,
          "master supplement_driven_lead_bits must be 1 .. supplement_lead_bits (" +
              std::to_string(supplement_lead_bits) + "), got " + std::to_string(supplement_driven_lead_bits));
  require(crc.table_fault_width <= 48,
          "master crc table_fault_width must be 0 .. 48 (0: none), got " + std::to_string(crc.table_fault_width));
  safety.validate();
  diagnostics.validate();
}

Master::Master(sim::Kernel& kernel, line::Line& line, const MasterParams& params)
    : kernel_(kernel), pins_(line.master()), params_(params), rng_(params.seed),
      sample_strobe_(kernel, "master_sample", false), frame_active_(kernel, "master_frame", false),
      edge_timer_(kernel, sim::bind<&Master::clock_edge>(this)),
      operation_timer_(kernel, sim::bind<&Master::next_operation>(this)),
      layout_(protocol::position_frame_layout(protocol::EndatVersion::V2_1, params.position_bits)),
      delay_(params.measurement, params.f_c) {
  params_.validate();
  t_d_ = params_.fixed_t_d;
  position_bits_ = params_.position_bits;
  pins_.data_in.on_change(sim::bind<&Master::on_data_in>(this));
}

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
      run_crc_self_test();
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
      startup_agreeing_ = 0;
      safety_.report().startup_reads = 0;
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

Operation& Master::Sequence::frame(ModeCommand c, std::uint8_t address, std::uint16_t parameter,
                                   Operation::Purpose purpose, unsigned word) {
  Operation& o = ops.emplace_back();
  o.script_index = script_index;
  o.command = c;
  o.address = address;
  o.parameter = parameter;
  o.purpose = purpose;
  o.manufacturer_word = word;
  return o;
}

Operation& Master::Sequence::add(Operation::Kind k) {
  Operation& o = ops.emplace_back();
  o.kind = k;
  o.script_index = script_index;
  return o;
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
    pins_.clock_out.write(false);
    kernel_.schedule(params_.power_on.pulse, sim::bind<&Master::power_on_pulse>(this, 1));
    return;
  }
  pins_.clock_out.write(true);
  ready_at_ = std::max(ready_at_, kernel_.now() + params_.power_on.t3);
  operation_timer_.start(params_.power_on.t3);
}

void Master::expand_startup_routine() {
  // The German brochure, "Spannungsversorgung und Einschalten": EnDat 2.1 mode commands only.
  using P = Operation::Purpose;
  using MC = ModeCommand;
  Sequence routine = sequence();
  const auto step = [&routine](MC c, std::uint8_t address = 0, std::uint16_t parameter = 0, P purpose = P::Step) {
    routine.frame(c, address, parameter, purpose);
  };
  step(MC::EncoderReceiveReset);  // then reset_wait (50 ms)
  step(MC::SelectionOfMemoryArea, 0xB9);
  step(MC::EncoderSendParameters, 0, 0, P::Errors);
  step(MC::EncoderSendParameters, 1, 0, P::Warnings);
  step(MC::EncoderReceiveParameters, 0, 0x0000);  // 3.4.1: alarms cleared by writing 0000h
  step(MC::EncoderReceiveParameters, 1, 0x0000);  // 3.4.2: warnings likewise
  step(MC::SelectionOfMemoryArea, 0xA1);
  step(MC::EncoderSendParameters, 13, 0, P::Word13);
  step(MC::SelectionOfMemoryArea, 0xA5);
  step(MC::EncoderSendParameters, 37 - 32, 0, P::Word37);
  // The same routine / 2.1.2: then the propagation delay is measured.
  if (params_.delay_compensation) routine.add(Operation::Kind::MeasureDelay);
  startup_ = {};
  startup_.completed = true;
  run_first(routine);
}

void Master::note_startup(const FrameResult& f) {
  using P = Operation::Purpose;
  if (!of_startup_routine(current_->purpose)) return;
  if (f.outcome != FrameOutcome::Ok) {
    ++startup_.failed_frames;
    startup_.completed = false;
    return;
  }
  switch (current_->purpose) {
    case P::Errors: startup_.errors = f.echo_parameter; break;
    case P::Warnings: startup_.warnings = f.echo_parameter; break;
    case P::Word13:
      startup_.word13 = f.echo_parameter;
      if (params_.adopt_word13 && (f.echo_parameter & 0x3F) != 0) position_bits_ = f.echo_parameter & 0x3F;
      break;
    case P::Word37: startup_.word37 = f.echo_parameter; break;
    default: break;
  }
}

// 3.5.26: words 4 .. 47 of the encoder manufacturer's areas A1 (addresses 4 .. 15), A3 and A5
// (addresses 0 .. 15 each) with 2.1 frames; then word 47 against the sum of words 4 .. 46.
void Master::expand_checksum_check() {
  using MC = ModeCommand;
  Sequence reads = sequence();
  for (const auto& [mrs, first] : {std::pair{0xA1, 4U}, {0xA3, 16U}, {0xA5, 32U}}) {
    reads.frame(MC::SelectionOfMemoryArea, static_cast<std::uint8_t>(mrs));
    for (unsigned w = first; w < (first == 4 ? 16U : first + 16); ++w)
      reads.frame(MC::EncoderSendParameters, static_cast<std::uint8_t>(w % 16), 0, Operation::Purpose::ChecksumWord, w);
  }
  checksum_ = ChecksumCheck{};
  checksum_words_.assign(48, 0);
  checksum_read_ = 0;
  run_first(reads);
}

void Master::note_checksum_word(const FrameResult& f) {
  if (current_->purpose != Operation::Purpose::ChecksumWord || f.outcome != FrameOutcome::Ok) return;
  checksum_words_.at(current_->manufacturer_word) = f.echo_parameter;
  if (++checksum_read_ < 44 || current_->manufacturer_word != 47) return;
  checksum_->complete = true;
  checksum_->stored = checksum_words_[47];
  std::uint16_t sum = 0;
  for (unsigned w = 4; w <= 46; ++w) sum = static_cast<std::uint16_t>(sum + checksum_words_[w]);
  checksum_->computed = sum;
}

// ---- a careful master ---------------------------------------------------------------------

void Master::line_changed() {
  if (params_.careful.remeasure_after_line_change && params_.delay_compensation) remeasure_due_ = true;
}

void Master::encoder_power_interrupted() {
  if (params_.careful.remeasure_after_power_interruption && params_.delay_compensation) remeasure_due_ = true;
  if (params_.careful.reselect_after_power_interruption && (selected_[0] || selected_[1])) reselect_due_ = true;
}

void Master::note_failures() {
  if (frame_.measurement) return;
  const auto o = frame_.outcome;
  const bool failed = o == FrameOutcome::CrcError || o == FrameOutcome::NoStartBit || o == FrameOutcome::Type1Error ||
                      o == FrameOutcome::EchoMismatch || o == FrameOutcome::TooFewClocks;
  failures_in_a_row_ = failed ? failures_in_a_row_ + 1 : 0;
  const unsigned k = params_.careful.remeasure_after_crc_errors;
  if (k != 0 && failures_in_a_row_ >= k && params_.delay_compensation) {
    remeasure_due_ = true;
    failures_in_a_row_ = 0;
  }
}

bool Master::retry_frame() {
  const auto o = frame_.outcome;
  const bool failed = o != FrameOutcome::Ok && o != FrameOutcome::Type2Error;
  if (current_->kind != Operation::Kind::ReadPosition || frame_.measurement || !failed ||
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
  return std::max(Time::zero(), frame_.end + params_.t_b_wait - kernel_.now());
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

void Master::operation_frame_done() {
  if (current_->kind == Operation::Kind::AwaitNotBusy) {
    // 2.5.1 / 2.6.1: poll additional data 1 until the busy bit is reset.
    const auto& ai = frame_.additional_data;
    const bool ok = frame_.outcome == FrameOutcome::Ok;
    const auto is_1 = [](const AdditionalDatum& d) { return !protocol::is_additional_data_2(d.information()); };
    const bool ready = ok && std::any_of(ai.begin(), ai.end(), [&](const AdditionalDatum& d) { return is_1(d) && !d.busy(); });
    const bool unreadable = ok && std::none_of(ai.begin(), ai.end(), is_1);
    if (ready) frames_left_ = 1;
    else if (unreadable) {
      ++busy_unreadable_;
      frames_left_ = 1;
    } else if (frames_left_ == 1) ++busy_timeouts_;
  }
  if (current_->kind == Operation::Kind::StartupPositions && startup_position_read(frame_)) frames_left_ = 1;
  note_failures();
  if (retry_frame()) return;
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
  const bool measurement = delay_.active();
  frame_ = FrameResult{};
  frame_.index = frame_count_;
  frame_.operation = current_->script_index;
  frame_.start = kernel_.now();
  frame_.measurement = measurement;
  frame_.command = measurement ? ModeCommand::EncoderSendPositionValues : current_->command;
  supplement_word_ = std::uint32_t{current_->address} << 16 | current_->parameter;
  if (!measurement) roll_additional_data_1();
  frame_.mode_bits = measurement || !current_->mode_bits ? protocol::info(frame_.command).bits : *current_->mode_bits;
  frame_.f_c = measurement                            ? params_.measurement.f_c
               : of_startup_routine(current_->purpose) ? params_.startup_f_c
                                                       : params_.f_c;
  frame_.compensated = !measurement && params_.delay_compensation && t_d_.has_value();
  frame_.t_d_used = frame_.compensated ? *t_d_ : Time::zero();

  command_ = &protocol::info(frame_.command);
  payload_ = measurement ? 0 : supplement_word_;
  if (command_->payload_bits != 0) frame_.payload = payload_;
  supplement_start_ = 0;
  supplement_due_ = false;
  f_ = frame_.f_c;
  const Time period = sim::period_of(f_);
  high_ = period * params_.high_permille / 1000;
  low_ = period - high_;
  mode_bits_ = frame_.mode_bits;
  layout_ = protocol::answer_layout(*command_, position_bits_);
  frame_.answer_bits = answer_width();
  frame_.position_bits = position_bits_;
  clock_ = 0;
  last_clock_ = 0;
  clocking_done_ = false;
  rx_ = Rx::Polling;
  seen_low_ = false;
  require_low_ = params_.start_bit_detection == StartBitDetection::WaitLowThenHigh;
  high_samples_ = 0;
  rx_bits_.clear();
  words_left_ = measurement ? 0 : current_->continuous_words;
  poll_start_ = kernel_.now();
  ++epoch_;
  delay_.frame_started(measurement, rng_);
  frame_running_ = true;

  frame_active_.write(true);
  for (auto* o : observers_) o->on_frame_start(frame_);
  nominal_ = kernel_.now();
  falling_edge();
}

Time Master::jittered(Time nominal) {
  if (params_.jitter == Time::zero()) return nominal;
  boost::random::uniform_int_distribution<std::int64_t> d(-params_.jitter.count(), params_.jitter.count());
  return std::max(kernel_.now(), nominal + Time{d(rng_)});
}

void Master::falling_edge() {
  ++clock_;
  clock_low_ = true;
  pins_.clock_out.write(false);
  // 2.3: the master enables its driver with the second falling edge, sends a dummy 0 and the
  // six mode bits M2 first on falling edges 3 .. 8, then (2.1 parameter frames, docs/model.md
  // §3) 8 + 16 bits MSB first, and releases DATA after them.
  const unsigned payload = command_->payload_bits;
  const unsigned release = kFirstPolledClock + payload;
  if (clock_ == position::kMasterDrives) {
    pins_.data_enable.write(true);
    pins_.data_out.write(false);
  } else if (clock_ >= position::kFirstModeBit && clock_ <= position::kLastModeBit) {
    pins_.data_out.write(((mode_bits_ >> (position::kLastModeBit - clock_)) & 1U) != 0);
  } else if (clock_ > position::kLastModeBit && clock_ < release) {
    pins_.data_out.write(((payload_ >> (release - 1 - clock_)) & 1U) != 0);
  } else if (clock_ == release) {
    pins_.data_enable.write(false);
    pins_.data_out.write(false);
    if (payload != 0) poll_start_ = kernel_.now();
  }
  if (supplement_due_) drive_supplement_bit();
  // Without compensation DATA is taken at the falling edge; with it at FE + t_D (2.3).
  if (clock_ > release && rx_ != Rx::Done) {
    const unsigned slot = clock_ - 1;
    if (frame_.compensated) kernel_.schedule(frame_.t_d_used, sim::bind<&Master::sample>(this, sample_tag(epoch_, slot)));
    else sample_now(slot);
  }
  // 2.3.2 note 8: the first LOW phase is stretched to t_ST.
  nominal_ += clock_ == position::kFrameStart ? std::max(low_, params_.t_st) : low_;
  edge_timer_.start(jittered(nominal_) - kernel_.now());
}

void Master::clock_edge() {
  if (clock_low_) rising_edge();
  else falling_edge();
}

void Master::rising_edge() {
  clock_low_ = false;
  pins_.clock_out.write(true);
  frame_.end = kernel_.now();
  frame_.clocks = clock_;
  delay_.clock_rose(kernel_.now(), clock_);
  const Time timeout = command_->payload_bits != 0 ? params_.memory_access_timeout : params_.start_bit_timeout;
  if (rx_ == Rx::Polling && kernel_.now() - poll_start_ > timeout) {
    end_reception(FrameOutcome::NoStartBit);
  }
  // The encoder takes the supplement's last bit on this edge, so DATA must stay valid after it.
  // Released with the edge itself, the release would race the edge to the encoder, which takes
  // the fail-safe HIGH whenever the master's driver turns off faster than its CLOCK driver
  // switches. Every other bit the master sends stays until the next falling edge, half a period
  // after the encoder's edge, and at the highest f_c (16 MHz, D297403 2.3.2) that is all any
  // encoder can rely on: the last bit is held that long too (or half this frame's period, if
  // shorter), and the master is off the line long before the encoder takes DATA back for t_m.
  if (supplement_start_ != 0 && clock_ == last_clock_)
    kernel_.schedule(std::min(high_, sim::period_of(MasterParams::kMaxFc) / 2),
                     sim::bind<&Master::release_supplement>(this));
  const bool answered = rx_ == Rx::Done && !supplement_due_ && (last_clock_ == 0 || clock_ >= last_clock_);
  if (answered || (last_clock_ != 0 && clock_ >= last_clock_ && words_left_ == 0)) {
    clocking_done_ = true;
    if (!params_.extra_clock_after_last_bit && rx_ == Rx::Receiving) {
      // No further pulse: the last bit is taken where the next falling edge would be.
      const Time at = high_ + frame_.t_d_used;
      kernel_.schedule(at, sim::bind<&Master::sample>(this, sample_tag(epoch_, clock_)));
    }
    // Too few pulses (a fault): the answer stays incomplete once the last sample is due.
    if (rx_ == Rx::Receiving)
      kernel_.schedule(high_ + frame_.t_d_used + low_, sim::bind<&Master::incomplete>(this, sample_tag(epoch_, 0)));
    maybe_complete_frame();
    return;
  }
  nominal_ += high_;
  edge_timer_.start(jittered(nominal_) - kernel_.now());
}

void Master::incomplete(std::uint64_t tag) {
  if ((tag >> 32) != epoch_ || rx_ != Rx::Receiving) return;
  end_reception(FrameOutcome::TooFewClocks);
}

void Master::sample(std::uint64_t tag) {
  if ((tag >> 32) != epoch_ || rx_ == Rx::Done) return;  // a frame that has ended
  sample_now(static_cast<unsigned>(tag & 0xFFFF'FFFF));
}

void Master::sample_now(unsigned clock) {
  const bool value = pins_.data_in.read();
  sample_strobe_.write(!sample_strobe_.read());
  bool in_data = rx_ == Rx::Receiving;
  switch (rx_) {
    case Rx::Polling:
      // Fail-safe receivers read HIGH on the undriven line: wait for LOW, then the start bit.
      if (!seen_low_ && require_low_) {
        seen_low_ = !value;
        if (value && ++high_samples_ >= params_.type1_detect_samples) {
          for (auto* o : observers_) o->on_sample(frame_, clock, value, false);
          end_reception(FrameOutcome::Type1Error);
          return;
        }
      } else if (value) {
        in_data = true;
        rx_ = Rx::Receiving;
        rx_bits_.assign(1, 1);
        frame_.start_bit_clock = clock;
        const unsigned last_bit_clock = clock + answer_width() - 1;
        // A frame with a supplement clocks on until the master has checked the answer.
        if (!command_->supplement) {
          const int adjust = frame_.measurement ? 0 : current_->clock_adjust;  // a fault: too many or too few
          const int last = static_cast<int>(last_bit_clock + (params_.extra_clock_after_last_bit ? 1 : 0)) + adjust;
          last_clock_ = static_cast<unsigned>(std::max(last, static_cast<int>(clock)));
        }
      }
      break;
    case Rx::Receiving:
      rx_bits_.push_back(value ? 1 : 0);
      break;
    case Rx::Off:
    case Rx::Done:
      return;
  }
  for (auto* o : observers_) o->on_sample(frame_, clock, value, in_data);
  if (rx_ == Rx::Receiving && rx_bits_.size() == answer_width()) decode_answer();
}

unsigned Master::answer_width() const {
  const bool additional_data = command_->answer == protocol::AnswerFormat::Position &&
                               command_->version == protocol::EndatVersion::V2_2 && !frame_.measurement;
  return layout_.width() + (additional_data ? protocol::kAdditionalDatumBits * expected_additional_data() : 0);
}

void Master::decode_answer() {
  using protocol::Field;
  const auto values = layout_.decode(rx_bits_);
  const auto field = [&](Field f) { return values[static_cast<std::size_t>(f)]; };
  frame_.crc_received = static_cast<std::uint8_t>(field(Field::Crc));
  bool ok = true;
  switch (command_->answer) {
    case protocol::AnswerFormat::Position: {
      const bool v22 = command_->version == protocol::EndatVersion::V2_2;
      frame_.error1 = field(Field::Error1) != 0;
      frame_.error2 = v22 ? field(Field::Error2) != 0 : true;
      frame_.position = field(Field::Position);
      frame_.crc_expected = expected_crc_pos(position_bits_, frame_.error1, frame_.error2, v22, frame_.position);
      const auto ai_layout = protocol::additional_datum_layout();
      for (std::size_t at = layout_.width(); at < rx_bits_.size(); at += protocol::kAdditionalDatumBits) {
        const auto v = ai_layout.decode(std::span(rx_bits_).subspan(at));
        AdditionalDatum d;
        d.status = static_cast<std::uint8_t>(v[static_cast<std::size_t>(Field::Status)]);
        d.data = static_cast<std::uint16_t>(v[static_cast<std::size_t>(Field::AdditionalData)]);
        d.crc_received = static_cast<std::uint8_t>(v[static_cast<std::size_t>(Field::Crc)]);
        d.crc_expected = protocol::make_crc_norm(d.status, d.data, params_.crc.generator);
        d.crc_ok = crc_passes(d.crc_received, d.crc_expected) && v[static_cast<std::size_t>(Field::LeadingLow)] == 0;
        ok = ok && d.crc_ok;
        frame_.additional_data.push_back(d);
      }
      break;
    }
    case protocol::AnswerFormat::TestValues:
      frame_.error1 = field(Field::Error1) != 0;
      frame_.test_value = field(Field::TestValue);
      frame_.crc_expected = expected_crc_pos(protocol::kTestValueBits, frame_.error1, true, false, frame_.test_value);
      break;
    case protocol::AnswerFormat::Parameter:
      frame_.echo_address = static_cast<std::uint8_t>(field(Field::Address));
      frame_.echo_parameter = static_cast<std::uint16_t>(field(Field::Parameter));
      frame_.crc_expected = protocol::make_crc_norm(frame_.echo_address, frame_.echo_parameter, params_.crc.generator);
      break;
  }
  ok = ok && crc_passes(frame_.crc_received, frame_.crc_expected);
  FrameOutcome outcome = ok ? FrameOutcome::Ok : FrameOutcome::CrcError;
  // A2 type II: "the address or parameter is returned inverted".
  if (ok && command_->answer == protocol::AnswerFormat::Parameter &&
      frame_.echo_address == static_cast<std::uint8_t>(~(payload_ >> 16)))
    outcome = FrameOutcome::Type2Error;
  outcome = check_echo(outcome);
  // 2.4.2 ff.: "following transmission of the position value and CRC it must be monitored if an
  // error has occurred": the supplement only follows a clean answer.
  if (outcome == FrameOutcome::Ok && command_->supplement) {
    supplement_due_ = true;
    frame_.supplement = supplement_word_;
  }
  if (outcome == FrameOutcome::Ok) note_selection();
  word_received(outcome);
}

// The CRC the master expects, as its CrcCheck computes it (the spec's by default, A4).
std::uint8_t Master::expected_crc_pos(unsigned bits, bool error1, bool error2, bool v22, std::uint64_t position) const {
  const auto& c = params_.crc;
  const bool with_f2 = v22 || c.endat22_rule_for_21;
  // A table loop one step short at its faulty width leaves the last position bit out.
  const unsigned fed = bits == c.table_fault_width ? bits - 1 : bits;
  return protocol::make_crc_pos(fed, error1, error2, with_f2, position, c.generator);
}

// 2.1 parameter frames echo the address (MRS code, port) and, except for a read, the parameter.
FrameOutcome Master::check_echo(FrameOutcome outcome) const {
  if (!params_.careful.verify_echo || outcome != FrameOutcome::Ok || command_->answer != protocol::AnswerFormat::Parameter)
    return outcome;
  const bool address_ok = frame_.echo_address == static_cast<std::uint8_t>(payload_ >> 16);
  const bool parameter_ok = frame_.command == ModeCommand::EncoderSendParameters ||
                            frame_.echo_parameter == static_cast<std::uint16_t>(payload_);
  return address_ok && parameter_ok ? outcome : FrameOutcome::EchoMismatch;
}

void Master::drive_supplement_bit() {
  // docs/model.md §4: lead LOW bits, a start bit 1, then 8 + 16 bits MSB first, on falling edges.
  if (supplement_start_ == 0) {
    supplement_start_ = clock_;
    last_clock_ = clock_ + params_.supplement_lead_bits + protocol::kPayloadBits;
  }
  const unsigned k = clock_ - supplement_start_;
  const unsigned lead = params_.supplement_lead_bits;
  if (k == lead - params_.supplement_driven_lead_bits) pins_.data_enable.write(true);
  bool bit = false;
  if (k == lead) bit = true;
  else if (k > lead) bit = ((*frame_.supplement >> (protocol::kPayloadBits - (k - lead))) & 1U) != 0;
  pins_.data_out.write(bit);
}

void Master::release_supplement() { pins_.data_enable.write(false); }

void Master::note_selection() {
  // What the master expects after its own selections (2.4.2.2); a reset clears them (2.7).
  if (frame_.command == ModeCommand::EncoderReceiveReset) {
    selected_[0] = selected_[1] = false;
    return;
  }
  if (frame_.command != ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea) return;
  const auto mrs = static_cast<std::uint8_t>(supplement_word_ >> 16);
  if (!protocol::selects_additional_data(mrs)) return;
  const unsigned which = (mrs & 0x10) != 0 ? 1 : 0;
  selected_[which] = mrs != protocol::kStopAdditionalData1 && mrs != protocol::kStopAdditionalData2;
  selection_mrs_[which] = mrs;
}

void Master::record(const FrameResult& f) {
  ++frame_count_;
  if (frames_.size() < kept_frames_) frames_.push_back(f);
  recent_starts_.push_back(f.start);
  while (recent_starts_.size() > std::max<std::size_t>(params_.measurement.count, 1)) recent_starts_.pop_front();
}

void Master::word_received(FrameOutcome outcome) {
  if (words_left_ == 0) {
    end_reception(outcome, true);
    return;
  }
  // Continuous clock (2.3.1): keep clocking; after the HIGH bit and the LOW bits the next word
  // starts with its start bit, without a new mode command.
  frame_.outcome = outcome;
  frame_.end = kernel_.now();
  record(frame_);
  for (auto* o : observers_) o->on_result(frame_);
  --words_left_;
  ++frame_.word;
  frame_.index = frame_count_;
  frame_.start_bit_clock = 0;
  rx_ = Rx::Polling;
  seen_low_ = false;
  require_low_ = true;  // the HIGH bit after the CRC is not a start bit
  high_samples_ = 0;
  rx_bits_.clear();
  last_clock_ = 0;
  poll_start_ = kernel_.now();
}

void Master::end_reception(FrameOutcome outcome, bool answer_complete) {
  rx_ = Rx::Done;
  frame_.outcome = outcome;
  delay_.stop_counter();
  if (supplement_due_) return;  // clocking goes on through the supplement
  if (last_clock_ == 0 || (last_clock_ > clock_ && !answer_complete)) {
    // Aborted: finish the current clock period and leave CLOCK HIGH (A2: wait t_m).
    last_clock_ = clock_;
    if (!clock_low_) {
      edge_timer_.cancel();
      clocking_done_ = true;
    }
  }
  maybe_complete_frame();
}

void Master::maybe_complete_frame() {
  if (!frame_running_ || !clocking_done_ || rx_ != Rx::Done) return;
  frame_running_ = false;
  frame_active_.write(false);
  const bool error_handling = frame_.outcome == FrameOutcome::NoStartBit || frame_.outcome == FrameOutcome::Type1Error;
  ready_at_ = frame_.end + (error_handling ? params_.error_wait : params_.t_m_wait) + params_.t_r_wait;
  if (frame_.command == ModeCommand::EncoderReceiveReset && frame_.outcome == FrameOutcome::Ok)
    ready_at_ = std::max(ready_at_, frame_.end + params_.reset_wait);
  if (frame_.measurement && frame_.outcome == FrameOutcome::Ok)
    if (const auto count = delay_.take_count()) frame_.delay_count_time = *count;
  if (!frame_.measurement) {
    book_.note(frame_);
    diagnosis_.on_frame(frame_, diagnosis_frame(current_->purpose));
    note_safety(frame_);  // sets error_detected: what the master made of F1 and F2
    note_startup(frame_);
    note_checksum_word(frame_);
  }
  record(frame_);
  for (auto* o : observers_) o->on_frame_end(frame_);
  for (auto* o : observers_) o->on_result(frame_);
  operation_frame_done();
}

// ---- propagation-delay measurement (2.1.2) -----------------------------------------------

void Master::on_data_in(std::uint64_t level) {
  if (level != 0) delay_.data_rose(kernel_.now());
}

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
