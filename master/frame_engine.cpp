#include "endatsim/master/frame_engine.hpp"

#include <algorithm>

namespace endatsim::master {
namespace {

namespace position = protocol::frame_position;
// The encoder drives DATA from the turnaround (docs/model.md §1).
constexpr unsigned kFirstPolledClock = position::kTurnaround;

// Sample tags carry the frame's epoch in the upper and the clock slot in the lower 32 bits.
std::uint64_t sample_tag(std::uint64_t epoch, unsigned clock) { return epoch << 32 | clock; }

// A note's data: the clock slot, the value sampled and whether it was a bit of the answer below,
// the recorded frame's place from here up.
constexpr unsigned kNoteFrameShift = 40;

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

std::uint8_t expected_crc_pos(const CrcCheck& check, unsigned bits, bool error1, bool error2, bool v22,
                              std::uint64_t position) {
  const bool with_f2 = v22 || check.endat22_rule_for_21;
  // A table loop one step short at its faulty width leaves the last position bit out.
  const unsigned fed = bits == check.table_fault_width ? bits - 1 : bits;
  return protocol::make_crc_pos(fed, error1, error2, with_f2, position, check.generator);
}

bool crc_passes(const CrcCheck& check, std::uint8_t received, std::uint8_t expected) {
  return check.accept_any || received == expected;
}

FrameEngine::FrameEngine(sim::Kernel& kernel, line::Line::MasterSide pins, const MasterParams& params,
                         DelayMeasurement& delay, FrameClient& client, const std::vector<MasterObserver*>& observers)
    : kernel_(kernel), pins_(pins), params_(params), delay_(delay), client_(client), observers_(observers),
      timing_(params), sample_strobe_(kernel, "master_sample", false), frame_active_(kernel, "master_frame", false),
      layout_(protocol::position_frame_layout(protocol::EndatVersion::V2_1, params.position_bits)) {
  pins_.data_in.on_change(sim::bind<&FrameEngine::on_data_in>(this));
}

void FrameEngine::start(const FrameRequest& request) {
  frame_ = FrameResult{};
  frame_.index = request.index;
  frame_.operation = request.operation;
  frame_.start = kernel_.now();
  frame_.measurement = request.measurement;
  frame_.command = request.command;
  frame_.mode_bits = request.mode_bits;
  frame_.f_c = request.f_c;
  frame_.compensated = request.t_d.has_value();
  frame_.t_d_used = request.t_d.value_or(Time::zero());

  command_ = &protocol::info(frame_.command);
  supplement_word_ = request.payload;
  payload_ = request.measurement ? 0 : request.payload;
  if (command_->payload_bits != 0) frame_.payload = payload_;
  supplement_start_ = 0;
  supplement_due_ = false;
  clock_adjust_ = request.clock_adjust;
  timing_.begin(frame_.f_c, kernel_.now());
  layout_ = protocol::answer_layout(*command_, request.position_bits);
  frame_.answer_bits = answer_width();
  frame_.position_bits = request.position_bits;
  clock_ = 0;
  last_clock_ = 0;
  clocking_done_ = false;
  rx_ = Rx::Polling;
  hunt_.begin(params_.start_bit_detection == StartBitDetection::WaitLowThenHigh);
  rx_bits_.clear();
  words_left_ = request.continuous_words;
  poll_start_ = kernel_.now();
  ++epoch_;
  delay_.frame_started(request.measurement, timing_.rng());
  frame_running_ = true;

  frame_active_.write(true);
  note(Note::Start);
  for (auto* o : observers_) o->on_frame_start(frame_);
  falling_edge();
}

// ---- the clock and what the master sends ---------------------------------------------------

// Each edge queues the next straight into the kernel: one call when it comes up, where a
// restartable timer took two (its own, then its action's), on every edge of every frame.
void FrameEngine::next_edge(Time delay) {
  kernel_.schedule(delay, sim::bind<&FrameEngine::edge_due>(this, edge_epoch_));
}

void FrameEngine::edge_due(std::uint64_t epoch) {
  if (epoch == edge_epoch_) clock_edge();
}

void FrameEngine::clock_edge() {
  if (clock_low_) rising_edge();
  else falling_edge();
}

void FrameEngine::falling_edge() {
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
    pins_.data_out.write(((frame_.mode_bits >> (position::kLastModeBit - clock_)) & 1U) != 0);
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
    if (frame_.compensated)
      kernel_.schedule(frame_.t_d_used, sim::bind<&FrameEngine::sample>(this, sample_tag(epoch_, slot)));
    else sample_now(slot);
  }
  next_edge(timing_.after_falling(clock_, kernel_.now()) - kernel_.now());
}

void FrameEngine::rising_edge() {
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
    kernel_.schedule(std::min(timing_.high(), sim::period_of(MasterParams::kMaxFc) / 2),
                     sim::bind<&FrameEngine::release_supplement>(this));
  const bool answered = rx_ == Rx::Done && !supplement_due_ && (last_clock_ == 0 || clock_ >= last_clock_);
  if (answered || (last_clock_ != 0 && clock_ >= last_clock_ && words_left_ == 0)) {
    clocking_done_ = true;
    if (!params_.extra_clock_after_last_bit && rx_ == Rx::Receiving) {
      // No further pulse: the last bit is taken where the next falling edge would be.
      const Time at = timing_.high() + frame_.t_d_used;
      kernel_.schedule(at, sim::bind<&FrameEngine::sample>(this, sample_tag(epoch_, clock_)));
    }
    // Too few pulses (a fault): the answer stays incomplete once the last sample is due.
    if (rx_ == Rx::Receiving)
      kernel_.schedule(timing_.high() + frame_.t_d_used + timing_.low(), sim::bind<&FrameEngine::incomplete>(this, sample_tag(epoch_, 0)));
    maybe_complete_frame();
    return;
  }
  next_edge(timing_.after_rising(kernel_.now()) - kernel_.now());
}

void FrameEngine::drive_supplement_bit() {
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

void FrameEngine::release_supplement() { pins_.data_enable.write(false); }

// ---- what the master receives -------------------------------------------------------------

void FrameEngine::incomplete(std::uint64_t tag) {
  if ((tag >> 32) != epoch_ || rx_ != Rx::Receiving) return;
  end_reception(FrameOutcome::TooFewClocks);
}

void FrameEngine::sample(std::uint64_t tag) {
  if ((tag >> 32) != epoch_ || rx_ == Rx::Done) return;  // a frame that has ended
  sample_now(static_cast<unsigned>(tag & 0xFFFF'FFFF));
}

void FrameEngine::sample_now(unsigned clock) {
  const bool value = pins_.data_in.read();
  sample_strobe_.write(!sample_strobe_.read());
  bool in_data = rx_ == Rx::Receiving;
  switch (rx_) {
    case Rx::Polling:
      switch (hunt_.sample(value, params_.type1_detect_samples)) {
        case StartBitHunt::Result::Type1Error:
          note(Note::Sample, clock | std::uint64_t{value} << 32);
          for (auto* o : observers_) o->on_sample(frame_, clock, value, false);
          end_reception(FrameOutcome::Type1Error);
          return;
        case StartBitHunt::Result::StartBit:
          in_data = true;
          begin_answer(clock);
          break;
        case StartBitHunt::Result::Waiting:
          break;
      }
      break;
    case Rx::Receiving:
      rx_bits_.push_back(value ? 1 : 0);
      break;
    case Rx::Off:
    case Rx::Done:
      return;
  }
  note(Note::Sample, clock | std::uint64_t{value} << 32 | std::uint64_t{in_data} << 33);
  for (auto* o : observers_) o->on_sample(frame_, clock, value, in_data);
  if (rx_ == Rx::Receiving && rx_bits_.size() == answer_width()) decode_answer();
}

// The start bit: the answer begins, and with it the count of clock pulses it needs.
void FrameEngine::begin_answer(unsigned clock) {
  rx_ = Rx::Receiving;
  rx_bits_.assign(1, 1);
  frame_.start_bit_clock = clock;
  const unsigned last_bit_clock = clock + answer_width() - 1;
  // A frame with a supplement clocks on until the master has checked the answer.
  if (!command_->supplement) {
    const int last = static_cast<int>(last_bit_clock + (params_.extra_clock_after_last_bit ? 1 : 0)) + clock_adjust_;
    last_clock_ = static_cast<unsigned>(std::max(last, static_cast<int>(clock)));
  }
}

unsigned FrameEngine::answer_width() const {
  const bool additional_data = command_->answer == protocol::AnswerFormat::Position &&
                               command_->version == protocol::EndatVersion::V2_2 && !frame_.measurement;
  return layout_.width() + (additional_data ? protocol::kAdditionalDatumBits * client_.expected_additional_data() : 0);
}

void FrameEngine::decode_answer() {
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
      frame_.crc_expected = expected_crc_pos(params_.crc, frame_.position_bits, frame_.error1, frame_.error2, v22, frame_.position);
      decode_additional_data(ok);
      break;
    }
    case protocol::AnswerFormat::TestValues:
      frame_.error1 = field(Field::Error1) != 0;
      frame_.test_value = field(Field::TestValue);
      frame_.crc_expected = expected_crc_pos(params_.crc, protocol::kTestValueBits, frame_.error1, true, false, frame_.test_value);
      break;
    case protocol::AnswerFormat::Parameter:
      frame_.echo_address = static_cast<std::uint8_t>(field(Field::Address));
      frame_.echo_parameter = static_cast<std::uint16_t>(field(Field::Parameter));
      frame_.crc_expected = protocol::make_crc_norm(frame_.echo_address, frame_.echo_parameter, params_.crc.generator);
      break;
  }
  ok = ok && crc_passes(params_.crc, frame_.crc_received, frame_.crc_expected);
  FrameOutcome outcome = ok ? FrameOutcome::Ok : FrameOutcome::CrcError;
  // A2 type II: "the address or parameter is returned inverted".
  if (ok && command_->answer == protocol::AnswerFormat::Parameter &&
      frame_.echo_address == static_cast<std::uint8_t>(~protocol::payload_address(payload_)))
    outcome = FrameOutcome::Type2Error;
  outcome = check_echo(outcome);
  // 2.4.2 ff.: "following transmission of the position value and CRC it must be monitored if an
  // error has occurred": the supplement only follows a clean answer.
  if (outcome == FrameOutcome::Ok && command_->supplement) {
    supplement_due_ = true;
    frame_.supplement = supplement_word_;
  }
  if (outcome == FrameOutcome::Ok) {
    note(Note::Accepted);
    client_.answer_accepted(frame_);
  }
  word_received(outcome);
}

// Additional data 2 and 1 after the position (2.3.5), each with its own CRC.
void FrameEngine::decode_additional_data(bool& ok) {
  for (std::size_t at = layout_.width(); at < rx_bits_.size(); at += protocol::kAdditionalDatumBits) {
    const auto r = protocol::decode_additional_datum(std::span(rx_bits_).subspan(at));
    AdditionalDatum d;
    d.status = r.status;
    d.data = r.data;
    d.crc_received = r.crc;
    d.crc_expected = protocol::make_crc_norm(d.status, d.data, params_.crc.generator);
    d.crc_ok = crc_passes(params_.crc, d.crc_received, d.crc_expected) && r.leading_low;
    ok = ok && d.crc_ok;
    frame_.additional_data.push_back(d);
  }
}

// 2.1 parameter frames echo the address (MRS code, port) and, except for a read, the parameter.
FrameOutcome FrameEngine::check_echo(FrameOutcome outcome) const {
  if (!params_.careful.verify_echo || outcome != FrameOutcome::Ok || command_->answer != protocol::AnswerFormat::Parameter)
    return outcome;
  const bool address_ok = frame_.echo_address == protocol::payload_address(payload_);
  const bool parameter_ok = frame_.command == ModeCommand::EncoderSendParameters ||
                            frame_.echo_parameter == protocol::payload_parameter(payload_);
  return address_ok && parameter_ok ? outcome : FrameOutcome::EchoMismatch;
}

void FrameEngine::word_received(FrameOutcome outcome) {
  if (words_left_ == 0) {
    end_reception(outcome, true);
    return;
  }
  // Continuous clock (2.3.1): keep clocking; after the HIGH bit and the LOW bits the next word
  // starts with its start bit, without a new mode command.
  frame_.outcome = outcome;
  frame_.end = kernel_.now();
  note(Note::WordDone);
  client_.word_done(frame_);
  --words_left_;
  ++frame_.word;
  ++frame_.index;
  frame_.start_bit_clock = 0;
  rx_ = Rx::Polling;
  hunt_.begin(true);  // the HIGH bit after the CRC is not a start bit
  rx_bits_.clear();
  last_clock_ = 0;
  poll_start_ = kernel_.now();
}

void FrameEngine::end_reception(FrameOutcome outcome, bool answer_complete) {
  rx_ = Rx::Done;
  frame_.outcome = outcome;
  delay_.stop_counter();
  if (supplement_due_) return;  // clocking goes on through the supplement
  if (last_clock_ == 0 || (last_clock_ > clock_ && !answer_complete)) {
    // Aborted: finish the current clock period and leave CLOCK HIGH (A2: wait t_m).
    last_clock_ = clock_;
    if (!clock_low_) {
      ++edge_epoch_;  // the edge queued is not taken
      clocking_done_ = true;
    }
  }
  maybe_complete_frame();
}

void FrameEngine::maybe_complete_frame() {
  if (!frame_running_ || !clocking_done_ || rx_ != Rx::Done) return;
  frame_running_ = false;
  frame_active_.write(false);
  if (frame_.measurement && frame_.outcome == FrameOutcome::Ok)
    if (const auto count = delay_.take_count()) frame_.delay_count_time = *count;
  note(Note::Done);
  client_.frame_done(frame_);
}

// ---- the frame-level fast path ------------------------------------------------------------

void FrameEngine::note(Note n, std::uint64_t data) {
  sim::Tape* tape = kernel_.tape();
  if (tape == nullptr) return;
  if (recorded_.empty() || !(recorded_.back() == frame_)) recorded_.push_back(frame_);
  // The frame as it was then, by its place among the recorded ones, above the note's data.
  tape->add(sim::TapeItem::Kind::Model, kernel_.now(), this, static_cast<std::uint32_t>(n),
            data | std::uint64_t{recorded_.size() - 1} << kNoteFrameShift);
}

bool FrameEngine::samples_wanted(const MasterObserver* skip) const {
  return std::any_of(observers_.begin(), observers_.end(), [&](const MasterObserver* o) { return o != skip && o->wants_samples(); });
}

void FrameEngine::replay(const sim::TapeItem& item, const std::vector<FrameResult>& frames, Time shift,
                         std::uint64_t index_shift) {
  const Note n = static_cast<Note>(item.index);
  if (n == Note::Start) replayed_ = nullptr;
  const FrameResult& recorded = frames.at(item.value >> kNoteFrameShift);
  if (&recorded != replayed_) {
    frame_ = moved(recorded, shift, index_shift);
    replayed_ = &recorded;
  }
  switch (n) {
    case Note::Start:
      frame_running_ = true;
      ++epoch_;
      for (auto* o : observers_) o->on_frame_start(frame_);
      return;
    case Note::Sample: {
      const auto clock = static_cast<unsigned>(item.value & 0xFFFF'FFFF);
      const bool value = ((item.value >> 32) & 1U) != 0;
      const bool in_data = ((item.value >> 33) & 1U) != 0;
      for (auto* o : observers_) o->on_sample(frame_, clock, value, in_data);
      return;
    }
    case Note::Accepted: client_.answer_accepted(frame_); return;
    case Note::WordDone: client_.word_done(frame_); return;
    case Note::Done:
      frame_running_ = false;
      replayed_ = nullptr;  // the client may change the frame (error_detected)
      client_.frame_done(frame_);
      return;
  }
}

// The delay counter saves its value at a rising edge of DATA (2.1.2: at the start bit's).
void FrameEngine::on_data_in(std::uint64_t level) {
  if (level != 0) delay_.data_rose(kernel_.now());
}

}  // namespace endatsim::master
