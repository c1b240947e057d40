// A passive decoder of EnDat frames from the wires at the encoder's connector, the way a logic
// analyzer's protocol decoder reads them: one explicit state machine over time-stamped CLOCK and
// DATA levels, nothing from the master's or the encoder's models. It splits the clock into
// frames, reads the mode command on RE3..RE8 and a 2.1 payload after it (D297403 2.3, 2.4),
// finds the encoder's start bit and decodes its answer, additional data and CRC (2.3.1, 2.3.5,
// appendix A4), and the 2.2 command supplement, whose MRS codes it follows to know how many
// additional data the next answers carry (2.4.2.2).
//
// What it cannot see it takes as declared (a datasheet, a profile): the position width, the
// encoder's clock-to-data delay at its pins, its recovery time t_m. docs/analyzer.md says how
// frames are split and sampled.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/master_bits.hpp"
#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

using sim::Time;

struct DecoderParams {
  unsigned position_bits = protocol::encoder_default::kPositionBits;
  // CLOCK edge at the encoder pins -> DATA edge at the encoder pins (receiver, logic, driver).
  Time clock_to_data = protocol::encoder_default::kClockToData;
  // The encoder's recovery time I: a HIGH phase this long ends any frame (2.3.2).
  Time t_m = protocol::limit::kRecoveryTimeMin;
  // Rising edges the encoder lets pass after releasing DATA before it hunts for the
  // supplement's start bit: its own last bit may still be on the line.
  unsigned supplement_ignore_clocks = protocol::encoder_default::kSupplementIgnoredClocks;
};

struct DecodedDatum {
  std::uint8_t status = 0;  // WRN RM Busy I4..I0
  std::uint16_t data = 0;
  bool crc_ok = false;
  bool busy() const { return (status & protocol::AdditionalDataStatus::kBusy) != 0; }
  protocol::AdditionalDataNumber number() const {
    return protocol::additional_data_number(
        static_cast<protocol::Information>(status & protocol::AdditionalDataStatus::kInformation));
  }
};

// One frame as the wires show it. Clocks count rising edges from FE1 (RE1 is the first).
struct WireFrame {
  std::uint64_t index = 0;
  Time fe1{0};
  Time last_rise{0};
  unsigned clocks = 0;
  std::uint8_t mode_bits = 0;
  unsigned mode_bits_seen = 0;
  std::optional<protocol::ModeCommand> command;  // none: mode bits not seen or redundancy broken
  std::optional<std::uint32_t> payload;          // 2.1: 8 + 16 bits after the mode bits
  unsigned start_bit_clock = 0;                  // 0: no start bit
  unsigned answer_bits = 0;                      // S .. CRC and the additional data expected
  bool answer_complete = false;
  protocol::FieldValues fields{};
  bool crc_ok = false;
  std::vector<DecodedDatum> additional_data;     // wire order: additional data 2 first
  std::optional<std::uint32_t> supplement;
  unsigned supplement_last_clock = 0;            // the rising edge that took its last bit
  unsigned continuous_words = 0;                 // further words of a continuous clock
  // The first kMaxWordsKept of them, each decoded as the first (2.3.1: position and CRC).
  struct Word {
    protocol::FieldValues fields{};
    bool crc_ok = false;
  };
  static constexpr std::size_t kMaxWordsKept = 100;
  std::vector<Word> words;
  unsigned bad_words = 0;  // of all further words, those whose CRC failed
  bool all_crc_ok() const { return crc_ok && bad_words == 0; }
  bool complete = false;                         // every bit the frame needs was clocked
  // Bits taken while a capture showed DATA unknown (x): read as the level before the x, so the
  // frame's values and CRC cannot be trusted.
  unsigned unknown_bits = 0;
  unsigned first_unknown_clock = 0;              // the slot (or the master's clock) of the first
  // A complete answer with a good CRC, every bit of it read from a known level.
  bool clean() const { return answer_complete && crc_ok && unknown_bits == 0; }
  unsigned learnt_position_bits = 0;             // word 13 read (or its write activated) here: the width from the next frame on

  // A2 type II: a 2.1 parameter frame whose acknowledgment returns the address sent inverted,
  // the encoder's refusal (D297403 4.2.2).
  bool refused() const {
    if (!payload || !answer_complete) return false;
    const auto sent = protocol::payload_address(*payload);
    return fields[static_cast<std::size_t>(protocol::Field::Address)] == static_cast<std::uint8_t>(~sent);
  }
};

class FrameDecoder {
 public:
  explicit FrameDecoder(const DecoderParams& params) : params_(params) {}

  // Levels at the encoder pins, in time order. on_clock returns true when the edge is FE1.
  bool on_clock(Time t, bool level);
  void on_data(Time t, bool level);
  // A capture shows DATA unknown (x) from `t` until the next on_data().
  // DATA unknown (x) from `t`; `driven`: while the encoder's driver is recorded on (a driven x can
  // hide the start bit; an x on a released line decides nothing).
  void on_data_unknown(Time t, bool driven = false);
  // The encoder's bits are taken this long after their rising edges from now on (at the master's
  // connector: the round trip a delay measurement in the capture showed).
  void set_clock_to_data(Time t) { params_.clock_to_data = t; }
  // Ends the last frame (no more edges). A capture that ends at `end` reads the slot after the
  // last rising edge only if the frame was over by then (CLOCK HIGH for t_m).
  void finish(Time end = Time::max());

  // A capture's window opens at `start`, before the first CLOCK level it shows, and may open
  // inside a frame: from then on a falling edge begins the first frame only once CLOCK has been
  // seen HIGH for t_m, the rule that splits frames (D297403 2.3.2 recovery time I). The edges
  // before it belong to a frame the capture shows only part of and are skipped. Not called in a
  // live run, which starts at rest, nor for a capture known to (docs/analyzer.md).
  void begin_capture(Time start);
  // Clock edges skipped before the first frame of a capture.
  std::uint64_t edges_before_first_frame() const { return skipped_edges_; }
  // True if a capture that ends at `end` cuts the frame being clocked: CLOCK has not been HIGH
  // for t_m since its last rising edge, so the encoder has not ended it and more clocks may follow.
  bool cuts_frame(Time end) const { return in_frame_ && !(clock_level_ && end - last_rise_ >= params_.t_m); }

  // Frames begun so far: the index the next frame will have.
  std::uint64_t frames_begun() const { return frames_; }
  // The frame being clocked, if any (its fields grow as its bits arrive).
  const WireFrame* current() const { return in_frame_ ? &frame_ : nullptr; }
  // Frames that ended since the last call.
  std::vector<WireFrame> take_finished();
  // The position's width the decoder reads answers with: as declared, until a read of word 13
  // shows the encoder's own (3.5.6) or a reset activates a written one.
  unsigned position_bits() const { return params_.position_bits; }

 private:
  enum class State : std::uint8_t { Header, Payload, Hunt, Answer, MoreData, SupplementHunt, Supplement, Done };
  struct Sample {
    Time due;
    unsigned clock;
    bool master;  // a bit the master drives (taken on RE_clock) or the encoder's slot `clock`
  };

  void begin_frame(Time t);
  void end_frame();
  void resolve(Time t);
  struct Level {
    bool high = true;
    bool unknown = false;  // x: `high` is the level before it
    bool driven = false;   // an x while the encoder's driver was recorded on
    bool operator==(const Level&) const = default;
  };
  Level level_at(Time t) const;
  void take(const Sample& s);
  void on_rising(Time t);
  void on_master_bit(unsigned clock, bool bit);
  void on_encoder_bit(unsigned clock, bool bit);
  void decode_mode_command();
  void begin_answer(unsigned clock);
  void decode_answer(unsigned last_clock);
  void note_selection();
  void follow_parameter_reads();
  std::optional<unsigned> position_format_word() const;
  void learn_width(unsigned bits);
  unsigned expected_additional_data() const;

  DecoderParams params_;
  bool clock_level_ = true;
  Time last_rise_{0};
  bool at_rest_ = true;  // a frame may begin: false in a capture until CLOCK was HIGH for t_m
  Time capture_start_{0};
  std::uint64_t skipped_edges_ = 0;
  Time longest_high_{0};
  bool in_frame_ = false;
  std::uint64_t frames_ = 0;
  WireFrame frame_;
  State state_ = State::Done;
  std::vector<Time> rising_;
  std::deque<std::pair<Time, Level>> data_;  // DATA changes still needed for sampling
  static constexpr std::size_t kMaxChangesKept = 4096;
  Level data_level_;
  Level base_level_;  // DATA before the first change in data_
  std::deque<Sample> pending_;
  // The slot after the last rising edge, sampled half a period later if no edge follows: a master
  // that gives no pulse after the last bit samples it so (docs/model.md, clock pulses).
  std::optional<Sample> tail_;
  std::vector<std::uint8_t> bits_;
  protocol::ReceivedBits received_;  // a 2.1 payload or a 2.2 command supplement
  protocol::SupplementStart supplement_start_;
  bool seen_low_ = false;  // the LOW before the encoder's start bit
  protocol::Layout layout_{{}};
  protocol::PerAdditionalData<bool> selected_;
  std::optional<std::uint8_t> area_;  // MRS code of the memory area selected last
  std::optional<unsigned> written_width_;  // word 13 written, active after the next reset
  std::vector<WireFrame> finished_;
};

}  // namespace endatsim::checker
