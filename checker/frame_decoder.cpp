#include "endatsim/checker/frame_decoder.hpp"

#include <algorithm>
#include <span>

#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {
namespace {

namespace position = protocol::frame_position;
using N = protocol::AdditionalDataNumber;
using MC = protocol::ModeCommand;

// The CRC over a word's bits between its first bit (start bit or leading LOW) and its CRC: in
// wire order that is what MakeCrcPos and MakeCrcNorm feed the generator (A4.4.2).
bool crc_matches(std::span<const std::uint8_t> word) {
  constexpr std::size_t kCrcBits = protocol::kCrcBits;
  const auto covered = word.subspan(1, word.size() - 1 - kCrcBits);
  std::uint8_t received = 0;
  for (std::size_t i = word.size() - kCrcBits; i < word.size(); ++i) received = static_cast<std::uint8_t>(received << 1 | word[i]);
  return protocol::crc5(covered) == received;
}

}  // namespace

bool FrameDecoder::on_clock(Time t, bool level) {
  resolve(t);
  if (level == clock_level_) return false;
  clock_level_ = level;
  tail_.reset();  // the clock goes on: the slot after the last rising edge is read at the next one
  if (level) {
    last_rise_ = t;
    if (in_frame_) on_rising(t);
    else if (!at_rest_) ++skipped_edges_;
    return false;
  }
  const Time high = t - last_rise_;
  if (!at_rest_) {
    if (high < params_.t_m) {
      // A LOW first level shows at the capture's start as an edge from the idle HIGH: no edge seen.
      if (t != capture_start_) ++skipped_edges_;
      return false;
    }
    at_rest_ = true;
  }
  // A HIGH phase of t_m ends any frame at the encoder (2.3.2 recovery time I); a frame that has
  // had every clock it needs ends at a HIGH phase clearly longer than its own clock's.
  const bool fe1 = !in_frame_ || high >= params_.t_m || (frame_.complete && high > 2 * longest_high_);
  if (fe1) {
    if (in_frame_) end_frame();
    begin_frame(t);
    return true;
  }
  longest_high_ = std::max(longest_high_, high);
  return false;
}

void FrameDecoder::on_data(Time t, bool level) {
  resolve(t);
  const Level now{level, false};
  if (now == data_level_) return;
  data_level_ = now;
  data_.emplace_back(t, now);
}

void FrameDecoder::on_data_unknown(Time t, bool driven) {
  resolve(t);
  if (data_level_.unknown && data_level_.driven == driven) return;
  data_level_.unknown = true;
  data_level_.driven = driven;
  data_.emplace_back(t, data_level_);
}

void FrameDecoder::finish(Time end) {
  resolve(end);
  tail_.reset();
  resolve(Time::max());
  if (in_frame_) end_frame();
}

void FrameDecoder::begin_capture(Time start) {
  at_rest_ = false;
  capture_start_ = start;
  last_rise_ = start;  // CLOCK's level before the capture is unknown: its HIGH counts from here
  skipped_edges_ = 0;
}

std::vector<WireFrame> FrameDecoder::take_finished() {
  std::vector<WireFrame> out;
  out.swap(finished_);
  return out;
}

void FrameDecoder::begin_frame(Time t) {
  frame_ = WireFrame{};
  frame_.index = frames_++;
  frame_.fe1 = t;
  in_frame_ = true;
  state_ = State::Header;
  rising_.clear();
  longest_high_ = Time::zero();
  received_.clear();
  seen_low_ = false;
  bits_.clear();
  tail_.reset();
}

void FrameDecoder::end_frame() {
  // 2.7: a reset ends every selection of additional data.
  if (frame_.command == MC::EncoderReceiveReset) selected_.clear();
  follow_parameter_reads();
  finished_.push_back(frame_);
  in_frame_ = false;
}

// The master's bits are taken on rising edges at the encoder pins, as the encoder takes them;
// the encoder's bit of slot k is taken in the middle of its data-valid window, half-way between
// RE_k and RE_(k+1) plus the encoder's clock-to-data delay; after the frame's last rising edge,
// half its last period after it (a master that gives no pulse after the last bit).
void FrameDecoder::on_rising(Time t) {
  rising_.push_back(t);
  const auto k = static_cast<unsigned>(rising_.size());
  frame_.clocks = k;
  frame_.last_rise = t;
  const auto insert = [&](Sample s) {
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), s.due,
                                     [](Time due, const Sample& p) { return due < p.due; });
    pending_.insert(at, s);
  };
  insert({t, k, true});
  if (k < 2) return;
  const Time half = (t - rising_[k - 2]) / 2;
  insert({rising_[k - 2] + half + params_.clock_to_data, k - 1, false});
  tail_ = Sample{t + half + params_.clock_to_data, k, false};
}

FrameDecoder::Level FrameDecoder::level_at(Time t) const {
  Level level = base_level_;
  for (const auto& [when, value] : data_) {
    if (when > t) break;
    level = value;
  }
  return level;
}

void FrameDecoder::resolve(Time t) {
  while (!pending_.empty() && pending_.front().due < t) {
    const Sample s = pending_.front();
    pending_.pop_front();
    take(s);
  }
  // CLOCK stayed HIGH after the last rising edge long enough to end the frame (t_m, 2.3.2 recovery
  // time I; or, once it had every clock, twice its longest HIGH phase: on_clock's rule), and the
  // slot after that edge had no rising edge to read it. The changes after the edge are still kept
  // (below), so its level is known. Only an answer still short of its bits takes it: after a
  // complete answer the slot would only hold the end marker, or the line the encoder lets fall
  // after t_m.
  if (tail_ && state_ == State::Answer && in_frame_ && clock_level_ && tail_->due < t) {
    const Time high = t - last_rise_;
    if (high >= params_.t_m || (frame_.complete && high > 2 * longest_high_)) {
      const Sample s = *tail_;
      tail_.reset();
      take(s);
    }
  }
  // Changes before the earliest sample still due are folded into the level they left. In a frame,
  // the sample of the bit after the last rising edge is inserted only at the next one, and may be
  // due before it: changes after the last rising edge stay until then (a disturbance that ends as
  // the next edge comes must not be folded away), unless the line has been quiet for t_m or holds
  // more changes than any bit could (a bound on memory).
  Time horizon = pending_.empty() ? t : std::min(t, pending_.front().due);
  if (in_frame_ && t - last_rise_ < params_.t_m && data_.size() < kMaxChangesKept)
    horizon = std::min(horizon, last_rise_);
  while (!data_.empty() && data_.front().first <= horizon) {
    base_level_ = data_.front().second;
    data_.pop_front();
  }
}

// A bit read from a level a capture showed unknown (x) is counted where the frame uses it: the
// master's bits, the answer's, and each slot after the encoder's LOW, or while a recorded enable
// says the encoder drives, where the start bit or a further datum may begin. The line floats, and
// a capture may show x, before the mode command, between the turnaround and the encoder's LOW and
// after the answer: such bits, on a line no driver holds, decide nothing.
void FrameDecoder::take(const Sample& s) {
  const Level level = level_at(s.due);
  const State before = state_;
  const bool after_low = seen_low_;
  if (s.master) on_master_bit(s.clock, level.high);
  else on_encoder_bit(s.clock, level.high);
  if (!level.unknown || !in_frame_) return;
  bool used = false;
  switch (before) {
    case State::Header:
      used = s.master && s.clock >= position::kFirstModeBit && s.clock <= position::kLastModeBit;
      break;
    case State::Payload:
    case State::Supplement: used = s.master; break;
    case State::SupplementHunt: used = s.master && state_ == State::Supplement; break;
    case State::Answer:
    case State::MoreData: used = !s.master; break;  // a LOW after the data opens a further datum
    // After the encoder's LOW, or while its driver is recorded on, the start bit may come at any
    // slot: an x read as the level before may hide it.
    case State::Hunt: used = !s.master && (after_low || level.driven || state_ == State::Answer); break;
    case State::Done: break;
  }
  if (used && frame_.unknown_bits++ == 0) frame_.first_unknown_clock = s.clock;
}

void FrameDecoder::on_master_bit(unsigned clock, bool bit) {
  switch (state_) {
    case State::Header:
      if (clock < position::kFirstModeBit || clock > position::kLastModeBit) return;
      frame_.mode_bits = static_cast<std::uint8_t>(frame_.mode_bits << 1 | (bit ? 1 : 0));
      if (++frame_.mode_bits_seen == position::kModeBits) decode_mode_command();
      return;
    case State::Payload:
      if (received_.take(bit)) {
        frame_.payload = received_.value();
        state_ = State::Hunt;
      }
      return;
    case State::SupplementHunt:
      // The line floats until the master drives its lead bits; the supplement's start bit is
      // the first HIGH after a LOW (2.3, command supplement).
      if (supplement_start_.found(clock, bit, params_.supplement_ignore_clocks)) {
        state_ = State::Supplement;
        received_.clear();
      }
      return;
    case State::Supplement:
      if (received_.take(bit)) {
        frame_.supplement = received_.value();
        frame_.supplement_last_clock = clock;
        note_selection();
        frame_.complete = true;
        state_ = State::Done;
      }
      return;
    default:
      return;
  }
}

void FrameDecoder::decode_mode_command() {
  frame_.command = protocol::decode_mode_bits(frame_.mode_bits);
  if (!frame_.command) {  // A2 type I: the encoder answers no start bit
    state_ = State::Done;
    return;
  }
  const auto& info = protocol::info(*frame_.command);
  layout_ = protocol::answer_layout(info, params_.position_bits);
  const bool additional_data = info.answer == protocol::AnswerFormat::Position && info.version == protocol::EndatVersion::V2_2;
  frame_.answer_bits = layout_.width() + (additional_data ? protocol::kAdditionalDatumBits * expected_additional_data() : 0);
  received_.clear();
  seen_low_ = false;
  state_ = info.payload_bits != 0 ? State::Payload : State::Hunt;
}

// 3.5.6: word 13 of the encoder manufacturer's parameters (memory area A1h, 3.5) gives the clock
// pulses of the position value. A master that reads it, as masters do before their first
// position, shows the width of every answer after it; it overrides the declared width. A 2.1
// write of it (an EIB's commissioning, 3.5.7) that the encoder echoes takes effect with the next
// "Encoder receive reset", as the EIB activates what was written. Only answers the encoder
// acknowledged with a good CRC count, and a selection lasts until the next.
void FrameDecoder::follow_parameter_reads() {
  if (!frame_.command || !frame_.clean()) return;
  const auto address = [](std::uint32_t bits) { return protocol::payload_address(bits); };
  switch (*frame_.command) {
    case MC::SelectionOfMemoryArea:
      if (frame_.payload) area_ = address(*frame_.payload);
      return;
    case MC::EncoderSendPositionValuesAndSelectionOfMemoryArea:
      if (frame_.supplement && !protocol::selects_additional_data(address(*frame_.supplement)))
        area_ = address(*frame_.supplement);
      return;
    case MC::EncoderSendParameters:
      if (const auto bits = position_format_word()) learn_width(*bits);
      return;
    case MC::EncoderReceiveParameters: {
      const auto echo = protocol::make_payload(static_cast<std::uint8_t>(frame_.fields[static_cast<std::size_t>(protocol::Field::Address)]),
                                               static_cast<std::uint16_t>(frame_.fields[static_cast<std::size_t>(protocol::Field::Parameter)]));
      const auto bits = position_format_word();
      if (bits && echo == *frame_.payload) written_width_ = bits;  // an echo differs when refused (A2)
      return;
    }
    case MC::EncoderReceiveReset:
      if (written_width_) learn_width(*written_width_);
      written_width_.reset();
      return;
    default: return;
  }
}

// The width word 13 gives, for a 2.1 access to it in area A1h; none for any other access or a
// word that holds no width (bits 0..5 zero).
std::optional<unsigned> FrameDecoder::position_format_word() const {
  if (area_ != protocol::info(protocol::MemoryArea::Manufacturer1).mrs || !frame_.payload ||
      protocol::payload_address(*frame_.payload) != protocol::word::kPositionFormat)
    return std::nullopt;
  const auto word = frame_.command == MC::EncoderReceiveParameters
                        ? protocol::payload_parameter(*frame_.payload)
                        : static_cast<std::uint16_t>(frame_.fields[static_cast<std::size_t>(protocol::Field::Parameter)]);
  const unsigned bits = protocol::parameters::decode_position_bits(word);
  return bits != 0 ? std::optional(bits) : std::nullopt;
}

void FrameDecoder::learn_width(unsigned bits) {
  params_.position_bits = bits;
  frame_.learnt_position_bits = bits;
}

unsigned FrameDecoder::expected_additional_data() const {
  return (selected_[N::One] ? 1U : 0U) + (selected_[N::Two] ? 1U : 0U);
}

// The encoder drives LOW after the turnaround until its answer is ready; the start bit is the
// first HIGH after that LOW (2.3). With a continuous clock the next word follows the same way.
void FrameDecoder::on_encoder_bit(unsigned clock, bool bit) {
  switch (state_) {
    case State::Hunt: {
      const unsigned payload = frame_.command ? protocol::info(*frame_.command).payload_bits : 0;
      if (clock < position::kTurnaround + payload) return;
      if (!seen_low_) {
        seen_low_ = !bit;
        return;
      }
      if (!bit) return;
      if (frame_.continuous_words == 0 && frame_.start_bit_clock == 0) frame_.start_bit_clock = clock;
      bits_.assign(1, 1);
      state_ = State::Answer;
      return;
    }
    case State::Answer:
      // 2.3.5: each additional datum opens with a LOW bit; a HIGH there (the level after the CRC)
      // says no further datum follows, whatever the decoder believed was selected (an encoder
      // forgets its selection when its power is interrupted).
      if (!frame_.answer_complete && bits_.size() >= layout_.width() &&
          (bits_.size() - layout_.width()) % protocol::kAdditionalDatumBits == 0 && bit) {
        frame_.answer_bits = static_cast<unsigned>(bits_.size());
        decode_answer(clock - 1);
        return;
      }
      bits_.push_back(bit ? 1 : 0);
      if (bits_.size() == (frame_.answer_complete ? layout_.width() : frame_.answer_bits)) decode_answer(clock);
      return;
    case State::MoreData:
      // After the data the decoder expected, a LOW opens a datum it did not know was selected.
      state_ = State::Done;
      if (bit) return;
      bits_.push_back(0);
      frame_.answer_bits += protocol::kAdditionalDatumBits;
      frame_.answer_complete = false;
      frame_.complete = false;
      frame_.additional_data.clear();
      state_ = State::Answer;
      return;
    default:
      return;
  }
}

// last_clock: the slot of the answer's last bit.
void FrameDecoder::decode_answer(unsigned last_clock) {
  if (frame_.answer_complete) {  // a further word of a continuous clock
    ++frame_.continuous_words;
    WireFrame::Word w{layout_.decode(bits_), crc_matches(std::span(bits_).first(layout_.width()))};
    if (!w.crc_ok) ++frame_.bad_words;
    if (frame_.words.size() < WireFrame::kMaxWordsKept) frame_.words.push_back(w);
    seen_low_ = false;
    state_ = State::Hunt;
    return;
  }
  frame_.answer_complete = true;
  frame_.fields = layout_.decode(bits_);
  frame_.crc_ok = crc_matches(std::span(bits_).first(layout_.width()));
  for (std::size_t at = layout_.width(); at + protocol::kAdditionalDatumBits <= bits_.size();
       at += protocol::kAdditionalDatumBits) {
    const auto word = std::span(bits_).subspan(at, protocol::kAdditionalDatumBits);
    const auto r = protocol::decode_additional_datum(word);
    DecodedDatum d;
    d.status = r.status;
    d.data = r.data;
    d.crc_ok = r.leading_low && crc_matches(word);
    frame_.additional_data.push_back(d);
  }
  const auto& info = protocol::info(*frame_.command);
  const bool additional_data = info.answer == protocol::AnswerFormat::Position && info.version == protocol::EndatVersion::V2_2;
  if (additional_data) {  // what the encoder sent tells what is selected
    selected_.clear();
    for (const auto& d : frame_.additional_data) selected_[d.number()] = true;
  }
  if (info.supplement) {
    // The encoder releases DATA on the rising edge after its last bit's slot; the master sends
    // the supplement. Counted from the slot, not from the edges seen by the time the bit was
    // sampled: those depend on the clock-to-data delay against the period.
    supplement_start_.handed_over(last_clock + 1);
    state_ = State::SupplementHunt;
    return;
  }
  frame_.complete = true;
  seen_low_ = false;
  // 2.3.1: only "Encoder send position values" goes on with a continuous clock.
  if (*frame_.command == MC::EncoderSendPositionValues) state_ = State::Hunt;
  else if (additional_data && frame_.additional_data.size() < protocol::kAdditionalDataPerFrameMax) state_ = State::MoreData;
  else state_ = State::Done;
}

// 2.4.2.2: MRS codes 0x40 + I select additional data 1, 0x50 + (I - 16) additional data 2;
// 0x4F and 0x5F stop sending it.
void FrameDecoder::note_selection() {
  if (frame_.command != MC::EncoderSendPositionValuesAndSelectionOfMemoryArea) return;
  const auto mrs = protocol::payload_address(*frame_.supplement);
  if (!protocol::selects_additional_data(mrs)) return;
  selected_[protocol::additional_data_number(protocol::information_of_mrs(mrs))] = !protocol::stops_additional_data(mrs);
}

}  // namespace endatsim::checker
