#include "endatsim/master/startup.hpp"

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/timing.hpp"

namespace endatsim::master {
namespace {

using MC = ModeCommand;
using P = Operation::Purpose;
namespace word = protocol::word;

// 3.5.26: the checksum covers the encoder manufacturer's words 4 .. 46.
constexpr unsigned kFirstChecksummedWord = protocol::parameters::kManufacturerChecksumFirstWord;

}  // namespace

// The German brochure (older edition), "Spannungsversorgung und Einschalten": EnDat 2.1 mode commands only.
void StartupRoutine::plan(Sequence& s, bool measure_delay) {
  const auto step = [&s](MC c, std::uint8_t address = 0, std::uint16_t parameter = 0, P purpose = P::Step) {
    s.frame(c, address, parameter, purpose);
  };
  const auto read_manufacturer_word = [&step](unsigned w, P purpose) {
    step(MC::SelectionOfMemoryArea, protocol::mrs_of(protocol::manufacturer_area(w)));
    step(MC::EncoderSendParameters, word::manufacturer_address(w), 0, purpose);
  };
  step(MC::EncoderReceiveReset);  // then reset_wait (50 ms)
  step(MC::SelectionOfMemoryArea, protocol::mrs_of(protocol::MemoryArea::OperatingStatus));
  step(MC::EncoderSendParameters, word::kErrors, 0, P::Errors);
  step(MC::EncoderSendParameters, word::kWarnings, 0, P::Warnings);
  // 3.4.1 / 3.4.2: alarms and warnings are deleted by writing 0000h "and sending the mode command
  // Encoder receive reset" (the brochure's routine names the clearing only; the reset completes
  // it, and reset_wait follows it as it follows the first).
  step(MC::EncoderReceiveParameters, word::kErrors, 0x0000);
  step(MC::EncoderReceiveParameters, word::kWarnings, 0x0000);
  step(MC::EncoderReceiveReset);
  read_manufacturer_word(word::kPositionFormat, P::Word13);
  read_manufacturer_word(word::kCommandSet, P::Word37);
  // The same routine / 2.1.2: then the propagation delay is measured.
  if (measure_delay) s.add(Operation::Kind::MeasureDelay);
  info_ = {};
  info_.completed = true;
}

bool StartupRoutine::of_routine(P p) {
  return p == P::Step || p == P::Errors || p == P::Warnings || p == P::Word13 || p == P::Word37;
}

std::optional<unsigned> StartupRoutine::note(P p, const FrameResult& f) {
  if (!of_routine(p)) return std::nullopt;
  if (f.outcome != FrameOutcome::Ok) {
    ++info_.failed_frames;
    info_.completed = false;
    return std::nullopt;
  }
  switch (p) {
    case P::Errors: info_.errors = f.echo_parameter; break;
    case P::Warnings: info_.warnings = f.echo_parameter; break;
    case P::Word13:
      info_.word13 = f.echo_parameter;
      if (const unsigned bits = protocol::parameters::decode_position_bits(f.echo_parameter); bits != 0) return bits;
      break;
    case P::Word37: info_.word37 = f.echo_parameter; break;
    default: break;
  }
  return std::nullopt;
}

void ChecksumVerification::plan(Sequence& s) {
  for (unsigned w = kFirstChecksummedWord; w <= word::kManufacturerChecksum; ++w) {
    if (w == kFirstChecksummedWord || word::manufacturer_address(w) == 0)
      s.frame(MC::SelectionOfMemoryArea, protocol::mrs_of(protocol::manufacturer_area(w)));
    s.frame(MC::EncoderSendParameters, word::manufacturer_address(w), 0, P::ChecksumWord, w);
  }
  result_ = ChecksumCheck{};
  words_.assign(protocol::kManufacturerWords, 0);
  read_ = 0;
}

void ChecksumVerification::note(const Operation& o, const FrameResult& f) {
  if (o.purpose != P::ChecksumWord || f.outcome != FrameOutcome::Ok) return;
  words_.at(o.manufacturer_word) = f.echo_parameter;
  constexpr unsigned kWordsRead = word::kManufacturerChecksum + 1 - kFirstChecksummedWord;
  if (++read_ < kWordsRead || o.manufacturer_word != word::kManufacturerChecksum) return;
  result_->complete = true;
  result_->stored = words_[word::kManufacturerChecksum];
  result_->computed = protocol::parameters::manufacturer_checksum(words_);
}

bool plan_endat22_read(Sequence& s, std::uint64_t words, std::optional<std::uint16_t> word37) {
  using I = protocol::Information;
  if (!word37 || !protocol::parameters::decode_command_set(*word37).endat22) return false;
  const auto frame = [&s](MC c, std::uint8_t address, P purpose = P::None, unsigned w = 0) {
    s.frame(c, address, 0, purpose, w);
  };
  const auto await = [&s](P purpose, unsigned w) {
    Operation& o = s.add(Operation::Kind::AwaitNotBusy);
    // Polls 50 us apart (the model's choice) until past t_ac max (2.3.2), with a 25 % margin.
    constexpr sim::Time kPollCycle = sim::us(50);
    constexpr sim::Time kPollUntil = protocol::limit::kMemoryAccessMax + protocol::limit::kMemoryAccessMax / 4;
    o.cycle = kPollCycle;
    o.count = static_cast<unsigned>(kPollUntil / kPollCycle);
    o.purpose = purpose;
    o.manufacturer_word = w;
  };
  const auto select = MC::EncoderSendPositionValuesAndSelectionOfMemoryArea;
  frame(select, protocol::selection_mrs(I::MemoryParameterLsb));
  frame(select, protocol::mrs_of(protocol::MemoryArea::ManufacturerEndat22));
  await(P::None, 0);
  for (unsigned w = 0; w < protocol::kEndat22Words; ++w) {
    if (((words >> w) & 1U) == 0) continue;
    frame(MC::EncoderSendPositionValuesAndSendParameter, static_cast<std::uint8_t>(w));
    await(P::Endat22Lsb, w);
    frame(select, protocol::selection_mrs(I::MemoryParameterMsb));
    frame(MC::EncoderSendPositionValuesWithAdditionalData, 0, P::Endat22Msb, w);
    frame(select, protocol::selection_mrs(I::MemoryParameterLsb));
  }
  return true;
}

}  // namespace endatsim::master
