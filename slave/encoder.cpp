#include "endatsim/slave/encoder.hpp"

#include "endatsim/sim/parameter.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/eib.hpp"

namespace endatsim::slave {
namespace {

using protocol::ErrorCause;
namespace position = protocol::frame_position;
using MC = ModeCommand;
using sim::require;
using protocol::parameters::EncoderFunction;
namespace pm = protocol::parameters;

}  // namespace

Encoder::Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params)
    : Encoder(kernel, line.encoder(), params) {}

Encoder::Encoder(sim::Kernel& kernel, line::Line::EncoderSide pins, const EncoderParams& params)
    : kernel_(kernel), pins_(pins), params_(params),
      memory_((params.validate(), params.memory.value_or(default_memory_image(params)))),
      positions_(params_, memory_), additional_data_(params_, memory_, positions_),
      errors_(params_, memory_, positions_, additional_data_), eib_(params_, memory_),
      access_(kernel, memory_, additional_data_, *this), commands_(params_, memory_, access_, additional_data_, eib_, bus_),
      driver_(kernel, pins_, params.output_delay),
      recovery_timer_(kernel, sim::bind<&Encoder::on_recovery_time_elapsed>(this)),
      end_marker_timer_(kernel, sim::bind<&Encoder::on_end_marker_due>(this)),
      readiness_(kernel, sim::bind<&Encoder::on_started>(this), params.unsettled_positions) {
  pins_.clock_in.on_change(sim::bind<&Encoder::on_clock>(this));
  adopt_encoder_type(params_.position_bits);
  positions_.apply_function_initialization(kernel_.now());
  errors_.note_bus_address();
  enable();  // idle: DATA driven LOW, unless word 5 puts the driver at high impedance (2.10)
  if (params_.startup_time > Time::zero()) go_offline(params_.startup_time);
}

// 3.5.7: what the encoder is follows word 14: absolute or incremental with its reference marks
// (2.3.4.3), a touch probe (2.3.4.4), or an EIB that is not yet initiated (A2 cause 5), whose
// manufacturer areas stay open for initial commissioning meanwhile.
void Encoder::adopt_encoder_type(unsigned position_bits) {
  const auto type = pm::decode_encoder_type(memory_.manufacturer_word(word::kEncoderType));
  eib_.follow_encoder_type(type);
  positions_.adopt(type, position_bits);
}

// The EIB has become the connected encoder (eib.hpp). Relative positions count from here, as
// after switching on (2.3.4.3).
void Encoder::commissioned(std::optional<unsigned> position_bits) {
  if (!position_bits) return;
  adopt_encoder_type(*position_bits);
  positions_.count_from(kernel_.now());
}

// 2.3.3 (the figure's labels in the German brochure, older edition: "*) hochohmig"; docs/model.md §8): during
// run-up DATA is high-impedance and the encoder takes no clock; afterwards DATA is driven LOW,
// the EnDat idle level (2.3).
void Encoder::go_offline(Time duration) {
  state_ = State::Idle;
  release();
  readiness_.run_up(duration);
}

void Encoder::on_started() {
  drive(false);
  enable();
}

bool Encoder::drives_bus() const { return bus_.drives(memory_.instructions()); }

void Encoder::on_clock(std::uint64_t level) {
  if (!readiness_.takes_edge()) return;  // running up, or t_R: not ready for the next query yet
  if (level == 0) on_falling_edge();
  else on_rising_edge();
}

// ---- the frame, edge by edge ---------------------------------------------------------------

void Encoder::begin_frame() {
  // 2.2: "the position value is saved in the encoder with the falling clock edge";
  // 2.3: "with the first falling clock edge, the send block in the encoder must be deactivated".
  state_ = State::Header;
  clock_ = 1;
  mode_bits_ = 0;
  command_ = nullptr;
  commands_.forget_pending();
  answer_.clear();
  EncoderFrame f;
  f.start = kernel_.now();
  positions_.update_reference(f.start);
  positions_.check_multiturn_overflow(f.start);
  f.true_position = positions_.latched(f.start);
  f.position = positions_.sent(f.true_position);
  frames_.add(f);
  errors_.latch();
  frames_.last().error_present = errors_.error_present();
  if (sim::Tape* tape = kernel_.tape()) tape->add(sim::TapeItem::Kind::Model, kernel_.now(), this, static_cast<std::uint32_t>(Note::Begin), 0);
  release();
}

void Encoder::on_falling_edge() {
  recovery_timer_.cancel();
  if (state_ == State::Idle) {
    begin_frame();
    return;
  }
  ++clock_;
  EncoderFrame& f = frames_.last();
  const unsigned payload = command_ != nullptr ? command_->payload_bits : 0;
  switch (state_) {
    case State::Type1:
    case State::Answer:
      if (clock_ == params_.driver_enable_edge + payload) {
        drive(state_ == State::Type1 && params_.type1 == Type1Handling::AbortHigh);
        enable();
      }
      break;
    case State::EndOfData:
      // 2.3.1: a continuous clock is only possible with "Encoder send position values";
      // the next position is saved with the falling edge after the HIGH bit.
      if (f.command == MC::EncoderSendPositionValues) {
        f.continuous_positions.push_back(positions_.latched(kernel_.now()));
        ++f.continuous_words;
        state_ = State::ContinuousGap;
        gap_low_bits_ = 0;
      } else if (payload != 0) {
        f.too_many_clocks = true;  // 2.4.1: "more clock pulses than required" -> A2
      }
      break;
    default:
      break;
  }
}

void Encoder::on_rising_edge() {
  recovery_timer_.start(recovery_time());
  if (state_ == State::Idle) return;  // a rising edge without a frame: nothing to do
  EncoderFrame& f = frames_.last();
  f.clocks = clock_;
  const bool bit = pins_.data_in.read();
  switch (state_) {
    case State::Header:
      // 2.3: the encoder accepts the mode bits on the rising edges of clocks 3 .. 8.
      if (clock_ >= position::kFirstModeBit && clock_ <= position::kLastModeBit)
        mode_bits_ = static_cast<std::uint8_t>(mode_bits_ << 1 | bit);
      if (clock_ == position::kLastModeBit) decode_mode_command();
      break;
    case State::Payload:
      if (received_.take(bit)) answer_parameter_frame();
      break;
    case State::Answer:
      emit_answer_bit();
      break;
    case State::ContinuousGap:
      if (gap_low_bits_ < params_.continuous_low_bits) {
        ++gap_low_bits_;
        drive(false);
      } else {
        load_continuous_word();
        emit_answer_bit();
      }
      break;
    case State::HandoverLevel:
      hand_over_for_supplement();
      break;
    case State::SupplementHunt:
      // docs/model.md §4: the line floats (fail-safe HIGH) until the master drives its lead
      // bits, so the encoder waits for a LOW before it takes a HIGH as the start bit. Right
      // after its release it still sees its own last bit, so it ignores a few edges.
      if (supplement_start_.found(clock_, bit, params_.supplement_ignore_clocks)) {
        state_ = State::Supplement;
        received_.clear();
      }
      break;
    case State::Supplement:
      if (received_.take(bit)) process_supplement();
      break;
    case State::SupplementDone:
      clock_after_supplement();
      break;
    default:
      break;
  }
}

// 2.4.2.1: "If a non-permissible memory area is received by the encoder or more clock pulses than
// necessary are sent, an error message is output compliant to Appendix A2": cause 2, type II, the
// MRS code and block address acknowledged inverted; the selection does not take place.
void Encoder::clock_after_supplement() {
  EncoderFrame& f = frames_.last();
  if (f.too_many_clocks) return;
  f.too_many_clocks = true;
  const auto address = protocol::payload_address(f.supplement.value_or(0));
  if (command_->command != MC::EncoderSendPositionValuesAndSelectionOfMemoryArea ||
      protocol::selects_additional_data(address) || f.supplement_ignored)
    return;
  f.error = ErrorCause::MrsFrameDisrupted;
  commands_.selection_disrupted(f.supplement.value_or(0));
}

void Encoder::decode_mode_command() {
  EncoderFrame& f = frames_.last();
  f.mode_bits = mode_bits_;
  f.command = protocol::decode_mode_bits(mode_bits_);
  if (!f.command || (protocol::info(*f.command).version == EndatVersion::V2_2 && params_.version == EndatVersion::V2_1))
    return abort_type1(ErrorCause::ModeCommandDisrupted);
  command_ = &protocol::info(*f.command);
  if (command_->answer == protocol::AnswerFormat::Position && eib_.refuses_positions())
    return abort_type1(ErrorCause::ModeCommandDisrupted);
  if (!bus_.selected() && *f.command != MC::EncoderReceiveCommunicationCommand) {
    state_ = State::Type1;  // 2.10: only the addressed encoder reacts; this one keeps off the bus
    return;
  }
  if (command_->payload_bits != 0) {
    state_ = State::Payload;
    received_.clear();
    return;
  }
  answer_position();
}

void Encoder::abort_type1(ErrorCause cause) {
  EncoderFrame& f = frames_.last();
  f.type1_error = true;  // appendix A2, type I: mode command disrupted or not supported
  f.error = cause;
  state_ = State::Type1;
}

// What a completed write sets going besides the stored word: an EIB's commissioning (3.5.7), the
// bus address error (3.6.4), and the RM reset of operating parameters 2 word 11 (3.10.5). A 2.1
// write completes with its acknowledgment, a 2.2 one when Busy is reset (3.10).
void Encoder::written(const Selection& s, std::uint8_t address) {
  commissioned(eib_.completes_at_write(s, address));
  errors_.note_bus_address();
  // 3.10.5: bit 0 = 1 and bit 1 = 0 reset RM of an incremental encoder and set the warning
  // "reference point not reached"; "this does not influence position value and position value 2":
  // the reference found stays in use. A reference mark crossed from then on sets RM again.
  if (s.area == MemoryArea::OperatingParameters2 && address == word::kReferencing &&
      (memory_.word(s, word::kReferencing) & pm::kReferencingMask) == pm::kReferencingResetRm)
    positions_.reset_reference_mark(kernel_.now());
}

void Encoder::answer_position() {
  EncoderFrame& f = frames_.last();
  state_ = State::Answer;
  const bool energy_saving = (memory_.instructions() & pm::kInstructionEnergySaving) != 0;  // 3.6.5
  // 2.3.2: t_cal runs from FE1.
  answer_.not_before(params_.earliest_start_bit_clock, f.start + params_.t_cal_for(command_->version, energy_saving));
  if (command_->answer == protocol::AnswerFormat::TestValues) {
    const auto it = params_.sensors.test_values.find(commands_.test_port());
    answer_.load(protocol::encode_test_values(errors_.error_message_1(),
                                              it == params_.sensors.test_values.end() ? 0 : it->second, params_.crc));
    return;
  }
  if (readiness_.take_unsettled()) {  // a fault: a value from before the position settled (seeded by the frame)
    const std::uint64_t mask = protocol::position_mask(positions_.position_bits());
    std::uint64_t z = (frames_.count() + 1) * 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    f.position = (z ^ (z >> 31)) & mask;
  }
  // 2.3.1: F2 is low-active; it is only sent with 2.2 mode commands.
  answer_.load(protocol::encode_position_frame(command_->version, positions_.position_bits(),
                                               {errors_.error_message_1(), !errors_.error_message_2(), f.position}, params_.crc));
  if (command_->version == EndatVersion::V2_2)
    additional_data_.append(answer_.bits(), f.additional_data_status, f.start, f.true_position, busy());
}

void Encoder::answer_parameter_frame() {
  EncoderFrame& f = frames_.last();
  f.payload = received_.value();
  const auto d = commands_.decide(command_->command, received_.value(), kernel_.now());
  if (d.silent) {
    state_ = State::Type1;  // 2.10: another encoder is addressed
    return;
  }
  if (d.error) f.error = d.error;
  answer_.load(protocol::encode_parameter_frame(d.address, d.parameter, params_.crc));
  state_ = State::Answer;
  answer_.not_before(params_.earliest_start_bit_clock + protocol::kPayloadBits, kernel_.now() + d.start_delay);
}

void Encoder::emit_answer_bit() {
  EncoderFrame& f = frames_.last();
  if (!answer_.started() && f.continuous_words == 0) {
    // docs/model.md §1: LOW until t_cal (or t_ac) has elapsed, start bit no earlier than RE11
    // (RE35 after a 2.1 parameter frame).
    if (!answer_.start_due(clock_, kernel_.now())) {
      drive(false);
      return;
    }
    f.start_bit_clock = clock_;
  }
  if (!answer_.sent()) {
    drive(answer_.next());
    return;
  }
  if (command_->supplement) {
    if (params_.supplement_handover == SupplementHandover::EndLevel) {
      drive(true);  // 2.3: the level after the CRC says that no additional data follows
      state_ = State::HandoverLevel;
      return;
    }
    hand_over_for_supplement();
    return;
  }
  // docs/model.md §2: after the last CRC bit DATA goes HIGH and stays HIGH for t_m.
  drive(true);
  state_ = State::EndOfData;
}

// docs/model.md §4: the encoder hands DATA to the master for the command supplement.
void Encoder::hand_over_for_supplement() {
  release();
  state_ = State::SupplementHunt;
  supplement_start_.handed_over(clock_);
}

void Encoder::load_continuous_word() {
  EncoderFrame& f = frames_.last();
  answer_.load(protocol::encode_position_frame(EndatVersion::V2_1, positions_.position_bits(),
                                               {errors_.error_message_1(), true, f.continuous_positions.back()}, params_.crc));
  state_ = State::Answer;
}

// ---- EnDat 2.2 command supplement and additional data ------------------------------------

void Encoder::process_supplement() {
  EncoderFrame& f = frames_.last();
  f.supplement = received_.value();
  state_ = State::SupplementDone;
  end_marker_timer_.start(params_.supplement_end_marker_delay);
  const auto d = commands_.decide_supplement(command_->command, received_.value());
  f.supplement_ignored = d.ignored;
  if (d.memory_access) f.error = d.error;
}

void Encoder::on_end_marker_due() {
  if (state_ != State::SupplementDone) return;
  drive(true);
  enable();
}

// ---- end of frame, reset ---------------------------------------------------------------------

Time Encoder::recovery_time() const {
  const bool v22 = state_ != State::Idle && command_ != nullptr && command_->version == EndatVersion::V2_2;
  // 3.4.4: word 3 bits 0/1 choose the short recovery time, for 2.2 mode commands only, and only
  // after the reset that activates word 3.
  return v22 && memory_.function_activated(EncoderFunction::ShortRecoveryTime) && params_.t_m_short ? *params_.t_m_short : params_.t_m;
}

void Encoder::on_recovery_time_elapsed() {
  // 2.3: "The transfer is terminated after expiry of a certain time (recovery time I)":
  // DATA falls back to LOW and the encoder is ready again after t_R.
  if (state_ == State::Idle) return;
  finish_frame();
}

void Encoder::finish_frame() {
  end_frame();
  if (sim::Tape* tape = kernel_.tape()) {
    recorded_.push_back(frames_.last());
    tape->add(sim::TapeItem::Kind::Model, kernel_.now(), this, static_cast<std::uint32_t>(Note::Finish), recorded_.size() - 1);
  }
}

// ---- the frame-level fast path ----------------------------------------------------------------

bool Encoder::frame_invariant() const {
  return state_ == State::Idle && !readiness_.running_up() && readiness_.settled() && !busy() &&
         !recovery_timer_.pending() && !end_marker_timer_.pending() && positions_.frame_invariant() &&
         additional_data_.frame_invariant();
}

bool Encoder::latches_again(const EncoderFrame& recorded, Time shift, Time until) const {
  for (const std::uint64_t p : recorded.continuous_positions)
    if (p != recorded.true_position) return false;
  const Time from = recorded.start + shift;
  return positions_.latches_again(from, recorded.true_position) && holds_position(from, until);
}

// What begin_frame and finish_frame do to the encoder, without the pins: the frame's record is
// the recorded one at its new time.
void Encoder::replay(const sim::TapeItem& item, const std::vector<EncoderFrame>& frames, Time shift) {
  const Time now = kernel_.now();
  if (static_cast<Note>(item.index) == Note::Begin) {
    positions_.update_reference(now);
    positions_.check_multiturn_overflow(now);
    (void)positions_.sent(positions_.latched(now));
    errors_.latch();
    frames_.add(moved(frames.at(frames.size() - 1), shift));
    return;
  }
  end_marker_timer_.cancel();
  bus_.frame_ended();
  readiness_.frame_ended(params_.t_r);
}

void Encoder::end_frame() {
  EncoderFrame& f = frames_.last();
  // A 2.1 parameter frame that ends before its 8 + 16 bits are in (A2 cause 3).
  if (state_ == State::Payload) commands_.transmission_cut_short();
  state_ = State::Idle;
  end_marker_timer_.cancel();
  bus_.frame_ended();
  drive(false);
  enable();
  readiness_.frame_ended(params_.t_r);
  using Pending = ParameterCommands::Pending;
  const Pending pending = commands_.take_pending();
  if (f.too_many_clocks && pending.kind != Pending::Kind::None) {
    f.error = ErrorCause::MrsFrameDisrupted;  // the access is discarded
    access_.discard_nvm_write();
    return;
  }
  switch (pending.kind) {
    case Pending::Kind::Select:
      access_.select(pending.selection);
      break;
    case Pending::Kind::Write:
      access_.write(pending.selection, pending.address, pending.value);
      break;
    case Pending::Kind::Reset:
      reset();
      break;
    case Pending::Kind::None:
      break;
  }
}

void Encoder::reset() {
  restart_state();
  if (params_.reset_time > Time::zero()) go_offline(params_.reset_time);
}

void Encoder::restart_state() {
  // 2.7 ("same reaction as from switching power on and off", the English brochure): additional data
  // deselected (2.4.2.2), word 2, word 3 and the operating parameters activated (3.4.3, 3.4.4, 3.6).
  memory_.activate_on_reset();
  positions_.apply_function_initialization(kernel_.now());
  additional_data_.restart();
  access_.restart();
  // 3.5.7: an EIB becomes the connected encoder at reset or power-on (EibActivation::Reset).
  commissioned(eib_.completes_at_reset());
  positions_.restart_reference_search(kernel_.now());
  commands_.restart();
  readiness_.restart_settling(params_.unsettled_positions);
}

// ---- faults (scenario events) ---------------------------------------------------------------

void Encoder::set_error_sources(std::uint16_t errors, std::uint16_t warnings) {
  params_.error_sources = errors;
  params_.warning_sources = warnings;
}

void Encoder::set_memory_access_times(Time read, Time write) {
  require(read >= Time::zero() && read <= kMaxFaultTime && write >= Time::zero() && write <= kMaxFaultTime,
          "memory access times must be " + sim::format_time_range(Time::zero(), kMaxFaultTime));
  params_.t_ac_read = read;
  params_.t_ac_write = write;
}

void Encoder::set_t_cal(Time t_cal) {
  require(t_cal >= Time::zero() && t_cal <= EncoderParams::kMaxModelTime,
          "t_cal must be 0 .. " + sim::format_time(EncoderParams::kMaxModelTime) + " (the model's limit)");
  params_.t_cal = t_cal;
  params_.t_cal_22.reset();  // the event sets the calculation time of every mode command, in every mode
  params_.t_cal_energy_saving.reset();
}

void Encoder::power_interruption(Time duration) {
  require(duration > Time::zero() && duration <= kMaxFaultTime, "a power interruption lasts " + sim::format_time_range(Time::zero(), kMaxFaultTime));
  access_.power_interrupted(params_.interrupted_nvm_write == InterruptedNvmWrite::Torn);
  state_ = State::Idle;
  recovery_timer_.cancel();
  end_marker_timer_.cancel();
  commands_.forget_pending();
  restart_state();  // 2.7: a reset is "the same reaction as switching the power off and on"
  // 3.6.4: only switching the power off and on, with word 4 at 0000h, clears error bit 1.
  errors_.power_cycled();
  go_offline(duration + params_.startup_time);
}

void Encoder::corrupt_word(const Selection& s, std::uint8_t address, std::uint16_t xor_mask) {
  memory_.force(s, address, static_cast<std::uint16_t>(memory_.word(s, address) ^ xor_mask));
}

void Encoder::set_probe_deflected(bool deflected) { positions_.set_probe_deflected(deflected, kernel_.now()); }

void Encoder::set_stuck_error_messages(bool error1_stuck, bool error2_stuck) {
  params_.error_message_1_stuck = error1_stuck;
  params_.error_message_2_stuck = error2_stuck;
}

void Encoder::slip(std::int64_t steps) { positions_.slip(steps); }

void Encoder::set_position2_fault(std::int64_t deviation) { params_.sensors.position2_fault = deviation; }

void Encoder::set_sensor_values(const SensorValues& v) {
  Sensors& s = params_.sensors;
  if (v.temperature1) s.temperature1 = *v.temperature1;
  if (v.temperature2) s.temperature2 = *v.temperature2;
  if (v.additional_sensors) s.additional_sensors = *v.additional_sensors;
  if (v.valuation_numbers) s.valuation_numbers = *v.valuation_numbers;
}

// ---- word 3: function initialization (3.4.4) ----------------------------------------------------
// Reference pulse initialization, multiturn error messages and diagnostics reset are decoded but
// change nothing the model shows: "functions are initialized encoder-specifically".

}  // namespace endatsim::slave
