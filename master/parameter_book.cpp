#include "endatsim/master/parameter_book.hpp"

namespace endatsim::master {

using MC = protocol::ModeCommand;
using I = protocol::Information;

void ParameterBook::note(const FrameResult& f) {
  if (f.outcome != FrameOutcome::Ok || !f.payload) return;
  const auto address = protocol::payload_address(*f.payload);
  const std::pair key{area_mrs_, address};
  switch (f.command) {
    case MC::SelectionOfMemoryArea: area_mrs_ = address; break;
    case MC::EncoderSendParameters: words_[key] = f.echo_parameter; break;
    case MC::EncoderReceiveParameters: words_[key] = protocol::payload_parameter(*f.payload); break;
    default: break;
  }
}

std::optional<std::uint16_t> ParameterBook::parameter(std::uint8_t mrs, std::uint8_t address) const {
  const auto it = words_.find({mrs, address});
  if (it == words_.end()) return std::nullopt;
  return it->second;
}

void ParameterBook::begin_endat22_read() {
  endat22_lsb_.assign(kEndat22Words, std::nullopt);
  endat22_msb_.assign(kEndat22Words, std::nullopt);
}

void ParameterBook::note_endat22_byte(const FrameResult& f, unsigned w, bool msb) {
  if (f.outcome != FrameOutcome::Ok || w >= endat22_lsb_.size()) return;
  const I wanted = msb ? I::MemoryParameterMsb : I::MemoryParameterLsb;
  for (const auto& d : f.additional_data) {
    if (!d.crc_ok || d.busy() || protocol::datum_address(d.data) != w || d.information() != wanted) continue;
    (msb ? endat22_msb_ : endat22_lsb_)[w] = protocol::datum_byte(d.data);
  }
}

std::optional<std::uint16_t> ParameterBook::endat22_word(unsigned w) const {
  if (w >= endat22_lsb_.size() || !endat22_lsb_[w] || !endat22_msb_[w]) return std::nullopt;
  return protocol::parameter_of(*endat22_msb_[w], *endat22_lsb_[w]);
}

std::vector<std::uint16_t> ParameterBook::endat22_words(bool& complete) const {
  std::vector<std::uint16_t> e(kEndat22Words, 0);
  complete = endat22_lsb_.size() == kEndat22Words;
  for (unsigned w = 0; w < kEndat22Words && w < endat22_lsb_.size(); ++w) {
    complete = complete && endat22_lsb_[w] && endat22_msb_[w];
    e[w] = protocol::parameter_of(endat22_msb_[w].value_or(0), endat22_lsb_[w].value_or(0));
  }
  return e;
}

}  // namespace endatsim::master
