#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "line/line.hpp"
#include "protocol/protocol.hpp"

namespace endatsim::slave {

using protocol::EndatVersion;
using protocol::ModeCommand;
using sim::Time;

enum class EncoderKind : std::uint8_t { Singleturn, Multiturn, Linear };

// What the encoder puts on DATA after a mode command with a broken redundancy or one it does
// not support (type I, appendix A2). The wire behaviour is not documented in any readable
// source (timing-model §6): A = abort with DATA HIGH until CLOCK stays HIGH for t_m;
// B = DATA stays LOW, no start bit ever comes.
enum class Type1Handling : std::uint8_t { AbortHigh, NoStartBit };

// Position source: fixed (counts_per_s = 0) or constant velocity, wrapping at 2^position_bits.
struct MotionProfile {
  std::uint64_t start = 0;
  std::int64_t counts_per_s = 0;
};

struct EncoderParams {
  EncoderKind kind = EncoderKind::Singleturn;
  EndatVersion version = EndatVersion::V2_2;  // a 2.1 encoder answers 2.2 commands as not supported
  unsigned position_bits = 25;                 // word 13: clock pulses for the position value
  unsigned multiturn_bits = 0;                 // upper bits of the position that count revolutions
  Time t_cal = sim::us(5);                     // 2.3.2: position calculation time, FE1 -> start bit (max 1 ms)
  Time t_m = sim::us(20);                      // 2.3.2: recovery time I, 10 .. 30 us
  std::optional<Time> t_m_short;               // 1.25 .. 3.75 us, 2.2 commands only (word 3, 3.4.4)
  bool short_t_m_selected = false;
  Time t_r = sim::ns(500);                     // 2.3.2: t_R, time before the next query can be received
  Time output_delay = sim::ns(60);             // clock input -> data output inside the encoder
  unsigned continuous_low_bits = 1;            // 2.3.1.1: "a maximum of 7 Low Bits" between words
  unsigned driver_enable_edge = 9;             // FE that turns the encoder's driver on (timing-model §1.2)
  Type1Handling type1 = Type1Handling::AbortHigh;
  MotionProfile motion;
  bool error1 = false;  // F1 = 1 / F2 = 0: an error source is active (3.4.1)

  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
  std::uint64_t position_at(Time t) const;
};

// Ground truth of one frame as the encoder saw it.
struct EncoderFrame {
  Time start;                          // FE1 at the encoder logic
  std::uint8_t mode_bits = 0;
  std::optional<ModeCommand> command;  // none: redundancy broken
  bool type1_error = false;
  std::uint64_t position = 0;          // latched at FE1
  unsigned start_bit_clock = 0;        // RE index of the start bit, 0 if none was sent
  unsigned clocks = 0;                 // rising edges seen
  unsigned continuous_words = 0;       // further words sent with a continuous clock
  std::vector<std::uint64_t> continuous_positions;
};

class Encoder {
 public:
  Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params);
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  const EncoderParams& params() const { return params_; }
  const std::vector<EncoderFrame>& frames() const { return frames_; }
  std::uint64_t ignored_clock_edges() const { return ignored_edges_; }
  bool idle() const { return state_ == State::Idle; }

  // Internal signals worth tracing: what the encoder logic drives before its output delay.
  sim::Signal& data_logic() { return data_logic_; }
  sim::Signal& enable_logic() { return enable_logic_; }

 private:
  enum class State : std::uint8_t { Idle, Header, Answer, EndOfData, ContinuousGap, Type1 };

  void on_clock(std::uint64_t level);
  void on_falling_edge();
  void on_rising_edge();
  void on_recovery_time_elapsed();
  void begin_frame();
  void decode_mode_command();
  void load_answer();
  void emit_answer_bit();
  Time recovery_time() const;
  void drive(bool level) { data_logic_.write(level); }
  void release() { enable_logic_.write(false); }
  void enable() { enable_logic_.write(true); }

  sim::Kernel& kernel_;
  line::Line::EncoderSide pins_;
  EncoderParams params_;
  sim::Signal data_logic_;
  sim::Signal enable_logic_;
  sim::TransportDelay data_out_delay_;
  sim::TransportDelay enable_out_delay_;
  sim::Timer recovery_timer_;

  State state_ = State::Idle;
  Time ready_at_{0};
  unsigned clock_ = 0;  // index k of the current clock period: FE_k, RE_k
  std::uint8_t mode_bits_ = 0;
  std::vector<std::uint8_t> answer_;
  std::size_t next_bit_ = 0;
  unsigned gap_low_bits_ = 0;
  std::vector<EncoderFrame> frames_;
  std::uint64_t ignored_edges_ = 0;
};

}  // namespace endatsim::slave
