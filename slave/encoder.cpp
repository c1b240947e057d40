#include "slave/encoder.hpp"

#include <stdexcept>

namespace endatsim::slave {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

}  // namespace

void EncoderParams::validate() const {
  require(position_bits >= 1 && position_bits <= 48,
          "encoder position_bits (word 13) must be 1 .. 48, got " + std::to_string(position_bits));
  require(multiturn_bits < position_bits, "encoder multiturn_bits must be less than position_bits (" +
                                              std::to_string(position_bits) + "), got " +
                                              std::to_string(multiturn_bits));
  require(kind == EncoderKind::Multiturn || multiturn_bits == 0,
          "multiturn_bits (" + std::to_string(multiturn_bits) + ") needs kind \"multiturn\"");
  require(kind != EncoderKind::Multiturn || multiturn_bits > 0, "kind \"multiturn\" needs multiturn_bits > 0");
  // 2.3.2 allows at most 1 ms; longer ones are accepted so that an overrun can be shown, and
  // the checker reports them (t_cal).
  require(t_cal >= Time::zero() && t_cal <= sim::ms(100),
          "t_cal must be 0 .. 100 ms (the model's limit), got " + sim::format_time(t_cal));
  require(t_m >= sim::us(10) && t_m <= sim::us(30),
          "t_m must be 10 .. 30 us (2.3.2), got " + sim::format_time(t_m));
  if (t_m_short)
    require(*t_m_short >= sim::ns(1250) && *t_m_short <= sim::ns(3750),
            "t_m_short must be 1.25 .. 3.75 us (2.3.2 note 3), got " + sim::format_time(*t_m_short));
  require(!short_t_m_selected || t_m_short.has_value(), "short_t_m_selected needs t_m_short");
  require(t_r >= Time::zero() && t_r <= sim::us(100), "t_R must be 0 .. 100 us, got " + sim::format_time(t_r));
  require(output_delay >= Time::zero() && output_delay <= sim::us(1),
          "encoder output_delay must be 0 .. 1 us, got " + sim::format_time(output_delay));
  require(continuous_low_bits >= 1 && continuous_low_bits <= 7,
          "continuous_low_bits must be 1 .. 7 (2.3.1.1: at most 7 low bits), got " +
              std::to_string(continuous_low_bits));
  require(driver_enable_edge == 9 || driver_enable_edge == 10,
          "driver_enable_edge must be 9 or 10 (the turnaround clocks), got " + std::to_string(driver_enable_edge));
  require(motion.start < (std::uint64_t{1} << position_bits),
          "motion.start must be below 2^position_bits = " + std::to_string(std::uint64_t{1} << position_bits) +
              ", got " + std::to_string(motion.start));
}

std::uint64_t EncoderParams::position_at(Time t) const {
  const __int128 range = __int128{1} << position_bits;
  __int128 p = static_cast<__int128>(motion.start) +
               static_cast<__int128>(motion.counts_per_s) * t.count() / 1'000'000'000'000;
  p %= range;
  if (p < 0) p += range;
  return static_cast<std::uint64_t>(p);
}

Encoder::Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params)
    : kernel_(kernel), pins_(line.encoder()), params_(params),
      data_logic_(kernel, "encoder_data_logic", false), enable_logic_(kernel, "encoder_enable_logic", true),
      data_out_delay_(kernel, data_logic_, pins_.data_out, params.output_delay),
      enable_out_delay_(kernel, enable_logic_, pins_.data_enable, params.output_delay),
      recovery_timer_(kernel, sim::bind<&Encoder::on_recovery_time_elapsed>(this)) {
  params_.validate();
  pins_.clock_in.on_change(sim::bind<&Encoder::on_clock>(this));
}

void Encoder::on_clock(std::uint64_t level) {
  if (kernel_.now() < ready_at_) {  // t_R: not ready for the next query yet
    ++ignored_edges_;
    return;
  }
  if (level == 0) on_falling_edge();
  else on_rising_edge();
}

void Encoder::begin_frame() {
  // 2.2: "the position value is saved in the encoder with the falling clock edge";
  // 2.3: "with the first falling clock edge, the send block in the encoder must be deactivated".
  state_ = State::Header;
  clock_ = 1;
  mode_bits_ = 0;
  EncoderFrame f;
  f.start = kernel_.now();
  f.position = params_.position_at(kernel_.now());
  frames_.push_back(f);
  release();
}

void Encoder::on_falling_edge() {
  recovery_timer_.cancel();
  if (state_ == State::Idle) {
    begin_frame();
    return;
  }
  ++clock_;
  EncoderFrame& f = frames_.back();
  switch (state_) {
    case State::Header:
    case State::Type1:
    case State::Answer:
      if (clock_ == params_.driver_enable_edge) {
        drive(state_ == State::Type1 && params_.type1 == Type1Handling::AbortHigh);
        enable();
      }
      break;
    case State::EndOfData:
      // 2.3.1: a continuous clock is only possible with "Encoder send position values";
      // the next position is saved with the falling edge after the HIGH bit.
      if (f.command == ModeCommand::EncoderSendPositionValues) {
        f.continuous_positions.push_back(params_.position_at(kernel_.now()));
        ++f.continuous_words;
        state_ = State::ContinuousGap;
        gap_low_bits_ = 0;
      }
      break;
    case State::Idle:
    case State::ContinuousGap:
      break;
  }
}

void Encoder::on_rising_edge() {
  recovery_timer_.start(recovery_time());
  if (state_ == State::Idle) return;  // a rising edge without a frame: nothing to do
  EncoderFrame& f = frames_.back();
  f.clocks = clock_;
  switch (state_) {
    case State::Header:
      // 2.3: the encoder accepts the mode bits on the rising edges of clocks 3 .. 8.
      if (clock_ >= 3 && clock_ <= 8) mode_bits_ = static_cast<std::uint8_t>(mode_bits_ << 1 | pins_.data_in.read());
      if (clock_ == 8) decode_mode_command();
      break;
    case State::Answer:
      emit_answer_bit();
      break;
    case State::ContinuousGap:
      if (gap_low_bits_ < params_.continuous_low_bits) {
        ++gap_low_bits_;
        drive(false);
      } else {
        load_answer();
        emit_answer_bit();
      }
      break;
    case State::EndOfData:
    case State::Type1:
    case State::Idle:
      break;
  }
}

void Encoder::decode_mode_command() {
  EncoderFrame& f = frames_.back();
  f.mode_bits = mode_bits_;
  f.command = protocol::decode_mode_bits(mode_bits_);
  const bool supported =
      f.command == ModeCommand::EncoderSendPositionValues ||
      (f.command == ModeCommand::EncoderSendPositionValuesWithAdditionalData && params_.version == EndatVersion::V2_2);
  if (!supported) {
    f.type1_error = true;  // appendix A2, type I: mode command disrupted or not supported
    state_ = State::Type1;
    return;
  }
  state_ = State::Answer;
  const auto type = protocol::info(*f.command).version;
  answer_ = protocol::encode_position_frame(type, params_.position_bits,
                                            {params_.error1, !params_.error1, f.position});
  next_bit_ = 0;
}

void Encoder::load_answer() {
  EncoderFrame& f = frames_.back();
  answer_ = protocol::encode_position_frame(EndatVersion::V2_1, params_.position_bits,
                                            {params_.error1, !params_.error1, f.continuous_positions.back()});
  next_bit_ = 0;
  state_ = State::Answer;
}

void Encoder::emit_answer_bit() {
  EncoderFrame& f = frames_.back();
  if (next_bit_ == 0 && f.continuous_words == 0) {
    // Timing-model §1.2: LOW until t_cal has elapsed since FE1, start bit no earlier than RE11.
    if (clock_ < 11 || kernel_.now() - f.start < params_.t_cal) {
      drive(false);
      return;
    }
    f.start_bit_clock = clock_;
  }
  if (next_bit_ < answer_.size()) {
    drive(answer_[next_bit_++] != 0);
    return;
  }
  // Timing-model §1.3: after the last CRC bit DATA goes HIGH and stays HIGH for t_m.
  drive(true);
  state_ = State::EndOfData;
}

Time Encoder::recovery_time() const {
  const auto& f = frames_;
  const bool v22 = state_ != State::Idle && !f.empty() && f.back().command &&
                   protocol::info(*f.back().command).version == EndatVersion::V2_2;
  return v22 && params_.short_t_m_selected ? *params_.t_m_short : params_.t_m;
}

void Encoder::on_recovery_time_elapsed() {
  // 2.3: "The transfer is terminated after expiry of a certain time (recovery time I)":
  // DATA falls back to LOW and the encoder is ready again after t_R.
  if (state_ == State::Idle) return;
  state_ = State::Idle;
  drive(false);
  enable();
  ready_at_ = kernel_.now() + params_.t_r;
}

}  // namespace endatsim::slave
