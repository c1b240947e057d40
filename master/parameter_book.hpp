// The encoder's memory as the master has read it (D297403 2.4 .. 2.6): the words of 2.1
// parameter frames, by the memory area selected last (2.4.1), and the words of the EnDat 2.2
// area (MRS BD) that came back byte by byte in additional data 1 (2.5.1: I = 5 address | LSB,
// I = 6 address | MSB). The start-up, the safety functions and the diagnosis read from it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/protocol/memory_area.hpp"

namespace endatsim::master {

class ParameterBook {
 public:
  static constexpr unsigned kEndat22Words = protocol::kEndat22Words;  // words 0 .. 63 of the 2.2 area (3.9.1)

  // A frame's contribution: a selection points later frames at its area; a read or a write
  // records the word (the value read, or the value written and acknowledged).
  void note(const FrameResult& f);
  // A word of a 2.1 area by the MRS code of its area and its address, as last read or written.
  std::optional<std::uint16_t> parameter(std::uint8_t mrs, std::uint8_t address) const;

  // Reading the 2.2 area starts again: nothing of it known.
  void begin_endat22_read();
  // Takes the byte of word `w` an answer carries in additional data 1 (LSB or MSB, as `msb`
  // says), if it carries one with a valid CRC and Busy reset.
  void note_endat22_byte(const FrameResult& f, unsigned w, bool msb);
  // Word `w` of the 2.2 area once both its bytes came.
  std::optional<std::uint16_t> endat22_word(unsigned w) const;
  // All 64 words (unknown bytes as 0) and whether every one is known.
  std::vector<std::uint16_t> endat22_words(bool& complete) const;

 private:
  std::map<std::pair<std::uint8_t, std::uint8_t>, std::uint16_t> words_;  // {MRS code, address} -> value
  std::uint8_t area_mrs_ = 0;                     // the 2.1 memory area selected last
  std::vector<std::optional<std::uint8_t>> endat22_lsb_, endat22_msb_;
};

}  // namespace endatsim::master
